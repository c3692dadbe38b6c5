// `geocean float` end to end: a box at Archimedes' draft (sea and fresh
// water), the columns and JSON keys, several bodies (repeated options and a
// scene file), thrust along the heading, each wave model moving the draft,
// and bad input (exit 2, the message naming the option and the value).
#include "globe/raster/GeoTiffWriter.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using geocean::test::run;

namespace {
const std::string kGeocean = GEOCEAN_EXE;

using Row = std::map<std::string, std::string>;
std::vector<Row> csv(const std::string& out) {
  std::istringstream in(out);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  std::stringstream hs(line);
  for (std::string x; std::getline(hs, x, ',');) head.push_back(x);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row r;
    std::stringstream ls(line);
    std::size_t i = 0;
    for (std::string x; std::getline(ls, x, ','); ++i) r[i < head.size() ? head[i] : "?"] = x;
    EXPECT_EQ(i, head.size()) << line;
    rows.push_back(r);
  }
  return rows;
}
double num(const Row& r, const char* k) { return std::stod(r.at(k)); }
}  // namespace

TEST(FloatCli, BoxFloatsAtArchimedesDraftWithEveryColumn) {
  auto r = run(kGeocean + " float --body box:6x3x2 --density 600 --at 30,-40 --seconds 20 --every 5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csv(r.out);
  ASSERT_EQ(rows.size(), 5u);
  for (const char* k : {"t_s", "id", "lat", "lon", "height_m", "draft_m", "roll_deg", "pitch_deg", "heading_deg",
                        "speed_mps", "grounded"})
    EXPECT_TRUE(rows[0].count(k)) << k;
  const double draft = 600.0 / 1025.0 * 2.0;  // (rho_b / rho_w) H
  EXPECT_NEAR(num(rows.back(), "draft_m"), draft, 0.005 * draft);
  EXPECT_NEAR(num(rows.back(), "height_m"), 1.0 - draft, 0.005 * draft);
  EXPECT_EQ(rows.back().at("grounded"), "false");
  EXPECT_NEAR(num(rows.back(), "t_s"), 20.0, 1e-9);
  // Fresh water (--water-density 1000), --waves none said aloud, another
  // step: the body starts at, and after 20 s still floats at, the draft
  // (rho_b / rho_w) H of that water (sea water's forces would lift it to 1.17 m).
  r = run(kGeocean + " float --body box:6x3x2 --density 600 --at 30,-40 --seconds 20 --every 20"
                     " --water-density 1000 --waves none --dt 0.02");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto fresh = csv(r.out);
  ASSERT_EQ(fresh.size(), 2u);  // t = 0 and 20
  EXPECT_NEAR(num(fresh.back(), "draft_m"), 1.2, 0.005 * 1.2);
}

TEST(FloatCli, JsonSeveralBodiesAndASceneFile) {
  auto r = run(kGeocean + " float --body box:4x4x2 --at 30,-40 --body cylinder:1x3 --at 30.01,-40 --density 500,"
                          " --density 300 --seconds 2 --format json 2>&1");
  EXPECT_NE(r.exitCode, 0);  // "500," is not a number
  r = run(kGeocean + " float --body box:4x4x2 --at 30,-40 --body cylinder:1x3 --at 30.01,-40 --density 500"
                     " --density 300 --seconds 2 --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int lines = 0;
  std::istringstream in(r.out);
  for (std::string l; std::getline(in, l); ++lines) {
    EXPECT_EQ(l.front(), '{');
    EXPECT_NE(l.find("\"draft_m\":"), std::string::npos);
    EXPECT_NE(l.find("\"grounded\":false"), std::string::npos);
  }
  EXPECT_EQ(lines, 6);  // 2 bodies x 3 output times
  const std::string scene = std::string(GEOCEAN_BINARY_DIR) + "/float_scene_test.csv";
  {
    std::ofstream f(scene);
    f << "body,density,lat,lon,heading,thrust\n# two boats\nboat:12,400,30,-40,90,5000\nbox:3x2x1,500,30.01,-40\n";
  }
  r = run(kGeocean + " float --scene " + scene + " --seconds 30 --every 30 --no-world");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csv(r.out);
  ASSERT_EQ(rows.size(), 4u);
  // The boat under thrust heads east (heading 90) and moves; the box does
  // not. A bare hull (no keel, no rudder) is directionally unstable: its yaw
  // wanders from rounding-level asymmetry (7 degrees in 30 s measured).
  EXPECT_GT(num(rows[2], "speed_mps"), 0.5);
  EXPECT_NEAR(num(rows[2], "heading_deg"), 90.0, 15.0);
  EXPECT_GT(num(rows[2], "lon"), -40.0);
  EXPECT_LT(num(rows[3], "speed_mps"), 0.01);
}

TEST(FloatCli, WavesMoveTheDraft) {
  auto r = run(kGeocean + " float --body boat:20 --density 400 --at 30,-40 --waves gerstner --wind 12"
                          " --seconds 20 --every 0.5 --no-world");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  double lo = 1e9, hi = -1e9;
  for (const auto& row : csv(r.out)) {
    lo = std::min(lo, num(row, "height_m")), hi = std::max(hi, num(row, "height_m"));
    EXPECT_LT(std::abs(num(row, "roll_deg")), 45.0);
  }
  EXPECT_GT(hi - lo, 0.3);  // a 12 m/s sea (Hs ~3 m) lifts and drops the boat
  // The other wave models of --waves too (shorter: FFT synthesises its
  // tables at every step's time).
  for (const char* model : {"noise", "fft"}) {
    r = run(kGeocean + " float --body boat:20 --density 400 --at 30,-40 --waves " + model +
            " --wind 12 --seconds 8 --every 0.5 --no-world");
    ASSERT_EQ(r.exitCode, 0) << model << ": " << r.err;
    lo = 1e9, hi = -1e9;
    for (const auto& row : csv(r.out)) lo = std::min(lo, num(row, "height_m")), hi = std::max(hi, num(row, "height_m"));
    EXPECT_GT(hi - lo, 0.3) << model;
    std::printf("[ measured ] %s: the boat's centre of mass rose and fell over %.2f m in 8 s\n", model, hi - lo);
  }
}

TEST(FloatCli, BadInputNamesTheOptionAndTheValue) {
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"--body box:-1x2x2 --density 500 --at 30,-40", "size -1 m must be > 0"},
      {"--body box:1x2 --density 500 --at 30,-40", "expected box:LxBxH"},
      {"--body raft:3 --density 500 --at 30,-40", "kind 'raft'"},
      {"--body box:1x1x1 --density nan --at 30,-40", "--density 'nan' is not a finite number"},
      {"--body box:1x1x1 --density -3 --at 30,-40", "--density -3 kg/m^3 must be > 0"},
      {"--body box:1x1x1 --density 2000 --at 30,-40", "it would sink"},
      {"--body box:1x1x1 --density 500 --at 95,0", "--at"},
      {"--body box:1x1x1 --density 500 --at 47,8", "is land, not ocean"},
      {"--body box:1x1x1 --density 500 --at 30,-40 --waves tsunami", "--waves 'tsunami'"},
      {"--body box:1x1x1 --body box:1x1x1 --density 500 --at 30,-40", "--at is given 1 times for 2 --body"},
      {"--body box:1x1x1 --density 500 --at 30,-40 --dt 0", "--dt 0 s must be > 0"},
      {"--body box:1x1x1 --density 500 --at 30,-40 --format xml", "--format 'xml'"},
      {"--scene /nonexistent.csv", "cannot be read"},
      {"--at 30,-40", "give --body"},
  };
  for (const auto& c : cases) {
    auto r = run(kGeocean + " float " + c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
  }
}

TEST(FloatCli, GroundedComesFromTheHullTouchingTheTerrain) {
  // test_beach.cpp's synthetic beach as an elevation GeoTIFF (2e-5 degree
  // cells, the ground rising 1 in 10 to the east through the waterline at
  // longitude 0; sea where it is below 0): an 8 x 3 x 2 m box of density
  // 500 (draft 1 m) 150 m out, its 3 kN engine pushing it east. Afloat it
  // is not grounded; stopped on the beach (the terrain contact on its hull)
  // it is.
  const int w = 1000, h = 500;
  const double step = 2e-5, mPerDeg = 111319.49;  // WGS84 equator: a pi / 180
  std::vector<float> px(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      px[std::size_t(y) * w + x] = float(std::clamp((-0.01 + (x + 0.5) * step) * mPerDeg / 10.0, -20.0, 10.0));
  geocean::raster::GeoTiffWriteOptions wo;
  wo.transform.originLonDeg = -0.01, wo.transform.originLatDeg = 0.005;
  wo.transform.lonStepDeg = step, wo.transform.latStepDeg = -step;
  const std::string tif = ::testing::TempDir() + "/float_beach.tif";
  geocean::raster::writeGeoTiff(tif, px.data(), w, h, 1, geocean::raster::SampleType::F32, wo);
  const std::string at = "0," + std::to_string(-150.0 / mPerDeg);
  auto r = run(kGeocean + " float --no-default-world --elevation " + tif + " --body box:8x3x2 --density 500 --at " +
               at + " --heading 90 --thrust 3000 --seconds 160 --every 10");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = csv(r.out);
  ASSERT_EQ(rows.size(), 17u);
  EXPECT_EQ(rows[0].at("grounded"), "false");  // afloat at its draft in 15 m of water
  EXPECT_EQ(rows[3].at("grounded"), "false");  // under way, 30 s in
  EXPECT_GT(num(rows[3], "speed_mps"), 1.0);
  // Stopped at the shore (test_beach: within 14 m of the waterline, at rest).
  EXPECT_EQ(rows.back().at("grounded"), "true");
  EXPECT_LT(num(rows.back(), "speed_mps"), 0.05);
  EXPECT_GT(num(rows.back(), "lon") * mPerDeg, -14.0);
  EXPECT_LT(num(rows.back(), "lon") * mPerDeg, 4.0);
  // --no-world means no rasters at all: layers with it are refused.
  r = run(kGeocean + " float --no-world --elevation " + tif + " --body box:8x3x2 --density 500 --at " + at);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--no-world takes no --mask, --elevation"), std::string::npos) << r.err;
}
