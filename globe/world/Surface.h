// Surface classes and the mask encoding: the one place where a mask value
// becomes ocean, land or lake, and hence water or not. The classifier
// (plugin/landsea), the host's world textures and the ocean's own water
// grids all go through MaskEncoding::classify.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace geocean::world {

enum class Surface : std::uint8_t { Ocean = 0, Land = 1, Lake = 2 };
const char* toString(Surface s);  // "ocean" | "land" | "lake"

// How mask values map to classes (default: 0 ocean, 1 land, 2 lake;
// values >= 256 or unmapped count as land).
struct MaskEncoding {
  std::array<Surface, 256> classOf{};
  MaskEncoding();
  static MaskEncoding parse(const std::string& spec);  // "0=ocean,1=land,2=lake,3=land"

  // A sample's class: NaN, negative and > 255 are land; others round to
  // the nearest integer value.
  Surface classify(float value) const;
  // The water rule: ocean and lake are water.
  bool isWater(float value) const { return classify(value) != Surface::Land; }
};

// The coverage rule (issue 12): what is drawn and what the query answers
// are one function of the water coverage. Coverage is the cubic B-spline
// of the 0/1 water indicator (MaskEncoding::isWater) of the 4 x 4 cells
// around the point, the CPU twin of textureBSplineGather
// (shaders/geo_uv.glsl) that the ocean and the terrain draw magnified; the
// shoreline is its 0.5 isoline.
inline bool coverageIsWater(float coverage) { return coverage > 0.5f; }

// Cubic B-spline weights along one axis at continuous pixel coordinate p
// (cell i spans [i, i + 1), centre i + 0.5): the four cells first .. first+3.
struct BSplineTaps {
  int first = 0;
  float w[4] = {0, 0, 0, 0};
  explicit BSplineTaps(double p) {
    // Far outside any raster every tap lands on the clamped edge cell
    // anyway; bounding q keeps int(i) defined for any placement (NaN too).
    double q = p - 0.5;
    if (!(q > -1e9)) q = -1e9;
    if (!(q < 1e9)) q = 1e9;
    const double i = std::floor(q);
    const float f = float(q - i), f2 = f * f, f3 = f2 * f;
    first = int(i) - 1;
    w[0] = (1.0f - 3.0f * f + 3.0f * f2 - f3) / 6.0f;
    w[1] = (4.0f - 6.0f * f2 + 3.0f * f3) / 6.0f;
    w[2] = (1.0f + 3.0f * f + 3.0f * f2 - 3.0f * f3) / 6.0f;
    w[3] = f3 / 6.0f;
  }
};

// Coverage and class at continuous pixel (px, py) of a mask whose cells'
// classes cellClass(cx, cy) returns (the caller wraps or clamps cx, cy).
// Water (coverage > 0.5) takes the water class of more weight, ocean or
// lake; anything else is land.
struct CoverageClass {
  float coverage = 0.0f;
  Surface surface = Surface::Land;
};
template <class CellClass>
CoverageClass coverageClassAt(double px, double py, CellClass&& cellClass) {
  const BSplineTaps tx(px), ty(py);
  // Separable, row by row (the order of the sums is part of the function).
  float ocean = 0.0f, lake = 0.0f;
  int wet = 0;
  for (int j = 0; j < 4; ++j) {
    float rowOcean = 0.0f, rowLake = 0.0f;
    for (int i = 0; i < 4; ++i) {
      const Surface s = cellClass(tx.first + i, ty.first + j);
      rowOcean += s == Surface::Ocean ? tx.w[i] : 0.0f;
      rowLake += s == Surface::Lake ? tx.w[i] : 0.0f;
      wet += s != Surface::Land;
    }
    ocean += ty.w[j] * rowOcean;
    lake += ty.w[j] * rowLake;
  }
  CoverageClass c;
  // All water is 1 exactly (the float weights sum to 1 - 6e-8).
  c.coverage = wet == 16 ? 1.0f : std::min(1.0f, ocean + lake);
  if (coverageIsWater(c.coverage)) c.surface = lake > ocean ? Surface::Lake : Surface::Ocean;
  return c;
}

}  // namespace geocean::world
