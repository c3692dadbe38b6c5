// Terrain collision on a 512 x 512 height field: the cell walk finds exactly
// the brute-force reference's first hit, and boxes thrown at 50 m/s with
// dt = 1/30 neither penetrate nor tunnel (the figures, printed).
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Terrain.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

using namespace geocean;
using namespace geocean::bodies;

namespace {
constexpr int kN = 512;
constexpr double kSpacing = 2.0;
const geo::Geodetic kOrigin{46.5, 8.0, 0.0};

std::shared_ptr<HeightField> scene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  std::vector<double> h(std::size_t(kN) * kN);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i)
      h[std::size_t(j) * kN + i] = 20 * std::sin(i / 37.0) * std::cos(j / 23.0) + 5 * std::sin(i / 7.0 + j / 11.0) + jitter(rng);
  return std::make_shared<HeightField>(kOrigin, kN, kN, kSpacing, std::move(h));
}
}  // namespace

TEST(BodyTerrain, CellWalkAndQuadtreeFindTheBruteForceFirstHit) {
  const auto T = scene(3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xy(-20.0, kN * kSpacing + 20.0), z(-30.0, 40.0);
  int hits = 0;
  for (int k = 0; k < 300; ++k) {
    const glm::dvec3 a(xy(rng), xy(rng), z(rng) + 20.0);
    // Long, short and nearly vertical segments.
    const double len = k % 3 == 0 ? 800.0 : (k % 3 == 1 ? 3.0 : 0.05);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    glm::dvec3 d(u(rng) * len, u(rng) * len, -std::abs(u(rng)) * 60.0 - 1.0);
    const auto ref = T->sweepBruteForce(a, a + d);
    // sweep() picks the cell walk or the quadtree by length; both, each way.
    for (const auto& fast : {T->sweep(a, a + d), T->sweepCellWalk(a, a + d), T->sweepQuadtree(a, a + d)}) {
      ASSERT_EQ(fast.has_value(), ref.has_value()) << k;
      if (ref) {
        EXPECT_EQ(fast->t, ref->t) << k;  // the same triangle test on the same triangle
      }
    }
    if (ref) {
      ++hits;
      EXPECT_NEAR(ref->pointEnu.z, T->heightAt(ref->pointEnu.x, ref->pointEnu.y), 1e-9);
    }
  }
  EXPECT_GT(hits, 100);
}

TEST(BodyTerrain, BoxesAtFiftyMetresPerSecondNeitherPenetrateNorTunnel) {
  const auto T = scene(5);
  const double dt = 1.0 / 30;
  Simulation sim({.stepS = dt});
  const glm::dvec3 half(1.0, 0.5, 0.5);
  std::vector<glm::dvec3> corners;
  for (int c = 0; c < 8; ++c) corners.emplace_back(c & 1 ? half.x : -half.x, c & 2 ? half.y : -half.y, c & 4 ? half.z : -half.z);
  auto contact = std::make_shared<TerrainContact>(T, corners);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> pos(150.0, kN * kSpacing - 150.0), ang(0.0, 2 * M_PI), dip(0.17, 1.4);
  std::vector<BodyId> ids;
  for (int b = 0; b < 100; ++b) {
    const double x = pos(rng), y = pos(rng), az = ang(rng), el = dip(rng);
    const glm::dvec3 pEnu(x, y, T->heightAt(x, y) + 3.0);
    const glm::dvec3 vEnu = 50.0 * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el));
    BodyState s;
    s.positionEcef = T->frame().originEcef + T->frame().toEcef(pEnu);
    s.velocityEcef = T->frame().toEcef(vEnu);
    s.orientation = glm::quat_cast(T->frame().rotation());
    s.angularVelocityBody = {0.3, -0.2, 0.5};
    ids.push_back(sim.addBody(MassProperties::box(1000.0, 2.0 * half), s));
    sim.addBodyConstraint(ids.back(), contact);
  }
  long steps = 0, penetrating = 0;
  double maxDepth = 0.0;
  int tunnelled = 0;
  double seconds = 0.0;
  for (int k = 0; k < 90; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.step();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (BodyId id : ids) {
      const BodyState& s = sim.body(id).state;
      bool below = false;
      for (const auto& c : corners) {
        const glm::dvec3 q = T->toPatch(s.positionEcef + s.bodyToEcef(c));
        const double depth = T->heightAt(q.x, q.y) - q.z;
        if (depth > 1e-6) below = true;
        maxDepth = std::max(maxDepth, depth);
      }
      ++steps;
      penetrating += below;
    }
  }
  for (BodyId id : ids) {
    const glm::dvec3 q = T->toPatch(sim.body(id).state.positionEcef);
    if (q.z < T->heightAt(q.x, q.y) - 1.0) ++tunnelled;
  }
  std::printf("[ measured ] %ld body-steps: penetrating %ld (rate %.4f), max depth %.3g m, tunnelled %d of %zu, "
              "%.2f us per body-step (gravity + integration + swept contact of 8 points)\n",
              steps, penetrating, double(penetrating) / steps, maxDepth, tunnelled, ids.size(), 1e6 * seconds / steps);
  EXPECT_EQ(penetrating, 0);
  EXPECT_EQ(tunnelled, 0);
  EXPECT_LT(maxDepth, 1e-6);
}
