// A boat driven at a beach stops at the shore with zero penetration (issue
// 14 item 6): a synthetic beach in an elevation raster given to the ocean
// façade (sea to the west, the ground rising 1 in 10 to the east, the
// waterline at longitude 0), the terrain patch built from that layer stack
// (terrainPatch), the hull floating on the façade's sea (flat without a
// sea state: ocean where the relief is below 0) and pushed east by its
// engine, TerrainContact on every hull vertex.
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/Raster.h"
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Spawn.h"
#include "plugin/bodies/Terrain.h"
#include "plugin/ocean/Ocean.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace geocean::bodies {
namespace {

constexpr double kMPerDegLon = 111319.49;  // WGS84 equator: a * pi / 180

// Drives `hull` (density kg/m^3, engine N) east at the beach from 150 m
// out for 160 s and checks it stops at the shore with no vertex below the
// ground. The keel meets the 1-in-10 slope `draft` below the waterline,
// i.e. 10 x draft west of it.
// atRest: it must also end at rest, grounded (a hull that keeps its heading).
void driveAtTheBeach(const HullMesh& hullMesh, double density, double thrustN, bool atRest) {
  // 2e-5 degree cells (2.2 m) over 0.02 x 0.01 degrees around (0, 0).
  const int w = 1000, h = 500;
  const double step = 2e-5;
  std::vector<float> px(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double east = (-0.01 + (x + 0.5) * step) * kMPerDegLon;
      px[std::size_t(y) * w + x] = float(std::clamp(east / 10.0, -20.0, 10.0));
    }
  raster::GeoTransform t;
  t.originLonDeg = -0.01, t.originLatDeg = 0.005, t.lonStepDeg = step, t.latStepDeg = -step;
  ocean::Ocean oc;
  oc.setElevation(raster::Raster::fromPixels(std::move(px), w, h, 1, t, std::nullopt, "beach"));
  const auto snap = oc.current();
  auto sea = std::make_shared<OceanSea>(snap);

  // 400 m x 400 m of it, 2 m cells, from 333 m west of the waterline.
  const geo::Geodetic sw{-0.002, -0.003, 0.0};
  auto patch = terrainPatch(*snap, sw, 201, 2.0);
  // The patch is the layer's relief: 1 in 10 through the waterline.
  const double x0 = -0.003 * kMPerDegLon;  // the patch's west edge, east of lon 0 (m)
  EXPECT_NEAR(patch->heightAt(-x0 - 50.0, 200.0), -5.0, 0.05);
  EXPECT_NEAR(patch->heightAt(-x0 + 30.0, 200.0), 3.0, 0.05);

  auto hull = std::make_shared<const HullMesh>(hullMesh);
  Simulation sim({.stepS = 1.0 / 60});
  const double startLon = -150.0 / kMPerDegLon;
  const BodyState start = restingUpright(*hull, density / 1025.0, 0.0, startLon, 90.0);
  double draft = 0.0;  // keel below the still water at rest
  for (const auto& v : hull->vertices()) draft = std::max(draft, -geo::fromEcef(start.positionEcef + start.bodyToEcef(v)).heightM);
  const double halfLength = 0.5 * (hull->maxCorner().x - hull->minCorner().x);
  const auto id = sim.addBody(hull->massProperties(density), start);
  sim.addBodyForce(id, std::make_shared<HullForce>(hull, sea));
  sim.addBodyForce(id, std::make_shared<Thrust>(thrustN));
  // Wet sand on the hull: mu 0.5 (TerrainContact's note); without friction it slides along the beach.
  sim.addBodyConstraint(id, std::make_shared<TerrainContact>(patch, hull->vertices(), 0.5));

  double worstDepth = 0.0, maxSpeed = 0.0;
  double eastAt130 = 0.0, maxEast = -1e9;  // east of the waterline (m)
  for (int k = 1; k <= 160 * 60; ++k) {
    sim.step();
    const BodyState& s = sim.body(id).state;
    for (const auto& v : hull->vertices()) {
      const glm::dvec3 p = patch->toPatch(s.positionEcef + s.bodyToEcef(v));
      worstDepth = std::max(worstDepth, patch->heightAt(p.x, p.y) - p.z);
    }
    maxSpeed = std::max(maxSpeed, glm::length(s.velocityEcef));
    if (k == 130 * 60) eastAt130 = patch->toPatch(s.positionEcef).x;
    maxEast = std::max(maxEast, patch->toPatch(s.positionEcef).x + x0);
  }
  const BodyState& s = sim.body(id).state;
  const glm::dvec3 c = patch->toPatch(s.positionEcef);
  double clearance = 1e9;  // lowest hull point above the ground at the end
  for (const auto& v : hull->vertices()) {
    const glm::dvec3 p = patch->toPatch(s.positionEcef + s.bodyToEcef(v));
    clearance = std::min(clearance, p.z - patch->heightAt(p.x, p.y));
  }
  // Zero penetration: no hull vertex below the patch after any step (the
  // contact's lift leaves it on the surface to rounding: 1e-9 m).
  EXPECT_LE(worstDepth, 1e-9);
  EXPECT_GT(maxSpeed, 1.0) << "it was under way";
  // The shore stops it: its centre never gets past the waterline by more
  // than half a length, and it got there (to the draft's depth line, where
  // the keel meets the slope).
  const double centreEastOfWaterline = c.x + x0;
  EXPECT_LT(maxEast, halfLength);
  EXPECT_GT(maxEast, -10.0 * draft - halfLength) << "it reached the shore";
  if (atRest) {
    // At rest on the ground (touching it), the last 30 s moved under 0.5 m,
    // between the draft's depth line and the waterline plus half a length.
    EXPECT_LT(glm::length(s.velocityEcef), 0.05);
    EXPECT_LT(std::abs(c.x - eastAt130), 0.5);
    EXPECT_LT(clearance, 0.01);
    EXPECT_GT(centreEastOfWaterline, -10.0 * draft - halfLength);
    EXPECT_LT(centreEastOfWaterline, halfLength);
  }
  std::printf("draft %.2f m, half length %.1f m: its centre reached %.1f m and ended %.1f m east of the waterline\n", draft,
              halfLength, maxEast, centreEastOfWaterline);
  ::testing::Test::RecordProperty("centre_east_of_waterline_m", std::to_string(centreEastOfWaterline));
}

// An 8 x 3 x 2 m box of density 500 (draft 1 m), a 3 kN engine: it reaches
// about 2 m/s and grounds where the water is 1 m deep, 10 m before the waterline.
TEST(BodyBeach, ABoatDrivenAtABeachStopsAtTheShoreWithZeroPenetration) {
  driveAtTheBeach(HullMesh::box({8.0, 3.0, 2.0}), 500.0, 3000.0, true);
}

// The same with the boat hull (12 m, its stem and transom; the viewer's
// boats are these), density 450 and an engine of 0.4 L^3 N as the viewer's.
// A bare hull (no keel or rudder, plugin/bodies/README) is directionally
// unstable: measured, it turns to run along the beach as it arrives and
// motors on there at 1 m/s, so it is held to no penetration and to the
// shore stopping its way east, not to rest.
TEST(BodyBeach, ABoatHullDrivenAtABeachStopsAtTheShoreWithZeroPenetration) {
  driveAtTheBeach(HullMesh::boat(12.0), 450.0, 0.4 * 12.0 * 12.0 * 12.0, false);
}

}  // namespace
}  // namespace geocean::bodies
