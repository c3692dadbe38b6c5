// `geocean view` in a real window: GLFW on an Xvfb X server (xvfb-run),
// Mesa llvmpipe through GLX. Scripted runs (--frames N) exit by themselves
// and leave a screenshot of the window and a per-frame CSV.
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/ImageIo.h"
#include "tests/support/IslandRelief.h"
#include "tests/support/Subprocess.h"
#include "tests/view/ViewStats.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kGeocean = GEOCEAN_EXE;

// Skips (with the reason) when there is no xvfb-run; that is the only reason to skip.
#define REQUIRE_XVFB()                                                                                       \
  if (!geocean::test::haveTool("xvfb-run"))                                                                   \
  GTEST_SKIP() << "xvfb-run is not installed (Debian packages xvfb and xauth, in quickstart.sh): "           \
                  "geocean view was not run in a window"

geocean::test::ProcessResult view(const std::string& args) {
  // -a: a free server number, so tests may run in parallel.
  return geocean::test::runUnderXvfb("800x600x24", kGeocean + " view " + args);
}

std::string tempPath(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/geocean_view";
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

// The first answer row of `geocean query <args>` (CSV), split into its
// fields, at least 6 (sea_height_m is the sixth): a failed or short answer
// is a test failure, and empty fields are returned.
std::vector<std::string> queryRow(const std::string& args) {
  const auto q = geocean::test::run(kGeocean + " query " + args);
  EXPECT_EQ(q.exitCode, 0) << q.err;
  std::stringstream qs(q.out);
  std::string line;
  std::getline(qs, line);
  std::getline(qs, line);
  std::vector<std::string> f;
  std::stringstream ls(line);
  for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
  if (f.size() < 6) {
    ADD_FAILURE() << "geocean query " << args << ": " << q.out;
    f.resize(6, "nan");
  }
  return f;
}

struct Rgb {
  int r, g, b;
};
Rgb at(const geocean::raster::Image8& img, int x, int y) {
  const unsigned char* p = img.pixels.data() + (size_t(y) * size_t(img.width) + size_t(x)) * size_t(img.channels);
  return {p[0], p[1], p[2]};
}
bool isBlack(Rgb c) { return std::max({c.r, c.g, c.b}) < 24; }

// A frame with the HUD against the same frame without it: the largest
// channel difference in the right half (no panel there) and the number of
// pixels in the panel's corner that differ by more than 64 (its text).
struct HudDiff {
  int rightDiff = 0, panelText = 0;
};
HudDiff hudDiff(const geocean::raster::Image8& img, const geocean::raster::Image8& bare) {
  HudDiff d;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgb a = at(img, x, y), b = at(bare, x, y);
      const int diff = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
      if (x >= img.width / 2) d.rightDiff = std::max(d.rightDiff, diff);
      if (x < 140 && y < 100 && diff > 64) ++d.panelText;
    }
  return d;
}

using geocean::test::readStats;
using geocean::test::StatsRow;

// From 20,000 km the window shows the whole Earth: a disc of angular radius
// asin(R / d) (geometry, not our renderer) centred in the window, black space
// around it; the HUD panel sits in the top-left corner.
TEST(ViewWindow, OrbitScreenshotShowsTheGlobeAndTheHud) {
  REQUIRE_XVFB();
  const std::string withHud = tempPath("orbit_hud.png"), noHud = tempPath("orbit_nohud.png");
  const std::string common = " --size 320x180 --frames 3 --screenshot ";
  auto r = view(common + withHud);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = view(common + noHud + " --no-hud");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto img = geocean::raster::readImage8(withHud), bare = geocean::raster::readImage8(noHud);
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 180);
  ASSERT_GE(img.channels, 3);
  ASSERT_EQ(bare.width, 320);
  ASSERT_EQ(bare.channels, img.channels);

  // The view starts over (20 N, 30 W), 20,000 km up, 45 deg vertical field of view.
  // Ellipsoid radius there (geocentric) and the eye's distance from the centre.
  const glm::dvec3 eye = geocean::geo::toEcef({20.0, -30.0, 2.0e7});
  const glm::dvec3 ground = geocean::geo::toEcef({20.0, -30.0, 0.0});
  const double d = glm::length(eye), radius = glm::length(ground);
  const double fpx = 0.5 * img.height / std::tan(0.5 * 45.0 * 3.14159265358979 / 180.0);
  const double discPx = std::tan(std::asin(radius / d)) * fpx;
  const double cx = img.width / 2.0, cy = img.height / 2.0;
  // The sun stands 40 deg above the nadir's horizon in the south-east
  // (azimuth 135): the terminator lies 50 deg of arc from the nadir, inside
  // the visible cap (76 deg), so the north-west rim is night. The disc is
  // tested in its south-east half, all of it in daylight.
  int inside = 0, insideLit = 0, outside = 0, outsideBlack = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy, rr = std::hypot(dx, dy);
      // 3 px inside the limb (anti-aliasing); 8 px outside it (the
      // atmosphere's glow). Outside is counted right of the disc, away from the HUD.
      if (rr < discPx - 3.0 && dx + dy > 0.0) ++inside, insideLit += !isBlack(at(img, x, y));
      if (rr > discPx + 8.0 && x > cx) ++outside, outsideBlack += isBlack(at(img, x, y));
    }
  ASSERT_GT(inside, 4000);
  ASSERT_GT(outside, 5000);
  EXPECT_GT(insideLit, 0.99 * inside) << "disc radius " << discPx << " px";
  EXPECT_GT(outsideBlack, 0.99 * outside);

  // The HUD: the same frame without it is the same picture away from the
  // panel (frames are scripted: same poses, same simulation times), and the
  // panel's text changes many pixels (a line of 10 glyphs lights > 100).
  const auto [rightDiff, panelText] = hudDiff(img, bare);
  EXPECT_LE(rightDiff, 1);
  EXPECT_GT(panelText, 300);
}

// --fly-to with --frames: the scripted flight ends on the last frame 2 m
// above the sea at the target; the HUD's sea height is the plugin's query of
// the drawn surface, checked against `geocean query` (a separate route to
// the same sea: the CLI's SeaQuery, default sea state = the viewer's).
TEST(ViewWindow, FlyToEndsTwoMetresAboveTheSeaWithTheQueriedSeaHeight) {
  REQUIRE_XVFB();
  const std::string shot = tempPath("flyto.png"), stats = tempPath("flyto.csv");
  const int frames = 12;
  const auto r = view("--size 320x180 --fly-to 36.0,-5.6 --frames " + std::to_string(frames) + " --screenshot " +
                      shot + " --stats " + stats);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = readStats(stats);
  ASSERT_EQ(int(rows.size()), frames);
  EXPECT_NEAR(rows.front().altM, 2.0e7, 1.0);
  const StatsRow& last = rows.back();
  EXPECT_NEAR(last.latDeg, 36.0, 1e-7);
  EXPECT_NEAR(last.lonDeg, -5.6, 1e-7);
  EXPECT_NEAR(last.altM, 2.0, 1e-3);
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_LT(rows[i].altM, rows[i - 1].altM) << "frame " << i;
  ASSERT_TRUE(std::isfinite(last.seaM)) << "the Strait of Gibraltar is sea";
  // Frame f is drawn at simulation time f / 30 s.
  const std::string t = std::to_string((frames - 1) / 30.0);
  const auto f = queryRow("--waves noise --time " + t + " 36.0 -5.6");
  // The viewer's CSV prints 4 decimals: 0.05 mm of rounding.
  EXPECT_NEAR(last.seaM, std::stod(f[5]), 5.1e-5);

  // 2 m above the sea looking just below the horizon: sky above, water below.
  const auto img = geocean::raster::readImage8(shot);
  ASSERT_EQ(img.width, 320);
  auto meanOf = [&](int y0, int y1, int x0) {
    double s[3] = {0, 0, 0};
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < img.width; ++x, ++n) {
        const Rgb c = at(img, x, y);
        s[0] += c.r, s[1] += c.g, s[2] += c.b;
      }
    return Rgb{int(s[0] / n), int(s[1] / n), int(s[2] / n)};
  };
  const Rgb sky = meanOf(0, 20, img.width / 2);  // right of the HUD
  const Rgb sea = meanOf(img.height * 3 / 4, img.height, 0);
  EXPECT_GT(sea.b, sea.r + 20) << "sea " << sea.r << "," << sea.g << "," << sea.b;
  EXPECT_GT(sky.r + sky.g + sky.b, sea.r + sea.g + sea.b + 60)
      << "sky " << sky.r << "," << sky.g << "," << sky.b << " sea " << sea.r << "," << sea.g << "," << sea.b;
}

// --panel opens the control panel (issue 13 item 8; P toggles it): in the
// window's top right, the globe below as without it (the panel's
// clicks are HudPanel.*, headless).
TEST(ViewWindow, ThePanelOpensAtTheTopRightAndLeavesTheGlobeBelowAsItWas) {
  REQUIRE_XVFB();
  const std::string withPanel = tempPath("orbit_panel.png"), without = tempPath("orbit_nopanel.png");
  const std::string common = " --size 640x360 --frames 3 --screenshot ";
  auto r = view(common + withPanel + " --panel");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = view(common + without);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto a = geocean::raster::readImage8(withPanel), b = geocean::raster::readImage8(without);
  ASSERT_EQ(a.width, b.width);
  int topRight = 0, elsewhere = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Rgb p = at(a, x, y), q = at(b, x, y);
      const bool d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)}) > 0;
      // The HUD's fps line differs from run to run: the top left is not compared.
      // The panel ends at 62 % of 360 px (its raster layers line included).
      if (x >= a.width / 2 && y < a.height * 7 / 10) topRight += d;
      else if (y >= a.height * 7 / 10) elsewhere += d;
    }
  EXPECT_GT(topRight, 10000) << "the panel fills a good part of the top right";
  EXPECT_EQ(elsewhere, 0) << "the globe below is as without it";
}

// The shader warm-up (an off-screen descent before the first frame, so
// llvmpipe's first-use compiles do not stall the user's flight) leaves no
// trace in the picture: the flight's last frame, with boats and the
// mirrored pass reused over 5 frames, is the same pixel for pixel as
// without it (state a frame leaves behind would show). The HUD's fps line
// is off.
TEST(ViewWindow, TheShaderWarmUpLeavesThePictureAsItWas) {
  REQUIRE_XVFB();
  const std::string warm = tempPath("warm_up.png"), cold = tempPath("no_warm_up.png");
  const std::string common = " --size 320x180 --frames 24 --fly-to 36.0,-5.6 --boats 3 --reflection-every 5 --no-hud --screenshot ";
  auto r = view(common + warm);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = view(common + cold + " --no-warm-up");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto a = geocean::raster::readImage8(warm), b = geocean::raster::readImage8(cold);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
  EXPECT_EQ(differ, 0u);
}

TEST(ViewWindow, BadOptionsExit2NamingTheOption) {
  REQUIRE_XVFB();
  auto r = view("--frames 2 --fly-to 95,0");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--fly-to"), std::string::npos) << r.err;
  r = view("--screenshot x.png");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--screenshot"), std::string::npos) << r.err;
  r = view("--frames 2 --camera 36,-5.6,500,0,-30 --fly-to 36,-5.6");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--camera and --fly-to"), std::string::npos) << r.err;
  r = view("--frames 2 --camera 36,-5.6,-5,0,-30");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--camera: altitude"), std::string::npos) << r.err;
  r = view("--frames 2 --stats /nonexistent-dir/s.csv");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("/nonexistent-dir/s.csv"), std::string::npos) << r.err;
}

// The sea-state and light options `render` and `fly` take (issue 13 item
// 8), scripted from orbit over the Atlantic (20 N, 30 W, the sea height
// under the camera in --stats). --beaufort 5 is --wind at the middle of the
// WMO class (9.35 m/s at 10 m) times 1.026 (to 19.5 m): the same bits and
// sea; Beaufort 9 another sea. --sun 135,-30 puts the night under the
// camera: the globe goes dark. --time T starts the clock at T: frame 0 of
// --time 10 + 2/30 is frame 2 of the run from 10 s (1/30 s per scripted
// frame), and 10 s later the sea under the camera is another.
// Bad values exit 2 naming the option.
TEST(ViewWindow, SeaStateAndLightOptionsAreThoseOfRenderAndFly) {
  REQUIRE_XVFB();
  const auto run = [](const std::string& name, const std::string& args, int frames) {
    const std::string png = tempPath(name + ".png"), csv = tempPath(name + ".csv");
    const auto r = view("--size 160x90 --no-hud --frames " + std::to_string(frames) + " --screenshot " + png +
                        " --stats " + csv + " " + args);
    EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.err;
    return std::pair{geocean::raster::readImage8(png), readStats(csv)};
  };
  char wind[64];
  std::snprintf(wind, sizeof wind, "%.17g", 9.35 * 1.026);
  char later[64];
  std::snprintf(later, sizeof later, "%.17g", 10.0 + 2.0 / 30.0);
  const auto [img0, rows0] = run("opts_default", "", 3);
  const auto [imgB5, rowsB5] = run("opts_b5", "--beaufort 5", 3);
  const auto [imgW, rowsW] = run("opts_wind", std::string("--wind ") + wind, 3);
  const auto [imgB9, rowsB9] = run("opts_b9", "--beaufort 9", 3);
  const auto [imgNight, rowsNight] = run("opts_night", "--sun 135,-30", 3);
  const auto [img10, rows10] = run("opts_time10", "--time 10", 3);
  const auto [imgT, rowsT] = run("opts_time_later", std::string("--time ") + later, 1);
  ASSERT_EQ(rows0.size(), 3u);
  ASSERT_EQ(rowsB5.size(), 3u);
  ASSERT_EQ(rowsW.size(), 3u);
  ASSERT_EQ(rowsB9.size(), 3u);
  ASSERT_EQ(rowsT.size(), 1u);
  EXPECT_EQ(imgB5.pixels, imgW.pixels);
  for (int f = 0; f < 3; ++f) EXPECT_EQ(rowsB5[f].seaM, rowsW[f].seaM) << f;
  EXPECT_GT(std::abs(rowsB9[0].seaM - rowsB5[0].seaM), 1e-3);  // another sea under the camera
  ASSERT_EQ(rows10.size(), 3u);
  EXPECT_EQ(rowsT[0].seaM, rows10[2].seaM);
  EXPECT_GT(std::abs(rows10[0].seaM - rows0[0].seaM), 1e-3);  // 10 s later: another sea height
  const auto brightness = [](const geocean::raster::Image8& im) {
    double sum = 0.0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        const Rgb c = at(im, x, y);
        sum += c.r + c.g + c.b;
      }
    return sum / (3.0 * im.width * im.height);
  };
  std::printf("mean brightness: sun 40 degrees high %.1f, 30 degrees below %.1f\n", brightness(img0),
              brightness(imgNight));
  EXPECT_LT(brightness(imgNight), 0.5 * brightness(img0));
  for (const auto& [args, says] : {std::pair{"--frames 2 --beaufort 13", "--beaufort 13 is not a Beaufort number"},
                                   std::pair{"--frames 2 --sun 0,nan", "--sun AZ,EL: 'nan' is not a number"},
                                   std::pair{"--frames 2 --time 1e13", "--time 1e+13 s is outside"},
                                   std::pair{"--frames 2 --reflection-size 1", "--reflection-size: 1"}}) {
    const auto r = view(args);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
  }
}

// `geocean fly --hud` (headless EGL, no X server): the same HUD in the PNGs.
// Frames are deterministic, so away from the panel the pictures with and
// without it are the same, and the panel's text changes many pixels.
TEST(FlyHud, DrawsTheHudIntoThePngsAndNothingElse) {
  const std::string withHud = tempPath("fly_hud"), noHud = tempPath("fly_nohud");
  const std::string common = " fly --to 36.0,-5.6 --frames 3 --size 320x180 --out ";
  auto r = geocean::test::run(kGeocean + common + withHud + " --hud");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = geocean::test::run(kGeocean + common + noHud);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* frame : {"/frame_00000.png", "/frame_00002.png"}) {
    const auto img = geocean::raster::readImage8(withHud + frame), bare = geocean::raster::readImage8(noHud + frame);
    ASSERT_EQ(img.width, 320);
    ASSERT_EQ(bare.width, 320);
    ASSERT_EQ(img.channels, bare.channels);
    const auto [rightDiff, panelText] = hudDiff(img, bare);
    EXPECT_LE(rightDiff, 1) << frame;
    EXPECT_GT(panelText, 300) << frame;
  }
}

// No display at all (not even Xvfb): view says so and suggests `render`.
TEST(ViewWindow, WithoutADisplaySaysSoAndSuggestsRender) {
  const auto r = geocean::test::run("env -u DISPLAY -u WAYLAND_DISPLAY " + kGeocean + " view --fly-to 36,-5.6");
  EXPECT_EQ(r.exitCode, 4);
  EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("geocean render"), std::string::npos) << r.err;
}

}  // namespace

// Issue 15: `view --coast-region` as render and fly have it: the sea under
// the camera at the end of a --fly-to (the viewer's own query through the
// plugin) is the CLI query's with the same region, and another surface
// than without it (off the Dutch coast, 20 to 30 m deep); a bad use exits 2
// naming it.
TEST(ViewWindow, CoastRegionMakesTheViewedSeaTheQueriedOne) {
  REQUIRE_XVFB();
  const std::string sea = " --waves gerstner --wind 12 --wind-dir 270";
  const int frames = 3;
  auto lastSea = [&](const std::string& extra, const std::string& name) {
    const std::string stats = tempPath(name + ".csv");
    const auto r = view("--size 96x54 --no-hud --fly-to 52.6,4.45 --frames " + std::to_string(frames) + sea + extra +
                        " --stats " + stats);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const auto rows = readStats(stats);
    return rows.empty() ? std::nan("") : rows.back().seaM;
  };
  const double with = lastSea(" --coast-region 52.6,4.45,20000", "coast"), without = lastSea("", "no_coast");
  ASSERT_TRUE(std::isfinite(with) && std::isfinite(without));
  const std::string t = std::to_string((frames - 1) / 30.0);
  const auto f = queryRow(sea + " --coast-region 52.6,4.45,20000 --time " + t + " 52.6 4.45");
  std::printf("sea under the camera: %.4f m with the region (query %s m), %.4f m without\n", with, f[5].c_str(), without);
  EXPECT_NEAR(with, std::stod(f[5]), 5.1e-5);  // the CSV's 4 decimals
  EXPECT_GT(std::abs(with - without), 0.01) << "the coast region changes the sea there";
  const auto bad = view("--frames 2 --coast-region 52.6,4.45");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("GEOCEAN_WAVES_GERSTNER"), std::string::npos) << bad.err;
}

// The user's rasters in the window (issue 12 item 1): `view --mask` and
// `view --elevation` put layers over the default world, and the sea under
// the camera (what the HUD and --stats show, the plugin's query of the
// drawn stack) follows them as `geocean query` with the same files does.
// Two points the 5' default world calls open sea: one under a user's mask
// patch of land (0.2 degrees square, 15" cells), one on the flank of a
// user's relief island (tests/support/IslandRelief.h, the render test's:
// 31 m high 0.13 degrees east of its peak), where the relief, finer than
// every mask, decides land. Without the layers both answer a sea height.
TEST(ViewWindow, TheUsersMaskAndReliefDecideWhatIsSeaUnderTheCamera) {
  REQUIRE_XVFB();
  namespace gr = geocean::raster;
  const std::string dir = tempPath("layers");
  std::filesystem::create_directories(dir);
  const double step = 1.0 / 240.0;
  gr::GeoTiffWriteOptions wo;
  const std::string mask = dir + "/land_patch.tif", relief = dir + "/island.tif";
  {
    std::vector<std::uint8_t> px(48 * 48, 1);  // 1 = land (the default encoding 0=ocean,1=land,2=lake)
    wo.transform = {0.5, 0.1, step, -step, false};
    gr::writeGeoTiff(mask, px.data(), 48, 48, 1, gr::SampleType::U8, wo);
  }
  geocean::test::writeIslandRelief(relief);
  const int frames = 3;
  const std::string t = std::to_string((frames - 1) / 30.0);
  auto lastSea = [&](const std::string& at, const std::string& layers, const std::string& name) {
    const std::string stats = tempPath(name + ".csv");
    const auto r = view("--size 96x54 --no-hud --fly-to " + at + " --frames " + std::to_string(frames) + layers +
                        " --stats " + stats);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const auto rows = readStats(stats);
    return rows.empty() ? -1e9 : rows.back().seaM;  // -1e9: no row (the failure is reported above)
  };
  // Surface class and sea height (fields 3 and 6) of `geocean query`.
  auto query = [&](const std::string& lat, const std::string& lon, const std::string& layers) {
    return queryRow("--time " + t + layers + " " + lat + " " + lon);
  };
  struct Case {
    std::string lat, lon, layers, name;
  };
  for (const Case& c : {Case{"0.0", "0.6", " --mask " + mask, "mask"},
                        Case{"0.25", "0.38", " --elevation " + relief, "relief"}}) {
    SCOPED_TRACE(c.name);
    const double with = lastSea(c.lat + "," + c.lon, c.layers, c.name), without = lastSea(c.lat + "," + c.lon, "", c.name + "_none");
    const auto qWith = query(c.lat, c.lon, c.layers), qWithout = query(c.lat, c.lon, "");
    EXPECT_EQ(qWith[2], "land");
    EXPECT_TRUE(std::isnan(with)) << "the view shows a sea height " << with << " where the user's layer is land";
    EXPECT_EQ(qWithout[2], "ocean");
    ASSERT_TRUE(std::isfinite(without));
    EXPECT_NEAR(without, std::stod(qWithout[5]), 5.1e-5);  // the CSV's 4 decimals
  }
}

// The panel's "raster layers shown" (issue 13 item 8) as a user drives it:
// key 1 (the panel's first layer, a checkbox there too) hides the user's
// mask and key 1 again shows it, while the camera hangs 2 km over a point
// the 5' default world calls open sea and the user's mask patch calls land.
// The sea under the camera (the plugin's query of the drawn stack, in
// --stats and the window's title) goes land -> the queried sea of the
// default world -> land: the ocean's stack and the host's world change
// together. The keys wait on the title (xdotool search --sync), so a slow
// machine only takes longer.
TEST(ViewWindow, KeyOneHidesAndShowsTheUsersMaskInTheQueriedSea) {
  REQUIRE_XVFB();
  if (!geocean::test::haveTool("xdotool")) GTEST_SKIP() << "xdotool is not installed (Debian xdotool, in quickstart.sh)";
  namespace gr = geocean::raster;
  const std::string dir = tempPath("toggle");
  std::filesystem::create_directories(dir);
  const std::string mask = dir + "/land_patch.tif", stats = dir + "/stats.csv";
  {
    const double step = 1.0 / 240.0;
    std::vector<std::uint8_t> px(48 * 48, 1);  // land, 0.2 degrees square from (0.1 N, 0.5 E)
    gr::GeoTiffWriteOptions wo;
    wo.transform = {0.5, 0.1, step, -step, false};
    gr::writeGeoTiff(mask, px.data(), 48, 48, 1, gr::SampleType::U8, wo);
  }
  std::filesystem::remove(stats);
  const std::string script =
      kGeocean + " view --camera 0.0,0.6,2000,0,-90 --mask " + mask +
      " --frames 100000 --size 96x54 --no-hud --stats " + stats +
      " & v=$!; "
      "timeout 120 xdotool search --sync --onlyvisible --name Geocean >/dev/null; "
      "timeout 120 xdotool search --sync --name \"sea +land\" >/dev/null; xdotool key 1; "
      "timeout 120 xdotool search --sync --name \"sea +[-+][0-9]\" >/dev/null; xdotool key 1; "
      "timeout 120 xdotool search --sync --name \"sea +land\" >/dev/null; sleep 1; "
      "xdotool key Escape; wait $v";
  const auto r = geocean::test::runUnderXvfb("640x480x24", "sh -c '" + script + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = readStats(stats);
  ASSERT_GT(rows.size(), 3u);
  // Runs of land (NaN) and sea (finite) frames, in order.
  std::vector<bool> runs;
  const StatsRow* sea = nullptr;
  for (const StatsRow& row : rows) {
    const bool isSea = std::isfinite(row.seaM);
    if (runs.empty() || runs.back() != isSea) runs.push_back(isSea);
    if (isSea && !sea) sea = &row;
  }
  EXPECT_EQ(runs, (std::vector<bool>{false, true, false})) << "land, then sea with the mask hidden, then land";
  ASSERT_NE(sea, nullptr);
  // The hidden mask's frame answers what `geocean query` without it does.
  char t[32];
  std::snprintf(t, sizeof t, "%.17g", sea->frame / 30.0);
  const auto q = queryRow(std::string("--time ") + t + " 0.0 0.6");
  EXPECT_EQ(q[2], "ocean");
  EXPECT_NEAR(sea->seaM, std::stod(q[5]), 5.1e-5);  // the CSV's 4 decimals
}
