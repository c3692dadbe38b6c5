// A mask's water coverage as a tile pyramid (globe/raster/TilePyramid.h),
// the one the host's terrain and the ocean both draw a streamed mask from
// (issue 12): the same value map, so the same on-disk cache and texels.
#pragma once

#include "globe/raster/TilePyramid.h"
#include "globe/world/LayerStack.h"
#include "globe/world/Surface.h"

#include <memory>
#include <vector>

namespace geocean::world {

// Coverage per texel: 1 water, 0 land by the encoding (a global mask's
// nodata land, as MaskEncoding::classify; a regional mask's NaN, where the
// layers below answer).
std::shared_ptr<const raster::TilePyramid> waterPyramid(std::shared_ptr<const raster::Raster> mask,
                                                        const MaskEncoding& encoding = {},
                                                        raster::PyramidOptions options = {});
// A relief's water, for a coast the relief decides (an elevation layer finer
// than every mask, LayerStack::drawingMask() null): 1 below 0 m (ocean, as
// LayerStack::classifyBatch), 0 at and above; a regional relief keeps its
// nodata (NaN), where the layers below answer, as a regional mask's.
std::shared_ptr<const raster::TilePyramid> reliefWaterPyramid(std::shared_ptr<const raster::Raster> relief,
                                                              raster::PyramidOptions options = {});
// The water pyramid of a layer streamedWaterLayer gave: a mask's or a relief's.
std::shared_ptr<const raster::TilePyramid> waterPyramid(const RasterLayer& layer, raster::PyramidOptions options = {});

// The mask layer drawn from its tiles: the first mask to answer, when it
// is north up and finer than the drawn water grid's step (gridLonStepDeg,
// at most 5'); null otherwise, and when an elevation layer finer than every
// mask decides the coast (drawingMask() null). A global layer is drawn from
// its tiles alone; a regional one (isStreamedRegional) over the water grid,
// which is then the whole stack's resample and answers outside the layer's
// extent and where it has no data, as the query's layers do.
const RasterLayer* streamedMaskLayer(const LayerStack& stack, double gridLonStepDeg);
// At most this many streamed layers of a kind are drawn (the ocean's
// shader falls through them in answer order: GEOCEAN_WATER_PAGES_LAYERS).
constexpr int kMaxStreamedLayers = 4;

// The layer the drawn water streams from (the host's terrain and the
// ocean alike): streamedMaskLayer, or, where a relief decides the coast
// (drawingMask() null), the first elevation layer when it answers first of
// all the mask and elevation layers, is north up and finer than the grid,
// and is regional or has no nodata (a global pyramid's texels are drawn
// alone: a nodata hole has no layer below in its programs). Its coast is
// then the relief's own 0 m line at its cells (reliefWaterPyramid), as the
// query's, instead of its resample on the grid. Null otherwise.
const RasterLayer* streamedWaterLayer(const LayerStack& stack, double gridLonStepDeg);

// The streamed water layers in answer order (issue 12 item 2: several of a
// kind): streamedWaterLayer first, then each next mask or relief layer of
// the stack while it streams by the same rule (north up, finer than the
// grid; a global relief only without nodata), up to kMaxStreamedLayers: a
// relief's water is its 0 m line (waterPyramid(const RasterLayer&)), as
// the query classifies it by sign. The chain ends after a global layer
// (it answers everywhere) and at a layer that does not stream (it is in
// the grid below, waterGridBelow). Empty when streamedWaterLayer is null.
// A fifth streamable layer is drawn from the grid below, resampled at its
// step (design: plugin/render/README.md). beyondLimit (optional): the
// first layer that would stream but is past the limit, else null.
std::vector<const RasterLayer*> streamedWaterLayers(const LayerStack& stack, double gridLonStepDeg,
                                                    const RasterLayer** beyondLimit = nullptr);
// The water grid drawn where the streamed layers of `chain` have no data:
// a global last layer's pyramid level (waterLayerOf at gridLonStepDeg), else
// waterLayerBelow of the stack without all of them. For one layer exactly
// what loadLayeredWorld and the ocean's grids drew before the chain.
WorldLayer waterGridBelow(const LayerStack& stack, const std::vector<const RasterLayer*>& chain, double gridLonStepDeg);

// A global water grid read from a water pyramid's coarse level: the
// coarsest level whose texel is at most stepDeg (and at most 16384 wide),
// its texels (the mean water of the mask cells under them) as coverage;
// nodata is land, as MaskEncoding::classify. Reads one level's tiles
// (from the disk cache) instead of classifying every grid cell through
// the stack. When that level is finer than stepDeg (a 1' mask's 4' level
// for a 5' step) it is resampled, a band of tiles at a time, onto the
// step's own grid: the grid (and the memory it and what is built from it
// take) does not grow with the raster. A texel is 1 exactly where every
// level texel it overlaps is, so where every mask cell under it is water;
// above 0 where any of them has water.
WorldLayer waterLayerOf(const raster::TilePyramid& water, double stepDeg);
// Any pyramid's level chosen as above as a global grid of its first
// channel, NaN where it has no data.
WorldLayer levelLayerOf(const raster::TilePyramid& pyramid, double stepDeg);

// The elevation layer drawn from its tiles (issue 12 item 2): the first
// elevation layer to answer, when it is north up and finer than the drawn
// elevation grid's step (gridLonStepDeg); null otherwise. Regional ones as
// the mask's: over the stack's resampled grid.
const RasterLayer* streamedElevationLayer(const LayerStack& stack, double gridLonStepDeg);
// The streamed elevation layers in answer order (issue 12 item 2, several
// reliefs): streamedElevationLayer first, then each next elevation layer
// (masks and imagery have no elevation) while it streams by the same rule,
// up to kMaxStreamedLayers; the chain ends after a global layer and at a
// relief that does not stream (it is in the grid below). The host's
// terrain draws at a point the first of them whose bilinear sample has
// data there, as LayerStack::elevationBatch (geo_uv.glsl,
// GEOCEAN_ELEVATION_TILES_LAYERS). beyondLimit (optional): the first
// relief that would stream but is past the limit, else null.
std::vector<const RasterLayer*> streamedElevationLayers(const LayerStack& stack, double gridLonStepDeg,
                                                        const RasterLayer** beyondLimit = nullptr);
// A streamed layer that does not cover the Earth (drawn over the grid).
bool isStreamedRegional(const raster::Raster& r);

// The grid a regional streamed mask is drawn over: the water grid
// (waterLayerOf, the drawing rule) of the stack's other layers, the ones
// that answer outside the mask and at its nodata. So outside its extent
// the coast is theirs exactly (the default world's 5' mask copied cell for
// cell, not a resample that mixes the region in), as the query's. Without
// other layers: all land. (A regional relief is drawn over the whole
// stack's resample: relief has no class to keep.)
WorldLayer waterLayerBelow(const LayerStack& stack, const raster::Raster& streamed);
// The same without every raster of `streamed`.
WorldLayer waterLayerBelow(const LayerStack& stack, const std::vector<const raster::Raster*>& streamed);

// A regional pyramid's water for a WaterIndex: its finest level of at most
// maxTexels texels, nodata (NaN) as water. A level texel is the mean of the
// mask cells under it that have data (exact in float for levels <= 12), so
// it is 1 only where each of them is water; where none has data the layers
// below answer, and the index of their grid (waterLayerBelow) speaks for
// them. So the grid's index and this one both all water over a rectangle
// means the drawn coverage is water throughout it.
WorldLayer regionalWaterCover(const raster::TilePyramid& water, std::size_t maxTexels = std::size_t(1) << 22);

}  // namespace geocean::world
