// What the renderers need to know of the world on the CPU: bilinear
// elevation and water coverage, the finest texel the geometry can show, and
// where the water is water all around (WaterIndex). No GL: the host's
// textures and the ocean's own are made from the same layers.
#pragma once

#include "globe/world/WaterIndex.h"
#include "globe/world/WorldData.h"

namespace geocean::world {

class WorldGrids {
 public:
  // Throws std::runtime_error for an empty or inconsistent layer.
  WorldGrids(WorldLayer elevation, WorldLayer water);

  float elevationAt(double latDeg, double lonDeg) const;  // metres, bilinear
  float waterAt(double latDeg, double lonDeg) const;      // coverage in [0, 1], bilinear
  // The finer of the elevation and water texels, degrees: the finest detail
  // the terrain's geometry can show.
  double finestShapeTexelDeg() const { return finestShapeTexelDeg_; }
  // Which texel rectangles of the water layer are water throughout.
  const WaterIndex& waterIndex() const { return waterIndex_; }
  const WorldLayer& elevation() const { return elevation_; }
  const WorldLayer& water() const { return water_; }

 private:
  WorldLayer elevation_, water_;
  WaterIndex waterIndex_;
  double finestShapeTexelDeg_ = 0.0;
};

// Throws std::runtime_error unless the layer has width x height x >= channels values.
void checkLayer(const WorldLayer& l, const char* what, int channels);

}  // namespace geocean::world
