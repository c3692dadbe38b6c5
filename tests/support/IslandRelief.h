// The synthetic island of the drawing commands' layer tests (issue 12): a
// 290 m Gaussian peak at (0.25 N, 0.25 E) in a 200 m deep sea,
// -200 + 490 exp(-r^2 / 0.15^2) m, on 15" cells over -0.5 .. 1 degrees
// (360 x 360, F32 GeoTIFF). The 5' default mask calls the whole of it
// ocean; its relief's sign makes it an island about 30 km across.
#pragma once

#include "globe/raster/GeoTiffWriter.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace geocean::test {

inline void writeIslandRelief(const std::string& path) {
  constexpr int n = 360;
  constexpr double step = 1.0 / 240.0;
  std::vector<float> px(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double lat = 1.0 - (y + 0.5) * step, lon = -0.5 + (x + 0.5) * step;
      const double r2 = ((lat - 0.25) * (lat - 0.25) + (lon - 0.25) * (lon - 0.25)) / (0.15 * 0.15);
      px[std::size_t(y) * n + x] = float(-200.0 + 490.0 * std::exp(-r2));
    }
  raster::GeoTiffWriteOptions wo;
  wo.transform = {-0.5, 1.0, step, -step, false};
  raster::writeGeoTiff(path, px.data(), n, n, 1, raster::SampleType::F32, wo);
}

}  // namespace geocean::test
