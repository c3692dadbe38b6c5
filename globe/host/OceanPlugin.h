// Host-side loader for the ocean plugin: dlopens libgeocean_ocean.so,
// checks its ABI version against the header this host was built with, and
// resolves every function of the C ABI into a table. The host never links
// the plugin, so it sees exactly what another engine would.
//
//   std::string error;
//   auto plugin = geocean::host::OceanPlugin::load(path, error);  // "" = default name
//   if (!plugin) { report(error); }
//   geocean_ocean* ocean = nullptr;
//   plugin->api().create(GEOCEAN_ABI_VERSION, &ocean);
//
// Thread-safety: load() and the destructor are not thread-safe with respect
// to each other; the function table may be used from any thread (each
// function's own rules are in the header and docs/PLUGIN_ABI.md).
#pragma once

#include "geocean/geocean_ocean.h"

#include <memory>
#include <string>

namespace geocean::host {

// The C ABI as function pointers, one per function of geocean_ocean.h.
struct OceanApi {
  uint32_t (*abiVersion)(void) = nullptr;
  const char* (*versionString)(void) = nullptr;
  const char* (*lastError)(void) = nullptr;
  const char* (*statusString)(geocean_status) = nullptr;
  geocean_status (*create)(uint32_t, geocean_ocean**) = nullptr;
  void (*destroy)(geocean_ocean*) = nullptr;
  geocean_status (*setMaskFile)(geocean_ocean*, const char*, geocean_georef) = nullptr;
  geocean_status (*setElevationFile)(geocean_ocean*, const char*, geocean_georef) = nullptr;
  geocean_status (*setMaskPixels)(geocean_ocean*, const float*, int32_t, int32_t,
                                  const geocean_grid_placement*) = nullptr;
  geocean_status (*setElevationPixels)(geocean_ocean*, const float*, int32_t, int32_t,
                                       const geocean_grid_placement*) = nullptr;
  geocean_status (*setDefaultWorld)(geocean_ocean*) = nullptr;
  geocean_status (*clearRasters)(geocean_ocean*) = nullptr;
  geocean_status (*queryClass)(const geocean_ocean*, size_t, const double*, const double*, uint8_t*) = nullptr;
  geocean_status (*queryElevation)(const geocean_ocean*, size_t, const double*, const double*, float*) = nullptr;
  geocean_status (*seaStateInit)(geocean_sea_state*) = nullptr;
  geocean_status (*seaStateSetBeaufort)(geocean_sea_state*, int32_t) = nullptr;
  geocean_status (*setSeaState)(geocean_ocean*, const geocean_sea_state*) = nullptr;
  geocean_status (*querySeaSurface)(const geocean_ocean*, size_t, const double*, const double*, double, double*,
                                    double*, uint8_t*) = nullptr;
  geocean_status (*significantWaveHeight)(const geocean_ocean*, double*) = nullptr;
  // ABI 1.1 (NULL when a 1.0 host loads a 1.0 plugin).
  geocean_status (*viewInit)(geocean_view*) = nullptr;
  geocean_status (*viewFromPose)(geocean_view*, double, double, double, double, double, double, int32_t,
                                 int32_t) = nullptr;
  geocean_status (*update)(geocean_ocean*, const geocean_view*) = nullptr;
  geocean_status (*draw)(geocean_ocean*) = nullptr;
  geocean_status (*releaseGl)(geocean_ocean*) = nullptr;
  // ABI 1.2 (NULL when the plugin's minor is below 2).
  geocean_status (*rasterOptionsInit)(geocean_raster_options*) = nullptr;
  geocean_status (*setMaskFileWithOptions)(geocean_ocean*, const char*, const geocean_raster_options*) = nullptr;
  geocean_status (*setElevationFileWithOptions)(geocean_ocean*, const char*, const geocean_raster_options*) = nullptr;
  geocean_status (*setDefaultWorldWithOptions)(geocean_ocean*, const geocean_raster_options*) = nullptr;
  geocean_status (*setMaskEncoding)(geocean_ocean*, const char*) = nullptr;
  geocean_status (*surfaceOutputsInit)(geocean_surface_outputs*) = nullptr;
  geocean_status (*querySurface)(const geocean_ocean*, size_t, const double*, const double*, const double*, size_t,
                                 const geocean_surface_outputs*) = nullptr;
  // ABI 1.2, the host/layer contract (NULL when the plugin's minor is below 2).
  geocean_status (*getLayerInfo)(const geocean_ocean*, geocean_layer_info*) = nullptr;
  geocean_status (*coversOpaquely)(geocean_ocean*, double, double, double, double, double, int32_t*) = nullptr;
  geocean_status (*setLayerInputs)(geocean_ocean*, const geocean_layer_inputs*) = nullptr;
  // ABI 1.3, raster layers (NULL when the plugin's minor is below 3).
  geocean_status (*addMaskLayerFile)(geocean_ocean*, const char*, int32_t, const char*,
                                     const geocean_raster_options*) = nullptr;
  geocean_status (*addElevationLayerFile)(geocean_ocean*, const char*, int32_t, const geocean_raster_options*) = nullptr;
  geocean_status (*addMaskLayerPixels)(geocean_ocean*, const char*, const float*, int32_t, int32_t,
                                       const geocean_grid_placement*, int32_t, const char*) = nullptr;
  geocean_status (*addElevationLayerPixels)(geocean_ocean*, const char*, const float*, int32_t, int32_t,
                                            const geocean_grid_placement*, int32_t) = nullptr;
  geocean_status (*removeLayer)(geocean_ocean*, const char*, size_t*) = nullptr;
  geocean_status (*clearLayers)(geocean_ocean*) = nullptr;
  geocean_status (*layerCount)(const geocean_ocean*, size_t*) = nullptr;
  // ABI 1.4, floating bodies (NULL when the plugin's minor is below 4).
  geocean_status (*bodiesConfigInit)(geocean_bodies_config*) = nullptr;
  geocean_status (*bodyDescInit)(geocean_body_desc*) = nullptr;
  geocean_status (*bodiesCreate)(geocean_ocean*, const geocean_bodies_config*, geocean_bodies**) = nullptr;
  void (*bodiesDestroy)(geocean_bodies*) = nullptr;
  geocean_status (*bodiesAdd)(geocean_bodies*, const geocean_body_desc*, geocean_body_id*) = nullptr;
  geocean_status (*bodiesRemove)(geocean_bodies*, geocean_body_id) = nullptr;
  geocean_status (*bodiesCount)(const geocean_bodies*, size_t*) = nullptr;
  geocean_status (*bodiesAdvanceTo)(geocean_bodies*, double, int64_t*) = nullptr;
  geocean_status (*bodiesTime)(const geocean_bodies*, double*) = nullptr;
  geocean_status (*bodiesGetPoses)(const geocean_bodies*, int32_t, geocean_body_pose*, size_t, size_t*) = nullptr;
  geocean_status (*bodiesGetHull)(const geocean_bodies*, geocean_body_id, double*, size_t, uint32_t*, size_t, size_t*,
                                  size_t*) = nullptr;
  // ABI 1.5, the sea state at points and the near-shore region (NULL when
  // the plugin's minor is below 5).
  geocean_status (*querySeaState)(const geocean_ocean*, size_t, const double*, const double*, double*, double*,
                                  double*, double*) = nullptr;
  geocean_status (*setCoastRegion)(geocean_ocean*, double, double, double) = nullptr;
  geocean_status (*clearCoastRegion)(geocean_ocean*) = nullptr;
};

class OceanPlugin {
 public:
  // The file name the loader tries when given no path (found through the
  // dynamic linker's search path, e.g. LD_LIBRARY_PATH or the install libdir).
  static constexpr const char* kDefaultLibrary = "libgeocean_ocean.so.1";

  // Loads the plugin at `path` ("" = kDefaultLibrary). On failure returns
  // nullptr and sets `error`: the dlopen message, the missing symbol, or the
  // two ABI versions that do not match.
  static std::unique_ptr<OceanPlugin> load(const std::string& path, std::string& error,
                                           uint32_t hostAbiVersion = GEOCEAN_ABI_VERSION);
  // The plugin for Geocean's own executables, first found of: $GEOCEAN_PLUGIN;
  // beside the running executable (the build tree); the install libdir
  // relative to the executable's bindir; kDefaultLibrary on the search
  // path. On failure `error` lists every place tried and why.
  static std::unique_ptr<OceanPlugin> loadForExecutable(std::string& error);
  ~OceanPlugin();  // dlcloses the library: destroy every ocean first
  OceanPlugin(const OceanPlugin&) = delete;
  OceanPlugin& operator=(const OceanPlugin&) = delete;

  const OceanApi& api() const { return api_; }
  uint32_t pluginAbiVersion() const { return pluginAbi_; }
  const std::string& path() const { return path_; }

  // True if a plugin of ABI `plugin` serves a host built against `host`:
  // same major, plugin minor >= host minor.
  static bool compatible(uint32_t host, uint32_t plugin);

 private:
  OceanPlugin() = default;
  void* handle_ = nullptr;
  OceanApi api_;
  uint32_t pluginAbi_ = 0;
  std::string path_;
};

}  // namespace geocean::host
