// The render commands as a user runs them: bad input is named, no display
// is reported, a frame is written.
#include "RenderFixture.h"

#include "tests/support/Subprocess.h"

#include <algorithm>
#include <filesystem>

namespace geocean::render::test {
namespace {

const std::string kExe = GEOCEAN_EXE;

TEST(RenderCli, BadCameraIsNamedAndExits2) {
  const auto r = geocean::test::run(kExe + " render --camera 0,abc,100,0,-90 --out /tmp/x.png");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("'abc' is not a number"), std::string::npos) << r.err;
  const auto r2 = geocean::test::run(kExe + " render --camera 95,0,100,0,-90 --out /tmp/x.png");
  EXPECT_EQ(r2.exitCode, 2);
  EXPECT_NE(r2.err.find("latitude"), std::string::npos) << r2.err;
  const auto r3 = geocean::test::run(kExe + " render --size 0x10 --out /tmp/x.png");
  EXPECT_EQ(r3.exitCode, 2);
  EXPECT_NE(r3.err.find("--size"), std::string::npos) << r3.err;
}

TEST(RenderCli, RendersAFrameWithNegativeCoordinates) {
  const std::string out = ::testing::TempDir() + "/cli_frame.png";
  std::filesystem::remove(out);
  const auto r = geocean::test::run(kExe + " render --camera -33.9,18.4,200000,0,-90 --size 64x48 --out " + out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image img = readImage(out);
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 48);
}

}  // namespace
}  // namespace geocean::render::test

namespace geocean::render::test {
namespace {

TEST(RenderCli, ViewWithoutADisplaySaysSoAndExits4) {
  const auto r = geocean::test::run("env -u DISPLAY -u WAYLAND_DISPLAY " + kExe + " view");
  EXPECT_EQ(r.exitCode, 4);
  EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("geocean render"), std::string::npos) << r.err;
}

TEST(RenderCli, FlyWritesFramesAndATimingsCsv) {
  const std::string dir = ::testing::TempDir() + "/cli_flight";
  std::filesystem::remove_all(dir);
  const auto r = geocean::test::run(kExe + " fly --to 36.0,-5.6 --frames 3 --size 48x32 --out " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (int f = 0; f < 3; ++f)
    EXPECT_TRUE(std::filesystem::exists(dir + "/frame_0000" + std::to_string(f) + ".png"));
  const auto csv = geocean::test::run("cat " + dir + "/timings.csv");
  // Header + one row per frame; the last frame is 2 m above the sea.
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 4);
  EXPECT_NE(csv.out.find(",2.000,"), std::string::npos) << csv.out;
  const auto bad = geocean::test::run(kExe + " fly --to 95,0 --out " + dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("latitude"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace geocean::render::test
