// The default world from data/ through the raster reader (globe/raster).
#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/world/WorldData.h"

#include <algorithm>
#include <cmath>

namespace geocean::world {

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
  nodataToSeaLevel(d.elevation);
  d.water = waterLayerOf(*raster::Raster::open(files.mask));
  return d;
}

WorldLayer waterLayerOf(const raster::Raster& mask, const MaskEncoding& encoding) {
  WorldLayer l = layerOf(mask, 0);
  for (float& v : l.values) v = encoding.isWater(v) ? 1.0f : 0.0f;
  return l;
}

void nodataToSeaLevel(WorldLayer& elevation) {
  for (float& v : elevation.values)
    if (v != v) v = 0.0f;
}

WorldLayer globalGridFor(const raster::Raster* r) {
  WorldLayer l;
  const double step = r ? std::max(std::abs(r->transform().lonStepDeg), 1.0 / 12.0) : 1.0;
  l.width = std::max(1, int(std::lround(360.0 / step)));
  l.height = std::max(1, int(std::lround(180.0 / step)));
  l.lonStepDeg = 360.0 / l.width;
  l.latStepDeg = -180.0 / l.height;
  l.values.resize(std::size_t(l.width) * l.height);
  return l;
}

bool globalInMemory(const raster::Raster& r) { return r.inMemory() && r.wholeGlobeNorthUp(); }

double drawingGridStepDeg(const raster::Raster* r) {
  return r && globalInMemory(*r) ? r->transform().lonStepDeg : globalGridFor(r).lonStepDeg;
}

}  // namespace geocean::world
