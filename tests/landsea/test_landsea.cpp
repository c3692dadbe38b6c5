// Land/sea/lake classification on the default world against known places
// and against GMT's gmtselect (GSHHG polygons, an independent implementation).
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/World.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/landsea/LayeredLandSea.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <unistd.h>
#include <random>
#include <sstream>

using namespace geocean;
using ocean::Surface;

namespace {
std::shared_ptr<const raster::Raster> defaultMask() {
  static auto m = raster::Raster::open(raster::defaultWorld().mask);
  return m;
}
std::shared_ptr<const raster::Raster> defaultElevation() {
  static auto e = raster::Raster::open(raster::defaultWorld().elevation);
  return e;
}
}  // namespace

TEST(LandSea, KnownPlacesOnTheDefaultWorld) {
  const ocean::LandSea ls(defaultMask(), defaultElevation());
  // Spot checks published with the source mask (data/README.md) and a few more.
  struct Place {
    const char* name;
    double lat, lon;
    Surface s;
  } places[] = {
      {"Sahara", 23, 10, Surface::Land},          {"Pacific", 0, -150, Surface::Ocean},
      {"Lake Victoria", -1, 33, Surface::Lake},   {"Caspian Sea", 42, 50.5, Surface::Lake},
      {"Lake Superior", 47.7, -87.5, Surface::Lake}, {"Greenland", 75, -40, Surface::Land},
      {"Atlantic", 30, -40, Surface::Ocean},      {"Mariana Trench", 11.35, 142.2, Surface::Ocean},
      {"Point Nemo", -48.88, -123.39, Surface::Ocean}, {"Antarctica (South Pole)", -90, 0, Surface::Land},
      {"Arctic Ocean (North Pole)", 90, 0, Surface::Ocean}, {"Fiji Sea, lon 180", -17, 180, Surface::Ocean},
      {"Chukotka, lon -180 side", 67, -179.9, Surface::Land}, {"Mount Everest", 27.99, 86.93, Surface::Land},
  };
  for (const auto& p : places) EXPECT_EQ(ls.classify(p.lat, p.lon), p.s) << p.name;
  EXPECT_LT(ls.elevationM(11.35, 142.2), -5000.0f);  // Mariana Trench at 20' resolution
  EXPECT_GT(ls.elevationM(27.99, 86.93), 3000.0f);   // Himalaya at 20' resolution
}

TEST(LandSea, AgreesWithGmtSelectAwayFromCoasts) {
  if (!geocean::test::haveTool("gmt")) GTEST_SKIP() << "gmt not installed";
  const ocean::LandSea ls(defaultMask(), nullptr);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> z(-1, 1), lon(-180, 180);
  std::vector<double> la, lo;
  std::ostringstream pts;
  pts.precision(10);
  for (int i = 0; i < 4000; ++i) {  // uniform on the sphere within 60 deg: GSHHG low and high define
    // Antarctica differently (ice front vs grounding line), so the ice shelves are left out
    const double lat = std::asin(z(rng) * std::sin(60 * M_PI / 180)) * 180 / M_PI;
    la.push_back(lat);
    lo.push_back(lon(rng));
    pts << lo.back() << ' ' << la.back() << ' ' << i << '\n';
  }
  // -Dl: GSHHG low resolution (Debian gmt-gshhg-low); keep only ocean points.
  auto r = geocean::test::run("gmt gmtselect -Dl -Nk/s/s/s/s -fg", pts.str());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<bool> gmtOcean(la.size(), false);
  std::istringstream in(r.out);
  double a, b;
  int id;
  while (in >> a >> b >> id) gmtOcean[std::size_t(id)] = true;
  int disagree = 0, disagreeFar = 0;
  for (std::size_t i = 0; i < la.size(); ++i) {
    const bool ours = ls.classify(la[i], lo[i]) == Surface::Ocean;
    if (ours == gmtOcean[i]) continue;
    ++disagree;
    // A point is "away from the coast" if every mask cell within 0.25 deg
    // has the same class: there the two shorelines cannot differ.
    bool uniform = true;
    for (double dy = -0.25; dy <= 0.25; dy += 1.0 / 12)
      for (double dx = -0.25; dx <= 0.25; dx += 1.0 / 12)
        uniform &= (ls.classify(la[i] + dy, lo[i] + dx) == Surface::Ocean) == ours;
    disagreeFar += uniform;
    if (uniform) ADD_FAILURE() << "far from coast: " << la[i] << "," << lo[i] << " ours ocean=" << ours;
  }
  // Near coasts, GSHHG low (~1 km generalised) and the 5' raster of GSHHG high
  // differ; away from them they must agree exactly (lakes aside: the low
  // database omits small lakes, which our mask has as lakes, not ocean).
  EXPECT_EQ(disagreeFar, 0);
  EXPECT_LT(disagree, 4000 * 3 / 100) << disagree;  // coastal cells: < 3% of the globe at 5'
}

TEST(LandSea, BatchEqualsSingleAndMaskAloneIsEnough) {
  const ocean::LandSea maskOnly(defaultMask(), nullptr);
  const ocean::LandSea both(defaultMask(), defaultElevation());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ulat(-90, 90), ulon(-180, 180);
  std::vector<double> la(10000), lo(10000);
  for (std::size_t i = 0; i < la.size(); ++i) {
    la[i] = ulat(rng);
    lo[i] = ulon(rng);
  }
  std::vector<Surface> a(la.size()), b(la.size());
  maskOnly.classifyBatch(la.data(), lo.data(), la.size(), a.data());
  both.classifyBatch(la.data(), lo.data(), la.size(), b.data());
  for (std::size_t i = 0; i < la.size(); ++i) {
    ASSERT_EQ(a[i], maskOnly.classify(la[i], lo[i]));
    ASSERT_EQ(a[i], b[i]);  // the mask decides wherever it has data
  }
  EXPECT_TRUE(std::isnan(maskOnly.elevationM(0, 0)));
}

TEST(LandSea, ElevationAloneGivesOceanBelowSeaLevel) {
  const ocean::LandSea elevOnly(nullptr, defaultElevation());
  EXPECT_EQ(elevOnly.classify(0, -150), Surface::Ocean);
  EXPECT_EQ(elevOnly.classify(23, 10), Surface::Land);
  EXPECT_EQ(elevOnly.classify(11.35, 142.2), Surface::Ocean);
}

TEST(LandSea, CoverageIsSmoothAcrossTheCoast) {
  const ocean::LandSea ls(defaultMask(), nullptr);
  EXPECT_EQ(ls.waterCoverage(0, -150), 1.0f);
  EXPECT_EQ(ls.waterCoverage(23, 10), 0.0f);
  // Walk west from Portugal into the Atlantic at 40 N: coverage rises from 0
  // to 1 in steps no bigger than the step/cell ratio allows (twice it; the
  // cubic B-spline's slope is at most 2/3 per cell along an axis).
  float prev = ls.waterCoverage(40.0, -7.0);
  EXPECT_EQ(prev, 0.0f);
  const double step = 0.001;  // degrees; one 5' cell is 0.0833 degrees
  bool crossed = false;
  for (double lon = -7.0; lon > -11.0; lon -= step) {
    const float c = ls.waterCoverage(40.0, lon);
    EXPECT_LE(std::abs(c - prev), 2 * step / (1.0 / 12) + 1e-4) << lon;
    crossed |= c > 0.5f && prev <= 0.5f;
    prev = c;
  }
  EXPECT_TRUE(crossed);
  EXPECT_EQ(prev, 1.0f);
}

// The coverage rule (issue 12 item 4), brute force: the class at a point
// is world::coverageClassAt over the mask's own cells read one by one
// (no class table, no coast flags), at random points and on a fine walk
// along the coasts of Gibraltar; classify, classifyBatch, waterCoverage and
// a cached (not in-memory) mask all give it.
TEST(LandSea, ClassIsTheCoverageRuleEverywhere) {
  const auto mask = defaultMask();
  const ocean::LandSea ls(mask, nullptr);
  raster::OpenOptions cachedOpt;
  cachedOpt.inMemoryLimitBytes = 0;
  const auto cachedMask = raster::Raster::open(raster::defaultWorld().mask, cachedOpt);
  ASSERT_FALSE(cachedMask->inMemory());
  const ocean::LandSea cached(cachedMask, nullptr);
  const ocean::MaskEncoding enc;
  const auto& t = mask->transform();
  auto brute = [&](double lat, double lon) {
    double px = t.pixelX(lon);
    px -= std::floor(px / mask->width()) * mask->width();
    return world::coverageClassAt(px, t.pixelY(lat), [&](int cx, int cy) {
      cx = ((cx % mask->width()) + mask->width()) % mask->width();
      return enc.classify(mask->pixel(cx, std::clamp(cy, 0, mask->height() - 1)));
    });
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ulat(-89.0, 89.0), ulon(-180, 180), u01(0, 1);
  std::vector<double> la, lo;
  for (int i = 0; i < 100000; ++i) la.push_back(ulat(rng)), lo.push_back(ulon(rng));
  for (int i = 0; i < 100000; ++i) la.push_back(35.8 + 0.5 * u01(rng)), lo.push_back(-6.0 + u01(rng));  // the strait
  std::vector<Surface> batch(la.size());
  ls.classifyBatch(la.data(), lo.data(), la.size(), batch.data());
  int coastal = 0, differsFromNearest = 0;
  for (std::size_t i = 0; i < la.size(); ++i) {
    const world::CoverageClass b = brute(la[i], lo[i]);
    coastal += b.coverage > 0.0f && b.coverage < 1.0f;
    differsFromNearest += b.surface != enc.classify(mask->sampleNearest(la[i], lo[i]));
    // The paths compute the pixel coordinate in other roundings (a step's
    // inverse, a division): coverages differ by float rounding, and the
    // class may differ only within that of 0.5.
    ASSERT_NEAR(ls.waterCoverage(la[i], lo[i]), b.coverage, 1e-6f) << la[i] << "," << lo[i];
    if (i % 20 == 0) {
      ASSERT_NEAR(cached.waterCoverage(la[i], lo[i]), b.coverage, 1e-6f) << la[i] << "," << lo[i];
    }
    if (std::abs(b.coverage - 0.5f) < 1e-6f) continue;
    ASSERT_EQ(ls.classify(la[i], lo[i]), b.surface) << la[i] << "," << lo[i] << " coverage " << b.coverage;
    ASSERT_EQ(batch[i], b.surface) << la[i] << "," << lo[i];
    if (i % 20 == 0) {
      ASSERT_EQ(cached.classify(la[i], lo[i]), b.surface) << la[i] << "," << lo[i] << " (cached)";
    }
  }
  std::printf("%d coastal points, %d where the nearest cell's class is not the drawn one\n", coastal,
              differsFromNearest);
  EXPECT_GT(coastal, 20000);
  EXPECT_GT(differsFromNearest, 500);  // the rule is not the nearest cell
}

// Fuzz finding 6 (tests/fuzz/regressions/fuzz_capi_pixels/coverage_offset_overflow.bin):
// a global mask 1 or 2 cells wide. The 4 x 4 taps reach two cells either
// side, more than one width out, so the class table's single wrap read the
// neighbouring row's cell or before the buffer (UBSan). The truth is the
// texture's GL_REPEAT: column index modulo the width, row clamped, as
// the brute force of ClassIsTheCoverageRuleEverywhere. Rows alternate
// ocean and land, columns differ, so a tap read from the wrong cell moves
// the coverage by up to one tap's weight (1/6 and more).
TEST(LandSea, NarrowGlobalMaskWrapsEveryTap) {
  const ocean::MaskEncoding enc;
  for (const int w : {1, 2, 3}) {
    const int h = 6;
    std::vector<float> px(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) px[std::size_t(y) * w + x] = float((x + y + (x == 1 ? y / 2 : 0)) % 2);
    raster::GeoTransform gt;
    gt.originLonDeg = -180.0, gt.originLatDeg = 90.0, gt.lonStepDeg = 360.0 / w, gt.latStepDeg = -180.0 / h;
    gt.global = true;
    const auto mask = raster::Raster::fromPixels(px, w, h, 1, gt);
    const ocean::LandSea ls(mask, nullptr);
    auto brute = [&](double lat, double lon) {
      double p = gt.pixelX(lon);
      p -= std::floor(p / w) * w;
      return world::coverageClassAt(p, gt.pixelY(lat), [&](int cx, int cy) {
        return enc.classify(mask->pixel(((cx % w) + w) % w, std::clamp(cy, 0, h - 1)));
      });
    };
    int moved = 0;
    for (double lat = -89.75; lat < 90.0; lat += 0.5)
      for (double lon = -180.0; lon < 180.0; lon += 360.0 / w / 37.0) {
        const world::CoverageClass b = brute(lat, lon);
        // Same pixel coordinate up to the step's inverse vs a division: float rounding.
        ASSERT_NEAR(ls.waterCoverage(lat, lon), b.coverage, 1e-6f) << "width " << w << " at " << lat << "," << lon;
        if (std::abs(b.coverage - 0.5f) > 1e-6f) {
          ASSERT_EQ(ls.classify(lat, lon), b.surface) << "width " << w << " at " << lat << "," << lon;
        }
        moved += b.coverage > 0.0f && b.coverage < 1.0f;
      }
    EXPECT_GT(moved, 100) << "width " << w;  // the walk crosses coasts, not one class
  }
}

// A lone water cell in land is not drawn (its centre's coverage is
// (2/3)^2 = 0.44, the B-spline's centre weight squared), so it is land; a
// lone land cell in water likewise is water.
TEST(LandSea, ALoneCellFollowsTheDrawnCoverage) {
  for (const float inside : {0.0f, 1.0f}) {
    std::vector<float> px(9 * 9, inside == 0.0f ? 1.0f : 0.0f);
    px[4 * 9 + 4] = inside;
    raster::GeoTransform gt;
    gt.originLonDeg = 0.0, gt.originLatDeg = 9.0, gt.lonStepDeg = 1.0, gt.latStepDeg = -1.0;
    const ocean::LandSea ls(raster::Raster::fromPixels(px, 9, 9, 1, gt), nullptr);
    const float c = ls.waterCoverage(4.5, 4.5);
    EXPECT_NEAR(c, inside == 0.0f ? 4.0f / 9.0f : 5.0f / 9.0f, 1e-6f);
    EXPECT_EQ(ls.classify(4.5, 4.5), inside == 0.0f ? Surface::Land : Surface::Ocean);
    // Two cells away the neighbour's weight is zero.
    EXPECT_EQ(ls.waterCoverage(4.5, 6.5), inside == 0.0f ? 0.0f : 1.0f);
  }
}

TEST(LandSea, MaskEncodingOption) {
  auto e = ocean::MaskEncoding::parse("5=ocean,7=lake");
  EXPECT_EQ(e.classOf[5], Surface::Ocean);
  EXPECT_EQ(e.classOf[7], Surface::Lake);
  EXPECT_EQ(e.classOf[0], Surface::Land);
  EXPECT_THROW(ocean::MaskEncoding::parse("5=sea"), std::invalid_argument);
  EXPECT_THROW(ocean::MaskEncoding::parse("300=ocean"), std::invalid_argument);
  EXPECT_THROW(ocean::MaskEncoding::parse("x"), std::invalid_argument);
}

TEST(LandSea, NearWaterCoversEveryWaterCellAndTwoCellsAround) {
  const auto mask = defaultMask();
  const ocean::LandSea ls(mask, nullptr);
  const ocean::MaskEncoding enc;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ulat(-90, 90), ulon(-180, 180);
  std::vector<double> la(20000), lo(20000);
  for (std::size_t i = 0; i < la.size(); ++i) {
    la[i] = ulat(rng);
    lo[i] = ulon(rng);
  }
  std::vector<Surface> near(la.size());
  ls.classifyNearWaterBatch(la.data(), lo.data(), la.size(), near.data());
  const double cell = 1.0 / 12;  // the 5' mask
  for (std::size_t i = 0; i < la.size(); ++i) {
    // Brute force over the 5 x 5 cell neighbourhood (clamped at the poles),
    // by the cells' own classes (classify() answers by the coverage rule).
    bool water = false;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const double lat = std::clamp(la[i] + dy * cell, -89.99, 89.99);
        water |= enc.isWater(mask->sampleNearest(lat, lo[i] + dx * cell));
      }
    ASSERT_EQ(near[i] == Surface::Ocean, water) << la[i] << "," << lo[i];
    // What the grid may skip is never water by the coverage rule.
    if (near[i] == Surface::Land) {
      ASSERT_EQ(ls.classify(la[i], lo[i]), Surface::Land) << la[i] << "," << lo[i];
    }
  }
  // Tarifa (land at 5', one cell from the Strait) is near water; the central Sahara is not.
  const double tla[] = {36.04, 23.0}, tlo[] = {-5.6, 10.0};
  Surface t[2];
  ls.classifyNearWaterBatch(tla, tlo, 2, t);
  EXPECT_EQ(ls.classify(36.04, -5.6), Surface::Land);
  EXPECT_EQ(t[0], Surface::Ocean);
  EXPECT_EQ(t[1], Surface::Land);
}

// Regression (fuzz_capi_pixels): with an elevation raster alone, points it
// cannot sample (NaN, infinite) are land in a batch too, as classify() says;
// they used to keep whatever the caller's buffer held.
TEST(LandSea, ElevationAloneBatchSetsEveryPoint) {
  const ocean::LandSea elevOnly(nullptr, defaultElevation());
  const double nan = std::nan(""), inf = INFINITY;
  const double lat[] = {nan, 0.0, inf, 23.0, 0.0};
  const double lon[] = {0.0, -150.0, 0.0, 10.0, nan};
  Surface out[5];
  std::memset(out, 196, sizeof out);
  elevOnly.classifyBatch(lat, lon, 5, out);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(out[i], elevOnly.classify(lat[i], lon[i])) << i;
  EXPECT_EQ(out[0], Surface::Land);
  EXPECT_EQ(out[1], Surface::Ocean);
}

// ---- Poles are single points (issue 12 item 5) ----

TEST(Poles, ElevationAtAPoleDoesNotDependOnLongitude) {
  const auto w = raster::defaultWorld();
  raster::OpenOptions cached;
  cached.inMemoryLimitBytes = 0;  // the ImageCache batch path too
  for (const auto& r : {raster::Raster::open(w.elevation), raster::Raster::open(w.elevation, cached)}) {
    const ocean::LandSea ls(nullptr, r);
    for (const double pole : {-90.0, 90.0}) {
      const float at0 = ls.elevationM(pole, 0.0);
      ASSERT_FALSE(std::isnan(at0));
      std::vector<double> lat, lon;
      for (int i = 0; i < 72; ++i) lat.push_back(pole), lon.push_back(-180.0 + 5.0 * i + 0.37);
      std::vector<float> e(lat.size());
      ls.elevationBatch(lat.data(), lon.data(), lat.size(), e.data());
      for (std::size_t i = 0; i < e.size(); ++i) {
        EXPECT_EQ(e[i], at0) << pole << "," << lon[i] << (r->inMemory() ? " in memory" : " cached");
        EXPECT_EQ(ls.elevationM(pole, lon[i]), at0) << pole << "," << lon[i];
      }
    }
    // Points 2 cm apart across the South Pole (1 cm from it each side):
    // before, up to 81 m apart.
    const double oneCmDeg = 0.01 / 111694.0;
    for (double lon = -180.0; lon < 180.0; lon += 7.5) {
      const float a = ls.elevationM(-90.0 + oneCmDeg, lon), b = ls.elevationM(-90.0 + oneCmDeg, lon + 180.0);
      EXPECT_NEAR(a, b, 0.05) << lon;
    }
  }
}

TEST(Poles, TheBlendIsContinuousFromTheRowCentreToThePole) {
  // A global 10-degree raster whose polar rows are longitude ramps 0..35 and
  // 1700..1735: the pole's value is the row's upper median (18, 1718).
  std::vector<float> px(36 * 18);
  for (int y = 0; y < 18; ++y)
    for (int x = 0; x < 36; ++x) px[std::size_t(y) * 36 + x] = float(100 * y + x);
  const auto r = raster::Raster::fromPixels(px, 36, 18, 1, {-180.0, 90.0, 10.0, -10.0, true});
  for (double lon : {-175.0, -40.0, 0.0, 95.0, 179.0}) {
    EXPECT_EQ(r->sampleBilinear(90.0, lon), 18.0f) << lon;
    EXPECT_EQ(r->sampleBilinear(-90.0, lon), 1718.0f) << lon;
    EXPECT_EQ(r->sampleNearest(90.0, lon), 18.0f) << lon;
    // At the row's centre (lat 85) the row's own interpolation, untouched.
    const float centre = r->sampleBilinear(85.0, lon);
    EXPECT_NEAR(centre, r->sampleBilinear(85.0 - 1e-9, lon), 1e-3) << lon;
    // In between, a straight blend: halfway in latitude, halfway in value.
    EXPECT_NEAR(r->sampleBilinear(87.5, lon), 0.5 * (centre + 18.0), 1e-3) << lon;
  }
  // A regional raster has no pole: unchanged (NaN outside it).
  const auto regional = raster::Raster::fromPixels(px, 36, 18, 1, {-180.0, 90.0, 5.0, -5.0, false});
  EXPECT_EQ(regional->sampleNearest(89.0, -177.4), 0.0f);
  EXPECT_EQ(regional->sampleBilinear(90.0, -177.5), 0.0f);
}

TEST(Poles, TheMaskAtAPoleIsOneClass) {
  // A polar row of 25 land cells and 11 ocean cells: the pole is land at
  // every longitude, the rows' own cells just off it keep their class.
  std::vector<float> px(36 * 18, 0.0f);
  for (int x = 0; x < 25; ++x) px[std::size_t(17) * 36 + x] = 1.0f;
  const auto ring = raster::Raster::fromPixels(px, 36, 18, 1, {-180.0, 90.0, 10.0, -10.0, true});
  for (double lon = -180.0; lon < 180.0; lon += 2.5) EXPECT_EQ(ring->sampleNearest(-90.0, lon), 1.0f) << lon;
  EXPECT_EQ(ring->sampleNearest(-89.9, 175.0), 0.0f);
  const auto mask = raster::Raster::open(raster::defaultWorld().mask);
  for (double lon = -180.0; lon < 180.0; lon += 3.7) {
    EXPECT_EQ(mask->sampleNearest(-90.0, lon), 1.0f) << lon;  // Antarctica
    EXPECT_EQ(mask->sampleNearest(90.0, lon), 0.0f) << lon;   // the Arctic Ocean
  }
}

// A polar row of mixed classes: the classifier (its nearest cell and its
// 4 x 4 coverage rule) gives one class at the pole at every longitude, the
// class of the ring's majority (counted here: 27 ocean cells against 9 land
// at the north pole, 9 against 27 at the south), in memory (the
// class-byte fast path) and through the ImageCache alike; single points,
// batches, the near-water test and the coverage agree. Off the pole the
// cells keep their own class. Before, a land cell's longitude answered land
// at the north pole.
TEST(Poles, ClassifyAtAPoleIsOneClassWhateverTheLongitude) {
  constexpr int W = 36, H = 18;
  std::vector<float> px(std::size_t(W) * H, 1.0f);  // 1 land, 0 ocean (the default encoding)
  for (int x = 0; x < W; ++x) {
    px[std::size_t(x)] = x < 9 ? 1.0f : 0.0f;                  // north ring: land from -180 to -90
    px[std::size_t(H - 1) * W + x] = x < 9 ? 0.0f : 1.0f;      // south ring: ocean there
  }
  int northOcean = 0, southOcean = 0;
  for (int x = 0; x < W; ++x) northOcean += px[std::size_t(x)] == 0.0f, southOcean += px[std::size_t(H - 1) * W + x] == 0.0f;
  ASSERT_EQ(northOcean, 27);  // the ring's majority: ocean in the north, land in the south
  ASSERT_EQ(southOcean, 9);
  const raster::GeoTransform t{-180.0, 90.0, 10.0, -10.0, true};
  const std::string tif = ::testing::TempDir() + "/poles_mixed." + std::to_string(::getpid()) + ".tif";
  raster::GeoTiffWriteOptions wo;
  wo.transform = t;
  raster::writeGeoTiff(tif, px.data(), W, H, 1, raster::SampleType::F32, wo);
  raster::OpenOptions cached;
  cached.inMemoryLimitBytes = 0;
  for (const auto& mask : {raster::Raster::fromPixels(px, W, H, 1, t), raster::Raster::open(tif, cached)}) {
    const ocean::LandSea ls(mask, nullptr);
    const char* how = mask->inMemory() ? "in memory" : "cached";
    std::vector<double> lat, lon;
    for (double l = -180.0; l < 180.0; l += 1.3) lat.push_back(90.0), lon.push_back(l);
    for (double l = -180.0; l < 180.0; l += 1.3) lat.push_back(-90.0), lon.push_back(l);
    std::vector<Surface> batch(lat.size()), near(lat.size());
    ls.classifyBatch(lat.data(), lon.data(), lat.size(), batch.data());
    ls.classifyNearWaterBatch(lat.data(), lon.data(), lat.size(), near.data());
    int landCellsSeen = 0;
    for (std::size_t i = 0; i < lat.size(); ++i) {
      const Surface want = lat[i] > 0 ? Surface::Ocean : Surface::Land;
      EXPECT_EQ(ls.classify(lat[i], lon[i]), want) << lat[i] << "," << lon[i] << " " << how;
      EXPECT_EQ(batch[i], want) << lat[i] << "," << lon[i] << " " << how;
      EXPECT_EQ(ls.waterCoverage(lat[i], lon[i]), want == Surface::Land ? 0.0f : 1.0f) << lat[i] << "," << lon[i];
      if (want == Surface::Ocean) {
        EXPECT_EQ(near[i], Surface::Ocean) << lon[i] << " " << how;
      }
      // The test crossed cells of the other class in the ring.
      const int x = std::clamp(int((lon[i] + 180.0) / 10.0), 0, W - 1);
      landCellsSeen += lat[i] > 0 && px[std::size_t(x)] == 1.0f;
    }
    EXPECT_GT(landCellsSeen, 20);
    // Half a degree off the pole, in the middle of the rings' 9-cell runs
    // (lon -135, cell 4), the cells' own class: the coverage there is at
    // least 1 - 0.55^3 / 6 = 0.97 of that run's class (the one row of land
    // above the south ring weighs w0(0.45)).
    EXPECT_EQ(ls.classify(89.5, -135.0), Surface::Land) << how;
    EXPECT_EQ(ls.classify(-89.5, -135.0), Surface::Ocean) << how;
  }
  std::filesystem::remove(tif);
}

// A regional mask across the antimeridian is one piece (raster::lonNear):
// 16 x 4 cells of 0.125 degrees over 179 E .. 179 W, land on 179.5 E ..
// 179.5 W (columns 4..11), ocean beyond. The same answers whichever way
// the file states it (origin 179 or -181), in memory (the class bytes'
// fast path) or read through the ImageCache (the sampled path), one by one
// or in a batch, and the raw samples are the columns' own on both sides.
// Before, everything west of 180 was "no data here".
TEST(LandSea, ARegionalMaskAcrossTheAntimeridianAnswersOnBothSides) {
  const int w = 16, h = 4;
  std::vector<std::uint8_t> px(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) px[std::size_t(y) * w + x] = x >= 4 && x < 12 ? 1 : 0;
  std::vector<float> cols(std::size_t(w) * h);
  for (std::size_t i = 0; i < cols.size(); ++i) cols[i] = float(i % w);
  const auto colsRaster = raster::Raster::fromPixels(cols, w, h, 1, {179.0, -16.0, 0.125, -0.125, false});
  // Column 10 spans 180.25 .. 180.375, i.e. -179.75 .. -179.625.
  EXPECT_EQ(colsRaster->sampleNearest(-16.2, -179.7), 10.0f);
  EXPECT_EQ(colsRaster->sampleNearest(-16.2, 179.7), 5.0f);
  EXPECT_EQ(colsRaster->sampleNearest(-16.2, 180.3), 10.0f);
  EXPECT_NEAR(colsRaster->sampleBilinear(-16.2, -179.875), 8.5f, 1e-4f);  // halfway between the centres of 8 and 9
  EXPECT_NEAR(colsRaster->sampleBilinear(-16.2, -180.0), 7.5f, 1e-4f);    // of 7 and 8, across 180
  EXPECT_NEAR(colsRaster->sampleBilinear(-16.2, 180.0), 7.5f, 1e-4f);
  EXPECT_TRUE(std::isnan(colsRaster->sampleNearest(-16.2, -178.99)));  // past the east edge
  EXPECT_TRUE(std::isnan(colsRaster->sampleNearest(-16.2, 178.99)));   // past the west edge

  const std::string dir = ::testing::TempDir();
  const std::string pid = std::to_string(::getpid());
  std::vector<std::string> paths;
  for (const double origin : {179.0, -181.0}) {
    raster::GeoTiffWriteOptions wo;
    wo.transform = {origin, -16.0, 0.125, -0.125, false};
    wo.tileSize = 16;
    paths.push_back(dir + "/antimeridian_" + std::to_string(int(origin)) + "." + pid + ".tif");
    raster::writeGeoTiff(paths.back(), px.data(), w, h, 1, raster::SampleType::U8, wo);
  }
  // Cell centres inside the band and out, both sides; 2 cells from the band's edges.
  const std::vector<std::pair<double, Surface>> truth = {
      {179.8125, Surface::Land}, {179.9375, Surface::Land},  {-179.9375, Surface::Land},
      {-179.8125, Surface::Land},       {-179.6875, Surface::Land}, {179.0625, Surface::Ocean},
      {-179.0625, Surface::Ocean},      {-179.1875, Surface::Ocean}};
  std::vector<double> la, lo;
  for (const auto& [lon, s] : truth) la.push_back(-16.25), lo.push_back(lon);
  for (const auto& path : paths)
    for (const bool inMemory : {true, false}) {
      raster::OpenOptions o;
      if (!inMemory) o.inMemoryLimitBytes = 0;
      const auto mask = raster::Raster::open(path, o);
      ASSERT_EQ(mask->inMemory(), inMemory);
      const ocean::LandSea ls(mask, nullptr);
      std::vector<Surface> batch(la.size());
      ls.classifyBatch(la.data(), lo.data(), la.size(), batch.data());
      for (std::size_t i = 0; i < truth.size(); ++i) {
        EXPECT_EQ(ls.classify(la[i], lo[i]), truth[i].second) << path << " at " << lo[i] << " in memory " << inMemory;
        EXPECT_EQ(batch[i], truth[i].second) << path << " at " << lo[i] << " in memory " << inMemory;
        EXPECT_EQ(ls.classify(la[i], lo[i] + 360.0), truth[i].second) << "lon + 360";
      }
      // The coast crosses 0.5 coverage at the band's edges, on both sides.
      EXPECT_NEAR(ls.waterCoverage(-16.25, -179.5), 0.5f, 1e-6f);
      EXPECT_NEAR(ls.waterCoverage(-16.25, 179.5), 0.5f, 1e-6f);
      // Outside the raster: no data (the mask alone: land).
      EXPECT_TRUE(std::isnan(mask->sampleNearest(-16.25, -178.9)));
    }
  for (const auto& p : paths) std::filesystem::remove(p);
}

// A relief's cells without data (nodata) do not vote (issue 12): they take
// the layers below at their centres, as the relief's pages are drawn (a NaN
// texel takes the water grid below it, shaders/geo_uv.glsl), so near a
// relief's nodata edge the query's class is the drawn one. A regional 0.01
// degree relief: no data west of column 50, land (+20 m) north of row 50
// and sea (-20 m) south of it east of there; below it a global mask of
// ocean. Along the relief's coast within two cells of the nodata edge the
// class must be the B-spline rule with the nodata cells as ocean (what is
// drawn), where counting them as land (the query before) put ocean points
// on land.
TEST(LayeredLandSea, AReliefsNodataCellsTakeTheLayersBelowAsDrawn) {
  constexpr int W = 100, H = 100;
  constexpr float kNodata = -9999.0f;
  std::vector<float> px(std::size_t(W) * H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) px[std::size_t(y) * W + x] = x < 50 ? kNodata : y < 50 ? 20.0f : -20.0f;
  const raster::GeoTransform t{10.0, 1.0, 0.01, -0.01, false};
  const auto relief = raster::Raster::fromPixels(px, W, H, 1, t, double(kNodata));
  const auto ocean = raster::Raster::fromPixels(std::vector<float>(36 * 18, 0.0f), 36, 18, 1,
                                                {-180.0, 90.0, 10.0, -10.0, true});
  const ocean::LayeredLandSea ls({{world::LayerKind::Elevation, relief, {}, 1}, {world::LayerKind::Mask, ocean, {}, 0}});
  // The drawn rule, and the old one (nodata as land), at continuous pixel (x, y).
  const auto rule = [&](double x, double y, bool nodataIsWater) {
    return world::coverageClassAt(x, y, [&](int cx, int cy) {
      const float v = px[std::size_t(std::clamp(cy, 0, H - 1)) * W + std::size_t(std::clamp(cx, 0, W - 1))];
      return v == kNodata ? (nodataIsWater ? Surface::Ocean : Surface::Land) : v < 0.0f ? Surface::Ocean : Surface::Land;
    }).surface;
  };
  std::vector<double> la, lo;
  std::vector<Surface> want;
  int differs = 0;
  for (double x = 49.0; x <= 53.0; x += 0.05)
    for (double y = 48.0; y <= 52.0; y += 0.02) {
      la.push_back(t.latOf(y)), lo.push_back(t.lonOf(x));
      // Where the relief's bilinear sample has no data the mask below answers: ocean.
      const bool reliefAnswers = !std::isnan(relief->sampleBilinear(la.back(), lo.back()));
      want.push_back(reliefAnswers ? rule(x, y, true) : Surface::Ocean);
      differs += reliefAnswers && rule(x, y, false) != want.back();
    }
  std::vector<Surface> got(la.size());
  ls.classifyBatch(la.data(), lo.data(), la.size(), got.data());
  int wrong = 0, water = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    water += got[i] != Surface::Land;
    if (got[i] != want[i] && ++wrong <= 10)
      ADD_FAILURE() << "at " << la[i] << ", " << lo[i] << ": " << ocean::toString(got[i]) << ", drawn "
                    << ocean::toString(want[i]);
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(differs, 50) << "the points should be where nodata as land gives another class";
  EXPECT_GT(water, 1000);
  EXPECT_LT(water, int(got.size()) - 1000);
  // One point at a time (classify) answers the same.
  for (std::size_t i = 0; i < got.size(); i += 97) EXPECT_EQ(ls.classify(la[i], lo[i]), got[i]) << i;
  std::printf("%zu points, %d where nodata as land would differ from the picture\n", got.size(), differs);
}

TEST(LayeredLandSea, CellsPastARegionalReliefsEdgeTakeTheLayersBelowAsDrawn) {
  // A regional relief (land north of row 50, sea south) over an ocean mask.
  // The picture takes texels past a regional layer's edge from the layers
  // below at their centres (geo_uv.glsl pageTexel, GEOCEAN_WATER_PAGES_
  // REGIONAL); the query clamped them to the edge cells, so within the
  // B-spline's 2 cells of the edge the coast moved. Points along the
  // western edge, where the relief's bilinear sample still answers.
  constexpr int W = 100, H = 100;
  std::vector<float> px(std::size_t(W) * H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) px[std::size_t(y) * W + x] = y < 50 ? 20.0f : -20.0f;
  const raster::GeoTransform t{10.0, 1.0, 0.01, -0.01, false};
  const auto relief = raster::Raster::fromPixels(px, W, H, 1, t);
  const auto ocean = raster::Raster::fromPixels(std::vector<float>(36 * 18, 0.0f), 36, 18, 1,
                                                {-180.0, 90.0, 10.0, -10.0, true});
  const ocean::LayeredLandSea ls({{world::LayerKind::Elevation, relief, {}, 1}, {world::LayerKind::Mask, ocean, {}, 0}});
  // The drawn rule (past the edge: the ocean below) and the old one (clamped), at continuous pixel (x, y).
  const auto rule = [&](double x, double y, bool outsideIsBelow) {
    return world::coverageClassAt(x, y, [&](int cx, int cy) {
      if (outsideIsBelow && (cx < 0 || cx >= W || cy < 0 || cy >= H)) return Surface::Ocean;
      return px[std::size_t(std::clamp(cy, 0, H - 1)) * W + std::size_t(std::clamp(cx, 0, W - 1))] < 0.0f
                 ? Surface::Ocean
                 : Surface::Land;
    }).surface;
  };
  std::vector<double> la, lo;
  std::vector<Surface> want;
  int differs = 0, answered = 0;
  for (double x = -1.0; x <= 3.0; x += 0.02)
    for (double y = 47.0; y <= 51.0; y += 0.02) {
      la.push_back(t.latOf(y)), lo.push_back(t.lonOf(x));
      const bool reliefAnswers = !std::isnan(relief->sampleBilinear(la.back(), lo.back()));
      answered += reliefAnswers;
      want.push_back(reliefAnswers ? rule(x, y, true) : Surface::Ocean);
      differs += reliefAnswers && rule(x, y, false) != want.back();
    }
  std::vector<Surface> got(la.size());
  ls.classifyBatch(la.data(), lo.data(), la.size(), got.data());
  int wrong = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    if (got[i] != want[i] && ++wrong <= 10)
      ADD_FAILURE() << "at " << la[i] << ", " << lo[i] << ": " << ocean::toString(got[i]) << ", drawn "
                    << ocean::toString(want[i]);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(answered, int(got.size()) / 2);
  EXPECT_GT(differs, 50) << "the points should be where the clamped edge gives another class";
  for (std::size_t i = 0; i < got.size(); i += 89) EXPECT_EQ(ls.classify(la[i], lo[i]), got[i]) << i;
  std::printf("%zu points, %d where the clamped edge would differ from the picture\n", got.size(), differs);
}

TEST(LayeredLandSea, ARegionalMasksEdgeAndNodataCellsTakeTheLayersBelowAsDrawn) {
  // A regional mask (land north of row 50, ocean south, a block of cells
  // without data in the middle) over a global mask that is all lake. The
  // picture takes a regional mask's texels past its edge and its NaN texels
  // from the layers below at their centres (geo_uv.glsl pageTexel /
  // waterTexel); the query clamped the edge cells and counted nodata as land.
  // Points across the western edge and around the block, with the mask in
  // memory (the class table's fast path) and read through the ImageCache.
  constexpr int W = 100, H = 100;
  constexpr float kNodata = 255.0f;
  std::vector<float> px(std::size_t(W) * H);
  const auto hole = [](int x, int y) { return x >= 40 && x < 60 && y >= 40 && y < 60; };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) px[std::size_t(y) * W + x] = hole(x, y) ? kNodata : y < 50 ? 1.0f : 0.0f;
  const raster::GeoTransform t{10.0, 1.0, 0.01, -0.01, false};
  const auto lake = raster::Raster::fromPixels(std::vector<float>(36 * 18, 2.0f), 36, 18, 1,
                                               {-180.0, 90.0, 10.0, -10.0, true});
  const std::string tif = ::testing::TempDir() + "/regional_mask_edge.tif";
  raster::GeoTiffWriteOptions wo;
  wo.transform = t;
  wo.tileSize = 16;
  wo.nodata = kNodata;
  std::vector<std::uint8_t> bytes(px.begin(), px.end());
  raster::writeGeoTiff(tif, bytes.data(), W, H, 1, raster::SampleType::U8, wo);
  raster::OpenOptions cachedOpt;
  cachedOpt.inMemoryLimitBytes = 0;
  const auto inMemory = raster::Raster::fromPixels(px, W, H, 1, t, double(kNodata));
  const auto cached = raster::Raster::open(tif, cachedOpt);
  ASSERT_FALSE(cached->inMemory());
  // The drawn rule (past the edge and in the hole: the lake below) and the
  // old one (clamped edge, nodata as land), at continuous pixel (x, y).
  const auto rule = [&](double x, double y, bool drawn) {
    return world::coverageClassAt(x, y, [&](int cx, int cy) {
      if (drawn && (cx < 0 || cx >= W || cy < 0 || cy >= H)) return Surface::Lake;
      const float v = px[std::size_t(std::clamp(cy, 0, H - 1)) * W + std::size_t(std::clamp(cx, 0, W - 1))];
      return v == kNodata ? (drawn ? Surface::Lake : Surface::Land) : v == 0.0f ? Surface::Ocean : Surface::Land;
    }).surface;
  };
  std::vector<double> la, lo;
  std::vector<Surface> want;
  int differs = 0, answered = 0;
  const auto add = [&](double x, double y) {
    la.push_back(t.latOf(y)), lo.push_back(t.lonOf(x));
    // Where the mask's nearest cell has no data the lake below answers.
    const bool maskAnswers = !std::isnan(inMemory->sampleNearest(la.back(), lo.back()));
    answered += maskAnswers;
    want.push_back(maskAnswers ? rule(x, y, true) : Surface::Lake);
    differs += maskAnswers && rule(x, y, false) != want.back();
  };
  for (double x = -1.0; x <= 3.0; x += 0.02)
    for (double y = 47.0; y <= 53.0; y += 0.05) add(x, y);  // the western edge across the coast
  for (double x = 37.0; x <= 63.0; x += 0.1)
    for (double y = 37.0; y <= 63.0; y += 0.1)
      if (!(x > 42 && x < 58 && y > 42 && y < 58)) add(x, y);  // about the hole
  for (const auto& mask : {inMemory, cached}) {
    const ocean::LayeredLandSea ls({{world::LayerKind::Mask, mask, {}, 1}, {world::LayerKind::Mask, lake, {}, 0}});
    std::vector<Surface> got(la.size());
    ls.classifyBatch(la.data(), lo.data(), la.size(), got.data());
    int wrong = 0;
    for (std::size_t i = 0; i < got.size(); ++i)
      if (got[i] != want[i] && ++wrong <= 10)
        ADD_FAILURE() << (mask->inMemory() ? "in memory" : "cached") << " at " << la[i] << ", " << lo[i] << ": "
                      << ocean::toString(got[i]) << ", drawn " << ocean::toString(want[i]);
    EXPECT_EQ(wrong, 0);
    for (std::size_t i = 0; i < got.size(); i += 89) EXPECT_EQ(ls.classify(la[i], lo[i]), got[i]) << i;
  }
  EXPECT_GT(answered, int(la.size()) / 2);
  EXPECT_GT(differs, 200) << "the points should be where the old rule gives another class";
  std::printf("%zu points, %d where the clamped edge or nodata as land would differ from the picture\n", la.size(),
              differs);
}
