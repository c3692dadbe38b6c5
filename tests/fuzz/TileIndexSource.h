// The small source raster behind fuzz_tile_index and its seeds
// (make_seeds.cpp): 40 x 24 float32, pyramid tiles of 8 texels, so 4 levels
// and 9 coarse tiles of all three kinds (an all-nodata corner: Empty; a
// constant band: Constant; the rest varies: Data).
#pragma once

#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/TilePyramid.h"

#include <cmath>
#include <string>
#include <vector>

namespace geocean::fuzz {

constexpr int kTileSourceW = 40, kTileSourceH = 24, kPyramidTile = 8;

inline void writeTileIndexSource(const std::string& path) {
  std::vector<float> v(std::size_t(kTileSourceW) * kTileSourceH);
  for (int y = 0; y < kTileSourceH; ++y)
    for (int x = 0; x < kTileSourceW; ++x)
      v[std::size_t(y) * kTileSourceW + x] =
          x < 16 && y < 16 ? -9999.0f : x >= 32 ? 7.0f : 100.0f * std::sin(0.3f * float(x)) + float(y);
  raster::GeoTiffWriteOptions o;
  o.transform.originLonDeg = 10.0;
  o.transform.originLatDeg = 50.0;
  o.transform.lonStepDeg = 0.01;
  o.transform.latStepDeg = -0.01;
  o.tileSize = 16;
  o.nodata = -9999.0;
  raster::writeGeoTiff(path, v.data(), kTileSourceW, kTileSourceH, 1, raster::SampleType::F32, o);
}

inline raster::PyramidOptions tileIndexPyramidOptions(const std::string& cacheDir) {
  raster::PyramidOptions o;
  o.tileSize = kPyramidTile;
  o.cacheDir = cacheDir;
  o.progress = raster::BuildProgress::Off;
  return o;
}

}  // namespace geocean::fuzz
