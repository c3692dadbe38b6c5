// Land/sea/lake classification from a mask raster and/or an elevation
// raster. A mask alone is enough; an elevation alone gives ocean where the
// elevation is below 0.
#pragma once

#include "globe/raster/Raster.h"
#include "globe/world/Surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace geocean::ocean {

// The classes and the mask encoding are the host's (globe/world), shared
// with the renderers' water rule.
using world::MaskEncoding;
using world::Surface;
using world::toString;

// One mask and/or one elevation raster. The queries are virtual so a
// layer stack (LayeredLandSea.h) is a LandSea to the sea query, the grid,
// the picker and the renderer.
class LandSea {
 public:
  LandSea(std::shared_ptr<const raster::Raster> mask, std::shared_ptr<const raster::Raster> elevation,
          MaskEncoding encoding = {});
  virtual ~LandSea() = default;

  virtual Surface classify(double latDeg, double lonDeg) const;
  virtual void classifyBatch(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const;

  // For drawing water surfaces: Ocean where any mask cell within two cells
  // is ocean or lake, else Land. The renderers' shoreline is a smooth
  // (cubic B-spline) blend of the coverage whose support is 4 x 4 cells, so
  // it can put water up to two cells beyond the nearest-cell class; geometry
  // skipped by this test is guaranteed dry. Falls back to classifyBatch
  // without an in-memory mask. The table is built on first use.
  virtual void classifyNearWaterBatch(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const;

  // Fraction of water (ocean or lake) around the point, in [0, 1]: the
  // cubic B-spline of the 4 x 4 nearest mask cells' water indicator, as
  // the renderers filter it magnified (world::coverageClassAt). Where a
  // mask answers, classify() is this coverage's class: water above 0.5
  // (world::coverageIsWater), so the query follows the drawn shoreline.
  virtual float waterCoverage(double latDeg, double lonDeg) const;
  // Terrain elevation (ocean depth negative) in metres, bilinear; NaN when
  // there is no elevation raster or no data there.
  virtual float elevationM(double latDeg, double lonDeg) const;
  virtual void elevationBatch(const double* latDeg, const double* lonDeg, std::size_t n, float* out) const;

  // The layers below this one (LayeredLandSea sets it): cells without data
  // (NaN) and a regional raster's cells past its edge take their coverage
  // and class at the cells' centres, as the layer's pages are drawn (a NaN
  // or outside texel takes the water grid below at its centre, geo_uv.glsl);
  // unset, a relief's nodata counts as land and a mask's edge cells repeat
  // past its edge. Set before any query (not thread-safe against them).
  using CoverageBelow = std::function<world::CoverageClass(double latDeg, double lonDeg)>;
  void setCoverageBelow(CoverageBelow below);
  // This layer's coverage and class at a point where it answers: a mask's
  // coverage rule, or a relief's on its cells' water (below 0 m); no data
  // there is land (coverage 0).
  world::CoverageClass maskCoverageAt(double latDeg, double lonDeg) const;
  world::CoverageClass reliefCoverageAt(double latDeg, double lonDeg) const;

  // The single rasters (null for a layer stack).
  const raster::Raster* mask() const { return mask_.get(); }
  const raster::Raster* elevation() const { return elevation_.get(); }

 protected:
  LandSea() = default;  // for LayeredLandSea, which answers every query itself

 private:
  Surface classOfValue(float maskValue) const;
  // The coverage rule at a point where the mask has data.
  world::CoverageClass coverageClass(double latDeg, double lonDeg) const;
  // Flags kCoast on classes_ cells with another class within one cell.
  void markCoast(bool global);
  static constexpr std::uint8_t kCoast = 0x80, kClassBits = 0x7F;
  Surface fromElevation(float elevationM) const;
  // Where the relief decides (e: its bilinear value at the point, NaN: no
  // data, Land): the coverage rule on its own cells' water (below 0 m), as
  // a coast a relief decides is drawn (world::reliefWaterPyramid's cells,
  // B-spline filtered), so the query follows the picture; within a cell of
  // the bilinear 0 m line. A pole is one point: the sign of its value.
  Surface reliefClass(double latDeg, double lonDeg, float e) const { return reliefCoverage(latDeg, lonDeg, e).surface; }
  world::CoverageClass reliefCoverage(double latDeg, double lonDeg, float e) const;
  // Poles are single points (issue 12 item 5): at a pole (|lat| >= 90) of a
  // global mask whose polar row ends there, the class of the row's one pole
  // value (raster::Raster::sampleNearest: the row's upper median, for two
  // classes the majority) at every longitude, not the coverage rule's blend
  // of the cells under that longitude. False elsewhere (out untouched).
  bool poleClass(double latDeg, Surface& out) const;
  void fixPoles(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const;

  // Nearest-cell index into classes_, or -1 outside the mask / for NaN.
  struct FastIndex {
    double invLonStep = 0, invLatStep = 0, originLon = 0, originLat = 0;
    double centreLon = 0;  // a regional mask reads the longitude nearest it (raster::lonNear)
    int width = 0, height = 0;
    bool global = false;
    double pixelX(double lonDeg) const {
      return ((global ? lonDeg : raster::lonNear(lonDeg, centreLon)) - originLon) * invLonStep;
    }
    int index(double latDeg, double lonDeg) const {
      double x = pixelX(lonDeg);
      const double y = (latDeg - originLat) * invLatStep;
      if (global) x -= std::floor(x / width) * width;
      // Negated comparisons also reject NaN.
      if (!(x >= 0.0 && x < width)) return -1;
      if (!(y > -1.0 && y < height + 1.0)) return -1;  // one cell of slack at the poles
      const int ix = static_cast<int>(x);
      const int iy = std::clamp(static_cast<int>(std::floor(y)), 0, height - 1);
      return iy * width + ix;
    }
  };

  std::shared_ptr<const raster::Raster> mask_, elevation_;
  MaskEncoding encoding_;
  CoverageBelow below_;
  // A mask's cells without data (1 = NaN), kept only when it has some and
  // layers below answer there.
  std::vector<std::uint8_t> noData_;
  // The coverage rule over the 4 x 4 cells about continuous pixel (px, py)
  // where some have no data or lie past a regional mask's edge: those take
  // below_ at their centres. cellClass(cx, cy) is the class of a cell with
  // data, hasData(cx, cy) whether it has (cx, cy unclamped).
  template <class CellClass, class HasData>
  world::CoverageClass blendBelow(const raster::GeoTransform& t, double px, double py, CellClass&& cellClass,
                                  HasData&& hasData) const;
  // In-memory mask as class bytes (| kCoast near a coast, where the
  // coverage decides): the fast path (no float conversion).
  std::vector<std::uint8_t> classes_;
  FastIndex fast_;
  mutable std::vector<std::uint8_t> nearWater_;  // 1 = water within two cells
  mutable std::once_flag nearWaterOnce_;
};

// Classifies n points; by default LandSea::classifyBatch. Consumers (the
// screen grid, the picker) call it concurrently from several threads, so it
// must be thread-safe and deterministic per point.
using SurfaceClassifier =
    std::function<void(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out)>;
inline SurfaceClassifier classifierFor(std::shared_ptr<const LandSea> landSea) {
  return [ls = std::move(landSea)](const double* lat, const double* lon, std::size_t n, Surface* out) {
    ls->classifyBatch(lat, lon, n, out);
  };
}

}  // namespace geocean::ocean
