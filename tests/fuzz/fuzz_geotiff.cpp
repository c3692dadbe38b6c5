// libFuzzer: any bytes as a .tif through Raster::open (libtiff: directory,
// GeoTIFF tags and GeoKeys, GDAL_NODATA, strips/tiles, sample formats), then
// samples at points everywhere on the Earth. Contract (globe/raster/Raster.h):
// the file either opens or throws RasterError; no other exception, no memory
// error, no undefined behaviour, no hang, bounded memory.
#include "globe/raster/Raster.h"
#include "tests/fuzz/FuzzSupport.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

using geocean::raster::Georef;
using geocean::raster::OpenOptions;
using geocean::raster::Raster;
using geocean::raster::RasterError;

namespace {
// Points at the corners, poles, antimeridian and beyond the valid range.
const double kLat[] = {0.0, 45.5, -33.3, 89.999, -90.0, 90.0, 12.25, -0.001, 95.0, -1e9};
const double kLon[] = {0.0, -179.99, 180.0, 359.9, -180.0, 10.5, -45.0, 200.0, 361.0, 1e12};
constexpr int kPoints = sizeof kLat / sizeof kLat[0];

void exercise(const Raster& r) {
  float sum = 0;
  for (int c = 0; c < r.channels(); ++c) {
    for (int i = 0; i < kPoints; ++i) {
      sum += r.sampleNearest(kLat[i], kLon[i], c);
      sum += r.sampleBilinear(kLat[i], kLon[i], c);
    }
    float out[kPoints];
    r.sampleNearestBatch(kLat, kLon, kPoints, out, c);
    r.sampleBilinearBatch(kLat, kLon, kPoints, out, c);
    sum += out[0];
    sum += r.pixel(0, 0, c) + r.pixel(r.width() - 1, r.height() - 1, c) + r.pixel(-5, 1 << 30, c);
  }
  // Keep the samples alive (a NaN is a valid answer).
  volatile float sink = sum;
  (void)sink;
  if (r.memoryBytes() == 0 && r.inMemory()) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = geocean::fuzz::scratchPath("geotiff", ".tif");
  geocean::fuzz::writeFile(path, data, size);
  OpenOptions o;
  // A fuzzer's budget, not the library's: reject more than 4 M samples
  // before allocating (the library's own check, with a smaller limit).
  o.maxPixels = std::int64_t(1) << 22;
  // The input's length picks the read path, so every path sees every file shape.
  switch (size % 4) {
    case 0: break;                                   // decoded into memory
    case 1: o.fewLookups = true; break;              // libtiff tile reads
    case 2: o.inMemoryLimitBytes = 0; o.cacheBytes = 1 << 20; break;  // streamed: libtiff blocks, ImageCache over 256 KB
    case 3: o.georef = Georef::GlobalEquirect; break;
  }
  try {
    auto r = Raster::open(path, o);
    exercise(*r);
  } catch (const RasterError&) {
    // The documented way to refuse a file.
  }
  return 0;
}
