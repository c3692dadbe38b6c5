#include "plugin/landsea/LayeredLandSea.h"

#include <cmath>
#include <cstdint>

namespace geocean::ocean {

LayeredLandSea::LayeredLandSea(std::vector<world::RasterLayer> layers) : stack_(std::move(layers)) {
  const auto& all = stack_.layers();
  for (std::size_t li = 0; li < all.size(); ++li) {
    const world::RasterLayer& l = all[li];
    auto layer = l.kind == world::LayerKind::Mask ? std::make_unique<LandSea>(l.raster, nullptr, l.encoding)
                                                  : std::make_unique<LandSea>(nullptr, l.raster);
    // A layer's nodata cells and cells past a regional edge take the layers
    // below it, as drawn (issue 12).
    layer->setCoverageBelow([this, li](double lat, double lon) { return coverageFrom(li + 1, lat, lon); });
    perLayer_.push_back(std::move(layer));
  }
}

world::CoverageClass LayeredLandSea::coverageFrom(std::size_t first, double latDeg, double lonDeg) const {
  // The first layer from `first` with data at the point (as the stack
  // picks one: a mask's nearest cell, a relief's bilinear sample), its
  // coverage rule; land where none has data.
  const auto& all = stack_.layers();
  for (std::size_t k = first; k < all.size(); ++k) {
    const world::RasterLayer& l = all[k];
    if (l.kind == world::LayerKind::Mask) {
      if (!std::isnan(l.raster->sampleNearest(latDeg, lonDeg))) return perLayer_[k]->maskCoverageAt(latDeg, lonDeg);
    } else if (l.kind == world::LayerKind::Elevation) {
      if (!std::isnan(l.raster->sampleBilinear(latDeg, lonDeg))) return perLayer_[k]->reliefCoverageAt(latDeg, lonDeg);
    }
  }
  return {};
}

Surface LayeredLandSea::classify(double latDeg, double lonDeg) const {
  Surface s;
  classifyBatch(&latDeg, &lonDeg, 1, &s);
  return s;
}

void LayeredLandSea::byLayer(const double* lat, const double* lon, std::size_t n, Surface* out,
                             void (LandSea::*test)(const double*, const double*, std::size_t, Surface*) const) const {
  std::vector<std::int32_t> by(n);
  stack_.classifyBatch(lat, lon, n, out, by.data());
  // Points grouped by their answering layer, each group through its test.
  std::vector<double> la, lo;
  std::vector<std::size_t> where;
  std::vector<Surface> s;
  for (std::size_t li = 0; li < perLayer_.size(); ++li) {
    la.clear(), lo.clear(), where.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (by[i] == std::int32_t(li)) la.push_back(lat[i]), lo.push_back(lon[i]), where.push_back(i);
    if (where.empty()) continue;
    s.resize(where.size());
    (perLayer_[li].get()->*test)(la.data(), lo.data(), where.size(), s.data());
    for (std::size_t j = 0; j < where.size(); ++j) out[where[j]] = s[j];
  }
}

void LayeredLandSea::classifyBatch(const double* lat, const double* lon, std::size_t n, Surface* out) const {
  // The stack picks the layer by its nearest cell; its class is then its
  // coverage rule (LandSea::classify): a mask's, or a relief's on the sign
  // of its cells.
  byLayer(lat, lon, n, out, &LandSea::classifyBatch);
}

void LayeredLandSea::classifyNearWaterBatch(const double* lat, const double* lon, std::size_t n, Surface* out) const {
  byLayer(lat, lon, n, out, &LandSea::classifyNearWaterBatch);
}

float LayeredLandSea::waterCoverage(double latDeg, double lonDeg) const {
  Surface s;
  std::int32_t by = -1;
  stack_.classifyBatch(&latDeg, &lonDeg, 1, &s, &by);
  return by < 0 ? 0.0f : perLayer_[std::size_t(by)]->waterCoverage(latDeg, lonDeg);
}

float LayeredLandSea::elevationM(double latDeg, double lonDeg) const {
  float e;
  stack_.elevationBatch(&latDeg, &lonDeg, 1, &e);
  return e;
}

void LayeredLandSea::elevationBatch(const double* lat, const double* lon, std::size_t n, float* out) const {
  stack_.elevationBatch(lat, lon, n, out);
}

}  // namespace geocean::ocean
