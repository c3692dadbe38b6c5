// same_coast_mask: a land/sea/lake mask resampled to a finer grid along its
// own drawn coast, for issue 12 item 6's frame-time ratio with equal content
// (docs/PERFORMANCE.md): the bundled 5' mask at 30" is a 43200 x 21600
// streamed mask whose coastline is the default world's (the cubic B-spline
// coverage's 0.5 line the renderer draws), so the ratio against the default
// world measures the streaming, not a coast that puts more sea in view.
//   same_coast_mask IN.tif OUT.tif FACTOR   (global rasters; values 0 ocean, 1 land, 2 lake)
#include "globe/raster/GeoTiffWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

using namespace geocean;

namespace {

// Cubic B-spline weights at fraction t (geo_uv.glsl bsplineWeights4).
void bspline(double t, double w[4]) {
  const double s = 1.0 - t;
  w[0] = s * s * s / 6.0;
  w[1] = (4.0 - 6.0 * t * t + 3.0 * t * t * t) / 6.0;
  w[2] = (1.0 + 3.0 * t + 3.0 * t * t - 3.0 * t * t * t) / 6.0;
  w[3] = t * t * t / 6.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: same_coast_mask IN.tif OUT.tif FACTOR\n");
    return 2;
  }
  try {
    const auto src = raster::Raster::open(argv[1]);
    const int factor = std::stoi(argv[3]);
    if (!src->wholeGlobeNorthUp() || src->channels() != 1 || factor < 2 || factor > 64) {
      std::fprintf(stderr, "same_coast_mask: %s: needs a one-channel whole-globe north-up raster and FACTOR 2..64 (%s)\n",
                   argv[1], argv[3]);
      return 2;
    }
    const int W = src->width(), H = src->height();
    const std::vector<float>& v = src->pixels();
    raster::GeoTiffWriteOptions o;
    o.transform = src->transform();
    o.transform.lonStepDeg /= factor, o.transform.latStepDeg /= factor;
    std::printf("%s: %d x %d -> %s: %d x %d\n", argv[1], W, H, argv[2], W * factor, H * factor);
    const int T = o.tileSize;
    raster::writeGeoTiffTiles(argv[2], W * factor, H * factor, 1, raster::SampleType::U8, o,
                              [&](int x0, int y0, void* tile) {
      auto* out = static_cast<std::uint8_t*>(tile);
      for (int y = 0; y < T; ++y)
        for (int x = 0; x < T; ++x) {
          // The source's continuous texel position (centres at integers).
          const double px = (x0 + x + 0.5) / factor - 0.5, py = (y0 + y + 0.5) / factor - 0.5;
          const double ix = std::floor(px), iy = std::floor(py);
          double wx[4], wy[4];
          bspline(px - ix, wx), bspline(py - iy, wy);
          double weight[3] = {0.0, 0.0, 0.0};  // ocean, land, lake
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
              const int sx = ((int(ix) - 1 + i) % W + W) % W, sy = std::clamp(int(iy) - 1 + j, 0, H - 1);
              weight[std::clamp(int(v[std::size_t(sy) * W + sx]), 0, 2)] += wx[i] * wy[j];
            }
          // Water where the coverage is over 0.5 (the drawn shoreline); a lake where it outweighs the ocean.
          out[y * T + x] = weight[0] + weight[2] > 0.5 ? (weight[2] > weight[0] ? 2 : 0) : 1;
        }
    });
    std::printf("wrote %s\n", argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "same_coast_mask: %s\n", e.what());
    return 1;
  }
  return 0;
}
