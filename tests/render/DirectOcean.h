// A host layer that draws plugin/render's OceanRenderer in-process (tests
// and benchmarks: the geocean executable draws the ocean through the C ABI
// instead, globe/host/OceanLayer).
#pragma once

#include "globe/render/GlobeRenderer.h"
#include "globe/render/Layer.h"
#include "plugin/render/OceanRenderer.h"
#include "plugin/waves/WaveField.h"

#include <memory>
#include <stdexcept>
#include <string>

namespace geocean::render::test {

class DirectOceanLayer : public Layer {
 public:
  // wants: LayerInput bits; by default what the plugin's layer info asks
  // for (geocean_get_layer_info), so both draw the same picture.
  explicit DirectOceanLayer(std::shared_ptr<ocean_render::OceanRenderer> ocean,
                            unsigned wants = kLayerWantsReflection | kLayerWantsShadowMap)
      : ocean_(std::move(ocean)), wants_(wants) {}
  const char* name() const override { return "ocean"; }
  LayerInfo info() const override { return {true, ocean_->cellPx(), wants_}; }
  bool coversOpaquely(double lat0, double lat1, double lon0, double lon1, double footprintM) const override {
    return ocean_->coversOpaquely(lat0, lat1, lon0, lon1, footprintM);
  }
  void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare, const LayerInputs& in) override {
    ocean_render::OceanInputs oi;
    oi.reflectionColor = in.reflectionColor;
    if (in.reflectionColor) oi.reflectionCamera = in.reflectionCamera;
    oi.refraction = in.refraction;
    oi.shadowDepth = in.shadowDepth;
    oi.shadowSize = in.shadowSize;
    oi.shadowMatrix = in.shadowMatrix;
    oi.shadowOriginEcef = in.shadowOriginEcef;
    oi.shadowReachM = in.shadowReachM;
    oi.shadowPaper = in.shadowModel == ShadowModel::Paper;
    oi.sunPhong = in.sunModel == SunModel::Phong;
    oi.phongExponent = phongExponent;
    ocean_->setInputs(oi);
    ocean_->draw(cam, light, bare);
  }
  // Tests draw other sea states in the same session (one GL context).
  void setOcean(std::shared_ptr<ocean_render::OceanRenderer> ocean) { ocean_ = std::move(ocean); }
  const std::shared_ptr<ocean_render::OceanRenderer>& ocean() const { return ocean_; }
  // Phong's exponent for the next draws (0: from the slopes not drawn, as the plugin).
  double phongExponent = 0.0;

 private:
  std::shared_ptr<ocean_render::OceanRenderer> ocean_;
  unsigned wants_ = 0u;
};

// The default world's ocean (model by CLI name) on `grids`, added to the
// renderer; returns an error message naming the option (empty on success).
inline std::string addDirectOcean(GlobeRenderer& renderer, std::shared_ptr<const world::WorldGrids> grids,
                                  const std::string& modelName, double windMps, double windFromDeg,
                                  std::shared_ptr<ocean_render::OceanRenderer>* created = nullptr,
                                  std::shared_ptr<DirectOceanLayer>* layer = nullptr,
                                  ocean_render::OceanOptions oo = {}) {
  const auto model = waves::parseModel(modelName);
  if (!model) return "--waves '" + modelName + "' is not a GPU wave model (noise, noise-paper, gerstner, fft)";
  oo.model = *model;
  oo.sea.windSpeedMps = windMps;
  oo.sea.windFromDeg = windFromDeg;
  try {
    auto o = std::make_shared<ocean_render::OceanRenderer>(std::move(grids), ocean_render::defaultLandSea(), oo);
    auto l = std::make_shared<DirectOceanLayer>(o);
    renderer.addLayer(l);
    if (created) *created = o;
    if (layer) *layer = l;
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace geocean::render::test
