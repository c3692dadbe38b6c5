// Embree picking with double refinement, against truths outside the picker:
// the long-double closed form for the ellipsoid, GeographicLib positions of
// terrain vertices, and a classifier written here.
#include "globe/geo/Ellipsoid.h"
#include "plugin/pick/Picker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace geocean;
using pick::PickRay;
using pick::Picker;

namespace {
// First root t >= 0 of the ray with WGS84 in long double (64-bit mantissa).
bool referenceFirst(glm::dvec3 o, glm::dvec3 d, long double& t) {
  const long double a = geo::kWgs84A, b = (long double)geo::kWgs84A * (1.0L - 1.0L / 298.257223563L);
  const long double ox = o.x / a, oy = o.y / a, oz = o.z / b, dx = d.x / a, dy = d.y / a, dz = d.z / b;
  const long double A = dx * dx + dy * dy + dz * dz, B = ox * dx + oy * dy + oz * dz,
                    C = ox * ox + oy * oy + oz * oz - 1.0L, disc = B * B - A * C;
  if (disc < 0) return false;
  const long double t1 = (-B - std::sqrt(disc)) / A, t2 = (-B + std::sqrt(disc)) / A;
  if (t2 < 0) return false;
  t = t1 >= 0 ? t1 : t2;
  return true;
}

// Global 1-degree terrain: a 5000 m plateau at lat 5..15, lon 15..25; a
// -10 m polder at lat -5..5, lon 40..50; ocean floor at -4000 m elsewhere.
std::shared_ptr<const raster::Raster> syntheticTerrain() {
  std::vector<float> px(360 * 180);
  for (int j = 0; j < 180; ++j)
    for (int i = 0; i < 360; ++i) {
      const double lat = 89.5 - j, lon = -179.5 + i;
      float e = -4000.0f;
      if (lat > 5 && lat < 15 && lon > 15 && lon < 25) e = 5000.0f;
      if (lat > -5 && lat < 5 && lon > 40 && lon < 50) e = -10.0f;
      px[std::size_t(j) * 360 + i] = e;
    }
  raster::GeoTransform gt;
  gt.global = true;
  return raster::Raster::fromPixels(std::move(px), 360, 180, 1, gt);
}

// Land on the plateau and the polder, a lake at lat -30..-20 lon 100..110.
void classify(const double* lat, const double* lon, std::size_t n, ocean::Surface* out) {
  for (std::size_t i = 0; i < n; ++i) {
    const bool plateau = lat[i] > 4.5 && lat[i] < 15.5 && lon[i] > 14.5 && lon[i] < 25.5;
    const bool polder = lat[i] > -5.5 && lat[i] < 5.5 && lon[i] > 39.5 && lon[i] < 50.5;
    const bool lake = lat[i] > -30 && lat[i] < -20 && lon[i] > 100 && lon[i] < 110;
    out[i] = plateau || polder ? ocean::Surface::Land : lake ? ocean::Surface::Lake : ocean::Surface::Ocean;
  }
}
}  // namespace

TEST(Picker, OneMetreAboveTheSeaHitsAtOneMetre) {
  for (double lat : {0.0, 45.0, 89.99, -60.0}) {
    for (double lon : {0.0, 180.0, -179.9999, 33.3}) {
      const glm::dvec3 o = geo::toEcef({lat, lon, 1.0});
      const Picker p(nullptr, {}, o);
      const pick::PickResult r = p.pick({o, -geo::surfaceNormal(lat, lon)});
      ASSERT_TRUE(r.hit);
      EXPECT_EQ(r.kind, pick::HitKind::Sea);
      EXPECT_NEAR(r.distanceM, 1.0, 1e-6);  // GeographicLib Forward, nm
      EXPECT_NEAR(r.heightM, 0.0, 1e-6);
      EXPECT_NEAR(r.latDeg, lat, 1e-9);
    }
  }
}

// Issue 4 item 7: within 1 mm for every ray, grazing and from inside the
// ellipsoid included, whatever the scene's local origin.
TEST(Picker, SeaHitsWithin1mmOfLongDouble) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), logAlt(-1, 7.3);
  const Picker p(nullptr, {}, geo::toEcef({10, 10, 100}));
  std::vector<PickRay> rays;
  for (int i = 0; i < 4000; ++i) {
    const double alt = std::pow(10.0, logAlt(rng)) * (i % 7 == 0 ? -1.0 : 1.0);
    const glm::dvec3 o = geo::toEcef({90 * u(rng), 180 * u(rng), alt});
    rays.push_back({o, glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) - 0.8 * glm::normalize(o))});
  }
  // Grazing: tangent to the surface at a point, from 3000 km back along the tangent.
  for (double lat : {0.0, 30.0, 60.0, 85.0}) {
    for (double depth : {0.01, 1.0, 100.0}) {
      const geo::EnuFrame f = geo::enuFrame({lat, 20.0, -depth});
      rays.push_back({f.originEcef - f.north * 3e6, f.north});
    }
  }
  std::vector<pick::PickResult> res(rays.size());
  p.pickBatch(rays.data(), rays.size(), res.data());
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    long double t;
    const glm::dvec3 d = glm::normalize(rays[i].dir);
    const bool ref = referenceFirst(rays[i].originEcef, d, t);
    ASSERT_EQ(res[i].hit, ref) << i;
    if (!ref) continue;
    ++hits;
    EXPECT_NEAR(res[i].distanceM, double(t), 1e-3) << i;
    EXPECT_NEAR(res[i].heightM, 0.0, 1e-3) << i;
  }
  EXPECT_GT(hits, 1500);
}

TEST(Picker, TerrainIsHitBeforeTheSeaAndRefinedInDouble) {
  const auto terrain = syntheticTerrain();
  // Local origin on the other side of the Earth: float alone would be off
  // by metres here; the double refinement must not be.
  const Picker p(terrain, classify, geo::toEcef({-10, -160, 0}));
  EXPECT_GT(p.terrainTriangles(), 2 * 359 * 179u);
  // Straight down onto a plateau vertex (pixel centre lat 10.5, lon 20.5).
  const glm::dvec3 v = geo::toEcef({10.5, 20.5, 5000.0});
  const pick::PickResult r = p.pick({v + 1000.0 * geo::surfaceNormal(10.5, 20.5), -geo::surfaceNormal(10.5, 20.5)});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.kind, pick::HitKind::Terrain);
  EXPECT_EQ(r.surface, ocean::Surface::Land);
  EXPECT_NEAR(r.distanceM, 1000.0, 1e-6);  // the vertex lies on its triangles exactly
  EXPECT_NEAR(r.heightM, 5000.0, 1e-6);
  // Over the ocean the terrain is 4 km down: the sea is hit first, at 0 m.
  const glm::dvec3 o = geo::toEcef({-40.0, -30.0, 20.0});
  const pick::PickResult s = p.pick({o, -geo::surfaceNormal(-40.0, -30.0)});
  ASSERT_TRUE(s.hit);
  EXPECT_EQ(s.kind, pick::HitKind::Sea);
  EXPECT_EQ(s.surface, ocean::Surface::Ocean);
  EXPECT_NEAR(s.distanceM, 20.0, 1e-6);
  // A polder 10 m below the ellipsoid, classified land: the ray goes through
  // the (absent) sea surface and stops on the terrain.
  const glm::dvec3 q = geo::toEcef({0.5, 44.5, 100.0});
  const pick::PickResult t = p.pick({q, -geo::surfaceNormal(0.5, 44.5)});
  ASSERT_TRUE(t.hit);
  EXPECT_EQ(t.kind, pick::HitKind::Terrain);
  EXPECT_NEAR(t.heightM, -10.0, 1e-6);
  EXPECT_NEAR(t.distanceM, 110.0, 1e-6);
  // Terrain over a lake reports the lake.
  const glm::dvec3 l = geo::toEcef({-25.5, 105.5, 100.0});
  const pick::PickResult lr = p.pick({l, -geo::surfaceNormal(-25.5, 105.5)});
  ASSERT_TRUE(lr.hit);
  EXPECT_EQ(lr.kind, pick::HitKind::Terrain);
  EXPECT_EQ(lr.surface, ocean::Surface::Lake);
  EXPECT_NEAR(lr.heightM, -4000.0, 1e-6);
}

TEST(Picker, SideOnRayHitsTheCliffNotTheSeaBehindIt) {
  const auto terrain = syntheticTerrain();
  const Picker p(terrain, classify, geo::toEcef({10, 0, 0}));
  // Level ray eastwards at 3000 m over the sea at lon 14.9: the slope
  // between the -4000 m vertex at lon 14.5 and the 5000 m vertex at lon
  // 15.5 reaches the ray near lon 15.3 (the flat triangles sag below the
  // lon/lat interpolation by up to ~240 m in a 1-degree cell).
  const geo::EnuFrame f = geo::enuFrame({10.5, 14.9, 3000.0});
  const pick::PickResult r = p.pick({f.originEcef, f.east});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.kind, pick::HitKind::Terrain);
  EXPECT_GT(r.lonDeg, 15.2);
  EXPECT_LT(r.lonDeg, 15.4);
  // A level ray rises by s^2 / (2 N) over the ellipsoid (N ~ 6.378e6 m, the
  // prime-vertical radius here); 2 m covers the variation of N along the ray.
  EXPECT_NEAR(r.heightM, 3000.0 + r.distanceM * r.distanceM / (2.0 * 6.378e6), 2.0);
}

TEST(Picker, BatchMatchesSingleAndRejectsBadRays) {
  const auto terrain = syntheticTerrain();
  const Picker p(terrain, classify, geo::toEcef({0, 0, 0}));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PickRay> rays;
  for (int i = 0; i < 100; ++i) {
    const glm::dvec3 o = geo::toEcef({20 * u(rng) + 10, 20 * u(rng) + 20, 1e4});
    rays.push_back({o, glm::dvec3(u(rng), u(rng), u(rng)) * 0.3 - glm::normalize(o)});
  }
  rays.push_back({glm::dvec3(7e6, 0, 0), glm::dvec3(0.0)});
  rays.push_back({glm::dvec3(NAN, 0, 0), glm::dvec3(1, 0, 0)});
  std::vector<pick::PickResult> res(rays.size());
  p.pickBatch(rays.data(), rays.size(), res.data());
  for (std::size_t i = 0; i < 100; ++i) {
    const pick::PickResult s = p.pick(rays[i]);
    EXPECT_EQ(s.hit, res[i].hit);
    EXPECT_EQ(s.distanceM, res[i].distanceM);
  }
  EXPECT_FALSE(res[100].hit);
  EXPECT_FALSE(res[101].hit);
}

// The CLI's one-ray scene (terrain cells along the ray only) gives the
// whole-mesh answers: random rays over the plateau, level rays side-on at
// every height band, rays from below the sea surface down to the -4000 m
// floor near the poles (polar fans) and across the antimeridian.
TEST(Picker, TerrainAlongTheRayOnlyGivesTheWholeMeshAnswers) {
  const auto terrain = syntheticTerrain();
  const glm::dvec3 origin = geo::toEcef({10, 20, 0});
  const Picker whole(terrain, classify, origin);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  std::vector<PickRay> rays;
  for (int i = 0; i < 60; ++i) {  // onto and around the plateau, from 10 m to 20,000 km
    const glm::dvec3 target = geo::toEcef({10 + 8 * u(rng), 20 + 8 * u(rng), 0.0});
    const glm::dvec3 o = geo::toEcef({10 + 30 * u(rng), 20 + 30 * u(rng), std::pow(10.0, 1 + 6.3 * u01(rng))});
    rays.push_back({o, target - o});
  }
  for (int i = 0; i < 40; ++i) {  // level (grazing) rays at 0..6000 m in any direction
    const geo::EnuFrame f = geo::enuFrame({10 + 6 * u(rng), 20 + 6 * u(rng), 6000 * u01(rng)});
    const double az = 3.14159265 * u(rng);
    rays.push_back({f.originEcef, std::cos(az) * f.east + std::sin(az) * f.north});
  }
  for (int i = 0; i < 40; ++i) {  // from under the sea surface, near the poles and lon 180
    const double lat = (i % 2 ? 1 : -1) * (89.0 + 0.99 * u01(rng)), lon = i % 4 < 2 ? 180.0 * u(rng) : 179.9 + 0.2 * u01(rng);
    const geo::EnuFrame f = geo::enuFrame({i % 3 ? lat : 0.3 * lat, lon, -3000.0 * u01(rng)});
    rays.push_back({f.originEcef, -f.up + u(rng) * f.east + u(rng) * f.north});
  }
  std::vector<pick::PickResult> want(rays.size());
  whole.pickBatch(rays.data(), rays.size(), want.data());
  int terrainHits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Picker one(terrain, classify, rays[i].originEcef, std::vector<PickRay>{rays[i]});
    EXPECT_LT(one.terrainTriangles(), whole.terrainTriangles() / 10) << i;
    const pick::PickResult r = one.pick(rays[i]);
    ASSERT_EQ(r.hit, want[i].hit) << i;
    EXPECT_EQ(r.kind, want[i].kind) << i;
    EXPECT_EQ(r.surface, want[i].surface) << i;
    // Same double triangles; Embree may report the neighbour across an
    // edge, whose plane meets the ray at the same point to rounding.
    EXPECT_NEAR(r.distanceM, want[i].distanceM, 1e-6 * (1.0 + want[i].distanceM)) << i;
    terrainHits += want[i].kind == pick::HitKind::Terrain;
  }
  EXPECT_GT(terrainHits, 60);  // the test exercises the terrain, not only the sea
  // Several rays in one scene.
  const Picker some(terrain, classify, origin, rays);
  std::vector<pick::PickResult> got(rays.size());
  some.pickBatch(rays.data(), rays.size(), got.data());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(got[i].hit, want[i].hit) << i;
    EXPECT_EQ(got[i].kind, want[i].kind) << i;
    EXPECT_NEAR(got[i].distanceM, want[i].distanceM, 1e-6 * (1.0 + want[i].distanceM)) << i;
  }
}

// A regional raster (no longitude wrap, no polar fans) across lon 180: the
// one-ray scene still gives the whole-mesh answers.
TEST(Picker, TerrainAlongTheRayOnlyOnARegionalRaster) {
  // 0.25-degree cells over lat 30..50 (north up), lon 170..190 (past 180).
  const int W = 80, H = 80;
  std::vector<float> px(std::size_t(W) * H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const double lat = 50.0 - 0.25 * (j + 0.5), lon = 170.0 + 0.25 * (i + 0.5);
      px[std::size_t(j) * W + i] = float(3000.0 * std::sin(lat * 0.7) * std::cos(lon * 0.9) - 500.0);
    }
  raster::GeoTransform gt;
  gt.originLonDeg = 170.0, gt.originLatDeg = 50.0, gt.lonStepDeg = 0.25, gt.latStepDeg = -0.25;
  const auto terrain = raster::Raster::fromPixels(std::move(px), W, H, 1, gt);
  const auto land = [](const double*, const double*, std::size_t n, ocean::Surface* out) {
    std::fill(out, out + n, ocean::Surface::Land);  // no sea: every hit is terrain
  };
  const Picker whole(terrain, land, geo::toEcef({40, 180, 0}));
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  std::vector<PickRay> rays;
  for (int i = 0; i < 60; ++i) {
    const double lon = 180.0 + 9.0 * u(rng), lat = 40.0 + 9.0 * u(rng);
    const geo::EnuFrame f = geo::enuFrame({lat, lon, i % 2 ? 4000.0 * u01(rng) : std::pow(10.0, 3.5 + 2.5 * u01(rng))});
    const double az = 3.14159265 * u(rng), down = i % 2 ? 0.05 * u01(rng) : 0.3 + u01(rng);
    rays.push_back({f.originEcef, std::cos(az) * f.east + std::sin(az) * f.north - down * f.up});
  }
  std::vector<pick::PickResult> want(rays.size());
  whole.pickBatch(rays.data(), rays.size(), want.data());
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Picker one(terrain, land, rays[i].originEcef, std::vector<PickRay>{rays[i]});
    EXPECT_LT(one.terrainTriangles(), whole.terrainTriangles() / 4) << i;
    const pick::PickResult r = one.pick(rays[i]);
    ASSERT_EQ(r.hit, want[i].hit) << i;
    EXPECT_EQ(r.kind, want[i].kind) << i;
    EXPECT_NEAR(r.distanceM, want[i].distanceM, 1e-6 * (1.0 + want[i].distanceM)) << i;
    hits += want[i].hit;
  }
  EXPECT_GT(hits, 30);
}
