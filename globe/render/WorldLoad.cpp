// The default world from data/ through the raster reader (globe/raster).
#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/render/WorldTextures.h"

namespace geocean::render {

namespace {
WorldLayer layerOf(const raster::Raster& r) {
  if (!r.inMemory())
    throw raster::RasterError(r.path() + ": too large to upload as a texture (read through the cache)");
  WorldLayer l;
  l.width = r.width();
  l.height = r.height();
  l.channels = r.channels();
  l.values = r.pixels();
  const auto& t = r.transform();
  l.originLonDeg = t.originLonDeg;
  l.originLatDeg = t.originLatDeg;
  l.lonStepDeg = t.lonStepDeg;
  l.latStepDeg = t.latStepDeg;
  return l;
}
}  // namespace

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
