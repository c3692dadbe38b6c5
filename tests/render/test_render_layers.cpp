// The drawing commands take the user's rasters as layers (issue 12 item 1):
// a synthetic island in a user's relief, which the 5' default mask calls
// ocean, is drawn as land by `geocean render --elevation island.tif`
// (the host's world and the ocean plugin both built from the same stack),
// and `geocean pick` through the same pixel answers land. Golden image,
// looked at: tests/render/golden/island_5km.png.
#include "globe/gl/Framebuffer.h"
#include "globe/raster/GeoTiffWriter.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
// degrees. The picture resamples it to 5' (the default mask's cell): an
// island about 30 km across, three or four cells.
std::string islandTif() {
  static const std::string path = [] {
    constexpr int n = 360;
    constexpr double step = 1.0 / 240.0;
    std::vector<float> px(std::size_t(n) * n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double lat = 1.0 - (y + 0.5) * step, lon = -0.5 + (x + 0.5) * step;
        const double r2 = ((lat - 0.25) * (lat - 0.25) + (lon - 0.25) * (lon - 0.25)) / (0.15 * 0.15);
        px[std::size_t(y) * n + x] = float(-200.0 + 490.0 * std::exp(-r2));
      }
    geocean::raster::GeoTiffWriteOptions wo;
    wo.transform = {-0.5, 1.0, step, -step, false};
    const std::string p = ::testing::TempDir() + "/render_island.tif";
    geocean::raster::writeGeoTiff(p, px.data(), n, n, 1, geocean::raster::SampleType::F32, wo);
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
