// The default world on the GPU: imagery (Blue Marble), elevation (metres,
// ocean negative) and water coverage (1 water, 0 land; the GPU's bilinear
// filter turns it into the classifier's coverage, so the shoreline is the
// 0.5 contour and never shows 5' pixel steps). All three are global
// equirectangular rasters; `geo` holds (originLonDeg, originLatDeg,
// lonSpanDeg, latSpanDeg) so a shader maps lon/lat to texture coordinates.
#pragma once

#include "globe/render/WaterIndex.h"

#include <epoxy/gl.h>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace geocean::raster {
class Raster;
}

namespace geocean::render {

// Host-side inputs, row 0 first as stored, any global lon/lat grid.
struct WorldLayer {
  int width = 0, height = 0, channels = 1;
  std::vector<float> values;               // row-major, channels interleaved
  double originLonDeg = -180.0, originLatDeg = 90.0;  // edge of pixel (0, 0)
  double lonStepDeg = 1.0, latStepDeg = -1.0;         // per pixel
};

struct WorldData {
  WorldLayer imagery;    // RGB 0..255, sRGB
  WorldLayer elevation;  // metres, ocean negative
  WorldLayer water;      // 1 water (ocean or lake), 0 land
};

// An in-memory raster as a layer: all channels, or only `channel` (>= 0).
// Throws raster::RasterError for a cache-backed raster (too big to upload).
WorldLayer layerOf(const raster::Raster& r, int channel = -1);

// Loads the default world (globe/raster/World.h): imagery, ETOPO relief and
// the 5' land/sea mask. Throws raster::RasterError naming the file.
WorldData loadDefaultWorld();

class WorldTextures {
 public:
  explicit WorldTextures(const WorldData& data);
  ~WorldTextures();
  WorldTextures(const WorldTextures&) = delete;
  WorldTextures& operator=(const WorldTextures&) = delete;

  // Binds imagery, elevation, water to units 0, 1, 2.
  void bind() const;
  glm::vec4 imageryGeo() const { return imageryGeo_; }
  glm::vec4 elevationGeo() const { return elevationGeo_; }
  glm::vec4 waterGeo() const { return waterGeo_; }

  // CPU copies for picking and LOD bounds.
  float elevationAt(double latDeg, double lonDeg) const;
  float waterAt(double latDeg, double lonDeg) const;
  // The finer of the elevation and water texels, degrees: the finest detail
  // the terrain's geometry can show.
  double finestShapeTexelDeg() const { return finestShapeTexelDeg_; }
  // Which texel rectangles of the water texture are water throughout.
  const WaterIndex& waterIndex() const { return waterIndex_; }

 private:
  GLuint imagery_ = 0, elevation_ = 0, water_ = 0;
  glm::vec4 imageryGeo_{0.0f}, elevationGeo_{0.0f}, waterGeo_{0.0f};
  WorldLayer elev_, waterHost_;
  WaterIndex waterIndex_;
  double finestShapeTexelDeg_ = 0.0;
};

}  // namespace geocean::render
