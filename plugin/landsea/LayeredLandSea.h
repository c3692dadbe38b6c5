// Land/sea over a layer stack (globe/world/LayerStack.h): at each point the
// first layer with data answers, classes, elevation, coverage and the
// near-water test alike. The façade builds one when the user adds layers.
#pragma once

#include "globe/world/LayerStack.h"
#include "plugin/landsea/LandSea.h"

#include <memory>
#include <vector>

namespace geocean::ocean {

class LayeredLandSea final : public LandSea {
 public:
  // Not copyable or movable: its reliefs' coverage below calls back into it.
  LayeredLandSea(const LayeredLandSea&) = delete;
  LayeredLandSea& operator=(const LayeredLandSea&) = delete;
  // Throws std::invalid_argument for an empty stack.
  explicit LayeredLandSea(std::vector<world::RasterLayer> layers);

  // A mask layer's class by its coverage rule (LandSea::classify).
  Surface classify(double latDeg, double lonDeg) const override;
  void classifyBatch(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const override;
  // Each point by its answering layer's own test.
  void classifyNearWaterBatch(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const override;
  // The answering layer's coverage (a mask's four-cell blend, an
  // elevation's +-50 m ramp); 0 where no layer has data.
  float waterCoverage(double latDeg, double lonDeg) const override;
  float elevationM(double latDeg, double lonDeg) const override;
  void elevationBatch(const double* latDeg, const double* lonDeg, std::size_t n, float* out) const override;

  const world::LayerStack& stack() const { return stack_; }

 private:
  // The stack's answer, then each point again through its answering
  // layer's `test`.
  void byLayer(const double* lat, const double* lon, std::size_t n, Surface* out,
               void (LandSea::*test)(const double*, const double*, std::size_t, Surface*) const) const;
  // The water coverage and class of the layers from `first` on at a point:
  // what a layer's nodata cells and cells past its regional edge take
  // (LandSea::setCoverageBelow). Land where no layer has data.
  world::CoverageClass coverageFrom(std::size_t first, double latDeg, double lonDeg) const;
  world::LayerStack stack_;
  // One single-raster LandSea per layer, in stack order: coverage and
  // near-water per layer with the existing fast paths.
  std::vector<std::unique_ptr<const LandSea>> perLayer_;
};

}  // namespace geocean::ocean
