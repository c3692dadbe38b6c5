// The C ABI over the ocean façade (plugin/ocean/Ocean.h): each entry point
// checks and converts its C arguments and calls the façade. Every entry
// point runs inside guard(): no exception crosses extern "C", and every
// failure leaves a status and a thread-local message naming the function.
#include "geocean/geocean_ocean.h"
#include "plugin/capi/CapiSupport.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#ifndef GEOCEAN_VERSION_STRING
#define GEOCEAN_VERSION_STRING "unknown"
#endif

using namespace geocean::capi;
using geocean::ocean::Ocean;

namespace {

using geocean::ocean::NotReady;

// georef arrives as a plain int32_t (the enum's fixed C++ type), so any
// value a host passes is defined here and checked before it is converted.
geocean::raster::OpenOptions openOptions(int32_t georef, const char* what = "georef") {
  geocean::raster::OpenOptions o;
  switch (georef) {
    case GEOCEAN_GEOREF_FROM_FILE: o.georef = geocean::raster::Georef::FromFile; break;
    case GEOCEAN_GEOREF_GLOBAL_EQUIRECT: o.georef = geocean::raster::Georef::GlobalEquirect; break;
    default:
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(what) + " " + std::to_string(georef) + " is not a geocean_georef");
  }
  return o;
}

geocean::raster::OpenOptions openOptions(const geocean_raster_options* options) {
  requireNonNull(options, "options");
  requireStructSize(options, "options", "geocean_raster_options_init");
  geocean::raster::OpenOptions o = openOptions(options->georef, "options->georef");
  o.fewLookups = options->few_lookups != 0;
  return o;
}

std::shared_ptr<const Raster> fromMemory(const float* values, int32_t width, int32_t height,
                                         const geocean_grid_placement* p, const char* name) {
  requireNonNull(values, "values");
  requireNonNull(p, "placement");
  if (width <= 0 || height <= 0)
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
         "raster size " + std::to_string(width) + " x " + std::to_string(height) + " is not positive");
  // No caller can own more floats than the 47-bit user address space holds:
  // refused here by name instead of an allocation failing (or reading past
  // the caller's buffer where the kernel overcommits).
  constexpr std::size_t kMaxPixels = (std::size_t(1) << 47) / sizeof(float);
  if (std::size_t(width) * std::size_t(height) > kMaxPixels)
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "raster size " + std::to_string(width) + " x " + std::to_string(height) +
                                             " is larger than any buffer (2^47 bytes)");
  auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(p->origin_lon_deg) || !finite(p->origin_lat_deg))
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "placement origin is not finite");
  if (!(p->lon_step_deg > 0.0) || !finite(p->lon_step_deg))
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "placement lon_step_deg " + std::to_string(p->lon_step_deg) + " is not > 0");
  if (!(p->lat_step_deg != 0.0) || !finite(p->lat_step_deg))
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "placement lat_step_deg " + std::to_string(p->lat_step_deg) + " is not != 0");
  geocean::raster::GeoTransform t;
  t.originLonDeg = p->origin_lon_deg;
  t.originLatDeg = p->origin_lat_deg;
  t.lonStepDeg = p->lon_step_deg;
  t.latStepDeg = p->lat_step_deg;
  t.global = p->global != 0;
  // The file reader's rule: a "global" raster placed beyond a pole was
  // clamped to its edge row and answered everywhere (fuzz_capi_pixels).
  {
    double south = 0.0, north = 0.0;
    if (!t.rowsWithinPoles(height, south, north))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "placement latitude range [" + shortest(south) + ", " + shortest(north) +
                                               "] (origin_lat_deg " + shortest(p->origin_lat_deg) + ", lat_step_deg " +
                                               shortest(p->lat_step_deg) + ") is outside [-90, 90]");
  }
  if (t.global && std::abs(width * p->lon_step_deg - 360.0) > 1e-6 * 360.0)
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "placement is global but width * lon_step_deg = " +
                                             std::to_string(width * p->lon_step_deg) + ", not 360");
  std::vector<float> pixels(values, values + std::size_t(width) * std::size_t(height));
  std::optional<double> nodata;
  if (p->has_nodata) nodata = p->nodata;
  return Raster::fromPixels(std::move(pixels), width, height, 1, t, nodata, name);
}

// <dir of this library>/../share/geocean/data, for an installed plugin
// (raster::dataDir() looks beside the host executable instead).
std::string installedDataDir() {
  namespace fs = std::filesystem;
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&geocean_abi_version), &info) || !info.dli_fname) return {};
  std::error_code ec;
  const fs::path lib = fs::canonical(info.dli_fname, ec);
  if (ec) return {};
  const fs::path d = lib.parent_path().parent_path() / "share" / "geocean" / "data";
  return fs::exists(d / "landmask_5m.tif", ec) ? d.string() : std::string();
}

// A file name or layer name: an empty one would name nothing in messages
// (": no such file"), so it is refused by name.
void requireNonNullOrEmpty(const char* s, const char* what) {
  requireNonNull(s, what);
  if (!*s) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(what) + " is empty");
}

// WaveField::create names the C++ fields and prints values to 6 digits
// ("sea state: windSpeedMps = 70 is invalid (...)"); a C host set
// geocean_sea_state's, so the message names those, with the value it gave.
std::string abiSeaStateMessage(const std::string& m, const geocean_sea_state& s) {
  auto text = [](auto v) {
    char b[40];
    const auto r = std::to_chars(b, b + sizeof b, v);
    return std::string(b, r.ptr);
  };
  const struct {
    const char* cpp;
    const char* c;
    std::string value;
  } fields[] = {{"windSpeedMps", "wind_speed_mps", text(s.wind_speed_mps)},
                {"windFromDeg", "wind_from_deg", text(s.wind_from_deg)},
                {"fetchM", "fetch_m", text(s.fetch_m)},
                {"anchorLatDeg", "anchor_lat_deg", text(s.anchor_lat_deg)},
                {"anchorLonDeg", "anchor_lon_deg", text(s.anchor_lon_deg)},
                {"referenceDepthM", "reference_depth_m", text(s.reference_depth_m)},
                {"gerstnerComponents", "gerstner_components", text(s.gerstner_components)},
                {"noiseOctaves", "noise_octaves", text(s.noise_octaves)}};
  const std::size_t rest = m.find(" is invalid");
  for (const auto& f : fields)
    if (m.rfind(std::string("sea state: ") + f.cpp + " = ", 0) == 0 && rest != std::string::npos)
      return std::string("sea_state->") + f.c + " " + f.value + m.substr(rest);
  return m;
}

// The four file setters: handle and path checked, options converted, then
// the façade's setter (Ocean::setMaskFile or setElevationFile).
using FileSetter = void (Ocean::*)(const std::string&, const geocean::raster::OpenOptions&);
template <class Options>
geocean_status setFile(const char* function, geocean_ocean* ocean, const char* path, FileSetter set,
                       Options options) {
  return guard(function, [&] {
    requireNonNull(ocean, "ocean");
    requireNonNullOrEmpty(path, "path");
    (ocean->core.*set)(path, openOptions(options));
  });
}

geocean::ocean::MaskEncoding encodingOf(const char* spec) {
  return spec && *spec ? geocean::ocean::MaskEncoding::parse(spec) : geocean::ocean::MaskEncoding();
}
geocean::raster::OpenOptions layerOpenOptions(const geocean_raster_options* options) {
  return options ? openOptions(options) : geocean::raster::OpenOptions{};
}

}  // namespace

extern "C" {

GEOCEAN_API uint32_t geocean_abi_version(void) { return GEOCEAN_ABI_VERSION; }

GEOCEAN_API const char* geocean_version_string(void) { return GEOCEAN_VERSION_STRING; }

GEOCEAN_API const char* geocean_last_error(void) { return tlsLastError.c_str(); }

GEOCEAN_API const char* geocean_status_string(geocean_status status) {
  switch (status) {
    case GEOCEAN_OK: return "GEOCEAN_OK";
    case GEOCEAN_ERROR_NULL_ARGUMENT: return "GEOCEAN_ERROR_NULL_ARGUMENT";
    case GEOCEAN_ERROR_INVALID_ARGUMENT: return "GEOCEAN_ERROR_INVALID_ARGUMENT";
    case GEOCEAN_ERROR_ABI_VERSION: return "GEOCEAN_ERROR_ABI_VERSION";
    case GEOCEAN_ERROR_RASTER: return "GEOCEAN_ERROR_RASTER";
    case GEOCEAN_ERROR_NOT_READY: return "GEOCEAN_ERROR_NOT_READY";
    case GEOCEAN_ERROR_NO_GL_CONTEXT: return "GEOCEAN_ERROR_NO_GL_CONTEXT";
    case GEOCEAN_ERROR_GL: return "GEOCEAN_ERROR_GL";
    case GEOCEAN_ERROR_OUT_OF_MEMORY: return "GEOCEAN_ERROR_OUT_OF_MEMORY";
    case GEOCEAN_ERROR_INTERNAL: return "GEOCEAN_ERROR_INTERNAL";
  }
  return "GEOCEAN_ERROR_UNKNOWN_STATUS";
}

GEOCEAN_API geocean_status geocean_create(uint32_t host_abi_version, geocean_ocean** out) {
  return guard("geocean_create", [&] {
    requireNonNull(out, "out");
    *out = nullptr;
    const uint32_t hostMajor = host_abi_version >> 16, hostMinor = host_abi_version & 0xffffu;
    if (hostMajor != GEOCEAN_ABI_VERSION_MAJOR || hostMinor > GEOCEAN_ABI_VERSION_MINOR)
      fail(GEOCEAN_ERROR_ABI_VERSION, "host ABI " + std::to_string(hostMajor) + "." + std::to_string(hostMinor) +
                                          " is not served by this plugin (ABI " +
                                          std::to_string(GEOCEAN_ABI_VERSION_MAJOR) + "." +
                                          std::to_string(GEOCEAN_ABI_VERSION_MINOR) + ")");
    *out = new geocean_ocean;
  });
}

GEOCEAN_API void geocean_destroy(geocean_ocean* ocean) {
  guard("geocean_destroy", [&] {
    if (ocean) releaseDrawState(ocean->draw);
    delete ocean;
  });
}

GEOCEAN_API geocean_status geocean_set_mask_file(geocean_ocean* ocean, const char* path, geocean_georef georef) {
  return setFile("geocean_set_mask_file", ocean, path, &Ocean::setMaskFile, static_cast<int32_t>(georef));
}

GEOCEAN_API geocean_status geocean_set_elevation_file(geocean_ocean* ocean, const char* path,
                                                      geocean_georef georef) {
  return setFile("geocean_set_elevation_file", ocean, path, &Ocean::setElevationFile,
                 static_cast<int32_t>(georef));
}

GEOCEAN_API geocean_status geocean_raster_options_init(geocean_raster_options* options) {
  return guard("geocean_raster_options_init", [&] {
    requireNonNull(options, "options");
    *options = geocean_raster_options{};
    options->struct_size = sizeof(geocean_raster_options);
    options->georef = GEOCEAN_GEOREF_FROM_FILE;
  });
}

GEOCEAN_API geocean_status geocean_set_mask_file_with_options(geocean_ocean* ocean, const char* path,
                                                              const geocean_raster_options* options) {
  return setFile("geocean_set_mask_file_with_options", ocean, path, &Ocean::setMaskFile, options);
}

GEOCEAN_API geocean_status geocean_set_elevation_file_with_options(geocean_ocean* ocean, const char* path,
                                                                   const geocean_raster_options* options) {
  return setFile("geocean_set_elevation_file_with_options", ocean, path, &Ocean::setElevationFile,
                 options);
}

GEOCEAN_API geocean_status geocean_set_mask_pixels(geocean_ocean* ocean, const float* values, int32_t width,
                                                   int32_t height, const geocean_grid_placement* placement) {
  return guard("geocean_set_mask_pixels", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.setMask(fromMemory(values, width, height, placement, "<mask from memory>"));
  });
}

GEOCEAN_API geocean_status geocean_set_elevation_pixels(geocean_ocean* ocean, const float* values_m,
                                                        int32_t width, int32_t height,
                                                        const geocean_grid_placement* placement) {
  return guard("geocean_set_elevation_pixels", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.setElevation(fromMemory(values_m, width, height, placement, "<elevation from memory>"));
  });
}

GEOCEAN_API geocean_status geocean_set_default_world(geocean_ocean* ocean) {
  return guard("geocean_set_default_world", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.setDefaultWorld(Ocean::defaultWorldDir(installedDataDir));
  });
}

GEOCEAN_API geocean_status geocean_set_default_world_with_options(geocean_ocean* ocean,
                                                                  const geocean_raster_options* options) {
  return guard("geocean_set_default_world_with_options", [&] {
    requireNonNull(ocean, "ocean");
    const auto o = openOptions(options);
    ocean->core.setDefaultWorld(Ocean::defaultWorldDir(installedDataDir), o);
  });
}

GEOCEAN_API geocean_status geocean_clear_rasters(geocean_ocean* ocean) {
  return guard("geocean_clear_rasters", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.clearRasters();
  });
}

GEOCEAN_API geocean_status geocean_set_mask_encoding(geocean_ocean* ocean, const char* spec) {
  return guard("geocean_set_mask_encoding", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.setMaskEncoding(spec && *spec ? geocean::ocean::MaskEncoding::parse(spec)
                                              : geocean::ocean::MaskEncoding());
  });
}

// ---- Layers (ABI 1.3) -------------------------------------------------------

GEOCEAN_API geocean_status geocean_add_mask_layer_file(geocean_ocean* ocean, const char* path, int32_t priority,
                                                       const char* encoding, const geocean_raster_options* options) {
  return guard("geocean_add_mask_layer_file", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNullOrEmpty(path, "path");
    ocean->core.addMaskLayerFile(path, priority, encodingOf(encoding), layerOpenOptions(options));
  });
}

GEOCEAN_API geocean_status geocean_add_elevation_layer_file(geocean_ocean* ocean, const char* path,
                                                            int32_t priority, const geocean_raster_options* options) {
  return guard("geocean_add_elevation_layer_file", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNullOrEmpty(path, "path");
    ocean->core.addElevationLayerFile(path, priority, layerOpenOptions(options));
  });
}

GEOCEAN_API geocean_status geocean_add_mask_layer_pixels(geocean_ocean* ocean, const char* name, const float* values,
                                                         int32_t width, int32_t height,
                                                         const geocean_grid_placement* placement, int32_t priority,
                                                         const char* encoding) {
  return guard("geocean_add_mask_layer_pixels", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNullOrEmpty(name, "name");
    const auto enc = encodingOf(encoding);  // before the copy: a bad spec costs nothing
    ocean->core.addMaskLayer(fromMemory(values, width, height, placement, name), priority, enc);
  });
}

GEOCEAN_API geocean_status geocean_add_elevation_layer_pixels(geocean_ocean* ocean, const char* name,
                                                              const float* values_m, int32_t width, int32_t height,
                                                              const geocean_grid_placement* placement,
                                                              int32_t priority) {
  return guard("geocean_add_elevation_layer_pixels", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNullOrEmpty(name, "name");
    ocean->core.addElevationLayer(fromMemory(values_m, width, height, placement, name), priority);
  });
}

GEOCEAN_API geocean_status geocean_remove_layer(geocean_ocean* ocean, const char* path, size_t* out_removed) {
  return guard("geocean_remove_layer", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(path, "path");
    const std::size_t n = ocean->core.removeLayer(path);
    if (out_removed) *out_removed = n;
  });
}

GEOCEAN_API geocean_status geocean_clear_layers(geocean_ocean* ocean) {
  return guard("geocean_clear_layers", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.clearLayers();
  });
}

GEOCEAN_API geocean_status geocean_layer_count(const geocean_ocean* ocean, size_t* out_count) {
  return guard("geocean_layer_count", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(out_count, "out_count");
    *out_count = ocean->current()->layers.size();
  });
}

GEOCEAN_API geocean_status geocean_query_class(const geocean_ocean* ocean, size_t count, const double* lat_deg,
                                               const double* lon_deg, uint8_t* out_class) {
  return guard("geocean_query_class", [&] {
    requireNonNull(ocean, "ocean");
    if (count == 0) return;
    requireNonNull(lat_deg, "lat_deg");
    requireNonNull(lon_deg, "lon_deg");
    requireNonNull(out_class, "out_class");
    const auto snap = ocean->core.current();
    if (!snap->landSea) throw NotReady(NotReady::Missing::Rasters);
    static_assert(sizeof(geocean::ocean::Surface) == sizeof(uint8_t));
    static_assert(uint8_t(geocean::ocean::Surface::Ocean) == GEOCEAN_SURFACE_OCEAN &&
                  uint8_t(geocean::ocean::Surface::Land) == GEOCEAN_SURFACE_LAND &&
                  uint8_t(geocean::ocean::Surface::Lake) == GEOCEAN_SURFACE_LAKE);
    // Through a buffer: writing uint8_t storage through Surface lvalues would break aliasing rules.
    constexpr std::size_t kChunk = 1024;
    geocean::ocean::Surface buf[kChunk];
    for (std::size_t i = 0; i < count; i += kChunk) {
      const std::size_t n = std::min(kChunk, count - i);
      snap->classify(lat_deg + i, lon_deg + i, n, buf);
      for (std::size_t k = 0; k < n; ++k) out_class[i + k] = static_cast<uint8_t>(buf[k]);
    }
  });
}

GEOCEAN_API geocean_status geocean_query_elevation(const geocean_ocean* ocean, size_t count,
                                                   const double* lat_deg, const double* lon_deg,
                                                   float* out_elevation_m) {
  return guard("geocean_query_elevation", [&] {
    requireNonNull(ocean, "ocean");
    if (count == 0) return;
    requireNonNull(lat_deg, "lat_deg");
    requireNonNull(lon_deg, "lon_deg");
    requireNonNull(out_elevation_m, "out_elevation_m");
    // In chunks: the layered and cached samplers allocate per point they
    // get, so a batch of any size costs a fixed amount of memory here
    // (CapiBatchMemory.* holds every query to that).
    const auto snap = ocean->core.current();
    constexpr std::size_t kChunk = 1024;
    for (std::size_t i = 0; i < count; i += kChunk)
      snap->elevationAt(lat_deg + i, lon_deg + i, std::min(kChunk, count - i), out_elevation_m + i);
  });
}

GEOCEAN_API geocean_status geocean_sea_state_init(geocean_sea_state* sea_state) {
  return guard("geocean_sea_state_init", [&] {
    requireNonNull(sea_state, "sea_state");
    const geocean::waves::SeaState d;
    *sea_state = geocean_sea_state{};
    sea_state->struct_size = sizeof(geocean_sea_state);
    sea_state->model = GEOCEAN_WAVES_NOISE;
    sea_state->wind_speed_mps = d.windSpeedMps;
    sea_state->wind_from_deg = d.windFromDeg;
    sea_state->fetch_m = d.fetchM;
    sea_state->seed = d.seed;
    sea_state->gerstner_components = d.gerstnerComponents;
    sea_state->noise_octaves = d.noiseOctaves;
    sea_state->anchor_lat_deg = d.anchorLatDeg;
    sea_state->anchor_lon_deg = d.anchorLonDeg;
    sea_state->reference_depth_m = d.referenceDepthM;
  });
}

GEOCEAN_API geocean_status geocean_sea_state_set_beaufort(geocean_sea_state* sea_state, int32_t beaufort) {
  return guard("geocean_sea_state_set_beaufort", [&] {
    requireNonNull(sea_state, "sea_state");
    const auto s = geocean::waves::SeaState::fromBeaufort(beaufort);
    if (!s) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "beaufort " + std::to_string(beaufort) + " is not in 0 .. 12");
    sea_state->wind_speed_mps = s->windSpeedMps;
  });
}

GEOCEAN_API geocean_status geocean_set_sea_state(geocean_ocean* ocean, const geocean_sea_state* sea_state) {
  return guard("geocean_set_sea_state", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(sea_state, "sea_state");
    // Version 1.0 knows this layout only; a smaller size is a host bug.
    requireStructSize(sea_state, "sea_state", "geocean_sea_state_init");
    geocean::waves::Model model;
    switch (sea_state->model) {
      case GEOCEAN_WAVES_NOISE: model = geocean::waves::Model::Noise; break;
      case GEOCEAN_WAVES_NOISE_PAPER: model = geocean::waves::Model::NoisePaper; break;
      case GEOCEAN_WAVES_GERSTNER: model = geocean::waves::Model::Gerstner; break;
      case GEOCEAN_WAVES_FFT: model = geocean::waves::Model::Fft; break;
      default:
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
             "sea_state->model " + std::to_string(sea_state->model) + " is not a geocean_wave_model");
    }
    geocean::waves::SeaState s;
    s.windSpeedMps = sea_state->wind_speed_mps;
    s.windFromDeg = sea_state->wind_from_deg;
    s.fetchM = sea_state->fetch_m;
    s.seed = sea_state->seed;
    s.gerstnerComponents = sea_state->gerstner_components;
    s.noiseOctaves = sea_state->noise_octaves;
    s.anchorLatDeg = sea_state->anchor_lat_deg;
    s.anchorLonDeg = sea_state->anchor_lon_deg;
    s.referenceDepthM = sea_state->reference_depth_m;
    try {
      ocean->core.setSeaState(model, s);
    } catch (const std::invalid_argument& e) {
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, abiSeaStateMessage(e.what(), *sea_state));
    }
  });
}

// Since ABI 1.5: the near-shore region of interest (Ocean::setCoastRegion).
// The same rule as `geocean query --coast-region`: 201 nodes over size_m.
GEOCEAN_API geocean_status geocean_set_coast_region(geocean_ocean* ocean, double lat_deg, double lon_deg,
                                                    double size_m) {
  return guard("geocean_set_coast_region", [&] {
    requireNonNull(ocean, "ocean");
    if (!(lat_deg >= -90.0 && lat_deg <= 90.0))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "lat_deg " + std::to_string(lat_deg) + " is not in -90 .. 90");
    if (!(lon_deg >= -360.0 && lon_deg <= 360.0))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "lon_deg " + std::to_string(lon_deg) + " is not in -360 .. 360");
    if (!(size_m >= 500.0 && size_m <= 40000.0))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "size_m " + std::to_string(size_m) + " is not in 500 .. 40000");
    const auto snap = ocean->core.current();
    if (snap->waves && snap->model != geocean::waves::Model::Gerstner)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string("the sea state's model is ") +
                                               geocean::waves::toString(snap->model) +
                                               ": a coast region needs GEOCEAN_WAVES_GERSTNER");
    geocean::waves::CoastField::Region r;
    r.latDeg = lat_deg;
    r.lonDeg = lon_deg;
    r.nodes = 201;
    r.cellM = size_m / (r.nodes - 1);
    ocean->core.setCoastRegion(r);  // guard() maps its invalid_argument to INVALID_ARGUMENT
  });
}

GEOCEAN_API geocean_status geocean_clear_coast_region(geocean_ocean* ocean) {
  return guard("geocean_clear_coast_region", [&] {
    requireNonNull(ocean, "ocean");
    ocean->core.clearCoastRegion();
  });
}

GEOCEAN_API geocean_status geocean_query_sea_surface(const geocean_ocean* ocean, size_t count,
                                                     const double* lat_deg, const double* lon_deg, double time_s,
                                                     double* out_height_m, double* out_normal_enu,
                                                     uint8_t* out_class) {
  return guard("geocean_query_sea_surface", [&] {
    requireNonNull(ocean, "ocean");
    if (!std::isfinite(time_s))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "time_s " + std::to_string(time_s) + " is not finite");
    requireTimeInRange(time_s, "time_s");
    const auto snap = ocean->core.current();
    if (!snap->sea) throw NotReady(NotReady::Missing::SeaState);
    if (count == 0) return;
    requireNonNull(lat_deg, "lat_deg");
    requireNonNull(lon_deg, "lon_deg");
    requireNonNull(out_height_m, "out_height_m");
    geocean::ocean::SurfaceOutputs out;
    out.heightM = out_height_m;
    out.normalEnu = out_normal_enu;
    // The façade copies class bytes (memcpy), so uint8_t storage is written without aliasing it as Surface.
    out.surface = reinterpret_cast<geocean::ocean::Surface*>(out_class);
    snap->querySurface({lat_deg, lon_deg, count, &time_s, false}, out);
  });
}

GEOCEAN_API geocean_status geocean_surface_outputs_init(geocean_surface_outputs* outputs) {
  return guard("geocean_surface_outputs_init", [&] {
    requireNonNull(outputs, "outputs");
    *outputs = geocean_surface_outputs{};
    outputs->struct_size = sizeof(geocean_surface_outputs);
  });
}

GEOCEAN_API geocean_status geocean_query_surface(const geocean_ocean* ocean, size_t count, const double* lat_deg,
                                                 const double* lon_deg, const double* time_s, size_t time_count,
                                                 const geocean_surface_outputs* outputs) {
  return guard("geocean_query_surface", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(outputs, "outputs");
    requireStructSize(outputs, "outputs", "geocean_surface_outputs_init");
    geocean::ocean::SurfaceOutputs out;
    out.surface = reinterpret_cast<geocean::ocean::Surface*>(outputs->surface_class);
    out.elevationM = outputs->elevation_m;
    out.heightM = outputs->height_m;
    out.normalEnu = outputs->normal_enu;
    out.verticalVelocityMps = outputs->vertical_velocity_mps;
    out.horizontalVelocityEnMps = outputs->horizontal_velocity_en_mps;
    const auto snap = ocean->core.current();
    if (out.wantsSea() && !snap->sea) throw NotReady(NotReady::Missing::SeaState);
    if (count == 0) return;
    requireNonNull(lat_deg, "lat_deg");
    requireNonNull(lon_deg, "lon_deg");
    if (out.wantsSea()) {
      if (time_count != 1 && time_count != count)
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "time_count " + std::to_string(time_count) + " is neither 1 nor count (" +
                                                 std::to_string(count) + ")");
      requireNonNull(time_s, "time_s");
      for (std::size_t i = 0; i < time_count; ++i)
        if (!std::isfinite(time_s[i]))
          fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
               "time_s[" + std::to_string(i) + "] " + std::to_string(time_s[i]) + " is not finite");
        else
          requireTimeInRange(time_s[i], "time_s[" + std::to_string(i) + "]");
    }
    snap->querySurface({lat_deg, lon_deg, count, time_s, time_count == count && count > 1}, out);
  });
}

GEOCEAN_API geocean_status geocean_significant_wave_height(const geocean_ocean* ocean, double* out_hs_m) {
  return guard("geocean_significant_wave_height", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(out_hs_m, "out_hs_m");
    *out_hs_m = ocean->core.current()->significantWaveHeightM();
  });
}

GEOCEAN_API geocean_status geocean_query_sea_state(const geocean_ocean* ocean, size_t count, const double* lat_deg,
                                                   const double* lon_deg, double* out_hs_m,
                                                   double* out_peak_period_s, double* out_peak_wavelength_m,
                                                   double* out_wave_from_deg) {
  return guard("geocean_query_sea_state", [&] {
    requireNonNull(ocean, "ocean");
    const auto snap = ocean->core.current();
    if (!snap->sea) throw NotReady(NotReady::Missing::SeaState);
    if (count == 0) return;
    requireNonNull(lat_deg, "lat_deg");
    requireNonNull(lon_deg, "lon_deg");
    geocean::ocean::SurfaceOutputs out;
    out.hsM = out_hs_m;
    out.peakPeriodS = out_peak_period_s;
    out.peakWavelengthM = out_peak_wavelength_m;
    out.waveFromDeg = out_wave_from_deg;
    if (!out.wantsSeaState()) return;
    const double t = 0.0;  // the sea state does not depend on time
    snap->querySurface({lat_deg, lon_deg, count, &t, false}, out);
  });
}

}  // extern "C"
