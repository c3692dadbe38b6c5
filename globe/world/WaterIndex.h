// Where the water coverage texture is water all around: a pyramid of "any
// land in this 2^k x 2^k block" flags over a global equirectangular water
// layer (1 water, anything less counts as land). The renderers use it to
// give open water cheaper shaders and to leave out terrain that the ocean
// covers. A rectangle of texels starts from at most 6 x 6 blocks and
// refines only blocks with land that it covers in part: exact answers, in
// work that grows with the land along the rectangle's edges.
#pragma once

#include <cstdint>
#include <vector>

namespace geocean::world {

struct WorldLayer;

class WaterIndex {
 public:
  WaterIndex() = default;
  explicit WaterIndex(const WorldLayer& water);

  // True when every texel that the rectangle [x0, x1] x [y0, y1] of
  // continuous texel coordinates touches is water (texel i spans [i, i + 1);
  // x wraps around the globe, y is clamped to the raster; the corners may
  // come in any order). Empty index (no layer) or NaN bounds: false.
  bool allWater(double x0, double x1, double y0, double y1) const;
  // The same for a longitude / latitude rectangle (corners in any order)
  // widened by `marginTexels` on every side. Widen here, not in texel
  // coordinates by hand: latitude steps are negative (north up), so
  // texelY(lat0) - m, texelY(lat1) + m narrows the rectangle instead.
  bool allWaterAround(double lat0, double lat1, double lon0, double lon1, double marginTexels) const;

  // Continuous texel coordinates of a longitude / latitude in degrees.
  double texelX(double lonDeg) const { return (lonDeg - originLonDeg_) / lonStepDeg_; }
  double texelY(double latDeg) const { return (latDeg - originLatDeg_) / latStepDeg_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // Size of one texel, degrees (positive).
  double lonStepDeg() const { return lonStepDeg_ < 0 ? -lonStepDeg_ : lonStepDeg_; }
  double latStepDeg() const { return latStepDeg_ < 0 ? -latStepDeg_ : latStepDeg_; }

 private:
  bool anyLand(int x0, int x1, int y0, int y1) const;  // integer texels, x0..x1 within [0, width)
  bool blockHasLand(std::size_t k, int bx, int by, int x0, int x1, int y0, int y1) const;

  int width_ = 0, height_ = 0;
  double originLonDeg_ = 0, originLatDeg_ = 0, lonStepDeg_ = 1, latStepDeg_ = -1;
  struct Level {
    int width, height;
    std::vector<std::uint64_t> land;  // bit set: some texel of the block is not water
    bool at(int x, int y) const {
      const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
      return (land[i >> 6] >> (i & 63)) & 1u;
    }
    void set(int x, int y) {
      const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
      land[i >> 6] |= std::uint64_t(1) << (i & 63);
    }
  };
  std::vector<Level> levels_;
};

}  // namespace geocean::world
