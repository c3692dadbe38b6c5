#include "globe/host/OceanLayer.h"

#include <cmath>
#include <stdexcept>

namespace geocean::host {

PluginOceanLayer::PluginOceanLayer(std::shared_ptr<const OceanPlugin> plugin, geocean_ocean* ocean)
    : plugin_(std::move(plugin)), ocean_(ocean) {}

PluginOceanLayer::~PluginOceanLayer() { plugin_->api().destroy(ocean_); }

geocean_view hostView(const geocean_view& defaults, const render::ViewMatrices& vm, const render::ViewPose& pose,
                      const render::Lighting& light) {
  geocean_view v = defaults;
  for (int i = 0; i < 3; ++i) {
    v.eye_ecef_m[i] = vm.eyeEcef[i];
    v.sun_dir_ecef[i] = light.sunEcef[i];
  }
  std::fill(v.view_matrix, v.view_matrix + 16, 0.0);
  for (int c = 0; c < 3; ++c) {  // rows right, up, back (column-major storage)
    v.view_matrix[4 * c + 0] = vm.right[c];
    v.view_matrix[4 * c + 1] = vm.up[c];
    v.view_matrix[4 * c + 2] = -vm.forward[c];
  }
  v.view_matrix[15] = 1.0;
  // As render::viewMatrices builds it, in double (vm.proj is float).
  const double f = 1.0 / std::tan(0.5 * pose.fovYDeg * 3.14159265358979323846 / 180.0);
  std::fill(v.projection_matrix, v.projection_matrix + 16, 0.0);
  v.projection_matrix[0] = f / (double(pose.width) / double(pose.height));
  v.projection_matrix[5] = f;
  v.projection_matrix[11] = -1.0;
  v.projection_matrix[14] = vm.nearM;
  v.viewport_width_px = pose.width;
  v.viewport_height_px = pose.height;
  v.time_s = light.timeS;
  return v;
}

void PluginOceanLayer::draw(const render::ViewMatrices& vm, const render::ViewPose& pose,
                            const render::Lighting& light, bool bare) {
  const OceanApi& a = plugin_->api();
  geocean_view defaults;
  if (a.viewInit(&defaults) != GEOCEAN_OK) throw std::runtime_error(a.lastError());
  geocean_view v = hostView(defaults, vm, pose, light);
  v.draw_flags = bare ? GEOCEAN_DRAW_REFERENCE : 0u;
  if (a.update(ocean_, &v) != GEOCEAN_OK || a.draw(ocean_) != GEOCEAN_OK)
    throw std::runtime_error(std::string("ocean plugin: ") + a.lastError());
}

std::string addPluginOcean(render::GlobeRenderer& renderer, const std::string& modelName, double windMps,
                           double windFromDeg, std::shared_ptr<PluginOceanLayer>* created) {
  std::string error;
  std::shared_ptr<const OceanPlugin> plugin = OceanPlugin::loadForExecutable(error);
  if (!plugin) return error;
  const OceanApi& a = plugin->api();
  geocean_sea_state s;
  a.seaStateInit(&s);
  if (modelName == "noise")
    s.model = GEOCEAN_WAVES_NOISE;
  else if (modelName == "gerstner")
    s.model = GEOCEAN_WAVES_GERSTNER;
  else if (modelName == "fft")
    s.model = GEOCEAN_WAVES_FFT;
  else
    return "--waves '" + modelName + "' is not a GPU wave model (noise, gerstner, fft)";
  s.wind_speed_mps = windMps;
  s.wind_from_deg = windFromDeg;
  geocean_ocean* ocean = nullptr;
  if (a.create(GEOCEAN_ABI_VERSION, &ocean) != GEOCEAN_OK) return a.lastError();
  auto layer = std::make_shared<PluginOceanLayer>(plugin, ocean);  // owns the ocean from here
  if (a.setDefaultWorld(ocean) != GEOCEAN_OK || a.setSeaState(ocean, &s) != GEOCEAN_OK) return a.lastError();
  renderer.addLayer(layer);
  if (created) *created = layer;
  return {};
}

}  // namespace geocean::host
