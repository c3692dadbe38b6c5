// Translation on the ellipsoid: free fall and a projectile against closed
// forms, frame-rate independence bit for bit, the antimeridian and the pole,
// and the Coriolis deflection of a falling body.
#include "plugin/bodies/Gravity.h"
#include "plugin/bodies/Simulation.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/NormalGravity.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

using namespace geocean;
using namespace geocean::bodies;
using bodies::test::stateAt;

namespace {

const MassProperties kBox = MassProperties::box(1000.0, {4.0, 2.0, 1.0});

// GeographicLib's magnitude of normal gravity (independent of our formula).
double referenceGravity(double latDeg, double h) {
  double gy = 0.0, gz = 0.0;
  GeographicLib::NormalGravity::WGS84().Gravity(latDeg, h, gy, gz);
  return std::hypot(gy, gz);
}

// Fall distance from rest after t seconds in semi-implicit Euler with step dt.
double simulatedFall(double latDeg, double h0, double t, double dt, double* latOut = nullptr) {
  Simulation sim({.stepS = dt});
  const BodyId id = sim.addBody(kBox, stateAt({latDeg, 20.0, h0}));
  sim.advanceTo(t);
  const geo::Geodetic g = geo::fromEcef(sim.body(id).state.positionEcef);
  if (latOut) *latOut = g.latDeg;
  return h0 - g.heightM;
}

}  // namespace

TEST(BodyTranslation, FreeFallMatchesClosedFormWithKnownFirstOrderError) {
  const double lat = 30.0, h0 = 1000.0, t = 10.0, dt = 1.0 / 120.0;
  // Closed form for s'' = g0 + G s (gravity growing linearly as the body
  // falls, G the free-air gradient): s = g0 / G (cosh(sqrt(G) t) - 1).
  const double g0 = referenceGravity(lat, h0);
  const double G = (referenceGravity(lat, h0 - 1.0) - referenceGravity(lat, h0 + 1.0)) / 2.0;
  const double exact = g0 / G * (std::cosh(std::sqrt(G) * t) - 1.0);
  double latEnd = 0.0;
  const double sim = simulatedFall(lat, h0, t, dt, &latEnd);
  // Semi-implicit Euler under constant g gives s_n = g t^2/2 + g t dt/2
  // exactly: the O(dt) error is g t dt / 2 = 0.41 m here. The gradient
  // changes that term by order G g t^3 dt / 2 = 1.3e-4 m (measured 2.5e-5).
  const double known = g0 * t * dt / 2.0;
  EXPECT_LE(std::abs(sim - exact), known + 1.3e-4);
  EXPECT_NEAR(sim - exact, known, 1.3e-4);
  // First order: halving dt halves the error.
  const double half = simulatedFall(lat, h0, t, dt / 2.0) - exact;
  EXPECT_NEAR((sim - exact) / half, 2.0, 0.01);
  // Falling along the ellipsoid normal keeps the geodetic latitude (normals
  // are straight lines): only rounding, ~1e-15 deg per step.
  EXPECT_NEAR(latEnd, lat, 1e-11);
}

namespace {

struct Landing {
  double rangeM = 0.0;  // horizontal, in the launch point's ENU plane
  double timeS = 0.0;
};

// Launch from height 0 at speed v0, elevation and azimuth in degrees; the
// landing (height back to 0) is interpolated linearly between the two steps.
Landing fly(const geo::Geodetic& at, double v0, double elevDeg, double azDeg, double dt) {
  const double e = elevDeg * std::numbers::pi / 180.0, a = azDeg * std::numbers::pi / 180.0;
  const glm::dvec3 vEnu(v0 * std::cos(e) * std::sin(a), v0 * std::cos(e) * std::cos(a), v0 * std::sin(e));
  Simulation sim({.stepS = dt});
  const BodyState s0 = stateAt(at, vEnu);
  const BodyId id = sim.addBody(kBox, s0);
  const geo::EnuFrame f0 = geo::enuFrame(at);
  double hPrev = at.heightM;
  glm::dvec3 xPrev = s0.positionEcef;
  while (true) {
    sim.step();
    const glm::dvec3 x = sim.body(id).state.positionEcef;
    const double h = geo::fromEcef(x).heightM;
    if (h < at.heightM) {
      const double u = (hPrev - at.heightM) / (hPrev - h);
      const glm::dvec3 d = f0.toLocal(xPrev + (x - xPrev) * u - s0.positionEcef);
      return {std::hypot(d.x, d.y), sim.time() - dt + u * dt};
    }
    hPrev = h;
    xPrev = x;
  }
}

}  // namespace

TEST(BodyTranslation, ProjectileRangeMatchesClosedForm) {
  const geo::Geodetic at{30.0, 20.0, 0.0};
  const double v0 = 50.0, dt = 1.0 / 120.0;
  const double g = referenceGravity(at.latDeg, 0.0);
  const double rangeFlat = v0 * v0 / g;  // sin(2 * 45 deg) = 1
  const Landing l = fly(at, v0, 45.0, 45.0, dt);
  // Semi-implicit Euler lands one step early (z_n = vz t - g t (t + dt) / 2),
  // so the known O(dt) error is -v_h dt = -0.29 m. Curvature of the ground
  // (+5 mm), the tilt of gravity along the path (-3 mm) and the free-air
  // gradient (+7 mm) are outside the flat closed form: 2 cm covers them.
  const double vh = v0 * std::cos(std::numbers::pi / 4.0);
  EXPECT_NEAR(l.rangeM, rangeFlat - vh * dt, 0.02);
  EXPECT_NEAR(l.timeS, 2.0 * v0 * std::sin(std::numbers::pi / 4.0) / g - dt, 1e-3);
}

namespace {

// A force that depends on position and velocity and acts off the centre of
// mass, so the frame-rate test exercises translation, rotation and forces.
class SpringAtCorner final : public ForceModel {
 public:
  explicit SpringAtCorner(glm::dvec3 anchorEcef) : anchor_(anchorEcef) {}
  void accumulate(const Body& b, const StepContext& ctx, Wrench& w) const override {
    const glm::dvec3 corner = b.state.bodyToEcef({2.0, 1.0, 0.5});
    const glm::dvec3 stretch = (ctx.enu.originEcef - anchor_) + corner;
    const glm::dvec3 v = b.state.pointVelocityEcef(corner);
    w.addForceAtOffset(-2.0e4 * stretch - 500.0 * v, corner);
  }

 private:
  glm::dvec3 anchor_;
};

Simulation springScene() {
  Simulation sim;
  BodyState s = stateAt({-41.3, 174.8, 5.0}, {1.0, -2.0, 0.5});
  s.angularVelocityBody = {0.3, -0.7, 1.1};
  const BodyId id = sim.addBody(kBox, s);
  sim.addBodyForce(id, std::make_shared<SpringAtCorner>(geo::toEcef({-41.3, 174.8, 0.0})));
  sim.addBody(MassProperties::hollowCylinder(300.0, 0.4, 0.5, 5.0), stateAt({10.0, -60.0, 100.0}, {3.0, 0.0, 0.0}));
  return sim;
}

bool bitIdentical(const Simulation& a, const Simulation& b) {
  if (a.bodies().size() != b.bodies().size() || a.stepCount() != b.stepCount()) return false;
  for (std::size_t i = 0; i < a.bodies().size(); ++i) {
    if (std::memcmp(&a.bodies()[i].state, &b.bodies()[i].state, sizeof(BodyState)) != 0) return false;
  }
  return true;
}

}  // namespace

TEST(BodyTranslation, FrameRateIndependentBitForBit) {
  Simulation at10 = springScene(), at60 = springScene(), irregular = springScene(), oneCall = springScene();
  for (int k = 1; k <= 100; ++k) at10.advanceTo(k / 10.0);
  for (int k = 1; k <= 600; ++k) at60.advanceTo(k / 60.0);
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> frame(0.0005, 0.25);
  for (double t = frame(rng); t < 10.0; t += frame(rng)) irregular.advanceTo(t);
  irregular.advanceTo(10.0);
  oneCall.advanceTo(10.0);
  EXPECT_EQ(at10.stepCount(), 1200);
  EXPECT_TRUE(bitIdentical(at10, at60));
  EXPECT_TRUE(bitIdentical(at10, irregular));
  EXPECT_TRUE(bitIdentical(at10, oneCall));
  // The scene really moved (a frozen scene would pass the above).
  EXPECT_GT(glm::length(at10.bodies()[0].state.angularVelocityBody - glm::dvec3(0.3, -0.7, 1.1)), 0.1);
}

TEST(BodyTranslation, AccumulatorAndDrawInterpolation) {
  Simulation sim({.stepS = 0.01});
  const BodyId id = sim.addBody(kBox, stateAt({0.0, 0.0, 100.0}, {10.0, 0.0, 0.0}));
  EXPECT_EQ(sim.advanceTo(0.0349), 3);
  EXPECT_NEAR(sim.alpha(), 0.49, 1e-9);
  const BodyState d = sim.drawState(id);
  const Body& b = sim.body(id);
  EXPECT_NEAR(glm::length(d.positionEcef - glm::mix(b.previous.positionEcef, b.state.positionEcef, 0.49)), 0.0,
              1e-8);
  EXPECT_THROW(sim.advanceTo(0.02), std::invalid_argument);  // before the state's time
}

namespace {

// Position after t of a launch at `at`, as ECEF rotated about the z axis by
// -lonDeg so runs at different longitudes compare.
glm::dvec3 launchAndRotateBack(const geo::Geodetic& at, const glm::dvec3& vEnu, double t) {
  Simulation sim;
  const BodyId id = sim.addBody(kBox, stateAt(at, vEnu));
  sim.advanceTo(t);
  const glm::dvec3 x = sim.body(id).state.positionEcef;
  const double lon = -at.lonDeg * std::numbers::pi / 180.0;
  const double s = std::sin(lon), c = std::cos(lon);
  return {c * x.x - s * x.y, s * x.x + c * x.y, x.z};
}

}  // namespace

TEST(BodyTranslation, AntimeridianAndHighLatitudeMatchLongitudeZero) {
  // Physics is symmetric about the polar axis: a launch at lon 179.99 is the
  // launch at lon 0 rotated. 150 m/s east for 10 s crosses the antimeridian.
  const glm::dvec3 v(150.0, 20.0, 40.0);
  for (double lat : {0.0, 10.0, 80.0, -80.0}) {
    const glm::dvec3 a = launchAndRotateBack({lat, 0.0, 50.0}, v, 10.0);
    const glm::dvec3 b = launchAndRotateBack({lat, 179.99, 50.0}, v, 10.0);
    // Rounding only: ~1e-9 m per ECEF operation over 1200 steps.
    EXPECT_LT(glm::length(a - b), 1e-5) << "lat " << lat;
  }
  // And the run at 179.99 did cross: its end is west of the antimeridian.
  Simulation sim;
  const BodyId id = sim.addBody(kBox, stateAt({10.0, 179.99, 50.0}, v));
  sim.advanceTo(10.0);
  EXPECT_LT(geo::fromEcef(sim.body(id).state.positionEcef).lonDeg, -179.99);
}

TEST(BodyTranslation, CrossesThePole) {
  // 11 m south of the north pole on lon 0, moving north at 5 m/s and up at
  // 10 m/s for 4 s: over the pole and down the lon 180 meridian.
  const geo::Geodetic at{89.9999, 0.0, 0.0};
  Simulation sim;
  const BodyId id = sim.addBody(kBox, stateAt(at, {0.0, 5.0, 10.0}));
  sim.advanceTo(4.0);
  const glm::dvec3 x = sim.body(id).state.positionEcef;
  const geo::Geodetic end = geo::fromEcef(x);
  // Stays in the lon 0 / 180 meridian plane (y = 0) to rounding.
  EXPECT_LT(std::abs(x.y), 1e-8);
  EXPECT_NEAR(std::abs(end.lonDeg), 180.0, 1e-6);
  // Ground distance from GeographicLib's geodesic: 5 m/s * 4 s = 20 m; the
  // height (< 6 m) scales arcs by h / R ~ 1e-6 and the tilt of gravity over
  // 20 m changes the horizontal speed by ~1e-5 m/s: 1 mm.
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(at.latDeg, at.lonDeg, end.latDeg, end.lonDeg, s12);
  EXPECT_NEAR(s12, 20.0, 1e-3);
}

TEST(BodyTranslation, CoriolisDeflectsAFallingBodyEast) {
  // Textbook (e.g. Landau & Lifshitz, Mechanics sec. 39): a body dropped
  // from rest is deflected east by Omega g t^3 cos(lat) / 3 to first order in Omega.
  const double lat = 0.0, t = 10.0;
  Simulation sim({.coriolis = true});
  const geo::Geodetic at{lat, 45.0, 1000.0};
  const BodyId id = sim.addBody(kBox, stateAt(at));
  sim.advanceTo(t);
  const glm::dvec3 d = geo::enuFrame(at).toLocal(sim.body(id).state.positionEcef - geo::toEcef(at));
  const double expected = kWgs84Omega * referenceGravity(lat, 1000.0) * t * t * t / 3.0;  // 0.238 m
  // Terms of second order in Omega are (Omega t)^2 ~ 5e-7 of it; the step's
  // O(dt) error bounds the rest by dt / t ~ 1e-3 (measured 7e-6).
  EXPECT_NEAR(d.x, expected, 1e-3 * expected);
  EXPECT_LT(std::abs(d.y), 1e-3 * expected);
}
