// The host's world on the GPU: imagery (Blue Marble), elevation (metres,
// ocean negative) and water coverage (1 water, 0 land; the GPU's bilinear
// filter turns it into the classifier's coverage, so the shoreline is the
// 0.5 contour and never shows 5' pixel steps), from world::WorldData. The
// CPU side (bilinear lookups, the water index) is world::WorldGrids. A
// finer global mask (WorldData::waterSource) is also streamed as tiles
// (waterTiles, TilePool.h).
#pragma once

#include "globe/raster/TilePyramid.h"
#include "globe/gl/TilePool.h"
#include "globe/world/WorldGrids.h"

#include <epoxy/gl.h>
#include <glm/vec4.hpp>

#include <memory>
#include <vector>

namespace geocean::render {

class WorldTextures {
 public:
  // Takes the data: its elevation and water grids become grids() without a
  // copy, and its imagery is freed once on the GPU (callers that are done
  // with the data move it in; issue 12 item 6's peak memory).
  explicit WorldTextures(world::WorldData data);
  // As above, and the water coverage drawn from a tile pyramid (world::waterPyramid)
  // through a GPU tile pool: rasters of any size (issue 12 item 2). The
  // single water texture stays for the passes that do not stream (the sea
  // proxy) and the CPU grids for picking and LOD bounds.
  WorldTextures(world::WorldData data, std::shared_ptr<const raster::TilePyramid> water,
                gl::TilePoolOptions pool = {});
  ~WorldTextures();
  WorldTextures(const WorldTextures&) = delete;
  WorldTextures& operator=(const WorldTextures&) = delete;

  // Binds imagery, elevation, water to units 0, 1, 2 and the user's imagery
  // layers to units 8 and up.
  void bind() const;
  glm::vec4 imageryGeo() const { return imageryGeo_; }
  // The user's imagery layers (WorldData::imageryLayers), in answer order.
  int imageryLayers() const { return int(imageryLayers_.size()); }
  glm::vec4 imageryLayerGeo(int i) const { return imageryLayerGeo_[std::size_t(i)]; }
  glm::vec4 elevationGeo() const { return grids_->elevation().geo(); }
  glm::vec4 waterGeo() const { return grids_->water().geo(); }

  // CPU copies for picking and LOD bounds.
  const std::shared_ptr<const world::WorldGrids>& grids() const { return grids_; }
  float elevationAt(double latDeg, double lonDeg) const { return grids_->elevationAt(latDeg, lonDeg); }
  float waterAt(double latDeg, double lonDeg) const { return grids_->waterAt(latDeg, lonDeg); }
  double finestShapeTexelDeg() const { return grids_->finestShapeTexelDeg(); }
  const world::WaterIndex& waterIndex() const { return grids_->waterIndex(); }
  // The streamed water coverage, or null (the single texture only).
  gl::TilePool* waterTiles() const { return waterTiles_.get(); }
  // All streamed water layers in answer order (WorldData::waterSourcesBelow
  // after waterTiles, each its own pool): 0 without streamed water.
  int waterTileLayers() const { return waterTiles_ ? 1 + int(waterTilesBelow_.size()) : 0; }
  gl::TilePool* waterTiles(int layer) const {
    return layer == 0 ? waterTiles_.get() : waterTilesBelow_[std::size_t(layer - 1)].get();
  }
  // A regional streamed mask's own water index (world::regionalWaterCover,
  // over its extent; null otherwise): waterIndex() is the grid's below it,
  // which knows nothing of the mask's islands and coasts.
  const world::WaterIndex* regionalWaterIndex(int layer = 0) const {
    return std::size_t(layer) < regionalIndex_.size() ? regionalIndex_[std::size_t(layer)].get() : nullptr;
  }
  // The streamed elevation (WorldData::elevationTiles: R32F, NaN where the
  // raster has no data), or null.
  gl::TilePool* elevationTiles() const { return elevationTiles_.get(); }
  // All streamed elevation layers in answer order (WorldData::elevationTilesBelow
  // after elevationTiles, each its own pool): 0 without streamed elevation.
  int elevationTileLayers() const { return elevationTiles_ ? 1 + int(elevationTilesBelow_.size()) : 0; }
  gl::TilePool* elevationTiles(int layer) const {
    return layer == 0 ? elevationTiles_.get() : elevationTilesBelow_[std::size_t(layer - 1)].get();
  }

 private:
  std::shared_ptr<const world::WorldGrids> grids_;
  GLuint imagery_ = 0, elevation_ = 0, water_ = 0;
  glm::vec4 imageryGeo_{0.0f};
  std::vector<GLuint> imageryLayers_;
  std::vector<glm::vec4> imageryLayerGeo_;
  std::unique_ptr<gl::TilePool> waterTiles_, elevationTiles_;
  std::vector<std::unique_ptr<gl::TilePool>> waterTilesBelow_, elevationTilesBelow_;
  std::vector<std::unique_ptr<world::WaterIndex>> regionalIndex_;  // per streamed water layer
  void indexRegionalWater();
};

}  // namespace geocean::render
