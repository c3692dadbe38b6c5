#include "globe/world/TileWaterIndex.h"

#include <algorithm>
#include <cmath>

namespace geocean::world {

TileWaterIndex::TileWaterIndex(std::shared_ptr<const raster::TilePyramid> water, std::size_t maxTiles)
    : water_(std::move(water)), maxTiles_(std::max<std::size_t>(maxTiles, 4)) {
  tileSize_ = water_->tileSize();
  const raster::GeoTransform& t = water_->source().transform();
  originLonDeg_ = t.originLonDeg, originLatDeg_ = t.originLatDeg, lonStepDeg_ = t.lonStepDeg, latStepDeg_ = t.latStepDeg;
}

const TileWaterIndex::Tile& TileWaterIndex::tile(int level, int tx, int ty) {
  const std::uint64_t key = (std::uint64_t(level) << 56) | (std::uint64_t(std::uint32_t(ty)) << 28) | std::uint32_t(tx);
  auto it = tiles_.find(key);
  if (it == tiles_.end()) {
    if (tiles_.size() >= maxTiles_)
      tiles_.erase(std::min_element(tiles_.begin(), tiles_.end(),
                                    [](const auto& a, const auto& b) { return a.second.used < b.second.used; }));
    Tile t;
    // A level-0 tile under an Empty level-1 tile is all nodata: Mixed.
    if (water_->kind({level, tx, ty}) != raster::TileKind::Empty) {
      const std::shared_ptr<const std::vector<float>> v = water_->interior({level, tx, ty});
      const int c = water_->channels();
      t.cls.resize(std::size_t(tileSize_) * tileSize_);
      bool uniform = true;
      for (std::size_t i = 0; i < t.cls.size(); ++i) {
        const float f = (*v)[i * std::size_t(c)];
        t.cls[i] = std::uint8_t(f >= 1.0f ? Cover::Water : f <= 0.0f ? Cover::Land : Cover::Mixed);  // NaN: Mixed
        uniform = uniform && t.cls[i] == t.cls[0];
      }
      if (uniform) t.constant = Cover(t.cls[0]), t.cls = {};
    }
    it = tiles_.emplace(key, std::move(t)).first;
  }
  it->second.used = ++clock_;
  return it->second;
}

TileWaterIndex::Cover TileWaterIndex::cover(double x0, double x1, double y0, double y1) {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  const int w0 = water_->levelWidth(0), h0 = water_->levelHeight(0);
  if (!(x0 <= x1) || !(y0 <= y1) || x1 - x0 >= 0.5 * w0 || std::abs(x0) > 1e9) return Cover::Mixed;
  // The level whose texels are about an eighth of the rectangle (at most
  // 9 x 9 of them read), no coarser than level 12 (exact means).
  const double span = std::max(x1 - x0, y1 - y0);
  int level = 0;
  while (level + 1 < std::min(water_->levels(), 13) && span > 8.0 * double(1 << level)) ++level;
  const int w = water_->levelWidth(level), h = water_->levelHeight(level);
  const int iy0 = std::clamp(int(std::floor(y0)), 0, h0 - 1) >> level;
  const int iy1 = std::min(std::clamp(int(std::floor(y1)), 0, h0 - 1) >> level, h - 1);
  // x in [0, w0): one or two runs of level-0 columns.
  const double shift = std::floor(x0 / w0) * w0;
  const int a0 = std::clamp(int(std::floor(x0 - shift)), 0, w0 - 1);
  const int a1 = std::clamp(int(std::floor(x1 - shift)), a0, 2 * w0 - 1);
  int runs[2][2] = {{a0, std::min(a1, w0 - 1)}, {0, a1 - w0}};
  bool water = false, land = false;
  const Tile* t = nullptr;
  int tx = -1, ty = -1;
  for (int r = 0; r < (a1 >= w0 ? 2 : 1); ++r) {
    const int ix0 = runs[r][0] >> level, ix1 = std::min(runs[r][1] >> level, w - 1);
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix) {
        if (ix / tileSize_ != tx || iy / tileSize_ != ty) tx = ix / tileSize_, ty = iy / tileSize_, t = &tile(level, tx, ty);
        const Cover c = t->cls.empty() ? t->constant
                                       : Cover(t->cls[std::size_t(iy - ty * tileSize_) * tileSize_ + (ix - tx * tileSize_)]);
        if (c == Cover::Mixed) return Cover::Mixed;
        (c == Cover::Water ? water : land) = true;
        if (water && land) return Cover::Mixed;
      }
  }
  return water ? Cover::Water : Cover::Land;
}

}  // namespace geocean::world
