// Bad input throws std::invalid_argument naming the field and the value.
#include "plugin/bodies/Simulation.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

using namespace geocean;
using namespace geocean::bodies;
using bodies::test::stateAt;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expectThrowNaming(const std::function<void()>& f, const std::string& field, const std::string& value) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one naming " << field;
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(field), std::string::npos) << m;
    EXPECT_NE(m.find(value), std::string::npos) << m;
  }
}

glm::dmat3 diag(double a, double b, double c) {
  glm::dmat3 m(0.0);
  m[0][0] = a, m[1][1] = b, m[2][2] = c;
  return m;
}

}  // namespace

TEST(BodyValidation, Mass) {
  expectThrowNaming([] { MassProperties(kNan, diag(1, 1, 1)); }, "mass", "nan");
  expectThrowNaming([] { MassProperties(0.0, diag(1, 1, 1)); }, "mass", "= 0");
  expectThrowNaming([] { MassProperties(-5.0, diag(1, 1, 1)); }, "mass", "-5");
  expectThrowNaming([] { MassProperties::box(kInf, {1, 1, 1}); }, "mass", "inf");
  expectThrowNaming([] { MassProperties::solidCylinder(-1.0, 1, 1); }, "mass", "-1");
}

TEST(BodyValidation, Inertia) {
  expectThrowNaming([] { MassProperties(1.0, diag(1, 1, -1)); }, "inertia leading minor 3", "-1");
  expectThrowNaming([] { MassProperties(1.0, diag(1, 0, 1)); }, "inertia leading minor 2", "0");
  expectThrowNaming([] { MassProperties(1.0, diag(-2, 1, 1)); }, "inertia leading minor 1", "-2");
  expectThrowNaming([] { MassProperties(1.0, diag(1, kNan, 1)); }, "inertia[1][1]", "nan");
  glm::dmat3 asym = diag(2, 2, 2);
  asym[1][0] = 0.5;  // column 1, row 0 only
  expectThrowNaming([asym] { MassProperties(1.0, asym); }, "symmetric", "0.5");
  // Positive diagonal yet indefinite: off-diagonal terms larger than the diagonal.
  glm::dmat3 indefinite = diag(1, 1, 1);
  indefinite[0][1] = indefinite[1][0] = 2.0;
  expectThrowNaming([indefinite] { MassProperties(1.0, indefinite); }, "inertia leading minor 2", "-3");
}

TEST(BodyValidation, Shapes) {
  expectThrowNaming([] { MassProperties::box(1.0, {1, -2, 1}); }, "box size.y", "-2");
  expectThrowNaming([] { MassProperties::box(1.0, {1, 1, kNan}); }, "box size.z", "nan");
  expectThrowNaming([] { MassProperties::solidCylinder(1.0, 0.0, 1); }, "cylinder radius", "0");
  expectThrowNaming([] { MassProperties::solidCylinder(1.0, 1.0, kInf); }, "cylinder length", "inf");
  expectThrowNaming([] { MassProperties::hollowCylinder(1.0, 2.0, 1.0, 1); }, "inner radius", "2");
  expectThrowNaming([] { MassProperties::hollowCylinder(1.0, -0.1, 1.0, 1); }, "inner radius", "-0.1");
}

TEST(BodyValidation, StepAndTime) {
  expectThrowNaming([] { Simulation({.stepS = kNan}); }, "stepS", "nan");
  expectThrowNaming([] { Simulation({.stepS = kInf}); }, "stepS", "inf");
  expectThrowNaming([] { Simulation({.stepS = 0.0}); }, "stepS", "0");
  expectThrowNaming([] { Simulation({.stepS = -0.01}); }, "stepS", "-0.01");
  Simulation sim;
  expectThrowNaming([&] { sim.advanceTo(kNan); }, "advanceTo t", "nan");
  expectThrowNaming([&] { sim.advanceTo(-1.0); }, "advanceTo t", "-1");
}

TEST(BodyValidation, StateAndForces) {
  Simulation sim;
  const auto box = MassProperties::box(10.0, {1, 1, 1});
  BodyState s = stateAt({0, 0, 0});
  s.velocityEcef.y = kNan;
  expectThrowNaming([&] { sim.addBody(box, s); }, "velocity.y", "nan");
  s = stateAt({0, 0, 0});
  s.orientation = glm::dquat(0.0, 0.0, 0.0, 0.0);
  expectThrowNaming([&] { sim.addBody(box, s); }, "orientation norm", "0");
  expectThrowNaming([&] { sim.body(42); }, "body id", "42");
  // A force model returning NaN stops the step before any state changes.
  struct Bad final : ForceModel {
    void accumulate(const Body&, const StepContext&, Wrench& w) const override { w.addForce({0.0, 0.0, kNan}); }
  };
  const BodyId id = sim.addBody(box, stateAt({0, 0, 0}));
  const BodyState before = sim.body(id).state;
  sim.addForceModel(std::make_shared<Bad>());
  expectThrowNaming([&] { sim.step(); }, "force on body", "nan");
  EXPECT_EQ(sim.stepCount(), 0);
  EXPECT_EQ(sim.body(id).state.positionEcef, before.positionEcef);
  sim.removeBody(id);
  expectThrowNaming([&] { sim.body(id); }, "body id", std::to_string(id));
  expectThrowNaming([&] { sim.removeBody(id); }, "body id", std::to_string(id));
}
