// The default world from data/ through the raster reader (globe/raster).
#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/render/WorldTextures.h"

#include <algorithm>

namespace geocean::render {

WorldLayer layerOf(const raster::Raster& r, int channel) {
  if (!r.inMemory())
    throw raster::RasterError(r.path() + ": too large to upload as a texture (read through the cache)");
  WorldLayer l;
  l.width = r.width();
  l.height = r.height();
  if (channel < 0) {
    l.channels = r.channels();
    l.values = r.pixels();
  } else {
    const auto& px = r.pixels();
    const std::size_t stride = std::size_t(r.channels()), c = std::size_t(std::min(channel, r.channels() - 1));
    l.values.resize(std::size_t(l.width) * l.height);
    for (std::size_t i = 0; i < l.values.size(); ++i) l.values[i] = px[i * stride + c];
  }
  const auto& t = r.transform();
  l.originLonDeg = t.originLonDeg;
  l.originLatDeg = t.originLatDeg;
  l.lonStepDeg = t.lonStepDeg;
  l.latStepDeg = t.latStepDeg;
  return l;
}

WorldData loadDefaultWorld() {
  const raster::WorldFiles files = raster::defaultWorld();
  WorldData d;
  d.imagery = layerOf(*raster::Raster::open(files.imagery));
  d.elevation = layerOf(*raster::Raster::open(files.elevation));
  // NaN (nodata) elevations would poison the vertex shader: treat as sea level.
  for (float& v : d.elevation.values)
    if (v != v) v = 0.0f;
  d.water = layerOf(*raster::Raster::open(files.mask));
  // Mask classes -> water fraction: ocean (0) and lake (2) are water.
  for (float& v : d.water.values) v = (v == 0.0f || v == 2.0f) ? 1.0f : 0.0f;
  return d;
}

}  // namespace geocean::render
