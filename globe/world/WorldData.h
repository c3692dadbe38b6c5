// The world as global lon/lat grids on the CPU (no GL): imagery, elevation
// and water coverage, from rasters. The host uploads them as textures
// (globe/render/WorldTextures) and the ocean plugin makes its own from its
// rasters (plugin/render), both through this one description.
#pragma once

#include "globe/world/Surface.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace geocean::raster {
class Raster;
class TilePyramid;
}

namespace geocean::world {

// Row 0 first as stored, any global lon/lat grid.
struct WorldLayer {
  int width = 0, height = 0, channels = 1;
  std::vector<float> values;               // row-major, channels interleaved
  double originLonDeg = -180.0, originLatDeg = 90.0;  // edge of pixel (0, 0)
  double lonStepDeg = 1.0, latStepDeg = -1.0;         // per pixel
  // (originLonDeg, originLatDeg, lonSpanDeg, latSpanDeg): what a shader
  // needs to map lon/lat to texture coordinates.
  glm::vec4 geo() const {
    return {float(originLonDeg), float(originLatDeg), float(lonStepDeg * width), float(latStepDeg * height)};
  }
};

// A user's imagery layer (--imagery, issue 12 item 1) as drawn over the
// default imagery: RGBA8, sRGB colour premultiplied by the alpha, which is
// the layer's validity (0 where nodata or outside: the layer below shows).
// Row 0 first as stored; a regional or global lon/lat grid.
struct ImageryLayer {
  std::string name;  // the file
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  double originLonDeg = -180.0, originLatDeg = 90.0, lonStepDeg = 1.0, latStepDeg = -1.0;
  bool global = false;  // spans 360 degrees of longitude: wraps
  glm::vec4 geo() const {
    return {float(originLonDeg), float(originLatDeg), float(lonStepDeg * width), float(latStepDeg * height)};
  }
};
// The terrain shader's imagery slots (texture units 8 and up).
constexpr int kMaxImageryLayers = 4;

struct WorldData {
  WorldLayer imagery;    // RGB 0..255, sRGB
  // The user's imagery over `imagery`, in answer order (the first is on
  // top): LayerStack's order for LayerKind::Imagery.
  std::vector<ImageryLayer> imageryLayers;
  WorldLayer elevation;  // metres, ocean negative
  WorldLayer water;      // 1 water (ocean or lake), 0 land
  // A global mask finer than `water` that answers first (loadLayeredWorld):
  // the host draws it streamed as tiles (globe/render/WorldTextures), the
  // grids above stay for the CPU. Null: `water` is what is drawn.
  std::shared_ptr<const raster::Raster> waterSource;
  // waterSource is a relief that decides the coast (world::streamedWaterLayer),
  // streamed as its 0 m line (world::reliefWaterPyramid), not a mask.
  bool waterFromRelief = false;
  MaskEncoding waterEncoding;
  // Streamed masks under waterSource, in answer order
  // (world::streamedWaterLayers): the first with data at a point is drawn,
  // `water` is the grid under them all. Empty: waterSource alone.
  std::vector<std::shared_ptr<const raster::Raster>> waterSourcesBelow;
  std::vector<MaskEncoding> waterEncodingsBelow;
  // Per waterSourcesBelow: a relief whose 0 m line is drawn (as waterFromRelief).
  std::vector<bool> waterFromReliefBelow;
  // A global elevation layer finer than `elevation` that answers first: the
  // host draws it streamed (NaN texels fall back to `elevation`), the grid
  // stays for the CPU. Null: `elevation` is what is drawn.
  std::shared_ptr<const raster::TilePyramid> elevationTiles;
  // Streamed reliefs under elevationTiles, in answer order
  // (world::streamedElevationLayers): the first whose bilinear sample has
  // data at a point is drawn, `elevation` is the grid under them all.
  std::vector<std::shared_ptr<const raster::TilePyramid>> elevationTilesBelow;
};

// An in-memory raster as a layer: all channels, or only `channel` (>= 0).
// Throws raster::RasterError for a cache-backed raster (too big to upload).
WorldLayer layerOf(const raster::Raster& r, int channel = -1);
// A mask raster as water coverage (1 water, 0 land) by the encoding's rule.
WorldLayer waterLayerOf(const raster::Raster& mask, const MaskEncoding& encoding = {});
// NaN (nodata) elevations would poison a vertex shader: sea level instead.
void nodataToSeaLevel(WorldLayer& elevation);

// A global lon/lat grid for drawing a raster: the raster's step, but at most
// 5' (the default mask's) and 1 degree without a raster; values zeroed.
WorldLayer globalGridFor(const raster::Raster* r);
// A raster drawn on its own cells (layerOf): in memory and the whole globe,
// north up; any other is resampled onto globalGridFor's grid.
bool globalInMemory(const raster::Raster& r);
// The step of the grid a raster is drawn on: its own, or globalGridFor's.
double drawingGridStepDeg(const raster::Raster* r);
// The lat/lon of a layer's cell centres, row-major, in chunks of whole rows
// of about 1 M cells: f(first cell, latDeg, lonDeg, n) per chunk. The batch
// calls copy their points, so the whole grid's coordinates (and copies:
// 400 MB at 5') are never held at once.
template <class F>
void forCellChunks(const WorldLayer& l, F&& f) {
  const int rows = std::max(1, (1 << 20) / std::max(1, l.width));
  std::vector<double> lat, lon;
  for (int y0 = 0; y0 < l.height; y0 += rows) {
    const int y1 = std::min(l.height, y0 + rows);
    const std::size_t n = std::size_t(y1 - y0) * std::size_t(l.width);
    lat.resize(n), lon.resize(n);
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < l.width; ++x) {
        lat[std::size_t(y - y0) * std::size_t(l.width) + std::size_t(x)] = l.originLatDeg + (y + 0.5) * l.latStepDeg;
        lon[std::size_t(y - y0) * std::size_t(l.width) + std::size_t(x)] = l.originLonDeg + (x + 0.5) * l.lonStepDeg;
      }
    f(std::size_t(y0) * std::size_t(l.width), lat.data(), lon.data(), n);
  }
}

// Loads the default world (globe/raster/World.h): imagery, ETOPO relief and
// the 5' land/sea mask. Throws raster::RasterError naming the file.
WorldData loadDefaultWorld();

}  // namespace geocean::world
