// A global 30-arc-second raster (43200 x 21600, 933 M pixels) read through
// libtiff's block cache with bounded memory, sampled correctly in tile batches.
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/Raster.h"
#include "tests/support/ProcStatus.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

using namespace geocean::raster;
namespace fs = std::filesystem;

namespace {
constexpr int kW = 43200, kH = 21600;
std::uint8_t valueAt(int x, int y) { return std::uint8_t((x + 3 * y) & 255); }

using geocean::test::statusKb;
}  // namespace

TEST(RasterCache, Global30ArcSecondRasterStaysWithinTheCacheBound) {
  char tmpl[] = "/tmp/geocean-big-XXXXXX";
  const fs::path dir = mkdtemp(tmpl);
  const std::string path = (dir / "big.tif").string();
  GeoTiffWriteOptions o;
  o.transform.lonStepDeg = 360.0 / kW;
  o.transform.latStepDeg = -180.0 / kH;
  o.deflateLevel = 1;
  writeGeoTiffTiles(path, kW, kH, 1, SampleType::U8, o, [](int x0, int y0, void* tile) {
    auto* t = static_cast<std::uint8_t*>(tile);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) t[y * 256 + x] = valueAt(x0 + x, y0 + y);
  });

  // 300 k points in random order over the globe, in batches of 100 k (each
  // batch touches most of the 14 k tiles: far more than the cache holds).
  constexpr int kBatch = 100000, kBatches = 3;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ulat(-89.99, 89.99), ulon(-180, 180);
  std::vector<double> lat(kBatch), lon(kBatch);
  std::vector<float> near(kBatch), bil(kBatch);

  // Peak RSS from here on (clear_refs 5 resets VmHWM).
  { std::ofstream("/proc/self/clear_refs") << "5"; }
  const long baseKb = statusKb("VmRSS:");
  OpenOptions opt;
  opt.cacheBytes = std::size_t(64) << 20;
  auto r = Raster::open(path, opt);
  ASSERT_FALSE(r->inMemory());  // 933 M pixels as float would be 3.7 GB
  long bad = 0;
  for (int b = 0; b < kBatches; ++b) {
    for (int i = 0; i < kBatch; ++i) {
      lat[i] = ulat(rng);
      lon[i] = ulon(rng);
    }
    r->sampleNearestBatch(lat.data(), lon.data(), kBatch, near.data());
    for (int i = 0; i < kBatch; ++i) {
      const int x = int(std::floor((lon[i] + 180.0) * kW / 360.0));
      const int y = int(std::floor((90.0 - lat[i]) * kH / 180.0));
      bad += near[i] != valueAt(x, y);
    }
  }
  r->sampleBilinearBatch(lat.data(), lon.data(), kBatch, bil.data());
  for (int i = 0; i < kBatch; ++i) bad += !(std::abs(bil[i] - near[i]) <= 255.0f);
  const long peakKb = statusKb("VmHWM:");
  fs::remove_all(dir);
  EXPECT_EQ(bad, 0);
  // The bound: the 64 MB cache plus 32 MB for per-batch work arrays (sort
  // order and footprints of 100 k points, ~3.6 MB) and the decoders' buffers
  // and file handles. Loading the pixels would need 933 MB+.
  const long deltaMb = (peakKb - baseKb) / 1024;
  std::printf("peak RSS growth while sampling: %ld MB (cache 64 MB)\n", deltaMb);
  EXPECT_LT(deltaMb, 64 + 32);
}
