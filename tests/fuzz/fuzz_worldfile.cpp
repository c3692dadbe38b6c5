// libFuzzer: any text as the ESRI world file (.tfw) beside a small TIFF with
// no GeoTIFF tags, through Raster::open (globe/raster/GeoTiff.cpp
// readWorldFile -> GeoTransform), then the transform's pixel mapping and
// samples at points everywhere. Contract: the raster opens or Raster::open
// throws RasterError; no other exception, no undefined behaviour (a world
// file can say anything: 1e308-degree pixels, denormals, inf, nan).
#include "globe/raster/Raster.h"
#include "tests/fuzz/FuzzSupport.h"

#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

using geocean::raster::Raster;
using geocean::raster::RasterError;

namespace {
const double kLat[] = {0.0, 45.5, -33.3, 89.999, -90.0, 90.0, 12.25, -0.001, 95.0, -1e9, 1e300};
const double kLon[] = {0.0, -179.99, 180.0, 359.9, -180.0, 10.5, -45.0, 200.0, 361.0, 1e12, -1e300};
constexpr int kPoints = sizeof kLat / sizeof kLat[0];
constexpr int kW = 8, kH = 4;

// An 8 x 4 float32 TIFF with no georeferencing tags at all.
void writePlainTiff(const std::string& path) {
  TIFF* t = TIFFOpen(path.c_str(), "w");
  if (!t) std::abort();
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, kW);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, kH);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 32);
  TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, kH);
  std::vector<float> row(kW);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) row[x] = float(x + 10 * y) - 5.0f;
    if (TIFFWriteScanline(t, row.data(), y, 0) < 0) std::abort();
  }
  TIFFClose(t);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string image = [] {
    std::string p = geocean::fuzz::scratchPath("worldfile", ".tif");
    writePlainTiff(p);
    return p;
  }();
  static const std::string world = [] {
    std::string p = image.substr(0, image.size() - 4) + ".tfw";
    geocean::fuzz::scratchPath("worldfile", ".tfw");  // removed at exit
    return p;
  }();
  geocean::fuzz::writeFile(world, data, size);
  try {
    auto r = Raster::open(image);
    const auto& t = r->transform();
    double acc = 0;
    for (int i = 0; i < kPoints; ++i) {
      acc += t.pixelX(kLon[i]) + t.pixelY(kLat[i]) + t.lonOf(i) + t.latOf(-i);
      acc += r->sampleNearest(kLat[i], kLon[i]) + r->sampleBilinear(kLat[i], kLon[i]);
    }
    float out[kPoints];
    r->sampleNearestBatch(kLat, kLon, kPoints, out);
    r->sampleBilinearBatch(kLat, kLon, kPoints, out);
    // Kept alive; NaN and inf are valid answers here.
    volatile double sink = acc + out[0];
    (void)sink;
  } catch (const RasterError&) {
    // The documented way to refuse a world file.
  }
  return 0;
}
