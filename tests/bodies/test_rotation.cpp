// Rotation against Euler's equations: conservation laws of a torque-free
// asymmetric body, the intermediate-axis (Dzhanibekov) instability with the
// growth rate of linear stability theory, and torques from off-centre forces.
#include "plugin/bodies/Simulation.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace geocean;
using namespace geocean::bodies;
using bodies::test::stateAt;

namespace {

// 1 x 2 x 3 m, 1200 kg: Ixx = 1300 (largest), Iyy = 1000 (middle), Izz = 500 (smallest).
const MassProperties kBox = MassProperties::box(1200.0, {1.0, 2.0, 3.0});

struct Drift {
  double energy = 0.0, momentumNorm = 0.0, momentumVector = 0.0;  // max relative
};

Drift torqueFreeDrift(double dt, double seconds) {
  Simulation sim({.stepS = dt, .gravity = false});
  BodyState s = stateAt({20.0, 30.0, 0.0});
  s.angularVelocityBody = {0.4, 1.2, -0.7};
  const BodyId id = sim.addBody(kBox, s);
  const glm::dvec3 L0 = angularMomentumEcef(s, kBox);
  const double E0 = rotationalEnergy(s, kBox);
  Drift d;
  for (int n = 1; n * dt <= seconds; ++n) {
    sim.step();
    const BodyState& b = sim.body(id).state;
    const glm::dvec3 L = angularMomentumEcef(b, kBox);
    d.energy = std::max(d.energy, std::abs(rotationalEnergy(b, kBox) / E0 - 1.0));
    d.momentumNorm = std::max(d.momentumNorm, std::abs(glm::length(L) / glm::length(L0) - 1.0));
    d.momentumVector = std::max(d.momentumVector, glm::length(L - L0) / glm::length(L0));
  }
  return d;
}

}  // namespace

TEST(BodyRotation, TorqueFreeConservesEnergyAndMomentum) {
  const Drift d = torqueFreeDrift(1.0 / 120.0, 120.0);
  // The implicit midpoint rule keeps the quadratic invariants w.Iw and |Iw|
  // exactly; what is left is rounding and the Newton stop (1e-15) over
  // 14,400 steps (measured 1.2e-14 and 6e-15).
  EXPECT_LT(d.energy, 1e-12);
  EXPECT_LT(d.momentumNorm, 1e-12);
  // L in ECEF also depends on the orientation update, a second-order step:
  // its drift over 120 s is 1.4e-5 of |L| at dt = 1/120 and falls as dt^2.
  EXPECT_LT(d.momentumVector, 3e-5);
  const Drift half = torqueFreeDrift(1.0 / 240.0, 120.0);
  EXPECT_NEAR(d.momentumVector / half.momentumVector, 4.0, 0.4);
}

namespace {

// Spin at 2 rad/s about body axis `axis` with a 1e-6 rad/s nudge on the
// other two; returns the axis component's minimum (as a fraction of the
// spin) and the largest off-axis share over `seconds`.
struct Spin {
  double minAxisShare = 1.0, maxOffAxisShare = 0.0;
  double offAxisAt3 = 0.0, offAxisAt6 = 0.0;
};

Spin spinAbout(int axis, double seconds) {
  Simulation sim({.gravity = false});
  BodyState s = stateAt({0.0, 0.0, 0.0});
  s.angularVelocityBody = glm::dvec3(1e-6);
  s.angularVelocityBody[axis] = 2.0;
  const BodyId id = sim.addBody(kBox, s);
  Spin r;
  for (int n = 1; n <= int(seconds * 120.0); ++n) {
    sim.step();
    const glm::dvec3 w = sim.body(id).state.angularVelocityBody;
    const double len = glm::length(w);
    r.minAxisShare = std::min(r.minAxisShare, w[axis] / len);
    glm::dvec3 off = w;
    off[axis] = 0.0;
    r.maxOffAxisShare = std::max(r.maxOffAxisShare, glm::length(off) / len);
    if (n == 360) r.offAxisAt3 = glm::length(off);
    if (n == 720) r.offAxisAt6 = glm::length(off);
  }
  return r;
}

}  // namespace

TEST(BodyRotation, IntermediateAxisIsUnstableTheOthersAreNot) {
  const Spin largest = spinAbout(0, 60.0), middle = spinAbout(1, 60.0), smallest = spinAbout(2, 60.0);
  // About the largest and smallest axes the nudge stays a nudge: linear
  // theory bounds it by 1e-6 * sqrt(I ratio) / 2 rad/s ~ 1e-6.
  EXPECT_LT(largest.maxOffAxisShare, 1e-5);
  EXPECT_LT(smallest.maxOffAxisShare, 1e-5);
  EXPECT_GT(largest.minAxisShare, 0.999);
  // About the middle axis the body flips: the spin reverses in body axes.
  EXPECT_LT(middle.minAxisShare, -0.9);
  // Growth rate of the perturbation from the linearised Euler equations
  // (Landau & Lifshitz, Mechanics sec. 37): lambda = w sqrt((I2 - I1)(I3 - I2) / (I1 I3)).
  const double I1 = 500.0, I2 = 1000.0, I3 = 1300.0;
  const double lambda = 2.0 * std::sqrt((I2 - I1) * (I3 - I2) / (I1 * I3));
  const double measured = std::log(middle.offAxisAt6 / middle.offAxisAt3) / 3.0;
  // Between 3 s and 6 s the decaying mode is below e^{-2 lambda 3} ~ 1e-3 of
  // the growing one, and the amplitude (< 1e-3) keeps the linearisation valid: 1%.
  EXPECT_NEAR(measured, lambda, 0.01 * lambda);
}

TEST(BodyRotation, ConstantTorqueAboutAPrincipalAxis) {
  // tau = I dw/dt with no gyroscopic term when w is along a principal axis:
  // w(t) = tau t / I, exact for the midpoint rule.
  Simulation sim({.gravity = false});
  const BodyState s = stateAt({-10.0, 100.0, 0.0});
  const BodyId id = sim.addBody(kBox, s);
  struct Couple final : ForceModel {
    void accumulate(const Body& b, const StepContext&, Wrench& w) const override {
      // Equal and opposite forces 1 m either side along body y: a pure torque
      // of 2 * 50 N m about body z.
      const glm::dvec3 f = b.state.bodyToEcef({50.0, 0.0, 0.0});
      w.addForceAtOffset(f, b.state.bodyToEcef({0.0, -1.0, 0.0}));
      w.addForceAtOffset(-f, b.state.bodyToEcef({0.0, 1.0, 0.0}));
    }
  };
  sim.addForceModel(std::make_shared<Couple>());
  sim.advanceTo(2.0);
  const Body& b = sim.body(id);
  EXPECT_NEAR(b.state.angularVelocityBody.z, 100.0 * 2.0 / 500.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::dvec3(b.state.angularVelocityBody.x, b.state.angularVelocityBody.y, 0.0)), 0.0, 1e-12);
  // A couple has no net force: the centre of mass stays put.
  EXPECT_LT(glm::length(b.state.positionEcef - s.positionEcef), 1e-9);
  // The turned angle is tau t^2 / (2 I) = 0.4 rad, up to the midpoint rule's
  // O(dt) on a linearly growing rate: 0.4 * dt / 2 / 2.
  const double angle = 2.0 * std::acos(std::min(1.0, std::abs(glm::dot(b.state.orientation, s.orientation))));
  EXPECT_NEAR(angle, 0.4, 0.4 * (1.0 / 120.0));
}
