// The drawing commands take the user's rasters as layers (issue 12 item 1):
// a synthetic island in a user's relief, which the 5' default mask calls
// ocean, is drawn as land by `geocean render --elevation island.tif`
// (the host's world and the ocean plugin both built from the same stack),
// and `geocean pick` through the same pixel answers land. Golden image,
// looked at: tests/render/golden/island_5km.png.
#include "globe/gl/Framebuffer.h"
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/World.h"
#include "tests/support/IslandRelief.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

const std::string kExe = GEOCEAN_EXE;
// From 5 km above the sea 28 km south of the peak, looking north and down
// at 15 degrees: the whole island in the middle of the frame, its relief
// exaggerated 8 times so that the hump shows on the horizon. Its colour is
// the default Blue Marble's (sea there: imagery layers are not done yet).
const std::string kView = "0.0,0.25,5000,0,-15";
const std::string kCamera = " --camera " + kView + " --size 320x200 --fov 50 --sun 120,35 --exaggeration 8";

// A 290 m peak at (0.25, 0.25) in a 200 m deep sea, 15" cells over -0.5 .. 1
// degrees. Its relief is drawn from its own tiles (a regional layer finer
// than the grid streams: the dome's smooth silhouette), and so is its
// coast, which the relief's sign decides (world::reliefWaterPyramid): the
// 0 m circle, r = 0.15 sqrt(ln 2.45) = 0.142 degrees (31.6 km across), in
// the golden from x 15 to 305 and down to row 128 (computed from the view:
// 12..308, 128.6), where the 5' water grid drew a blob of 3-4 cells out to
// the frame's edges and row 148.
std::string islandTif() {
  static const std::string path = [] {
    const std::string p = ::testing::TempDir() + "/render_island.tif";
    geocean::test::writeIslandRelief(p);
    return p;
  }();
  return path;
}

geocean::gl::Image render(const std::string& extra, const std::string& name) {
  const std::string out = ::testing::TempDir() + "/" + name + ".png";
  std::filesystem::remove(out);
  const auto r = geocean::test::run(kExe + " render" + kCamera + " --out " + out + extra);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return geocean::gl::readImage(out);
}

// Mean absolute RGB difference over the rectangle [x0, x1) x [y0, y1).
double meanDiff(const geocean::gl::Image& a, const geocean::gl::Image& b, int x0, int x1, int y0, int y1) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = (std::size_t(y) * a.width + x) * 4 + c;
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
      }
  return sum / (3.0 * (x1 - x0) * (y1 - y0));
}

}  // namespace

TEST(RenderLayers, AnIslandInTheUsersReliefIsDrawnAndPickedAsLand) {
  const auto sea = render("", "island_without_layer");
  const auto island = render(" --elevation " + islandTif(), "island_5km");
  ASSERT_EQ(island.width, 320);
  ASSERT_EQ(sea.width, 320);
  // The sky above the horizon is the same; the island region differs.
  EXPECT_LT(meanDiff(sea, island, 0, 320, 0, 40), 1.0);
  EXPECT_GT(meanDiff(sea, island, 60, 260, 80, 140), 10.0);
  // The pixel the pick goes through: land on the island's flank, ocean
  // without the layer (the 5' default mask's answer).
  const std::string pick = kExe + " pick --camera " + kView + " --fov 50 --size 320x200 --pixel 160,110";
  auto p = geocean::test::run(pick + " --elevation " + islandTif());
  ASSERT_EQ(p.exitCode, 0) << p.err;
  EXPECT_NE(p.out.find(",land"), std::string::npos) << p.out;
  p = geocean::test::run(pick);
  ASSERT_EQ(p.exitCode, 0) << p.err;
  EXPECT_NE(p.out.find(",ocean"), std::string::npos) << p.out;

  // The drawn coast is the relief's 0 m circle (r = 0.142 degrees round
  // the peak, 15.8 km): straight ahead (column 160) its near edge is 12.0 km
  // off, atan(5 / 12.0) = 22.6 degrees down, 7.6 below the view's axis:
  // row 100 + 100 tan(7.6) / tan(25) = 128.6; the centre row meets the sea
  // 19.32 km off (slant), where the circle is 12.87 km either side: columns
  // 160 -+ 160 (12.87 / 19.32) / tan(36.7) = 160 -+ 143 (the horizontal
  // half-field atan(1.6 tan 25)). Tolerance 2 px: the 15" cells' B-spline
  // (within half a cell, 0.46 km, of the line: 0.5-1.5 px here) and a pixel.
  // The island is dark (the Blue Marble's sea on the terrain), the sea light.
  const auto dark = [&](int x, int y) { return island.rgba[(std::size_t(y) * island.width + x) * 4] < 55; };
  int bottom = 0, left = 320, right = 0;
  for (int y = 100; y < 200 && dark(160, y); ++y) bottom = y;  // the island's run from the centre
  for (int x = 160; x >= 0 && dark(x, 100); --x) left = x;
  for (int x = 160; x < 320 && dark(x, 100); ++x) right = x;
  EXPECT_NEAR(bottom + 0.5, 128.6, 2.0);
  EXPECT_NEAR(left + 0.0, 160.0 - 143.0, 2.0);
  EXPECT_NEAR(right + 1.0, 160.0 + 143.0, 2.0);

  const std::string golden = std::string(GEOCEAN_GOLDEN_DIR) + "/island_5km.png";
  if (std::getenv("GEOCEAN_UPDATE_GOLDEN")) {
    geocean::gl::writePng(golden, island);
    GTEST_SKIP() << "golden rewritten: " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden;
  const auto g = geocean::gl::readImage(golden);
  ASSERT_EQ(g.width, island.width);
  ASSERT_EQ(g.height, island.height);
  EXPECT_LE(meanDiff(g, island, 0, 320, 0, 200), 2.0) << "actual: " << ::testing::TempDir() << "/island_5km.png";
}

TEST(RenderLayers, BadLayerFilesAreNamed) {
  const std::string out = ::testing::TempDir() + "/bad_layer.png";
  auto r = geocean::test::run(kExe + " render --size 32x20 --out " + out + " --mask /nonexistent/region.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("/nonexistent/region.tif"), std::string::npos) << r.err;
  r = geocean::test::run(kExe + " fly --frames 2 --size 32x20 --out " + ::testing::TempDir() +
                         "/bad_fly --elevation /nonexistent/relief.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("/nonexistent/relief.tif"), std::string::npos) << r.err;
  r = geocean::test::run(kExe + " render --size 32x20 --out " + out + " --no-default-world");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--no-default-world needs --mask or --elevation"), std::string::npos) << r.err;
  r = geocean::test::run(kExe + " render --size 32x20 --out " + out + " --mask-encoding 0=ocean");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--mask-encoding needs --mask"), std::string::npos) << r.err;
}

namespace {

// A synthetic imagery layer over the Sahara (lon 5..15, lat 15..25, 0.05
// degree cells, 8-bit RGB): magenta, which no Blue Marble land pixel is,
// with a 2 x 2 degree hole of nodata (0) at its centre (20 N, 10 E).
std::string magentaTif() {
  static const std::string path = [] {
    constexpr int n = 200;
    constexpr double step = 0.05;
    std::vector<std::uint8_t> px(std::size_t(n) * n * 3);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double lat = 25.0 - (y + 0.5) * step, lon = 5.0 + (x + 0.5) * step;
        const bool hole = std::abs(lat - 20.0) < 1.0 && std::abs(lon - 10.0) < 1.0;
        const std::uint8_t rgb[3] = {230, 20, 230};
        for (int c = 0; c < 3; ++c) px[(std::size_t(y) * n + x) * 3 + c] = hole ? 0 : rgb[c];
      }
    geocean::raster::GeoTiffWriteOptions wo;
    wo.transform = {5.0, 25.0, step, -step, false};
    wo.nodata = 0.0;
    const std::string p = ::testing::TempDir() + "/render_magenta.tif";
    geocean::raster::writeGeoTiff(p, px.data(), n, n, 3, geocean::raster::SampleType::U8, wo);
    return p;
  }();
  return path;
}

struct Px {
  double r = 0, g = 0, b = 0;
};
// Mean colour and largest channel difference between a and b over the
// pixels whose Chebyshev distance from the frame's centre is in [d0, d1].
Px ring(const geocean::gl::Image& a, const geocean::gl::Image& b, int d0, int d1, int* maxDiff) {
  Px m;
  int n = 0;
  *maxDiff = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const int d = std::max(std::abs(x - a.width / 2), std::abs(y - a.height / 2));
      if (d < d0 || d > d1) continue;
      const std::size_t i = (std::size_t(y) * a.width + x) * 4;
      m.r += a.rgba[i], m.g += a.rgba[i + 1], m.b += a.rgba[i + 2];
      for (int c = 0; c < 3; ++c) *maxDiff = std::max(*maxDiff, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
      ++n;
    }
  m.r /= n, m.g /= n, m.b /= n;
  return m;
}

}  // namespace

// --imagery (issue 12 item 1): straight down on (20 N, 10 E) from 2,000 km,
// 200 x 200 pixels, 45 degrees: the layer's 10 x 10 degrees reach about 66
// pixels from the centre (the nadir angle of a point 5 degrees away), its
// hole about 13. Where the layer has data the land is magenta; in its hole
// and outside it the picture is the default imagery's, to the bit (alpha 0:
// albedo * 1 + 0). Looked at: imagery_sahara.png in the test's temp dir.
TEST(RenderLayers, AnImageryLayerIsDrawnWhereItHasDataAndTheLayerBelowElsewhere) {
  const std::string cam = " --camera 20,10,2000000,0,-90 --size 200x200 --fov 45 --sun 180,60 --no-ocean";
  const std::string outBase = ::testing::TempDir() + "/imagery_default.png";
  const std::string outImg = ::testing::TempDir() + "/imagery_sahara.png";
  std::filesystem::remove(outBase);
  std::filesystem::remove(outImg);
  auto r = geocean::test::run(kExe + " render" + cam + " --out " + outBase);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = geocean::test::run(kExe + " render" + cam + " --out " + outImg + " --imagery " + magentaTif());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto base = geocean::gl::readImage(outBase), img = geocean::gl::readImage(outImg);
  ASSERT_EQ(img.width, 200);
  ASSERT_EQ(base.width, 200);
  int diff = 0;
  ring(img, base, 0, 9, &diff);  // inside the hole (13 px), off its bilinear edge
  EXPECT_LE(diff, 1);
  ring(img, base, 80, 100, &diff);  // outside the layer (66 px)
  EXPECT_LE(diff, 1);
  const Px m = ring(img, base, 25, 55, &diff);  // the layer's data
  EXPECT_GT(m.r, 2.0 * m.g) << m.r << " " << m.g << " " << m.b;
  EXPECT_GT(m.b, 2.0 * m.g) << m.r << " " << m.g << " " << m.b;
  const Px d = ring(base, img, 25, 55, &diff);
  EXPECT_GT(d.r, d.b) << "the default there is desert (red above blue)";
}

TEST(RenderLayers, BadImageryFilesAreNamed) {
  const std::string out = ::testing::TempDir() + "/bad_imagery.png";
  const std::string dir = ::testing::TempDir();
  // One channel: a mask or a relief given as imagery.
  const std::vector<std::uint8_t> grey(16 * 8, 100);
  geocean::raster::GeoTiffWriteOptions wo;
  wo.transform = {0.0, 8.0, 1.0, -1.0, false};
  wo.tileSize = 0;
  geocean::raster::writeGeoTiff(dir + "/grey_imagery.tif", grey.data(), 16, 8, 1, geocean::raster::SampleType::U8, wo);
  auto r = geocean::test::run(kExe + " render --size 32x20 --no-ocean --out " + out + " --imagery " + dir +
                              "/grey_imagery.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find(dir + "/grey_imagery.tif: imagery needs 3 (RGB) or 4 (RGBA) channels, the file has 1"),
            std::string::npos)
      << r.err;
  // Floats beyond 8 bits.
  std::vector<float> hot(16 * 8 * 3, 10.0f);
  hot[5 * 3 + 1] = 300.0f;
  geocean::raster::writeGeoTiff(dir + "/hot_imagery.tif", hot.data(), 16, 8, 3, geocean::raster::SampleType::F32, wo);
  r = geocean::test::run(kExe + " fly --frames 2 --size 32x20 --no-ocean --out " + dir + "/bad_imagery_fly --imagery " +
                         dir + "/hot_imagery.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find(dir + "/hot_imagery.tif: imagery values must be 8-bit (0..255); pixel (5, 0) channel 1 is 300"),
            std::string::npos)
      << r.err;
  r = geocean::test::run(kExe + " render --size 32x20 --no-ocean --out " + out + " --imagery /nonexistent/photo.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("/nonexistent/photo.tif"), std::string::npos) << r.err;
}

// Golden (issue 12): the bundled 1.25' world mask (17280 x 8640, wider than
// one GL texture) drawn streamed from 2,500 km, straight down on the Aegean
// (38 N, 24 E), no ocean layer: the terrain's water from the mask's tiles.
// Looked at: tests/render/golden/world_1.25m_2500km.png. The control, the
// default 5' world from the same place, is the same picture but along the
// coasts: the islands' shores move by up to a 5' cell, a pixel or two here.
TEST(RenderLayers, GoldenThe1_25mWorldFrom2500km) {
  const std::string cache = ::testing::TempDir() + "/layers_tiles_125";
  ::setenv("GEOCEAN_TILE_CACHE", cache.c_str(), 1);
  const std::string cam = " --no-ocean --camera 38,24,2500000,0,-90 --size 320x240 --fov 45 --sun 150,45";
  const std::string fine = geocean::raster::defaultWorld().maskFine;
  const auto render = [&](const std::string& extra, const std::string& name) {
    const std::string out = ::testing::TempDir() + "/" + name + ".png";
    std::filesystem::remove(out);
    const auto r = geocean::test::run(kExe + " render" + cam + " --out " + out + extra);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return geocean::gl::readImage(out);
  };
  const auto world = render(" --mask " + fine, "world_1.25m_2500km");
  const auto control = render("", "world_5m_2500km");
  ::unsetenv("GEOCEAN_TILE_CACHE");
  ASSERT_EQ(world.width, 320);
  ASSERT_EQ(control.width, 320);
  // Coasts only: the two differ a little on average (0.23 of 255, 72009 of
  // 76800 pixels identical when this was written), not at all in most.
  const double d = meanDiff(world, control, 0, 320, 0, 240);
  int same = 0;
  for (std::size_t i = 0; i < world.rgba.size(); i += 4)
    same += world.rgba[i] == control.rgba[i] && world.rgba[i + 1] == control.rgba[i + 1] &&
            world.rgba[i + 2] == control.rgba[i + 2];
  std::printf("1.25' vs 5' world from 2,500 km: mean difference %.3f, %d of %d pixels identical\n", d, same,
              320 * 240);
  EXPECT_GT(d, 0.02);
  EXPECT_LT(d, 3.0);
  EXPECT_GT(same, 320 * 240 / 2);
  const std::string golden = std::string(GEOCEAN_GOLDEN_DIR) + "/world_1.25m_2500km.png";
  if (std::getenv("GEOCEAN_UPDATE_GOLDEN")) {
    geocean::gl::writePng(golden, world);
    GTEST_SKIP() << "golden written: " << golden;
  }
  const auto g = geocean::gl::readImage(golden);
  ASSERT_EQ(g.width, world.width);
  ASSERT_EQ(g.height, world.height);
  // As the island's: another Mesa/LLVM build may round shading by under 2 of 255 on average.
  EXPECT_LE(meanDiff(g, world, 0, 320, 0, 240), 2.0) << "actual: " << ::testing::TempDir() << "/world_1.25m_2500km.png";
}
