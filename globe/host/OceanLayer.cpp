#include "globe/host/OceanLayer.h"

#include <cmath>
#include <stdexcept>

namespace geocean::host {

PluginOceanLayer::PluginOceanLayer(std::shared_ptr<const OceanPlugin> plugin, geocean_ocean* ocean)
    : plugin_(std::move(plugin)), ocean_(ocean) {
  const OceanApi& a = plugin_->api();
  if (!a.getLayerInfo) return;
  geocean_layer_info li{};
  li.struct_size = sizeof li;
  if (a.getLayerInfo(ocean_, &li) != GEOCEAN_OK) throw std::runtime_error(a.lastError());
  info_.opaqueWater = (li.flags & GEOCEAN_LAYER_OPAQUE_WATER) != 0 && a.coversOpaquely;
  info_.cellPx = li.cell_px;
  info_.wants = ((li.flags & GEOCEAN_LAYER_WANTS_REFLECTION) ? render::kLayerWantsReflection : 0u) |
                ((li.flags & GEOCEAN_LAYER_WANTS_SCENE_COPY) ? render::kLayerWantsSceneCopy : 0u) |
                ((li.flags & GEOCEAN_LAYER_WANTS_SHADOW_MAP) ? render::kLayerWantsShadowMap : 0u);
}

PluginOceanLayer::~PluginOceanLayer() { plugin_->api().destroy(ocean_); }

render::LayerInfo PluginOceanLayer::info() const { return info_; }

bool PluginOceanLayer::coversOpaquely(double lat0, double lat1, double lon0, double lon1, double footprintM) const {
  const OceanApi& a = plugin_->api();
  int32_t covers = 0;
  if (a.coversOpaquely(ocean_, lat0, lat1, lon0, lon1, footprintM, &covers) != GEOCEAN_OK)
    throw std::runtime_error(std::string("ocean plugin: ") + a.lastError());
  return covers != 0;
}

geocean_view hostView(const geocean_view& defaults, const camera::Camera& cam, const camera::Lighting& light) {
  geocean_view v = defaults;
  for (int i = 0; i < 3; ++i) {
    v.eye_ecef_m[i] = cam.eyeEcef()[i];
    v.sun_dir_ecef[i] = light.sunEcef[i];
  }
  std::fill(v.view_matrix, v.view_matrix + 16, 0.0);
  for (int c = 0; c < 3; ++c) {  // rows right, up, back (column-major storage)
    v.view_matrix[4 * c + 0] = cam.right()[c];
    v.view_matrix[4 * c + 1] = cam.up()[c];
    v.view_matrix[4 * c + 2] = -cam.forward()[c];
  }
  v.view_matrix[15] = 1.0;
  const glm::dmat4& p = cam.gpu().projD;  // double: the float copy would lose bits
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) v.projection_matrix[4 * c + r] = p[c][r];
  v.viewport_width_px = cam.widthPx();
  v.viewport_height_px = cam.heightPx();
  v.time_s = light.timeS;
  return v;
}

void PluginOceanLayer::draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
                            const render::LayerInputs& inputs) {
  const OceanApi& a = plugin_->api();
  geocean_view defaults;
  if (a.viewInit(&defaults) != GEOCEAN_OK) throw std::runtime_error(a.lastError());
  geocean_view v = hostView(defaults, cam, light);
  v.draw_flags = (bare ? GEOCEAN_DRAW_REFERENCE : 0u) | (inputs.refraction ? 0u : GEOCEAN_DRAW_NO_REFRACTION) |
                 (completeTiles_ ? GEOCEAN_DRAW_COMPLETE_TILES : 0u) | (gridIspg_ ? GEOCEAN_DRAW_GRID_ISPG : 0u) |
                 (followCoast_ ? GEOCEAN_DRAW_FOLLOW_COAST : 0u) |
                 (inputs.sunModel == render::SunModel::Phong ? GEOCEAN_DRAW_SUN_PHONG : 0u) |
                 (inputs.shadowModel == render::ShadowModel::Paper ? GEOCEAN_DRAW_SHADOW_PAPER : 0u);
  if (a.setLayerInputs && info_.wants) {
    geocean_layer_inputs in{};
    in.struct_size = sizeof in;
    in.reflection_color_texture = inputs.reflectionColor;
    in.scene_color_texture = inputs.sceneColor;
    in.scene_depth_texture = inputs.sceneDepth;
    in.reflection_view = hostView(defaults, inputs.reflectionCamera, light);
    in.shadow_depth_texture = inputs.shadowDepth;
    in.shadow_size_px = uint32_t(inputs.shadowSize);
    for (int i = 0; i < 3; ++i) in.shadow_origin_ecef_m[i] = inputs.shadowOriginEcef[i];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) in.shadow_matrix[4 * c + r] = inputs.shadowMatrix[c][r];
    in.shadow_reach_m = inputs.shadowReachM;
    if (a.setLayerInputs(ocean_, &in) != GEOCEAN_OK)
      throw std::runtime_error(std::string("ocean plugin: ") + a.lastError());
  }
  if (a.update(ocean_, &v) != GEOCEAN_OK || a.draw(ocean_) != GEOCEAN_OK)
    throw std::runtime_error(std::string("ocean plugin: ") + a.lastError());
}

namespace {
// The ABI's sea state for a model by CLI name and a wind; an error names
// the model when it has no GPU form.
std::string seaStateOf(const OceanApi& a, const std::string& modelName, double windMps, double windFromDeg,
                       geocean_sea_state& s) {
  a.seaStateInit(&s);
  if (modelName == "noise")
    s.model = GEOCEAN_WAVES_NOISE;
  else if (modelName == "noise-paper")
    s.model = GEOCEAN_WAVES_NOISE_PAPER;
  else if (modelName == "gerstner")
    s.model = GEOCEAN_WAVES_GERSTNER;
  else if (modelName == "fft")
    s.model = GEOCEAN_WAVES_FFT;
  else
    return "--waves '" + modelName + "' is not a GPU wave model (noise, noise-paper, gerstner, fft)";
  s.wind_speed_mps = windMps;
  s.wind_from_deg = windFromDeg;
  return {};
}
}  // namespace

std::string setPluginSeaState(PluginOceanLayer& ocean, const std::string& modelName, double windMps,
                              double windFromDeg) {
  const OceanApi& a = ocean.plugin().api();
  geocean_sea_state s;
  if (std::string err = seaStateOf(a, modelName, windMps, windFromDeg, s); !err.empty()) return err;
  if (a.setSeaState(ocean.ocean(), &s) != GEOCEAN_OK) return a.lastError();
  return {};
}

namespace {
std::string addLayers(const OceanApi& a, geocean_ocean* ocean, const std::vector<world::LayerSource>& layers) {
  for (const world::LayerSource& l : layers) {
    const geocean_status st =
        l.kind == world::LayerKind::Mask
            ? a.addMaskLayerFile(ocean, l.path.c_str(), l.priority, l.encoding.c_str(), nullptr)
            : a.addElevationLayerFile(ocean, l.path.c_str(), l.priority, nullptr);
    if (st != GEOCEAN_OK) return a.lastError();
  }
  return {};
}
}  // namespace

std::string setPluginLayers(PluginOceanLayer& ocean, const std::vector<world::LayerSource>& layers) {
  const OceanApi& a = ocean.plugin().api();
  if (!a.clearLayers) return ocean.plugin().path() + ": plugin ABI below 1.3 takes no raster layers";
  if (a.clearLayers(ocean.ocean()) != GEOCEAN_OK) return a.lastError();
  return addLayers(a, ocean.ocean(), layers);
}

std::string addPluginOcean(render::GlobeRenderer& renderer, const std::string& modelName, double windMps,
                           double windFromDeg, std::shared_ptr<PluginOceanLayer>* created,
                           const std::vector<world::LayerSource>& layers, bool defaultWorld) {
  std::string error;
  std::shared_ptr<const OceanPlugin> plugin = OceanPlugin::loadForExecutable(error);
  if (!plugin) return error;
  const OceanApi& a = plugin->api();
  geocean_sea_state s;
  if (std::string err = seaStateOf(a, modelName, windMps, windFromDeg, s); !err.empty()) return err;
  geocean_ocean* ocean = nullptr;
  if (a.create(GEOCEAN_ABI_VERSION, &ocean) != GEOCEAN_OK) return a.lastError();
  auto layer = std::make_shared<PluginOceanLayer>(plugin, ocean);  // owns the ocean from here
  if (defaultWorld && a.setDefaultWorld(ocean) != GEOCEAN_OK) return a.lastError();
  if (!layers.empty() && !a.addMaskLayerFile)
    return plugin->path() + ": plugin ABI below 1.3 takes no raster layers (--mask, --elevation)";
  if (std::string err = addLayers(a, ocean, layers); !err.empty()) return err;
  if (a.setSeaState(ocean, &s) != GEOCEAN_OK) return a.lastError();
  renderer.addLayer(layer);
  if (created) *created = layer;
  return {};
}

}  // namespace geocean::host
