// same_coast_mask: a land/sea/lake mask resampled to a finer grid along its
// own drawn coast, for issue 12 item 6's frame-time ratio with equal content
// (docs/PERFORMANCE.md): the bundled 5' mask at 30" is a 43200 x 21600
// streamed mask whose coastline is the default world's (world::coverageClassAt, the B-spline
// coverage's 0.5 line the renderer draws), so the ratio against the default
// world measures the streaming, not a coast that puts more sea in view.
//   same_coast_mask IN.tif OUT.tif FACTOR   (global rasters; values 0 ocean, 1 land, 2 lake)
#include "globe/raster/GeoTiffWriter.h"
#include "globe/world/Surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

using namespace geocean;

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
    const world::MaskEncoding encoding;  // the default: 0 ocean, 1 land, 2 lake
    raster::writeGeoTiffTiles(argv[2], W * factor, H * factor, 1, raster::SampleType::U8, o,
                              [&](int x0, int y0, void* tile) {
      auto* out = static_cast<std::uint8_t*>(tile);
      for (int y = 0; y < T; ++y)
        for (int x = 0; x < T; ++x) {
          // The coverage rule the renderer and the query share, at the source's continuous pixel position.
          const world::CoverageClass c = world::coverageClassAt(
              (x0 + x + 0.5) / factor, (y0 + y + 0.5) / factor, [&](int cx, int cy) {
                cx = ((cx % W) + W) % W, cy = std::clamp(cy, 0, H - 1);
                return encoding.classify(v[std::size_t(cy) * W + cx]);
              });
          out[y * T + x] = std::uint8_t(c.surface);  // 0 ocean, 1 land, 2 lake
        }
    });
    std::printf("wrote %s\n", argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "same_coast_mask: %s\n", e.what());
    return 1;
  }
  return 0;
}
