// The ocean's own world grids (elevation for depth, water coverage for the
// shoreline) from its rasters, for its textures and its water index. Global
// in-memory rasters are copied pixel for pixel (so the ocean's shoreline is
// the host's when both load the same mask); anything else is resampled
// through the classifier. The mask encoding decides what is water.
#pragma once

#include "globe/world/WorldGrids.h"
#include "globe/raster/TilePyramid.h"
#include "plugin/landsea/LandSea.h"

#include <memory>
#include <vector>

namespace geocean::ocean_render {

// mask, elevation, landSea may each be null (no relief: deep water; no
// classes: water everywhere). With waterTiles (oceanWaterTiles) the water
// grid is that pyramid's coarse level (world::waterLayerOf), not a
// resample of every cell through the classifier.
std::shared_ptr<const world::WorldGrids> oceanWorld(const std::shared_ptr<const raster::Raster>& mask,
                                                    const std::shared_ptr<const raster::Raster>& elevation,
                                                    const ocean::LandSea* landSea,
                                                    const world::MaskEncoding& encoding = {},
                                                    const raster::TilePyramid* waterTiles = nullptr);

// The streamed water's pyramid when the land/sea is a layer stack whose
// coast is drawn from tiles (world::streamedWaterLayer at the water grid's
// step for `mask`, the snapshot's drawing mask, or without one the stack's
// drawing elevation: the host terrain's rule, pyramid and disk cache): a
// mask's coverage, or the 0 m line of a relief that decides the coast; null
// otherwise.
std::shared_ptr<const raster::TilePyramid> oceanWaterTiles(const ocean::LandSea* landSea,
                                                           const std::shared_ptr<const raster::Raster>& mask);

// True when `world`'s water index says where `water` (a streamed global
// mask's pyramid) is water: its water grid is one of the pyramid's levels,
// or one resampled onto the grid's step (oceanWorld's waterLayerOf), whose
// texels are 1 only where every mask cell under them is water. So open water drawn without the per-pixel
// coverage, and terrain left out under it, keep every island of the mask.
// Every streamed water layer's pyramid in answer order
// (world::streamedWaterLayers; the first is oceanWaterTiles'): several
// masks of which the first with data at a point answers. Empty: none.
std::vector<std::shared_ptr<const raster::TilePyramid>> oceanWaterTileLayers(
    const ocean::LandSea* landSea, const std::shared_ptr<const raster::Raster>& mask);

// Every streamed relief's pyramid in answer order, as the host terrain
// draws them (world::streamedElevationLayers at the ocean's elevation grid
// step for `elevation`, the snapshot's drawing elevation; the host's
// raster::TilePyramid::open, so its disk cache): the ocean reads its water
// depth from them (ElevationPages). Empty: none, or no layer stack.
std::vector<std::shared_ptr<const raster::TilePyramid>> oceanElevationTileLayers(
    const ocean::LandSea* landSea, const std::shared_ptr<const raster::Raster>& elevation);

// Where the relief is too coarse for the coast the mask draws: 1 at each
// elevation texel whose bilinear reach (the four cells between texel
// centres around it) holds a point the relief puts on land (>= 0 m; nodata
// is 0 m) while the water grid says water there (the mask, not the relief,
// decides: a relief that decides makes its land the grid's land), 0
// elsewhere; so the relief's 0 m line in the mask's sea lies where all its
// cell's texels are 1. ocean_shading.glsl keeps the depth seen through the
// water at the coverage's floor there: the line (straight across a 37 km
// ETOPO cell in the Strait of Gibraltar) draws no seam in the sea.
std::vector<float> reliefUnderMaskWater(const world::WorldGrids& world);

bool waterIndexFollowsTiles(const world::WorldGrids& world, const raster::TilePyramid& water);

// The screen grid's classifier for a streamed global mask whose water
// grid is a pyramid level (waterIndexFollowsTiles): Ocean within one grid
// texel (at least two mask cells: LandSea::classifyNearWaterBatch's
// reach) of a texel with any water (mean above 0), else Land; a pole's
// texel row is water if any of it is. A lookup instead of the layer
// stack's coverage rule on the streamed raster per vertex (30-330 ms a
// frame for the 1.25' mask). Cells it skips (four Land corners) have no
// water of the mask within the drawn shoreline's reach.
ocean::SurfaceClassifier nearWaterClassifier(const world::WorldLayer& water);

// The ocean's side of the host/layer contract: true when it draws every
// pixel over the rectangle opaque, for pixels whose footprint there is up to
// footprintM metres, with grid cells of cellPx pixels; `paged`: the water
// is drawn from a streamed mask's pages (footprint up to twice the mipmap's).
bool coversOpaquely(const world::WorldGrids& world, double cellPx, double lat0Deg, double lat1Deg, double lon0Deg,
                    double lon1Deg, double footprintM, bool paged = false);

}  // namespace geocean::ocean_render
