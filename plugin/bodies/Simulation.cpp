#include "plugin/bodies/Simulation.h"

#include "globe/geo/Parallel.h"
#include "plugin/bodies/Gravity.h"
#include "plugin/bodies/Validate.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <tbb/blocked_range.h>

#include <algorithm>
#include <exception>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace geocean::bodies {

using detail::fail;
using detail::requireFinite;
using detail::requirePositive;

namespace {

glm::dmat3 skew(const glm::dvec3& v) {
  // Column-major: skew(v) * u == cross(v, u).
  return glm::dmat3(0.0, v.z, -v.y, -v.z, 0.0, v.x, v.y, -v.x, 0.0);
}

// exp of the pure quaternion (0, theta / 2): rotation by |theta| about theta.
glm::dquat rotationQuat(const glm::dvec3& theta) {
  const double angle = glm::length(theta);
  // sin(angle/2)/angle by its series where the division would lose digits;
  // the next term, angle^6 / 322560, is below rounding for angle < 1e-3.
  const double a2 = angle * angle;
  const double s = angle < 1e-3 ? 0.5 - a2 / 48.0 + a2 * a2 / 3840.0 : std::sin(0.5 * angle) / angle;
  return {std::cos(0.5 * angle), theta.x * s, theta.y * s, theta.z * s};
}

}  // namespace

Simulation::Simulation(SimulationConfig config) : config_(config) {
  requirePositive("stepS", config_.stepS, "s");
  requireFinite("startS", config_.startS, "s");
}

BodyId Simulation::addBody(const MassProperties& mass, const BodyState& state) {
  validate(state);
  BodyState s = state;
  s.orientation = glm::normalize(s.orientation);
  const BodyId id = nextId_++;
  bodies_.push_back(Body{id, mass, s, s, {}, {}});
  return id;
}

void Simulation::removeBody(BodyId id) {
  auto it = std::lower_bound(bodies_.begin(), bodies_.end(), id, [](const Body& b, BodyId v) { return b.id < v; });
  if (it == bodies_.end() || it->id != id) fail("body id", static_cast<double>(id), "", "no such body");
  bodies_.erase(it);
}

Body& Simulation::body(BodyId id) { return const_cast<Body&>(std::as_const(*this).body(id)); }

const Body& Simulation::body(BodyId id) const {
  auto it = std::lower_bound(bodies_.begin(), bodies_.end(), id, [](const Body& b, BodyId v) { return b.id < v; });
  if (it == bodies_.end() || it->id != id) fail("body id", static_cast<double>(id), "", "no such body");
  return *it;
}

void Simulation::addForceModel(std::shared_ptr<const ForceModel> model) {
  if (!model) throw std::invalid_argument("geocean::bodies: force model is null");
  globalForces_.push_back(std::move(model));
}

void Simulation::addBodyForce(BodyId id, std::shared_ptr<const ForceModel> model) {
  if (!model) throw std::invalid_argument("geocean::bodies: force model is null");
  body(id).forces.push_back(std::move(model));
}

void Simulation::addBodyConstraint(BodyId id, std::shared_ptr<const StepConstraint> constraint) {
  if (!constraint) throw std::invalid_argument("geocean::bodies: step constraint is null");
  body(id).constraints.push_back(std::move(constraint));
}

StepContext Simulation::context(const BodyState& s) const {
  StepContext c;
  c.timeS = time();
  c.stepS = config_.stepS;
  c.geodetic = geo::fromEcef(s.positionEcef);
  c.enu = geo::enuFrame(c.geodetic);
  c.enu.originEcef = s.positionEcef;  // not toEcef(fromEcef(x)), which differs by rounding
  c.gravityMps2 = config_.gravity ? normalGravity(c.geodetic.latDeg, c.geodetic.heightM) : 0.0;
  return c;
}

std::int64_t Simulation::advanceTo(double tS) {
  requireFinite("advanceTo t", tS, "s");
  if (tS < time()) fail("advanceTo t", tS, "s", "must not be before the simulation time " + std::to_string(time()));
  std::int64_t n = 0;
  // A step ending within 1e-9 step of tS counts as ending at tS, so the
  // rounding of n * stepS never drops the step that ends at tS.
  const double limit = tS + 1e-9 * config_.stepS;
  while (timeOfStep(steps_ + 1) <= limit) {
    step();
    ++n;
  }
  alpha_ = std::clamp((tS - time()) / config_.stepS, 0.0, 1.0);
  return n;
}

void Simulation::step() {
  const std::size_t n = bodies_.size();
  std::vector<StepContext>& ctx = contexts_;
  ctx.resize(n);
  wrenches_.assign(n, Wrench{});
  // Runs f(i) for every body, on TBB's threads when config_.parallel; the
  // failure of the lowest index is rethrown, so both ways fail alike.
  auto forEachBody = [&](auto&& f) {
    if (!config_.parallel || n < 2) {
      for (std::size_t i = 0; i < n; ++i) f(i);
      return;
    }
    std::vector<std::exception_ptr> errors(n);
    geo::parallelFor(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        try {
          f(i);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    });
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
  };
  // Every distinct model once, in a fixed order (global, then by body).
  beganModels_.clear();
  for (const auto& m : globalForces_) m->beginStep(*this);
  for (const Body& b : bodies_)
    for (const auto& m : b.forces)
      if (beganModels_.insert(m.get()).second) m->beginStep(*this);
  // Phase 1: every force from the states at the step's start.
  forEachBody([&](std::size_t i) {
    const Body& b = bodies_[i];
    ctx[i] = context(b.state);
    for (const auto& m : globalForces_) m->accumulate(b, ctx[i], wrenches_[i]);
    for (const auto& m : b.forces) m->accumulate(b, ctx[i], wrenches_[i]);
    requireFinite("force on body " + std::to_string(b.id), wrenches_[i].force(), "N");
    requireFinite("torque on body " + std::to_string(b.id), wrenches_[i].torque(), "N m");
    const glm::dvec3 &am = wrenches_[i].addedMassBody(), &ai = wrenches_[i].addedInertiaBody();
    for (int k = 0; k < 3; ++k) {
      if (!(am[k] >= 0.0 && std::isfinite(am[k])))
        fail("added mass on body " + std::to_string(b.id) + " axis " + std::to_string(k), am[k], "kg",
             "must be finite and >= 0");
      if (!(ai[k] >= 0.0 && std::isfinite(ai[k])))
        fail("added inertia on body " + std::to_string(b.id) + " axis " + std::to_string(k), ai[k], "kg m^2",
             "must be finite and >= 0");
    }
  });
  // Phase 2: integrate (each body its own state).
  forEachBody([&](std::size_t i) {
    integrate(bodies_[i], ctx[i], wrenches_[i]);
    for (const auto& c : bodies_[i].constraints) c->afterStep(bodies_[i], bodies_[i].previous);
  });
  ++steps_;
}

void Simulation::integrate(Body& b, const StepContext& ctx, const Wrench& w) const {
  const double dt = config_.stepS;
  const geo::EnuFrame& enu = ctx.enu;
  BodyState& s = b.state;
  b.previous = s;

  // Translation, semi-implicit Euler in ENU at the centre of mass.
  glm::dvec3 vL = enu.toLocal(s.velocityEcef);
  glm::dvec3 aL;
  const glm::dvec3& am = w.addedMassBody();
  if (am == glm::dvec3(0.0)) {
    aL = enu.toLocal(w.force()) * b.mass.inverseMass();
    aL.z -= ctx.gravityMps2;
  } else {
    // (m 1 + R A R^T) a = F + m g, R = body axes in ENU; gravity acts on the
    // body's mass only (the entrained water is weightless in water).
    glm::dmat3 R;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 axis(0.0);
      axis[k] = 1.0;
      R[k] = enu.toLocal(s.bodyToEcef(axis));
    }
    glm::dmat3 A(0.0);
    for (int k = 0; k < 3; ++k) A[k][k] = am[k];
    const glm::dmat3 M = glm::dmat3(b.mass.massKg()) + R * A * glm::transpose(R);
    glm::dvec3 F = enu.toLocal(w.force());
    F.z -= b.mass.massKg() * ctx.gravityMps2;
    aL = glm::inverse(M) * F;
  }
  if (config_.coriolis) aL -= 2.0 * glm::cross(enu.toLocal(glm::dvec3(0.0, 0.0, kWgs84Omega)), vL);
  vL += aL * dt;
  s.positionEcef += enu.toEcef(vL * dt);
  s.velocityEcef = enu.toEcef(vL);

  // Rotation: implicit midpoint on I dw/dt = tau - w x I w (body axes).
  const glm::dvec3& ai = w.addedInertiaBody();
  glm::dmat3 Iadded = b.mass.inertiaBody();
  for (int k = 0; k < 3; ++k) Iadded[k][k] += ai[k];
  const bool plain = ai == glm::dvec3(0.0);
  const glm::dmat3& I = plain ? b.mass.inertiaBody() : Iadded;
  const glm::dmat3 Iinv = plain ? b.mass.inverseInertiaBody() : glm::inverse(Iadded);
  const glm::dvec3 tau = s.ecefToBody(w.torque());
  const glm::dvec3 w0 = s.angularVelocityBody;
  glm::dvec3 w1 = w0 + dt * (Iinv * (tau - glm::cross(w0, I * w0)));  // explicit predictor
  // Newton on G(w1) = I (w1 - w0) + dt (wm x I wm - tau), wm = (w0 + w1) / 2.
  // The residual contracts by ~(|w| dt)^2 per iteration; 8 is far more than
  // any step below |w| dt = 1 needs, and stopping at a fixed rule keeps the
  // result deterministic.
  for (int it = 0; it < 8; ++it) {
    const glm::dvec3 wm = 0.5 * (w0 + w1);
    const glm::dvec3 G = I * (w1 - w0) + dt * (glm::cross(wm, I * wm) - tau);
    const glm::dmat3 J = I + (0.5 * dt) * (skew(wm) * I - skew(I * wm));
    const glm::dvec3 delta = glm::inverse(J) * G;
    w1 -= delta;
    if (glm::length(delta) <= 1e-15 * glm::length(w1)) break;
  }
  // The orientation turns by the midpoint rate plus the other half of the
  // torque's kick, w_q = (w0 + w1) / 2 + dt I^-1 tau / 2: torque-free this is
  // the midpoint rule; for the torque it is symplectic Euler (turn with the
  // kicked rate), like the translation. Turning with (w0 + w1) / 2 alone is
  // x += dt v0 + dt^2 a0 / 2, v += dt a0, which gains energy under a
  // restoring torque by (omega dt)^2 / 2 per step (a floating box's roll grew
  // 6 % in 20 s).
  const glm::dvec3 wm = 0.5 * (w0 + w1) + (0.5 * dt) * (Iinv * tau);
  s.orientation = glm::normalize(s.orientation * rotationQuat(wm * dt));
  s.angularVelocityBody = w1;
}

BodyState Simulation::drawState(BodyId id) const {
  const Body& b = body(id);
  return interpolate(b.previous, b.state, alpha_);
}

}  // namespace geocean::bodies
