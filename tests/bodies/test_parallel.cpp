// The per-body phases on TBB (SimulationConfig::parallel) give the same
// bits as the sequential loop, for hull forces on a Gerstner sea with
// repulsion between the bodies, and a failing force is reported alike;
// contact-point bodies' one sea query for all centres per step gives the
// forces of a query per body.
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Spawn.h"
#include "plugin/ocean/Ocean.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace geocean::bodies {
namespace {

std::shared_ptr<const SeaSurface> gerstner() {
  ocean::Ocean o;
  waves::SeaState s;
  s.windSpeedMps = 12.0;
  s.anchorLatDeg = 30.0, s.anchorLonDeg = -40.0;
  o.setSeaState(waves::Model::Gerstner, s);
  return std::make_shared<OceanSea>(o.current());
}

Simulation fleet(bool parallel, const std::shared_ptr<const SeaSurface>& sea) {
  Simulation sim({.stepS = 1.0 / 60, .parallel = parallel});
  auto hull = std::make_shared<const HullMesh>(HullMesh::boat(15.0));
  auto force = std::make_shared<HullForce>(hull, sea);
  for (int i = 0; i < 24; ++i) {
    // 12 m apart: close enough that repulsion (radius 8 m) pushes neighbours.
    const auto id = sim.addBody(hull->massProperties(450.0),
                                restingUpright(*hull, 450.0 / 1025.0, 30.0 + (i / 6) * 1.1e-4,
                                               -40.0 + (i % 6) * 1.25e-4, 37.0 * i));
    sim.addBodyForce(id, force);
    if (i % 2) sim.addBodyForce(id, std::make_shared<Thrust>(2000.0));
  }
  return sim;
}

TEST(BodyParallel, TbbOverBodiesGivesTheSequentialBits) {
  const auto sea = gerstner();
  Simulation a = fleet(false, sea), b = fleet(true, sea);
  a.addForceModel(std::make_shared<Repulsion>(a, 8.0, 1e5));
  b.addForceModel(std::make_shared<Repulsion>(b, 8.0, 1e5));
  a.advanceTo(10.0);
  b.advanceTo(10.0);
  ASSERT_EQ(a.bodies().size(), b.bodies().size());
  for (std::size_t i = 0; i < a.bodies().size(); ++i) {
    const BodyState &x = a.bodies()[i].state, &y = b.bodies()[i].state;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(x.positionEcef[k], y.positionEcef[k]) << i;
      EXPECT_EQ(x.velocityEcef[k], y.velocityEcef[k]) << i;
      EXPECT_EQ(x.angularVelocityBody[k], y.angularVelocityBody[k]) << i;
    }
    EXPECT_EQ(x.orientation.w, y.orientation.w) << i;
    EXPECT_EQ(x.orientation.x, y.orientation.x) << i;
  }
  // They moved: the sea and the engines did something to compare.
  EXPECT_GT(glm::length(a.bodies()[1].state.velocityEcef), 0.3);
}

// A force that is not finite on some bodies: both ways report the same
// (lowest-id) body and leave every state at the step's start.
class BadOn final : public ForceModel {
 public:
  void accumulate(const Body& body, const StepContext&, Wrench& w) const override {
    if (body.id % 5 == 3) w.addForce(glm::dvec3(std::numeric_limits<double>::quiet_NaN()));
  }
};

TEST(BodyParallel, AFailingForceIsReportedForTheSameBodyEitherWay) {
  const auto sea = gerstner();
  std::string msg[2];
  for (int p = 0; p < 2; ++p) {
    Simulation s = fleet(p == 1, sea);
    s.advanceTo(0.5);
    const BodyState before = s.bodies()[0].state;
    s.addForceModel(std::make_shared<BadOn>());
    try {
      s.step();
      ADD_FAILURE() << "no throw";
    } catch (const std::invalid_argument& e) {
      msg[p] = e.what();
    }
    EXPECT_EQ(s.bodies()[0].state.positionEcef, before.positionEcef);
  }
  EXPECT_EQ(msg[0], msg[1]);
  EXPECT_NE(msg[0].find("force on body 3"), std::string::npos) << msg[0];
}


// Counts the sea's queries (a wrapper, to see the batch is what runs).
class CountingSea final : public SeaSurface {
 public:
  explicit CountingSea(std::shared_ptr<const SeaSurface> s) : s_(std::move(s)) {}
  void sample(const double* la, const double* lo, const double* t, std::size_t n, bool v, SeaSample* out) const override {
    ++calls;
    s_->sample(la, lo, t, n, v, out);
  }
  double decayWaveNumberPerM() const override { return s_->decayWaveNumberPerM(); }
  void sampleSlopes(const double* la, const double* lo, const double* t, std::size_t n, SeaSample* out) const override {
    s_->sampleSlopes(la, lo, t, n, out);
  }
  mutable int calls = 0;

 private:
  std::shared_ptr<const SeaSurface> s_;
};

TEST(BodyParallel, ContactPointsQueryAllCentresAndPointsAtOnceWithTheForcesOfOneQueryEach) {
  const auto sea = std::make_shared<CountingSea>(gerstner());
  Simulation sim({.stepS = 1.0 / 60, .parallel = false});
  auto cp = ContactPointForce::hollowCylinderProxy(20.0, 2.5, 4, sea);
  for (int i = 0; i < 40; ++i) {
    BodyState s = restingUpright(HullMesh::box({20.0, 5.0, 5.0}), 0.4, 30.0 + (i / 8) * 3e-4, -40.0 + (i % 8) * 3e-4,
                                 17.0 * i);
    const BodyId id = sim.addBody(MassProperties::box(0.4 * 1025 * 500.0, {20.0, 5.0, 5.0}), s);
    sim.addBodyForce(id, cp);
  }
  sim.advanceTo(3.0);  // moving in the waves
  sea->calls = 0;
  cp->beginStep(sim);  // what the next step does: one query for the 40 centres, one for their 320 points
  EXPECT_EQ(sea->calls, 2);
  // The same model without beginStep: each centre queried on its own.
  auto single = ContactPointForce::hollowCylinderProxy(20.0, 2.5, 4, sea);
  double worst = 0.0, scale = 0.0;
  sea->calls = 0;
  for (const Body& b : sim.bodies()) {
    const StepContext ctx = sim.context(b.state);
    Wrench w1, w2;
    cp->accumulate(b, ctx, w1);
    single->accumulate(b, ctx, w2);
    worst = std::max({worst, glm::length(w1.force() - w2.force()), glm::length(w1.torque() - w2.torque()) / 20.0});
    scale = std::max(scale, glm::length(w1.force()));
  }
  // The same points through the same kernel; lanes of other points in a
  // vector may round the inversion differently: rounding only.
  EXPECT_LE(worst, 1e-9 * scale) << worst << " of " << scale;
  EXPECT_GT(scale, 1e5);
  EXPECT_EQ(sea->calls, 40 * 2) << "the batched model queries nothing, the other its points and its centre";
}

}  // namespace
}  // namespace geocean::bodies
