#include "globe/host/OceanPlugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace geocean::host {

namespace {
std::string versionText(uint32_t v) { return std::to_string(v >> 16) + "." + std::to_string(v & 0xffffu); }

// dlsym into a typed pointer; false and an error naming the symbol if absent.
template <class Fn>
bool resolve(void* handle, const char* name, Fn& out, const std::string& path, std::string& error) {
  dlerror();
  void* sym = dlsym(handle, name);
  if (!sym) {
    const char* why = dlerror();
    error = path + ": missing symbol " + name + (why ? std::string(" (") + why + ")" : std::string());
    return false;
  }
  out = reinterpret_cast<Fn>(sym);
  return true;
}
}  // namespace

bool OceanPlugin::compatible(uint32_t host, uint32_t plugin) {
  return (host >> 16) == (plugin >> 16) && (plugin & 0xffffu) >= (host & 0xffffu);
}

std::unique_ptr<OceanPlugin> OceanPlugin::load(const std::string& path, std::string& error,
                                               uint32_t hostAbiVersion) {
  const std::string file = path.empty() ? kDefaultLibrary : path;
  // RTLD_LOCAL: the plugin's symbols do not leak into the host's namespace.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    error = "cannot load ocean plugin " + file + ": " + (why ? why : "unknown dlopen error");
    return nullptr;
  }
  std::unique_ptr<OceanPlugin> p(new OceanPlugin);
  p->handle_ = handle;
  p->path_ = file;
  OceanApi& a = p->api_;
  // The version first: a plugin of another major may lack the other symbols.
  if (!resolve(handle, "geocean_abi_version", a.abiVersion, file, error)) return nullptr;
  p->pluginAbi_ = a.abiVersion();
  if (!compatible(hostAbiVersion, p->pluginAbi_)) {
    error = file + ": plugin ABI " + versionText(p->pluginAbi_) + " cannot serve a host built for ABI " +
            versionText(hostAbiVersion) + " (need the same major and a minor >= the host's)";
    return nullptr;
  }
  const bool ok = resolve(handle, "geocean_version_string", a.versionString, file, error) &&
                  resolve(handle, "geocean_last_error", a.lastError, file, error) &&
                  resolve(handle, "geocean_status_string", a.statusString, file, error) &&
                  resolve(handle, "geocean_create", a.create, file, error) &&
                  resolve(handle, "geocean_destroy", a.destroy, file, error) &&
                  resolve(handle, "geocean_set_mask_file", a.setMaskFile, file, error) &&
                  resolve(handle, "geocean_set_elevation_file", a.setElevationFile, file, error) &&
                  resolve(handle, "geocean_set_mask_pixels", a.setMaskPixels, file, error) &&
                  resolve(handle, "geocean_set_elevation_pixels", a.setElevationPixels, file, error) &&
                  resolve(handle, "geocean_set_default_world", a.setDefaultWorld, file, error) &&
                  resolve(handle, "geocean_clear_rasters", a.clearRasters, file, error) &&
                  resolve(handle, "geocean_query_class", a.queryClass, file, error) &&
                  resolve(handle, "geocean_query_elevation", a.queryElevation, file, error) &&
                  resolve(handle, "geocean_sea_state_init", a.seaStateInit, file, error) &&
                  resolve(handle, "geocean_sea_state_set_beaufort", a.seaStateSetBeaufort, file, error) &&
                  resolve(handle, "geocean_set_sea_state", a.setSeaState, file, error) &&
                  resolve(handle, "geocean_query_sea_surface", a.querySeaSurface, file, error) &&
                  resolve(handle, "geocean_significant_wave_height", a.significantWaveHeight, file, error);
  if (!ok) return nullptr;
  // ABI 1.1 rendering: required by a 1.1 host, optional (NULL if absent) for a 1.0 host.
  if ((hostAbiVersion & 0xffffu) >= 1) {
    const bool ok11 = resolve(handle, "geocean_view_init", a.viewInit, file, error) &&
                      resolve(handle, "geocean_view_from_pose", a.viewFromPose, file, error) &&
                      resolve(handle, "geocean_update", a.update, file, error) &&
                      resolve(handle, "geocean_draw", a.draw, file, error) &&
                      resolve(handle, "geocean_release_gl", a.releaseGl, file, error);
    if (!ok11) return nullptr;
  } else {
    std::string ignored;
    resolve(handle, "geocean_view_init", a.viewInit, file, ignored);
    resolve(handle, "geocean_view_from_pose", a.viewFromPose, file, ignored);
    resolve(handle, "geocean_update", a.update, file, ignored);
    resolve(handle, "geocean_draw", a.draw, file, ignored);
    resolve(handle, "geocean_release_gl", a.releaseGl, file, ignored);
  }
  // ABI 1.2 queries and setters: present in every plugin of minor >= 2 (a
  // host of minor 2 gets no older plugin, compatible() saw to that).
  if ((p->pluginAbi_ & 0xffffu) >= 2) {
    const bool ok12 =
        resolve(handle, "geocean_raster_options_init", a.rasterOptionsInit, file, error) &&
        resolve(handle, "geocean_set_mask_file_with_options", a.setMaskFileWithOptions, file, error) &&
        resolve(handle, "geocean_set_elevation_file_with_options", a.setElevationFileWithOptions, file, error) &&
        resolve(handle, "geocean_set_default_world_with_options", a.setDefaultWorldWithOptions, file, error) &&
        resolve(handle, "geocean_set_mask_encoding", a.setMaskEncoding, file, error) &&
        resolve(handle, "geocean_surface_outputs_init", a.surfaceOutputsInit, file, error) &&
        resolve(handle, "geocean_query_surface", a.querySurface, file, error) &&
        resolve(handle, "geocean_get_layer_info", a.getLayerInfo, file, error) &&
        resolve(handle, "geocean_covers_opaquely", a.coversOpaquely, file, error) &&
        resolve(handle, "geocean_set_layer_inputs", a.setLayerInputs, file, error);
    if (!ok12) return nullptr;
  }
  // ABI 1.3 raster layers: present in every plugin of minor >= 3.
  if ((p->pluginAbi_ & 0xffffu) >= 3) {
    const bool ok13 = resolve(handle, "geocean_add_mask_layer_file", a.addMaskLayerFile, file, error) &&
                      resolve(handle, "geocean_add_elevation_layer_file", a.addElevationLayerFile, file, error) &&
                      resolve(handle, "geocean_add_mask_layer_pixels", a.addMaskLayerPixels, file, error) &&
                      resolve(handle, "geocean_add_elevation_layer_pixels", a.addElevationLayerPixels, file, error) &&
                      resolve(handle, "geocean_remove_layer", a.removeLayer, file, error) &&
                      resolve(handle, "geocean_clear_layers", a.clearLayers, file, error) &&
                      resolve(handle, "geocean_layer_count", a.layerCount, file, error);
    if (!ok13) return nullptr;
  }
  // ABI 1.4 floating bodies: present in every plugin of minor >= 4.
  if ((p->pluginAbi_ & 0xffffu) >= 4) {
    const bool ok14 = resolve(handle, "geocean_bodies_config_init", a.bodiesConfigInit, file, error) &&
                      resolve(handle, "geocean_body_desc_init", a.bodyDescInit, file, error) &&
                      resolve(handle, "geocean_bodies_create", a.bodiesCreate, file, error) &&
                      resolve(handle, "geocean_bodies_destroy", a.bodiesDestroy, file, error) &&
                      resolve(handle, "geocean_bodies_add", a.bodiesAdd, file, error) &&
                      resolve(handle, "geocean_bodies_remove", a.bodiesRemove, file, error) &&
                      resolve(handle, "geocean_bodies_count", a.bodiesCount, file, error) &&
                      resolve(handle, "geocean_bodies_advance_to", a.bodiesAdvanceTo, file, error) &&
                      resolve(handle, "geocean_bodies_time", a.bodiesTime, file, error) &&
                      resolve(handle, "geocean_bodies_get_poses", a.bodiesGetPoses, file, error) &&
                      resolve(handle, "geocean_bodies_get_hull", a.bodiesGetHull, file, error);
    if (!ok14) return nullptr;
  }
  // ABI 1.5 sea state at points and near-shore region: in every plugin of minor >= 5.
  if ((p->pluginAbi_ & 0xffffu) >= 5) {
    const bool ok15 = resolve(handle, "geocean_query_sea_state", a.querySeaState, file, error) &&
                      resolve(handle, "geocean_set_coast_region", a.setCoastRegion, file, error) &&
                      resolve(handle, "geocean_clear_coast_region", a.clearCoastRegion, file, error);
    if (!ok15) return nullptr;
  }
  // ABI 1.6 to 1.8 add no symbols: geocean_bodies_config's repulsion field,
  // the GEOCEAN_DRAW_COMPLETE_TILES, GEOCEAN_DRAW_FOLLOW_COAST,
  // GEOCEAN_DRAW_GRID_ISPG, GEOCEAN_DRAW_SUN_PHONG and GEOCEAN_DRAW_SHADOW_PAPER
  // flags, the shadow map's layer flag and inputs (a 1.8 host gets no older plugin).
  return p;
}

std::unique_ptr<OceanPlugin> OceanPlugin::loadForExecutable(std::string& error) {
  namespace fs = std::filesystem;
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("GEOCEAN_PLUGIN"); env && *env) candidates.push_back(env);
  std::error_code ec;
  const fs::path exeDir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  if (!ec) {
    candidates.push_back((exeDir / kDefaultLibrary).string());
    candidates.push_back((exeDir / GEOCEAN_BIN_TO_LIB / kDefaultLibrary).lexically_normal().string());
  }
  candidates.push_back(kDefaultLibrary);
  std::string tried;
  for (const std::string& c : candidates) {
    // A path that does not exist is skipped quietly; the search-path name is always tried.
    if (c.find('/') != std::string::npos && !fs::exists(c, ec)) {
      tried += "\n  " + c + ": no such file";
      continue;
    }
    std::string why;
    if (auto p = load(c, why)) return p;
    tried += "\n  " + why;
  }
  error = "cannot find the ocean plugin " + std::string(kDefaultLibrary) + " (set GEOCEAN_PLUGIN to its path):" + tried;
  return nullptr;
}

OceanPlugin::~OceanPlugin() {
  if (handle_) dlclose(handle_);
}

}  // namespace geocean::host
