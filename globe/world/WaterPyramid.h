// A mask's water coverage as a tile pyramid (globe/raster/TilePyramid.h),
// the one the host's terrain and the ocean both draw a streamed mask from
// (issue 12): the same value map, so the same on-disk cache and texels.
#pragma once

#include "globe/raster/TilePyramid.h"
#include "globe/world/LayerStack.h"
#include "globe/world/Surface.h"

#include <memory>

namespace geocean::world {

// Coverage per texel: 1 water, 0 land by the encoding (nodata land, as
// MaskEncoding::classify).
std::shared_ptr<const raster::TilePyramid> waterPyramid(std::shared_ptr<const raster::Raster> mask,
                                                        const MaskEncoding& encoding = {},
                                                        raster::PyramidOptions options = {});

// The mask layer drawn from its tiles: the first mask to answer, when it
// covers the Earth and is finer than the drawn water grid's step
// (gridLonStepDeg, at most 5'); null otherwise, and when an elevation layer
// finer than every mask decides the coast (drawingMask() null).
const RasterLayer* streamedMaskLayer(const LayerStack& stack, double gridLonStepDeg);

// A global water grid read from a water pyramid's coarse level: the
// coarsest level whose texel is at most stepDeg (and at most 16384 wide),
// its texels (the mean water of the mask cells under them) as coverage;
// nodata is land, as MaskEncoding::classify. Reads one level's tiles
// (from the disk cache) instead of classifying every grid cell through
// the stack.
WorldLayer waterLayerOf(const raster::TilePyramid& water, double stepDeg);
// Any pyramid's level chosen as above as a global grid of its first
// channel, NaN where it has no data.
WorldLayer levelLayerOf(const raster::TilePyramid& pyramid, double stepDeg);

// The elevation layer drawn from its tiles (issue 12 item 2): the first
// elevation layer to answer, when it covers the Earth and is finer than the
// drawn elevation grid's step (gridLonStepDeg); null otherwise.
const RasterLayer* streamedElevationLayer(const LayerStack& stack, double gridLonStepDeg);

}  // namespace geocean::world
