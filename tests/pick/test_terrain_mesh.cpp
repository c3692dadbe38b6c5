// globe/terrain: the mesh's vertices against PROJ's cs2cs (pixel centres
// written out here, not taken from GeoTransform), triangle counts worked
// out by hand, region meshes against the whole mesh, and the scene's
// double refinement.
#include "globe/geo/Ellipsoid.h"
#include "globe/terrain/TerrainMesh.h"
#include "globe/terrain/TerrainScene.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

using namespace geocean;
using terrain::TerrainMesh;

namespace {
// Height of pixel (i, j) of the rasters below: distinct, exact in float.
float heightOf(int i, int j) { return float(7 * (i % 50) - 40 * (j % 30)) + 0.25f; }

// Global, 1 degree: pixel (i, j) centre at lat 89.5 - j, lon -179.5 + i.
std::shared_ptr<const raster::Raster> globalRaster() {
  std::vector<float> px(360 * 180);
  for (int j = 0; j < 180; ++j)
    for (int i = 0; i < 360; ++i) px[std::size_t(j) * 360 + i] = heightOf(i, j);
  raster::GeoTransform gt;
  gt.global = true;
  return raster::Raster::fromPixels(std::move(px), 360, 180, 1, gt);
}

// Regional W x H, 0.5 x 0.25 degrees from lon 10, lat 50 (north up), with
// nodata at pixel (nanI, nanJ) unless negative.
std::shared_ptr<const raster::Raster> regionalRaster(int W, int H, int nanI = -1, int nanJ = -1) {
  std::vector<float> px(std::size_t(W) * H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) px[std::size_t(j) * W + i] = i == nanI && j == nanJ ? NAN : heightOf(i, j);
  raster::GeoTransform gt;
  gt.originLonDeg = 10.0, gt.originLatDeg = 50.0, gt.lonStepDeg = 0.5, gt.latStepDeg = -0.25;
  return raster::Raster::fromPixels(std::move(px), W, H, 1, gt);
}

using Triangle = std::array<double, 9>;
Triangle triangleAt(const TerrainMesh& m, std::size_t t) {
  Triangle out{};
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3& v = m.verticesEcef()[m.indices()[3 * t + k]];
    out[3 * k] = v.x, out[3 * k + 1] = v.y, out[3 * k + 2] = v.z;
  }
  return out;
}
}  // namespace

TEST(TerrainMesh, VerticesMatchProjCs2cs) {
  if (!test::haveTool("cs2cs")) GTEST_SKIP() << "cs2cs (Debian proj-bin) not installed";
  // A local origin on the far side of the Earth: large local vertices.
  const TerrainMesh m = TerrainMesh::whole(*globalRaster(), geo::toEcef({-35.0, 100.0, 0.0}));
  struct Probe {
    std::size_t vertex;
    double latDeg, lonDeg, heightM;
  };
  double northMean = 0.0;
  for (int i = 0; i < 360; ++i) northMean += heightOf(i, 0) / 360.0;
  const std::vector<Probe> probes = {
      {0, 89.5, -179.5, heightOf(0, 0)},                    // pixel (0, 0): corner, near the pole
      {90 * 360 + 359, -0.5, 179.5, heightOf(359, 90)},     // pixel (359, 90): antimeridian
      {45 * 360 + 200, 44.5, 20.5, heightOf(200, 45)},      // pixel (200, 45)
      {360 * 180, 90.0, 0.0, northMean},                    // the north fan's pole vertex
  };
  std::ostringstream in;
  in.precision(17);
  for (const Probe& p : probes) in << p.lonDeg << ' ' << p.latDeg << ' ' << p.heightM << '\n';
  const auto r = test::run("cs2cs -f %.6f +proj=longlat +datum=WGS84 +to +proj=geocent +datum=WGS84", in.str());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::istringstream out(r.out);
  for (const Probe& p : probes) {
    glm::dvec3 ref;
    ASSERT_TRUE(out >> ref.x >> ref.y >> ref.z);
    const glm::dvec3 ours = m.verticesEcef()[p.vertex];
    // The local vertex (what float consumers get) is the same point to rounding.
    EXPECT_NEAR(glm::length(m.originEcef() + m.localVertex(p.vertex) - ours), 0.0, 1e-8) << p.vertex;
    // cs2cs prints to 1 um and agrees with GeographicLib to 3 nm (PLATFORM.md).
    EXPECT_NEAR(ours.x, ref.x, 1e-5) << p.vertex;
    EXPECT_NEAR(ours.y, ref.y, 1e-5) << p.vertex;
    EXPECT_NEAR(ours.z, ref.z, 1e-5) << p.vertex;
  }
}

TEST(TerrainMesh, TriangleCounts) {
  // Global 360 x 180: two per cell with longitude wrap (360 x 179 cells) and
  // a 360-triangle fan at each pole.
  EXPECT_EQ(TerrainMesh::whole(*globalRaster(), glm::dvec3(0.0)).triangleCount(), 2u * 360 * 179 + 2 * 360);
  // Regional 8 x 6: 7 x 5 cells, no wrap, no fans.
  EXPECT_EQ(TerrainMesh::whole(*regionalRaster(8, 6), glm::dvec3(0.0)).triangleCount(), 2u * 7 * 5);
  // Nodata at interior vertex (3, 2): it is corner a of cell (3, 2) and d
  // of cell (2, 1) (both triangles), b of (2, 2) and c of (3, 1) (one each).
  EXPECT_EQ(TerrainMesh::whole(*regionalRaster(8, 6, 3, 2), glm::dvec3(0.0)).triangleCount(), 2u * 7 * 5 - 6);
  // A region: cells (0, 0), (3, 2), (6, 4) of the 7-column cell grid.
  terrain::CellRegion sel;
  sel.cells = {0, 2 * 7 + 3, 4 * 7 + 6};
  const TerrainMesh reg = TerrainMesh::region(*regionalRaster(8, 6, 3, 2), sel, glm::dvec3(0.0));
  EXPECT_EQ(reg.triangleCount(), 2u + 0 + 2);  // cell (3, 2) has the nodata corner a
  EXPECT_EQ(reg.verticesEcef().size(), 12u);       // four corners per cell, none shared
  // Global: one cell and the south fan.
  terrain::CellRegion polar;
  polar.cells = {178 * 360 + 359};  // last row, across the antimeridian
  polar.fan[1] = true;
  EXPECT_EQ(TerrainMesh::region(*globalRaster(), polar, glm::dvec3(0.0)).triangleCount(), 2u + 360);
}

// A region mesh is made of the whole mesh's triangles, bit for bit.
TEST(TerrainMesh, RegionTrianglesAreWholeMeshTriangles) {
  const auto r = globalRaster();
  const glm::dvec3 origin = geo::toEcef({10.0, 20.0, 0.0});
  const TerrainMesh whole = TerrainMesh::whole(*r, origin);
  std::map<Triangle, int> all;
  for (std::size_t t = 0; t < whole.triangleCount(); ++t) ++all[triangleAt(whole, t)];
  // Down onto the antimeridian near the north pole, and a level ray over Africa.
  const geo::EnuFrame f = geo::enuFrame({5.0, 20.0, 500.0});
  const std::vector<terrain::Ray> rays = {{geo::toEcef({88.7, 179.8, 2e5}), -geo::surfaceNormal(88.7, 179.8)},
                                          {f.originEcef, f.east + 0.2 * f.north}};
  const auto sel = terrain::cellsAlong(*r, rays);
  ASSERT_TRUE(sel.has_value());
  // The first ray comes within a cell of the north pole row, and again
  // where it leaves the shell near the south pole (the selection holds both
  // spans of a ray through the Earth, not only up to its first hit).
  EXPECT_TRUE(sel->fan[0]);
  EXPECT_TRUE(sel->fan[1]);
  const TerrainMesh reg = TerrainMesh::region(*r, *sel, origin);
  EXPECT_GT(reg.triangleCount(), 360u);
  EXPECT_LT(reg.triangleCount(), whole.triangleCount() / 10);
  for (std::size_t t = 0; t < reg.triangleCount(); ++t) EXPECT_EQ(all.count(triangleAt(reg, t)), 1u) << t;
}

TEST(TerrainScene, HitsAreRefinedInDouble) {
  const auto r = globalRaster();
  auto device = std::make_shared<const terrain::EmbreeDevice>();
  // Origin 9000 km away: float alone would be off by about a metre.
  const terrain::TerrainScene scene(device, std::make_shared<const TerrainMesh>(
                                                TerrainMesh::whole(*r, geo::toEcef({-40.0, -60.0, 0.0}))));
  // Straight down onto the vertex of pixel (200, 45) from 1000 m above it.
  const double h = heightOf(200, 45);
  const glm::dvec3 n = geo::surfaceNormal(44.5, 20.5);
  const glm::dvec3 v = geo::toEcef({44.5, 20.5, h});
  const terrain::TerrainHit hit = scene.intersect(v + 1000.0 * n, -n, 0.0, 1e7);
  ASSERT_TRUE(hit.hit);
  // The vertex lies on all its triangles: only rounding of the double
  // ray/plane test remains (~1e-9 m at these magnitudes).
  EXPECT_NEAR(hit.distanceM, 1000.0, 1e-6);
  EXPECT_EQ(scene.refine(hit.triangle, v + 1000.0 * n, -n), hit.distanceM);
  // Upwards from there, and within a range that stops short of the ground: nothing.
  EXPECT_FALSE(scene.intersect(v + 1000.0 * n, n, 0.0, 1e7).hit);
  EXPECT_FALSE(scene.intersect(v + 1000.0 * n, -n, 0.0, 990.0).hit);
}
