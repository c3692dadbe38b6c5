// What a global water pyramid (world::waterPyramid: 1 water, 0 land per
// texel) holds over a rectangle, at the mask's own resolution: all water,
// all land, or both. WaterIndex answers for the drawn 5' grid, whose texels
// are up to 10x a streamed mask's, so near a coast it sees land in almost
// every cell's reach; this one reads the pyramid's tiles (kept as one class
// byte per texel, at most maxTiles of them) and answers from the level
// whose texels are about an eighth of the rectangle: a level texel is the
// mean of the mask cells under it (exact in float for levels <= 12), so it
// is 1 only where each of them is water and 0 only where each is land.
// The answer covers the level texels the rectangle touches: exact or
// conservative (never all water / all land where a mask cell is not).
// One thread (the renderer's): it caches without locks.
#pragma once

#include "globe/raster/TilePyramid.h"

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace geocean::world {

class TileWaterIndex {
 public:
  enum class Cover : std::uint8_t { Land = 0, Water = 1, Mixed = 2 };

  // `water` must be global (its x wraps around the Earth).
  explicit TileWaterIndex(std::shared_ptr<const raster::TilePyramid> water, std::size_t maxTiles = 96);

  // Continuous level-0 texel coordinates (texel i spans [i, i + 1)).
  double texelX(double lonDeg) const { return (lonDeg - originLonDeg_) / lonStepDeg_; }
  double texelY(double latDeg) const { return (latDeg - originLatDeg_) / latStepDeg_; }
  // The rectangle [x0, x1] x [y0, y1] (level-0 texels, corners in any
  // order; x wraps, y clamps to the raster): Water when every mask cell it
  // touches is water, Land when every one is land, else Mixed (also for
  // NaN bounds, nodata texels, and rectangles of more than half the Earth).
  Cover cover(double x0, double x1, double y0, double y1);

  std::size_t tilesKept() const { return tiles_.size(); }

 private:
  struct Tile {
    Cover constant = Cover::Mixed;  // a Constant / Empty tile: no bytes
    std::vector<std::uint8_t> cls;  // tileSize^2 Cover bytes (Data tiles)
    std::uint64_t used = 0;
  };
  const Tile& tile(int level, int tx, int ty);

  std::shared_ptr<const raster::TilePyramid> water_;
  std::size_t maxTiles_;
  int tileSize_ = 256;
  double originLonDeg_ = 0, originLatDeg_ = 0, lonStepDeg_ = 1, latStepDeg_ = -1;
  std::unordered_map<std::uint64_t, Tile> tiles_;
  std::uint64_t clock_ = 0;
};

}  // namespace geocean::world
