// Fixed-step rigid-body simulation on the WGS84 ellipsoid.
//
// advanceTo(t) runs whole steps of config.stepS until the next one would pass
// t; step n ends at exactly startS + n * stepS (computed, never summed), so the
// state at a time depends only on the number of steps, not on the frame times
// that got there: the results are bit-identical at 10 fps, 60 fps or any
// irregular sequence (tests/bodies). The unstepped remainder is the
// accumulator; alpha() gives it as a fraction of a step for drawing.
//
// Each step, for every body:
//   1. forces and torques are accumulated from the state at the step's start
//      (all bodies first, so every force sees the same instant and a bad force
//      leaves every state untouched);
//   2. translation by semi-implicit (symplectic) Euler in the body's local
//      east-north-up frame: v += a dt, then dx = v dt, position += dx. Gravity
//      is (0, 0, -gamma) there. The ENU origin is the centre of mass itself, so
//      the step's arithmetic is on small numbers: the 6.4e6 m ECEF coordinate
//      enters once, in position += dx, where double keeps ~1 nm;
//   3. rotation by the implicit midpoint rule on Euler's equations in body axes
//      (I dw/dt = tau - w x I w, Newton-solved), which keeps the kinetic energy
//      and |L| of a torque-free body to rounding; then q <- q exp(w_mid dt / 2),
//      renormalised.
// Both are one force evaluation per step (the sea-height query is the cost).
#pragma once

#include "globe/geo/Ellipsoid.h"
#include "plugin/bodies/RigidBody.h"

#include <cstdint>
#include <memory>
#include <unordered_set>
#include <vector>

namespace geocean::bodies {

using BodyId = std::uint64_t;

class ForceModel;
class StepConstraint;
class Simulation;

struct Body {
  BodyId id = 0;
  MassProperties mass;
  BodyState state;     // at Simulation::time()
  BodyState previous;  // one step earlier (the start state before the first step)
  std::vector<std::shared_ptr<const ForceModel>> forces;  // this body's own models
  std::vector<std::shared_ptr<const StepConstraint>> constraints;  // run after each step (contacts)
};

// What a force model sees of the step: the state is body.state at timeS.
struct StepContext {
  double timeS = 0.0;
  double stepS = 0.0;
  geo::Geodetic geodetic;  // centre of mass
  geo::EnuFrame enu;       // axes at the centre of mass; enu.originEcef = body.state.positionEcef exactly
  double gravityMps2 = 0.0;  // normal gravity magnitude there (down along -enu.up)
};

// Issue 14's buoyancy points, hull triangles, drag and contacts implement this.
// Gravity is built in (it acts at the centre of mass and needs no model).
class ForceModel {
 public:
  virtual ~ForceModel() = default;
  virtual void accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const = 0;
  // Called once per step for every distinct model (global or a body's), on
  // one thread, with the states at the step's start, before any accumulate
  // of that step: work over all bodies at once (Repulsion's broadphase,
  // ContactPointForce's one sea query for every body's centre).
  virtual void beginStep(const Simulation& sim) const { (void)sim; }
};

// Runs after a body's integration with its state at the step's start, and
// may correct the new state (terrain contact: TerrainContact in Terrain.h).
class StepConstraint {
 public:
  virtual ~StepConstraint() = default;
  virtual void afterStep(Body& body, const BodyState& before) const = 0;
};

struct SimulationConfig {
  double stepS = 1.0 / 120.0;  // fixed step, s
  double startS = 0.0;         // time of the initial states, s
  bool gravity = true;         // WGS84 normal gravity (includes the centrifugal term)
  // ECEF rotates with the Earth: the Coriolis acceleration -2 Omega x v.
  // Off by default (3 mm/s^2 at 20 m/s; heading drift a game would not expect).
  bool coriolis = false;
  // Each step's force and integration phases run over the bodies on TBB's
  // threads (force models are const and thread-safe, a body's phase touches
  // only its own state and wrench); the results are the same bits as
  // sequentially, and a failure reports the lowest-id failing body either way.
  bool parallel = true;
};

// Not thread-safe: one thread calls a Simulation at a time; inside a step
// the per-body phases run on TBB (SimulationConfig::parallel).
class Simulation {
 public:
  explicit Simulation(SimulationConfig config = {});

  BodyId addBody(const MassProperties& mass, const BodyState& state);
  void removeBody(BodyId id);
  Body& body(BodyId id);
  const Body& body(BodyId id) const;
  const std::vector<Body>& bodies() const { return bodies_; }

  void addForceModel(std::shared_ptr<const ForceModel> model);  // acts on every body
  void addBodyForce(BodyId id, std::shared_ptr<const ForceModel> model);
  void addBodyConstraint(BodyId id, std::shared_ptr<const StepConstraint> constraint);

  // Runs every whole step ending at or before tS (tS >= time()); returns how many.
  std::int64_t advanceTo(double tS);
  void step();

  double time() const { return timeOfStep(steps_); }
  std::int64_t stepCount() const { return steps_; }
  const SimulationConfig& config() const { return config_; }
  // (last advanceTo time - time()) / stepS, in [0, 1).
  double alpha() const { return alpha_; }
  // Pose to draw after advanceTo(t): previous -> state by alpha (one step behind
  // t, so it never extrapolates).
  BodyState drawState(BodyId id) const;

  // Step context for a state (what force models get); public for tests and tools.
  StepContext context(const BodyState& s) const;

 private:
  double timeOfStep(std::int64_t n) const { return config_.startS + static_cast<double>(n) * config_.stepS; }
  void integrate(Body& b, const StepContext& ctx, const Wrench& w) const;

  SimulationConfig config_;
  std::vector<Body> bodies_;  // sorted by id (ids only grow): deterministic order
  std::vector<std::shared_ptr<const ForceModel>> globalForces_;
  std::int64_t steps_ = 0;
  BodyId nextId_ = 1;
  double alpha_ = 0.0;
  std::vector<Wrench> wrenches_;       // per body, reused across steps
  std::vector<StepContext> contexts_;  // per body, reused across steps
  std::unordered_set<const ForceModel*> beganModels_;  // step(): beginStep once each
};

}  // namespace geocean::bodies
