// `geocean mask` (issue 12): a 3" mask of the Strait of Gibraltar from
// GSHHG's full-resolution shorelines through GMT, read back by our raster
// reader and `geocean query --mask`, checked at known places and against
// GMT's own polygon test (`gmt select`, which never sees our raster), and
// the errors for bad arguments and a missing GMT.
#include "globe/raster/Raster.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>
#include <tiffio.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using geocean::test::haveTool;
using geocean::test::run;

namespace {
namespace fs = std::filesystem;
const std::string kGeocean = GEOCEAN_EXE;
// The strait from Tarifa to Gibraltar and Ceuta; 1200 x 600 cells of 3".
const std::string kRegion = "-6/-5/35.75/36.25";
constexpr double kCellDeg = 3.0 / 3600.0;

fs::path tempDir() {
  std::string t = (fs::temp_directory_path() / "geocean-mask-test-XXXXXX").string();
  if (!mkdtemp(t.data())) throw std::runtime_error("mkdtemp");
  return t;
}

// Built once for the suite (GMT takes a few seconds).
const fs::path& gibraltarMask() {
  static const fs::path path = [] {
    const fs::path dir = tempDir();
    const fs::path out = dir / "gibraltar_3s.tif";
    const auto r = run(kGeocean + " mask --region " + kRegion + " --resolution 3s --out " + out.string());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return out;
  }();
  return path;
}

struct LonLat {
  double lon, lat;
};

// GMT's answer from the GSHHG full-resolution polygons: "land" (land or an
// island in a lake), "lake" (lake or pond), else "ocean".
std::vector<std::string> gmtClasses(const std::vector<LonLat>& pts) {
  const fs::path dir = tempDir();
  {
    std::ofstream f(dir / "pts.txt");
    f.precision(12);
    for (std::size_t i = 0; i < pts.size(); ++i) f << pts[i].lon << ' ' << pts[i].lat << ' ' << i << '\n';
  }
  std::vector<std::string> cls(pts.size(), "ocean");
  for (const auto& [sel, name] : {std::pair{"-Ns/k/s/k/s", "land"}, std::pair{"-Ns/s/k/s/k", "lake"}}) {
    // In its own directory: GMT writes gmt.history into the cwd.
    const auto r = run("cd " + dir.string() + " && gmt select pts.txt -Df -fg " + sel);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::istringstream in(r.out);
    double lo, la;
    std::size_t id;
    while (in >> lo >> la >> id) cls.at(id) = name;
  }
  fs::remove_all(dir);
  return cls;
}

std::vector<std::string> queryClasses(const std::vector<LonLat>& pts, const fs::path& mask) {
  std::ostringstream csv;
  csv.precision(12);
  for (const auto& p : pts) csv << p.lat << ',' << p.lon << '\n';
  const auto r = run(kGeocean + " query --points - --no-default-world --mask " + mask.string(), csv.str());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::vector<std::string> cls;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string f;
    for (int k = 0; k < 3 && std::getline(ls, f, ','); ++k) {
    }
    cls.push_back(f);
  }
  return cls;
}

TEST(MaskCli, GibraltarAt3sIsATiledCompressedGeoTiffOurReaderAccepts) {
  ASSERT_TRUE(haveTool("gmt")) << "GMT (Debian gmt, gmt-gshhg-full) is a build requirement";
  const fs::path& mask = gibraltarMask();
  ASSERT_TRUE(fs::exists(mask));
  const auto r = geocean::raster::Raster::open(mask.string());
  EXPECT_EQ(r->width(), 1200);
  EXPECT_EQ(r->height(), 600);
  const auto& t = r->transform();
  EXPECT_NEAR(t.originLonDeg, -6.0, 1e-9);
  EXPECT_NEAR(t.originLatDeg, 36.25, 1e-9);
  EXPECT_NEAR(t.lonStepDeg, kCellDeg, 1e-12);
  EXPECT_NEAR(t.latStepDeg, -kCellDeg, 1e-12);
  EXPECT_FALSE(t.global);
  TIFF* tif = TIFFOpen(mask.c_str(), "r");
  ASSERT_NE(tif, nullptr);
  std::uint16_t compression = 0, bits = 0;
  TIFFGetField(tif, TIFFTAG_COMPRESSION, &compression);
  TIFFGetField(tif, TIFFTAG_BITSPERSAMPLE, &bits);
  EXPECT_TRUE(TIFFIsTiled(tif));
  EXPECT_EQ(compression, COMPRESSION_ADOBE_DEFLATE);
  EXPECT_EQ(bits, 8);
  TIFFClose(tif);
  // Small: 720,000 cells of mostly uniform land and sea.
  EXPECT_LT(fs::file_size(mask), 64u * 1024u);
  // Only the mask's values, and both land and sea.
  int counts[3] = {0, 0, 0};
  for (float v : r->pixels()) {
    ASSERT_TRUE(v == 0.0f || v == 1.0f || v == 2.0f) << v;
    ++counts[int(v)];
  }
  EXPECT_GT(counts[0], 100000);
  EXPECT_GT(counts[1], 100000);
}

// Coordinates from Wikipedia's articles: Tarifa 36°00'50"N 5°36'15"W,
// Gibraltar (the town on the Rock) 36°08'N 5°21'W, the Strait of
// Gibraltar 35°58'N 5°29'W (the middle of the water). Each is at least 3
// cells (~250 m) from GMT's shoreline (checked on a ring below), so the
// mask's cells cannot blur them.
TEST(MaskCli, KnownPlacesOfTheStrait) {
  ASSERT_TRUE(haveTool("gmt"));
  const std::vector<std::pair<std::string, LonLat>> places = {
      {"Tarifa", {-(5 + 36 / 60.0 + 15 / 3600.0), 36 + 50 / 3600.0}},
      {"Gibraltar", {-(5 + 21 / 60.0), 36 + 8 / 60.0}},
      {"Strait of Gibraltar", {-(5 + 29 / 60.0), 35 + 58 / 60.0}}};
  const std::vector<std::string> expected = {"land", "land", "ocean"};
  std::vector<LonLat> pts;
  for (const auto& [name, p] : places) pts.push_back(p);
  const auto ours = queryClasses(pts, gibraltarMask());
  ASSERT_EQ(ours.size(), pts.size());
  // GMT's polygons agree, at the place and on a ring of 3 cells around it.
  std::vector<LonLat> ring;
  for (const auto& p : pts)
    for (int a = 0; a < 16; ++a)
      ring.push_back({p.lon + 3 * kCellDeg * std::cos(a * M_PI / 8) / std::cos(p.lat * M_PI / 180),
                      p.lat + 3 * kCellDeg * std::sin(a * M_PI / 8)});
  const auto gmtAt = gmtClasses(pts), gmtRing = gmtClasses(ring);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(ours[i], expected[i]) << places[i].first;
    EXPECT_EQ(gmtAt[i], expected[i]) << places[i].first << " (gmt select)";
    for (int a = 0; a < 16; ++a) EXPECT_EQ(gmtRing[i * 16 + a], expected[i]) << places[i].first << " ring " << a;
  }
}

// 1500 random points: wherever GMT's polygons give one class on a 5 x 5
// grid of half-cell steps around the point (every mask cell the point's
// coverage weighs most lies within it), `geocean query --mask` gives that
// class too. Points nearer the shore may differ by the cell size.
TEST(MaskCli, QueryAgreesWithGmtSelectAwayFromTheShore) {
  ASSERT_TRUE(haveTool("gmt"));
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> lon(-5.99, -5.01), lat(35.76, 36.24);
  std::vector<LonLat> pts, around;
  for (int i = 0; i < 1500; ++i) {
    const LonLat p{lon(rng), lat(rng)};
    pts.push_back(p);
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) around.push_back({p.lon + dx * 0.5 * kCellDeg, p.lat + dy * 0.5 * kCellDeg});
  }
  const auto ours = queryClasses(pts, gibraltarMask());
  const auto gmt = gmtClasses(around);
  ASSERT_EQ(ours.size(), pts.size());
  int checked = 0, shore = 0;
  std::map<std::string, int> byClass;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    bool uniform = true;
    for (int k = 0; k < 25; ++k) uniform &= gmt[i * 25 + k] == gmt[i * 25 + 12];
    if (!uniform) {
      ++shore;
      continue;
    }
    ++checked;
    ++byClass[gmt[i * 25 + 12]];
    EXPECT_EQ(ours[i], gmt[i * 25 + 12]) << "at " << pts[i].lat << ", " << pts[i].lon;
  }
  std::printf("checked %d points (%d land, %d ocean), %d near the shore\n", checked, byClass["land"], byClass["ocean"],
              shore);
  EXPECT_GT(byClass["land"], 300);
  EXPECT_GT(byClass["ocean"], 300);
}

TEST(MaskCli, BandsOfTileRowsGiveTheSameMask) {
  ASSERT_TRUE(haveTool("gmt"));
  const fs::path dir = tempDir();
  const fs::path out = dir / "banded.tif";
  // 5 GMT runs of 128 rows (two 64-pixel tile rows) instead of one.
  const auto r = run(kGeocean + " mask --region " + kRegion + " --resolution 3s --tile 64 --band-rows 100 --out " +
                     out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("band 5/5"), std::string::npos) << r.err;
  const auto a = geocean::raster::Raster::open(gibraltarMask().string());
  const auto b = geocean::raster::Raster::open(out.string());
  ASSERT_EQ(a->pixels().size(), b->pixels().size());
  EXPECT_TRUE(a->pixels() == b->pixels());
  fs::remove_all(dir);
}

// The whole Earth (at 1 degree, seconds): a global raster (longitude wraps),
// the Caspian Sea a lake (GSHHG level 2), the central Pacific ocean, the
// Sahara and Antarctica land.
TEST(MaskCli, GlobalMaskWrapsAndKeepsLakes) {
  ASSERT_TRUE(haveTool("gmt"));
  const fs::path dir = tempDir();
  const fs::path out = dir / "world_1d.tif";
  const auto r = run(kGeocean + " mask --global --resolution 1d --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto m = geocean::raster::Raster::open(out.string());
  EXPECT_EQ(m->width(), 360);
  EXPECT_EQ(m->height(), 180);
  EXPECT_TRUE(m->transform().global);
  const std::vector<LonLat> pts = {{-150, 0}, {10, 23}, {50.5, 42}, {0, -85}, {179.99, 70}, {-179.99, 70}, {359.99, 70}};
  const std::vector<std::string> expected = {"ocean", "land", "lake", "land", "ocean", "ocean", "ocean"};
  const auto ours = queryClasses(pts, out);
  ASSERT_EQ(ours.size(), pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(ours[i], expected[i]) << pts[i].lat << "," << pts[i].lon;
  fs::remove_all(dir);
}

TEST(MaskCli, BadArgumentsAndAMissingGmtAreClearErrors) {
  const fs::path dir = tempDir();
  const std::string out = " --out " + (dir / "m.tif").string();
  struct Case {
    std::string args, says;
    int exit;
  };
  const std::vector<Case> cases = {
      {"--region -6/-5.001/35/36 --resolution 3s", "longitude span 0.999 degrees is not a whole number of 3s cells", 2},
      {"--region -6/-5/37/36 --resolution 3s", "S=37, N=36", 2},
      {"--region -6/-5/35 --resolution 3s", "want W/E/S/N", 2},
      {"--region -6/x/35/36 --resolution 3s", "'x' is not a number", 2},
      {"--region -6/-5/35/36 --resolution 3x", "unit 'x' is not s, m or d", 2},
      {"--region -6/-5/35/36 --resolution -3s", "'-3' is not a positive number", 2},
      {"--resolution 3s", "exactly one of --region W/E/S/N and --global", 2},
      {"--global --region -6/-5/35/36 --resolution 3s", "exactly one of", 2},
      {"--global --resolution 0.01s", "finer than 0.1s", 2},
      {"--region -6/-5/35/36 --resolution 3s --gmt /nonexistent/gmt", "cannot run '/nonexistent/gmt' (GMT)", 3},
  };
  for (const auto& c : cases) {
    const auto r = run(kGeocean + " mask " + c.args + out);
    EXPECT_EQ(r.exitCode, c.exit) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "m.tif")) << c.args;
    EXPECT_FALSE(fs::exists(dir / "m.tif.partial")) << c.args;
  }
  fs::remove_all(dir);
}

}  // namespace
