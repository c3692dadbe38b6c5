// Repulsion between bodies (paper 000 eq. 3-4, F_c): in free space (no
// gravity, no water) a collision of two bodies conserves the pair's linear
// momentum to rounding and ends as the elastic collision of textbook
// mechanics (the spring stores and returns the energy) within 0.5 %; a glancing collision of elongated bodies spins them and keeps the
// pair's angular momentum; the hash-grid broadphase finds every pair a
// brute-force sum over all pairs finds.
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/Simulation.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace geocean;
using namespace geocean::bodies;
using bodies::test::stateAt;

namespace {

struct Pair {
  BodyState a, b;
};

// A (ma) moving east at v0 towards B (mb) at rest 4 m east, both spheres of
// radius 1 m at the centre, stiffness k; no gravity; stepped for 2 s.
Pair headOn(double ma, double mb, double v0, double k, double dt) {
  Simulation sim({.stepS = dt, .gravity = false, .parallel = false});
  const BodyId a = sim.addBody(MassProperties::box(ma, {2.0, 2.0, 2.0}), stateAt({0.0, 0.0, 0.0}, {v0, 0.0, 0.0}));
  const geo::EnuFrame f = geo::enuFrame({0.0, 0.0, 0.0});
  BodyState sb;
  sb.positionEcef = f.originEcef + f.toEcef({4.0, 0.0, 0.0});
  const BodyId b = sim.addBody(MassProperties::box(mb, {2.0, 2.0, 2.0}), sb);
  sim.addForceModel(std::make_shared<Repulsion>(sim, 1.0, k));
  sim.advanceTo(2.0);
  return {sim.body(a).state, sim.body(b).state};
}

}  // namespace

TEST(BodyRepulsion, AHeadOnCollisionConservesMomentumAndIsElastic) {
  const double ma = 1000.0, mb = 3000.0, v0 = 2.0, k = 1e6;
  const geo::EnuFrame f = geo::enuFrame({0.0, 0.0, 0.0});
  // Textbook elastic collision: va = (ma - mb) / (ma + mb) v0, vb = 2 ma / (ma + mb) v0.
  const double va = (ma - mb) / (ma + mb) * v0, vb = 2.0 * ma / (ma + mb) * v0;
  double err[2];
  for (int h = 0; h < 2; ++h) {
    const double dt = h == 0 ? 1.0 / 600.0 : 1.0 / 1200.0;
    const Pair p = headOn(ma, mb, v0, k, dt);
    const glm::dvec3 ua = f.toLocal(p.a.velocityEcef), ub = f.toLocal(p.b.velocityEcef);
    // The contact is over (centres > 2 m apart): the velocities are final.
    EXPECT_GT(glm::length(p.b.positionEcef - p.a.positionEcef), 2.5);
    // Momentum: the pair's forces are exact negatives of each other, so the
    // total changes only by the rounding of the sums (v ~ 1 m/s: 1e-12 relative).
    const glm::dvec3 P = ma * p.a.velocityEcef + mb * p.b.velocityEcef;
    EXPECT_LE(glm::length(P - ma * f.toEcef({v0, 0.0, 0.0})), 1e-9 * ma * v0) << dt;
    // Along the line of centres only (a central force).
    EXPECT_LE(std::hypot(ua.y, ua.z), 1e-9);
    EXPECT_LE(std::hypot(ub.y, ub.z), 1e-9);
    err[h] = std::max(std::abs(ua.x - va), std::abs(ub.x - vb));
    // The contact starts and ends between steps (the spring's compression
    // is off by up to a step's travel, v0 dt) and symplectic Euler carries
    // an O(omega dt) energy oscillation while it lasts (omega = sqrt(k /
    // mu) = 36.5 rad/s, omega dt = 0.061): measured 3.3e-4 v0 at dt 1/600,
    // 6.3e-5 v0 at 1/1200; bound 0.5 % of v0.
    EXPECT_LE(err[h], 0.005 * v0) << "va " << ua.x << " (" << va << "), vb " << ub.x << " (" << vb << ")";
  }
  EXPECT_LE(err[1], err[0]) << "a finer step is no worse";
}

TEST(BodyRepulsion, AGlancingCollisionOfLongHullsSpinsThemAndKeepsTheAngularMomentum) {
  // Two 8 x 2 x 2 m boxes (spheresAlongHull: 4 spheres of 1 m along x), A
  // moving north at 3 m/s, B at rest 1.2 m east of A's line: they meet
  // off-centre (bow of A against the side of B), so both turn.
  const HullMesh hull = HullMesh::box({8.0, 2.0, 2.0});
  const auto spheres = Repulsion::spheresAlongHull(hull);
  ASSERT_EQ(spheres.size(), 4u);
  EXPECT_DOUBLE_EQ(spheres[0].radiusM, 1.0);
  EXPECT_DOUBLE_EQ(spheres.front().centreBody.x, -3.0);
  EXPECT_DOUBLE_EQ(spheres.back().centreBody.x, 3.0);
  const geo::EnuFrame f = geo::enuFrame({10.0, 20.0, 0.0});
  auto run = [&](double dt, double* spin) {
    Simulation sim({.stepS = dt, .gravity = false, .parallel = false});
    BodyState a = stateAt({10.0, 20.0, 0.0}, {0.0, 3.0, 0.0});
    a.orientation = bodies::test::orientationAt({10.0, 20.0, 0.0});  // x east
    a.orientation = glm::normalize(glm::angleAxis(std::numbers::pi / 2, f.up) * a.orientation);  // x north
    BodyState b = a;
    b.velocityEcef = glm::dvec3(0.0);
    b.orientation = bodies::test::orientationAt({10.0, 20.0, 0.0});  // x east: A hits B's side
    b.positionEcef = f.originEcef + f.toEcef({1.2 + 1.0, 12.0, 0.0});
    const MassProperties m = hull.massProperties(500.0);
    const BodyId ia = sim.addBody(m, a), ib = sim.addBody(m, b);
    auto rep = std::make_shared<Repulsion>(sim, 1.0, 2e5);
    rep->setSpheres(ia, spheres);
    rep->setSpheres(ib, spheres);
    sim.addForceModel(rep);
    // Angular momentum about a fixed point (5 m west of A's start): orbital + spin.
    const glm::dvec3 O = a.positionEcef - 5.0 * f.east;
    auto L = [&] {
      glm::dvec3 sum(0.0);
      for (const Body& x : sim.bodies())
        sum += glm::cross(x.state.positionEcef - O, x.mass.massKg() * x.state.velocityEcef) +
               angularMomentumEcef(x.state, x.mass);
      return sum;
    };
    const glm::dvec3 L0 = L();
    sim.advanceTo(8.0);
    *spin = glm::length(sim.body(ib).state.angularVelocityBody);
    // They met and parted: every sphere pair is apart again.
    const glm::dvec3 d = sim.body(ib).state.positionEcef - sim.body(ia).state.positionEcef;
    EXPECT_GT(glm::length(d), 8.0);
    return glm::length(L() - L0) / glm::length(L0);
  };
  double spin1 = 0, spin2 = 0;
  const double e1 = run(1.0 / 240.0, &spin1), e2 = run(1.0 / 480.0, &spin2);
  // The collision turned B (it was not a miss or a central hit).
  EXPECT_GT(spin1, 0.05);
  EXPECT_GT(spin2, 0.05);
  // Each step's impulses cancel exactly about any point (equal, opposite,
  // on one line); the rest is the rotation integrator under the contact
  // torque and rounding: measured 5e-8 and 8e-8 of |L| (dt 1/240, 1/480).
  EXPECT_LT(e1, 1e-6) << e1;
  EXPECT_LT(e2, 1e-6) << e2;
}

TEST(BodyRepulsion, TheBroadphaseFindsEveryPairABruteForceSumFinds) {
  // 300 bodies of 1-3 spheres in a 150 m patch (dense: many pairs overlap),
  // one step's force on each against the O(n^2) sum over all sphere pairs.
  constexpr int n = 300;
  Simulation sim({.stepS = 1.0 / 60.0, .gravity = false, .parallel = false});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto rep = std::make_shared<Repulsion>(sim, 2.0, 1e4);
  const geo::EnuFrame f = geo::enuFrame({-33.0, 151.0, 0.0});
  std::vector<std::vector<RepulsionSphere>> sp(n);
  for (int i = 0; i < n; ++i) {
    BodyState s;
    s.positionEcef = f.originEcef + f.toEcef({150.0 * u(rng), 150.0 * u(rng), 4.0 * u(rng)});
    s.orientation = glm::normalize(glm::dquat(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    const BodyId id = sim.addBody(MassProperties::box(1000.0, {2.0, 2.0, 2.0}), s);
    if (i % 3) {
      for (int k = 0; k < 1 + i % 3; ++k) sp[i].push_back({glm::dvec3(6.0 * u(rng) - 3.0, 0.0, 0.0), 0.5 + 2.5 * u(rng)});
      rep->setSpheres(id, sp[i]);
    } else {
      sp[i] = {{glm::dvec3(0.0), 2.0}};  // the default sphere
    }
  }
  rep->beginStep(sim);
  int touching = 0;
  for (int i = 0; i < n; ++i) {
    const BodyState& si = sim.bodies()[i].state;
    glm::dvec3 F(0.0), T(0.0);
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      const BodyState& sj = sim.bodies()[j].state;
      for (const auto& s : sp[i])
        for (const auto& t : sp[j]) {
          const glm::dvec3 oi = si.bodyToEcef(s.centreBody), oj = sj.bodyToEcef(t.centreBody);
          const glm::dvec3 d = (sj.positionEcef - si.positionEcef) + (oj - oi);
          const double overlap = s.radiusM + t.radiusM - glm::length(d);
          if (overlap <= 0.0) continue;
          const glm::dvec3 fi = -1e4 * overlap * glm::normalize(d);
          F += fi;
          T += glm::cross(oi, fi);
        }
    }
    Wrench w;
    rep->accumulate(sim.bodies()[i], sim.context(si), w);
    if (glm::length(F) > 0.0) ++touching;
    EXPECT_LE(glm::length(w.force() - F), 1e-9 * (1.0 + glm::length(F))) << i;
    EXPECT_LE(glm::length(w.torque() - T), 1e-8 * (1.0 + glm::length(T))) << i;
  }
  EXPECT_GT(touching, 100) << "a dense patch: most bodies touch another";
}
