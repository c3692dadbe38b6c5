#include "globe/world/WaterIndex.h"

#include "globe/world/WorldData.h"

#include <algorithm>
#include <cmath>

namespace geocean::world {

WaterIndex::WaterIndex(const WorldLayer& water)
    : width_(water.width),
      height_(water.height),
      originLonDeg_(water.originLonDeg),
      originLatDeg_(water.originLatDeg),
      lonStepDeg_(water.lonStepDeg),
      latStepDeg_(water.latStepDeg) {
  if (width_ <= 0 || height_ <= 0) {
    width_ = height_ = 0;
    return;
  }
  // One bit per block (the 5' mask: 1.2 MB for the finest level).
  const auto makeLevel = [](int w, int h) {
    return Level{w, h, std::vector<std::uint64_t>((std::size_t(w) * std::size_t(h) + 63) / 64, 0)};
  };
  Level base = makeLevel(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      if (!(water.values[(std::size_t(y) * width_ + x) * std::size_t(water.channels)] >= 1.0f))
        base.set(x, y);  // NaN counts as land
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& f = levels_.back();
    Level c = makeLevel((f.width + 1) / 2, (f.height + 1) / 2);
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x)
        if (f.at(x, y)) c.set(x / 2, y / 2);
    levels_.push_back(std::move(c));
  }
}

bool WaterIndex::anyLand(int x0, int x1, int y0, int y1) const {
  // Start at the finest level where the rectangle spans at most 6 blocks a
  // side; blocks with land that the rectangle only partly covers are split
  // into their children, so the answer is exact and the work stays near
  // the rectangle's edges.
  std::size_t k = 0;
  while (k + 1 < levels_.size() && (((x1 >> k) - (x0 >> k)) > 5 || ((y1 >> k) - (y0 >> k)) > 5)) ++k;
  for (int by = y0 >> k; by <= (y1 >> k); ++by)
    for (int bx = x0 >> k; bx <= (x1 >> k); ++bx)
      if (blockHasLand(k, bx, by, x0, x1, y0, y1)) return true;
  return false;
}

bool WaterIndex::blockHasLand(std::size_t k, int bx, int by, int x0, int x1, int y0, int y1) const {
  const Level& l = levels_[k];
  if (bx >= l.width || by >= l.height || !l.at(bx, by)) return false;
  const int s = 1 << k;
  if (k == 0 || (bx * s >= x0 && (bx + 1) * s - 1 <= x1 && by * s >= y0 && (by + 1) * s - 1 <= y1)) return true;
  for (int cy = 2 * by; cy <= 2 * by + 1; ++cy)
    for (int cx = 2 * bx; cx <= 2 * bx + 1; ++cx) {
      const int h = s / 2;
      if (cx * h > x1 || (cx + 1) * h - 1 < x0 || cy * h > y1 || (cy + 1) * h - 1 < y0) continue;
      if (blockHasLand(k - 1, cx, cy, x0, x1, y0, y1)) return true;
    }
  return false;
}

bool WaterIndex::allWater(double x0, double x1, double y0, double y1) const {
  if (levels_.empty()) return false;
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  if (!(x0 <= x1) || !(y0 <= y1)) return false;  // NaN
  const int iy0 = int(std::clamp(std::floor(y0), 0.0, double(height_ - 1)));
  const int iy1 = int(std::clamp(std::floor(y1), 0.0, double(height_ - 1)));
  // Far outside the globe's first turns (bad input): the whole row range.
  if (x1 - x0 >= width_ - 1 || std::abs(x0) > 1e9 || std::abs(x1) > 1e9) return !anyLand(0, width_ - 1, iy0, iy1);
  // Both ends in [0, 2 width): one or two runs of columns.
  const double shift = std::floor(x0 / width_) * width_;
  const int ix0 = std::clamp(int(std::floor(x0 - shift)), 0, width_ - 1);
  const int ix1 = std::clamp(int(std::floor(x1 - shift)), ix0, 2 * width_ - 1);
  if (ix1 < width_) return !anyLand(ix0, ix1, iy0, iy1);
  return !anyLand(ix0, width_ - 1, iy0, iy1) && !anyLand(0, ix1 - width_, iy0, iy1);
}

bool WaterIndex::allWaterAround(double lat0, double lat1, double lon0, double lon1, double marginTexels) const {
  double x0 = texelX(lon0), x1 = texelX(lon1), y0 = texelY(lat0), y1 = texelY(lat1);
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  return allWater(x0 - marginTexels, x1 + marginTexels, y0 - marginTexels, y1 + marginTexels);
}

}  // namespace geocean::world
