// The render commands as a user runs them: bad input is named, no display
// is reported, a frame is written.
#include "RenderFixture.h"

#include "tests/support/Subprocess.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

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

// Issue 15: --coast-region reaches the plugin (geocean_set_coast_region):
// bad values are named and exit 2, and off the Dutch coast (20 to 30 m
// deep in the default relief) the waves drawn with it are another surface.
TEST(RenderCli, CoastRegionIsCheckedAndChangesTheWaves) {
  const std::string base = kExe + " render --camera 52.6,4.45,40,90,-25 --size 96x54 --wind 12 --time 20";
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {" --coast-region 52.6,4.45", "needs GEOCEAN_WAVES_GERSTNER"},
           {" --waves gerstner --coast-region 52.6", "'52.6' is not LAT,LON[,SIZE_M]"},
           {" --waves gerstner --coast-region 52.6,4.45,90000", "size 90000 m is outside 500 .. 40000 m"},
           {" --waves gerstner --coast-region nan,4", "'nan' in 'nan,4' is not a finite number"},
           {" --waves gerstner --no-ocean --coast-region 52.6,4.45", "needs the ocean"}}) {
    const auto r = geocean::test::run(base + args + " --out /tmp/x.png");
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
  const std::string plain = ::testing::TempDir() + "/cli_coast_plain.png", coast = ::testing::TempDir() + "/cli_coast.png";
  const auto a = geocean::test::run(base + " --waves gerstner --out " + plain);
  const auto b = geocean::test::run(base + " --waves gerstner --coast-region 52.6,4.45,20000 --out " + coast);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const ImageDiff d = compare(readImage(plain), readImage(coast));
  EXPECT_GT(d.fractionOver16, 0.05) << "mean " << d.mean;
}

// Issue 13 item 8: --waves noise-paper is drawn (paper 002's model, before
// only queried): over its seam it is another sea than the default noise.
TEST(RenderCli, NoisePaperIsDrawn) {
  const std::string base = kExe + " render --camera 20,179.9995,150,0,-25 --size 96x54 --wind 10 --time 20";
  const std::string noise = ::testing::TempDir() + "/cli_noise.png", paper = ::testing::TempDir() + "/cli_paper.png";
  const auto a = geocean::test::run(base + " --waves noise --out " + noise);
  const auto b = geocean::test::run(base + " --waves noise-paper --out " + paper);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const ImageDiff d = compare(readImage(noise), readImage(paper));
  std::printf("noise vs noise-paper: mean %.2f, over 16 %.4f\n", d.mean, d.fractionOver16);
  // Two unrelated seas of the same Hs: measured 4 % of the pixels apart by
  // more than 16 (the sky and haze are alike); one sea drawn twice gives 0.
  EXPECT_GT(d.fractionOver16, 0.01) << "mean " << d.mean;
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
  // The mirrored pass's and the shadow map's own times close each row
  // (the last frame, 2 m up, draws the reflection: not 0).
  EXPECT_NE(csv.out.find(",total_ms,reflection_ms,shadow_ms\n"), std::string::npos) << csv.out;
  const std::string last = csv.out.substr(csv.out.rfind('\n', csv.out.size() - 2) + 1);
  const std::string reflection = last.substr(0, last.rfind(',')).substr(last.substr(0, last.rfind(',')).rfind(',') + 1);
  EXPECT_GT(std::stod(reflection), 0.0) << last;
  const auto bad = geocean::test::run(kExe + " fly --to 95,0 --out " + dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("latitude"), std::string::npos) << bad.err;
  // --repeat: untimed draws before each timed one; a count out of range names the option.
  const auto again = geocean::test::run(kExe + " fly --to 36.0,-5.6 --frames 2 --size 48x32 --no-images --repeat 1 --out " + dir);
  EXPECT_EQ(again.exitCode, 0) << again.err;
  const auto badRepeat = geocean::test::run(kExe + " fly --repeat -1 --out " + dir);
  EXPECT_EQ(badRepeat.exitCode, 2);
  EXPECT_NE(badRepeat.err.find("--repeat"), std::string::npos) << badRepeat.err;
}

// Issue 15 item 1: `fly --coast-follow` sets GEOCEAN_DRAW_FOLLOW_COAST on
// every draw (a plugin that refused the bit would fail the first frame):
// a flight from orbit down to the Dutch coast, whose first frames' nadirs
// are far outside the region, so builds start on the plugin's worker; the
// flight does not wait for them and exits cleanly with one in flight.
TEST(RenderCli, FlyWithCoastFollowRuns) {
  const std::string dir = ::testing::TempDir() + "/cli_flight_follow";
  std::filesystem::remove_all(dir);
  const auto r = geocean::test::run(kExe + " fly --to 52.6,4.45 --frames 3 --size 48x32 --waves gerstner --wind 12 "
                                           "--coast-region 52.6,4.45,10000 --coast-follow --out " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (int f = 0; f < 3; ++f)
    EXPECT_TRUE(std::filesystem::exists(dir + "/frame_0000" + std::to_string(f) + ".png"));
}

}  // namespace
}  // namespace geocean::render::test
