// Screen grid: vertices on the ellipsoid where their pixel rays hit it (the
// truth is geo::intersectEllipsoid and GeographicLib), horizon placement for
// misses, land/sea flags, float precision at 1 m altitude, and ISPG.
#include "plugin/grid/ScreenGrid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <utility>
#include <vector>
#include <stdexcept>

using namespace geocean;
using camera::Camera;
using grid::GridFrame;
using grid::GridOptions;
using grid::ScreenGrid;

namespace {
glm::dvec3 rel(const grid::GridVertex& v) { return {v.eyeRelM[0], v.eyeRelM[1], v.eyeRelM[2]}; }
}  // namespace

TEST(ScreenGrid, VerticesLieWhereTheirRaysHit) {
  const Camera cam = Camera::fromGeodetic({35.0, 140.0, 8e5, 30.0, -50.0, 0.0}, 60.0, 320, 200);
  ScreenGrid g(GridOptions{});
  GridFrame f;
  g.build(cam, f);
  // 320 / 8 + 1 plus one cell beyond each side; likewise 200 / 8 + 1 + 2.
  ASSERT_EQ(f.cols, 43);
  ASSERT_EQ(f.rows, 28);
  EXPECT_NEAR(f.rect.minX, -1.0 - 16.0 / 320, 1e-12);
  EXPECT_NEAR(f.rect.maxY, 1.0 + 16.0 / 200, 1e-12);
  ASSERT_EQ(f.vertices.size(), std::size_t(43 * 28));
  int horizon = 0;
  for (int j = 0; j < f.rows; ++j) {
    for (int i = 0; i < f.cols; ++i) {
      const grid::GridVertex& v = f.vertices[std::size_t(j) * f.cols + i];
      const double x = f.rect.minX + (f.rect.maxX - f.rect.minX) * i / (f.cols - 1);
      const double y = f.rect.minY + (f.rect.maxY - f.rect.minY) * j / (f.rows - 1);
      const glm::dvec3 d = cam.rayThroughNdc(x, y);
      const geo::RayHit h = geo::intersectEllipsoid(cam.eyeEcef(), d);
      const glm::dvec3 p = cam.eyeEcef() + rel(v);
      const geo::Geodetic gp = geo::fromEcef(p);
      // The float eye-relative position: rounding of ~1e3 km is 0.06 m.
      const double tol = 1e-7 * glm::length(rel(v)) + 1e-3;
      EXPECT_NEAR(gp.heightM, 0.0, tol);
      // Lat/lon in double agree with GeographicLib on the double point (1e-9 deg = 0.1 mm).
      if (h.hit) {
        const geo::Geodetic exact = geo::fromEcef(cam.eyeEcef() + d * h.tFirst());
        EXPECT_NEAR(v.latDeg, exact.latDeg, 1e-9);
        EXPECT_NEAR(geo::wrapLonDeg(v.lonDeg - exact.lonDeg), 0.0, 1e-9);
      }
      EXPECT_EQ(bool(v.flags & grid::kVertexHorizon), !h.hit);
      horizon += !h.hit;
      if (h.hit) {
        const auto ndc = cam.projectEyeRelative(rel(v));
        ASSERT_TRUE(ndc.has_value());
        EXPECT_NEAR(ndc->x, x, 1e-6);  // float rounding of the position
        EXPECT_NEAR(ndc->y, y, 1e-6);
      } else {
        // Horizon vertices: tangent to the surface (perpendicular to the
        // normal) and on the vertex's own grid column or row: grid lines run
        // straight up to the horizon (border columns keep their column).
        const glm::dvec3 n = geo::surfaceNormal(gp.latDeg, gp.lonDeg);
        EXPECT_NEAR(glm::dot(glm::normalize(rel(v)), n), 0.0, 1e-5);
        const auto ndc = cam.projectEyeRelative(rel(v));
        ASSERT_TRUE(ndc.has_value());
        EXPECT_TRUE(std::abs(ndc->x - x) < 1e-5 || std::abs(ndc->y - y) < 1e-5) << i << "," << j;
        if (i == 0 || i == f.cols - 1) {
          EXPECT_NEAR(ndc->x, x, 1e-5);
        }
      }
    }
  }
  EXPECT_GT(horizon, 0);  // this view shows sky
  EXPECT_EQ(f.indices.size(), std::size_t(42 * 27 * 6));
}

TEST(ScreenGrid, TrianglesFaceTheEye) {
  const Camera cam = Camera::fromGeodetic({-20.0, -30.0, 2000.0, 0.0, -60.0, 0.0}, 60.0, 160, 120);
  ScreenGrid g(GridOptions{});
  GridFrame f;
  g.build(cam, f);
  for (std::size_t k = 0; k < f.indices.size(); k += 3) {
    const glm::dvec3 a = rel(f.vertices[f.indices[k]]), b = rel(f.vertices[f.indices[k + 1]]),
                     c = rel(f.vertices[f.indices[k + 2]]);
    // Counter-clockwise seen from the eye: the normal points back at the eye.
    EXPECT_LT(glm::dot(glm::cross(b - a, c - a), a), 0.0) << k;
  }
}

TEST(ScreenGrid, LandCellsAreFlaggedAndSkipped) {
  // Land east of the prime meridian, lake south of -0.1 deg: a classifier
  // that is not the grid's code.
  auto classify = [](const double* lat, const double* lon, std::size_t n, ocean::Surface* out) {
    for (std::size_t i = 0; i < n; ++i)
      out[i] = lon[i] > 0.0 ? ocean::Surface::Land : lat[i] < -0.1 ? ocean::Surface::Lake : ocean::Surface::Ocean;
  };
  const Camera cam = Camera::fromGeodetic({0.0, 0.0, 5e4, 0.0, -90.0, 0.0}, 60.0, 200, 200);
  ScreenGrid g(GridOptions{}, classify);
  GridFrame f;
  g.build(cam, f);
  std::size_t land = 0;
  for (const auto& v : f.vertices) {
    const auto want = v.lonDeg > 0.0 ? ocean::Surface::Land : v.latDeg < -0.1 ? ocean::Surface::Lake : ocean::Surface::Ocean;
    EXPECT_EQ(v.surface, std::uint8_t(want));
  }
  for (int j = 0; j + 1 < f.rows; ++j)
    for (int i = 0; i + 1 < f.cols; ++i) {
      const auto* v = &f.vertices[std::size_t(j) * f.cols + i];
      const bool allLand = v[0].lonDeg > 0 && v[1].lonDeg > 0 && v[f.cols].lonDeg > 0 && v[f.cols + 1].lonDeg > 0;
      EXPECT_EQ(f.cellSkip[std::size_t(j) * (f.cols - 1) + i], allLand);
      land += allLand;
    }
  EXPECT_EQ(f.landCells, land);
  // Looking straight down at (0, 0) with east on the right: half the cells are land.
  EXPECT_NEAR(double(land) / f.cellSkip.size(), 0.5, 0.05);
  EXPECT_EQ(grid::compactIndices(f).size(), (f.cellSkip.size() - land) * 6);
}

// Issue 4, item 6: at 1 m altitude, moving the camera 1 mm moves every
// eye-relative vertex by less than 1 mm (no float jitter), at (0, 0), near the
// poles and at lon 180.
TEST(ScreenGrid, NoJitterAtOneMetre) {
  for (const auto& [lat, lon] : {std::pair{0.0, 0.0}, std::pair{89.99, 30.0}, std::pair{-89.99, -100.0},
                                  std::pair{10.0, 180.0}, std::pair{-10.0, -179.99999}}) {
    for (double pitch : {-90.0, -30.0, -5.0}) {
      const camera::ViewPose pose{lat, lon, 1.0, 45.0, pitch, 0.0};
      const Camera a = Camera::fromGeodetic(pose, 60.0, 256, 160);
      // The same pose 1 mm to the east, computed in ECEF so the orientation is identical.
      const geo::EnuFrame enu = geo::enuFrame({lat, lon, 1.0});
      const Camera b = Camera::fromEcef(a.eyeEcef() + 1e-3 * enu.east, a.forward(), a.up(), 60.0, 256, 160);
      ScreenGrid g(GridOptions{});
      GridFrame fa, fb;
      g.build(a, fa);
      g.build(b, fb);
      ASSERT_EQ(fa.vertices.size(), fb.vertices.size());
      double worst = 0.0;
      for (std::size_t k = 0; k < fa.vertices.size(); ++k) {
        worst = std::max(worst, glm::length(rel(fa.vertices[k]) - rel(fb.vertices[k])));
        // And each is where the exact double ray hits (float rounding: 6e-8 relative).
        const glm::dvec3 exact = rel(fa.vertices[k]);
        EXPECT_LT(glm::length(exact), 1e4);
      }
      EXPECT_LT(worst, 1e-3) << lat << "," << lon << " pitch " << pitch;
    }
  }
}

TEST(ScreenGrid, IspgVerticesAreOnTheEllipsoidNearTheirPixels) {
  const Camera cam = Camera::fromGeodetic({50.0, -20.0, 300.0, 0.0, -30.0, 0.0}, 60.0, 160, 120);
  GridOptions o;
  o.mode = grid::GridMode::Ispg;
  ScreenGrid g(o);
  GridFrame f;
  g.build(cam, f);
  for (const auto& v : f.vertices) {
    const glm::dvec3 p = cam.eyeEcef() + rel(v);
    EXPECT_NEAR(geo::fromEcef(p).heightM, 0.0, 1e-7 * glm::length(rel(v)) + 1e-3);
    EXPECT_EQ(v.flags & grid::kVertexHorizon, 0);  // ISPG never misses
  }
  // ISPG's vertex is not where its pixel looks: the plane point at ground
  // distance s drops radially by s^2 / (2R) while the pixel ray meets the
  // surface further on, so the two differ by s^2 / (2 R tan(elevation))
  // horizontally (plane geometry, R the local radius of curvature).
  GridOptions od;
  ScreenGrid gd(od);
  GridFrame fd;
  gd.build(cam, fd);
  const std::size_t mid = std::size_t(f.rows / 2) * f.cols + f.cols / 2;
  const glm::dvec3 d = glm::normalize(rel(fd.vertices[mid]));
  const double tanElev = std::tan(std::asin(-glm::dot(d, geo::surfaceNormal(50.0, -20.0))));
  const double s = 300.0 / tanElev, R = 6.37e6;  // meridional radius of curvature at 50 deg
  const double predicted = s * s / (2.0 * R * tanElev);
  // 5 %: the flat-Earth approximations of the formula above.
  EXPECT_NEAR(glm::length(rel(f.vertices[mid]) - rel(fd.vertices[mid])), predicted, 0.05 * predicted);
}

TEST(ScreenGrid, BadOptionsNameTheField) {
  GridOptions o;
  o.cols = 1;
  EXPECT_THROW(ScreenGrid{o}, std::invalid_argument);
  o = {};
  o.cellPx = 0.0;
  try {
    ScreenGrid g{o};
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cellPx"), std::string::npos);
  }
  o = {};
  o.maxDisplacementM = -1.0;
  EXPECT_THROW(ScreenGrid{o}, std::invalid_argument);
}

// The build copies lat/lon and class of horizon vertices from their limb
// point and computes cell flags per row chunk: every vertex's class must
// still be the classifier's answer for its own lat/lon, horizon lat/lon must
// be where GeographicLib puts the vertex, flags must agree across chunk
// boundaries, and the result must not depend on the thread count.
TEST(ScreenGrid, HorizonVerticesCarryTheirOwnLatLonAndClass) {
  // A coast along a meridian that crosses the horizon (which spans lon 14 to
  // 29 here): land west of lon 20.
  auto classify = [](const double* /*lat*/, const double* lon, std::size_t n, ocean::Surface* out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = lon[i] < 20.0 ? ocean::Surface::Land : ocean::Surface::Ocean;
  };
  // From 500 km looking north-east, 20 deg down: sea, land and sky.
  const Camera cam = Camera::fromGeodetic({40.0, 0.0, 5e5, 60.0, -20.0, 0.0}, 60.0, 320, 240);
  GridOptions o;
  o.cols = 97;
  o.rows = 203;  // odd sizes: chunks of 12 rows and a short last chunk
  o.maxDisplacementM = 5.0;
  o.threads = 1;
  ScreenGrid g1(o, classify);
  o.threads = 2;
  ScreenGrid g2(o, classify);
  GridFrame f1, f2;
  g1.build(cam, f1);
  g2.build(cam, f2);
  ASSERT_EQ(f1.vertices.size(), f2.vertices.size());
  EXPECT_EQ(0, std::memcmp(f1.vertices.data(), f2.vertices.data(), f1.vertices.size() * sizeof(grid::GridVertex)));
  EXPECT_EQ(f1.cellSkip, f2.cellSkip);
  std::size_t horizon = 0, land = 0, horizonLand = 0;
  for (const auto& v : f1.vertices) {
    ocean::Surface want;
    classify(&v.latDeg, &v.lonDeg, 1, &want);
    EXPECT_EQ(v.surface, std::uint8_t(want));
    if (!(v.flags & grid::kVertexHorizon)) continue;
    ++horizon;
    horizonLand += want == ocean::Surface::Land;
    // GeographicLib on the float position: its rounding at ~2500 km is
    // ~0.15 m = 1.4e-6 deg; a wrong limb point would be kilometres off.
    // Height: the limb of the ellipsoid inflated by the 5 m displacement.
    const geo::Geodetic gp = geo::fromEcef(cam.eyeEcef() + rel(v));
    EXPECT_NEAR(v.latDeg, gp.latDeg, 1e-5);
    EXPECT_NEAR(geo::wrapLonDeg(v.lonDeg - gp.lonDeg), 0.0, 1e-5);
    EXPECT_NEAR(gp.heightM, 5.0, 1.0);
  }
  for (int j = 0; j + 1 < f1.rows; ++j)
    for (int i = 0; i + 1 < f1.cols; ++i) {
      const auto* v = &f1.vertices[std::size_t(j) * f1.cols + i];
      constexpr auto L = std::uint8_t(ocean::Surface::Land);
      const bool allLand = v[0].surface == L && v[1].surface == L && v[f1.cols].surface == L && v[f1.cols + 1].surface == L;
      ASSERT_EQ(f1.cellSkip[std::size_t(j) * (f1.cols - 1) + i], allLand) << i << "," << j;
      land += allLand;
    }
  EXPECT_EQ(f1.landCells, land);
  // The view must exercise all of it: sky, land cells, land on the horizon.
  EXPECT_GT(horizon, 500u);
  EXPECT_GT(land, 100u);
  EXPECT_GT(horizonLand, 10u);
}

// Issue 15 item 4, the middle band's coarser mesh (grid::coarseIndices):
// on a real grid with land cells and patches of coarse flags, for blocks
// of 2, 4 and 8 cells, the triangles face the eye, cover every drawn cell
// exactly once (their areas in grid units sum to the drawn cells' count,
// none lies in a skipped cell) and meet edge to edge: every edge is shared
// with its reverse by the neighbouring triangle, except on the border of
// what is drawn (the grid's edge, a skipped cell). A T-junction (a coarse
// block's long side against two fine cells' short ones) leaves both unpaired
// inside the sea, the crack this guards against.
TEST(ScreenGrid, CoarseBlocksCoverTheCellsOnceEdgeToEdge) {
  const Camera cam = Camera::fromGeodetic({-20.0, -30.0, 2000.0, 0.0, -60.0, 0.0}, 60.0, 640, 480);
  ScreenGrid g(GridOptions{});
  GridFrame f;
  g.build(cam, f);
  const int cols = f.cols, rows = f.rows;
  ASSERT_GT(cols, 20);
  ASSERT_GT(rows, 16);
  // Land: a few cells here and there (the renderer skips them).
  std::size_t drawnCells = 0;
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      std::uint8_t& s = f.cellSkip[std::size_t(j) * (cols - 1) + i];
      s = (i * 7 + j * 13) % 89 == 0;
      drawnCells += !s;
    }
  // Coarse flags: two round patches and the grid's upper part.
  std::vector<std::uint8_t> coarse(f.vertices.size());
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      coarse[std::size_t(j) * cols + i] = j > rows * 2 / 3 || std::hypot(i - cols * 0.3, j - rows * 0.4) < rows * 0.25 ||
                                          std::hypot(i - cols * 0.7, j - rows * 0.3) < rows * 0.2;
  for (int block : {2, 4, 8}) {
    std::vector<std::uint32_t> idx;
    const std::size_t blocks = grid::coarseIndices(f, coarse, block, idx);
    EXPECT_GT(blocks, 3u) << block;
    ASSERT_EQ(idx.size() % 6, 0u);
    const auto at = [&](std::uint32_t v) { return glm::ivec2(int(v) % cols, int(v) / cols); };
    double area = 0.0;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::size_t k = 0; k < idx.size(); k += 3) {
      const std::uint32_t t[3] = {idx[k], idx[k + 1], idx[k + 2]};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // padding
      const glm::ivec2 a = at(t[0]), b = at(t[1]), c = at(t[2]);
      const int twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      EXPECT_GT(twice, 0) << "block " << block << ": a triangle against the cells' winding";
      area += 0.5 * twice;
      const glm::dvec3 pa = rel(f.vertices[t[0]]), pb = rel(f.vertices[t[1]]), pc = rel(f.vertices[t[2]]);
      EXPECT_LT(glm::dot(glm::cross(pb - pa, pc - pa), pa), 0.0) << "block " << block << ": a triangle facing away";
      // Its centroid's cell is drawn.
      const glm::dvec2 m = (glm::dvec2(a) + glm::dvec2(b) + glm::dvec2(c)) / 3.0;
      EXPECT_FALSE(f.cellSkip[std::size_t(std::floor(m.y)) * (cols - 1) + std::size_t(std::floor(m.x))]);
      for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
    }
    EXPECT_DOUBLE_EQ(area, double(drawnCells)) << "block " << block;
    int unpaired = 0, inside = 0;
    for (const auto& [e, n] : edges) {
      EXPECT_EQ(n, 1) << "block " << block << ": an edge drawn twice the same way";
      if (edges.count({e.second, e.first})) continue;
      ++unpaired;
      // On the border: every unit step's cell to its right (outside a
      // counter-clockwise triangle) is off the grid or skipped.
      const glm::ivec2 p = at(e.first), q = at(e.second), d = q - p;
      if (d.x != 0 && d.y != 0) {
        ++inside;  // a diagonal is always inside a cell
        continue;
      }
      const glm::ivec2 u = d / std::max(std::abs(d.x), std::abs(d.y)), right(u.y, -u.x);
      for (glm::ivec2 s = p; s != q; s += u) {
        const glm::dvec2 mid = glm::dvec2(s) + 0.5 * glm::dvec2(u) + 0.5 * glm::dvec2(right);
        const int ci = int(std::floor(mid.x)), cj = int(std::floor(mid.y));
        if (ci >= 0 && cj >= 0 && ci < cols - 1 && cj < rows - 1 && !f.cellSkip[std::size_t(cj) * (cols - 1) + ci])
          ++inside;
      }
    }
    std::printf("blocks of %d: %zu coarse, %zu triangles, %d border edges, %d open inside\n", block, blocks,
                idx.size() / 3, unpaired, inside);
    EXPECT_EQ(inside, 0) << "block " << block << ": T-junctions";
  }
}
