// The C ABI over the C++ plugin libraries. Every entry point runs inside
// guard(): no exception crosses extern "C", and every failure leaves a
// status and a thread-local message naming the function.
#include "geocean/geocean_ocean.h"

#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/render/GlProgram.h"
#include "globe/render/WorldTextures.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/render/OceanRenderer.h"
#include "plugin/waves/SeaQuery.h"
#include "plugin/waves/WaveField.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#ifndef GEOCEAN_VERSION_STRING
#define GEOCEAN_VERSION_STRING "unknown"
#endif

namespace {

using geocean::raster::Raster;
using geocean::raster::RasterError;

// The calling thread's last error; geocean_last_error() returns it.
thread_local std::string tlsLastError;

// A failure with a status, thrown inside an entry point and turned into the
// return value by guard().
struct Failure {
  geocean_status status;
  std::string message;
};

[[noreturn]] void fail(geocean_status status, std::string message) { throw Failure{status, std::move(message)}; }

template <class F>
geocean_status guard(const char* function, F&& body) noexcept {
  tlsLastError.clear();
  geocean_status status = GEOCEAN_OK;
  std::string message;
  try {
    body();
    return GEOCEAN_OK;
  } catch (const Failure& f) {
    status = f.status;
    message = f.message;
  } catch (const RasterError& e) {
    status = GEOCEAN_ERROR_RASTER;
    message = e.what();
  } catch (const std::invalid_argument& e) {
    status = GEOCEAN_ERROR_INVALID_ARGUMENT;
    message = e.what();
  } catch (const std::bad_alloc&) {
    status = GEOCEAN_ERROR_OUT_OF_MEMORY;
    message = "out of memory";
  } catch (const std::exception& e) {
    status = GEOCEAN_ERROR_INTERNAL;
    message = e.what();
  } catch (...) {
    status = GEOCEAN_ERROR_INTERNAL;
    message = "unknown exception";
  }
  try {
    tlsLastError = std::string(function) + ": " + message;
  } catch (...) {
    // No memory even for the message: the status still says what happened.
  }
  return status;
}

void requireNonNull(const void* p, const char* what) {
  if (!p) fail(GEOCEAN_ERROR_NULL_ARGUMENT, std::string(what) + " is NULL");
}

// Everything a query reads. Immutable once published: setters build a new
// snapshot and swap the pointer, so queries never lock while they work.
struct Snapshot {
  std::shared_ptr<const Raster> mask, elevation;
  std::shared_ptr<const geocean::ocean::LandSea> landSea;
  std::shared_ptr<const geocean::waves::WaveField> waves;
  // The query path shared with `geocean query` (rebuilt when either changes).
  std::shared_ptr<const geocean::waves::SeaQuery> sea;
  // What `waves` was made from: the renderer builds its own field from it.
  geocean::waves::Model model = geocean::waves::Model::Noise;
  geocean::waves::SeaState seaState;
};

geocean::raster::OpenOptions openOptions(geocean_georef georef) {
  geocean::raster::OpenOptions o;
  switch (georef) {
    case GEOCEAN_GEOREF_FROM_FILE: o.georef = geocean::raster::Georef::FromFile; break;
    case GEOCEAN_GEOREF_GLOBAL_EQUIRECT: o.georef = geocean::raster::Georef::GlobalEquirect; break;
    default: fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "georef " + std::to_string(int(georef)) + " is not a geocean_georef");
  }
  return o;
}

std::shared_ptr<const Raster> fromMemory(const float* values, int32_t width, int32_t height,
                                         const geocean_grid_placement* p, const char* name) {
  requireNonNull(values, "values");
  requireNonNull(p, "placement");
  if (width <= 0 || height <= 0)
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
         "raster size " + std::to_string(width) + " x " + std::to_string(height) + " is not positive");
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


// ---- Rendering helpers (ABI 1.1) -------------------------------------------

// The OpenGL context current on this thread (EGL or GLX), or nullptr. Asks
// the libraries only if the process already loaded them (RTLD_NOLOAD): a
// host without EGL or GLX has no such context, and libepoxy would abort if
// asked to resolve a function from a library that is not there.
void* currentGlContext() {
  using GetCurrent = void* (*)();
  struct Lib {
    const char* file;
    const char* symbol;
  };
  static constexpr Lib kLibs[] = {{"libEGL.so.1", "eglGetCurrentContext"},
                                  {"libEGL.so", "eglGetCurrentContext"},
                                  {"libGLX.so.0", "glXGetCurrentContext"},
                                  {"libGL.so.1", "glXGetCurrentContext"}};
  for (const Lib& lib : kLibs) {
    void* h = dlopen(lib.file, RTLD_LAZY | RTLD_NOLOAD);
    if (!h) continue;
    auto fn = reinterpret_cast<GetCurrent>(dlsym(h, lib.symbol));
    void* ctx = fn ? fn() : nullptr;
    dlclose(h);  // balances the NOLOAD reference; the library stays loaded
    if (ctx) return ctx;
  }
  return nullptr;
}

// Global equirectangular texture layers for the ocean shaders, from the
// ocean's rasters: a global raster in memory is copied pixel for pixel (the
// viewer's own textures, so the picture matches it); anything else is
// resampled through the classifier onto a global grid at the raster's step.
geocean::render::WorldData worldDataFor(const Snapshot& snap) {
  using geocean::render::WorldLayer;
  geocean::render::WorldData d;
  d.imagery.width = d.imagery.height = 1;  // the ocean shaders never sample imagery
  d.imagery.channels = 3;
  d.imagery.values = {0.0f, 0.0f, 0.0f};
  d.imagery.lonStepDeg = 360.0;
  d.imagery.latStepDeg = -180.0;
  auto directly = [](const std::shared_ptr<const Raster>& r) {
    return r && r->inMemory() && r->transform().global && r->transform().latStepDeg < 0 &&
           std::abs(r->transform().latStepDeg * r->height() + 180.0) < 1e-6;
  };
  // A global grid with the raster's steps, at most 5' (the default mask).
  auto globalGrid = [](const std::shared_ptr<const Raster>& r) {
    WorldLayer l;
    const double step = r ? std::max(std::abs(r->transform().lonStepDeg), 1.0 / 12.0) : 1.0;
    l.width = std::max(1, int(std::lround(360.0 / step)));
    l.height = std::max(1, int(std::lround(180.0 / step)));
    l.lonStepDeg = 360.0 / l.width;
    l.latStepDeg = -180.0 / l.height;
    l.values.resize(std::size_t(l.width) * l.height);
    return l;
  };
  auto centres = [](const WorldLayer& l, std::vector<double>& lat, std::vector<double>& lon) {
    lat.resize(l.values.size());
    lon.resize(l.values.size());
    for (int y = 0; y < l.height; ++y)
      for (int x = 0; x < l.width; ++x) {
        lat[std::size_t(y) * l.width + x] = l.originLatDeg + (y + 0.5) * l.latStepDeg;
        lon[std::size_t(y) * l.width + x] = l.originLonDeg + (x + 0.5) * l.lonStepDeg;
      }
  };
  std::vector<double> lat, lon;
  if (snap.elevation && directly(snap.elevation)) {
    d.elevation = geocean::render::layerOf(*snap.elevation, 0);
  } else if (snap.elevation) {
    d.elevation = globalGrid(snap.elevation);
    centres(d.elevation, lat, lon);
    snap.landSea->elevationBatch(lat.data(), lon.data(), lat.size(), d.elevation.values.data());
  } else {
    d.elevation = globalGrid(nullptr);
    // No relief: deep water everywhere, as the queries assume.
    std::fill(d.elevation.values.begin(), d.elevation.values.end(), -10000.0f);
  }
  // NaN (nodata) would poison the vertex shader: sea level, as the viewer does.
  for (float& v : d.elevation.values)
    if (v != v) v = 0.0f;
  if (snap.mask && directly(snap.mask)) {
    d.water = geocean::render::layerOf(*snap.mask, 0);
    for (float& v : d.water.values) v = (v == 0.0f || v == 2.0f) ? 1.0f : 0.0f;
  } else if (snap.landSea) {
    d.water = globalGrid(snap.mask ? snap.mask : snap.elevation);
    centres(d.water, lat, lon);
    std::vector<geocean::ocean::Surface> cls(lat.size());
    snap.landSea->classifyBatch(lat.data(), lon.data(), lat.size(), cls.data());
    for (std::size_t i = 0; i < cls.size(); ++i)
      d.water.values[i] = cls[i] == geocean::ocean::Surface::Land ? 0.0f : 1.0f;
  } else {
    d.water = globalGrid(nullptr);
    std::fill(d.water.values.begin(), d.water.values.end(), 1.0f);
  }
  return d;
}

// The GL resources of one ocean, in the context current at their creation.
struct GlResources {
  void* context = nullptr;
  std::shared_ptr<const Snapshot> builtFrom;  // rebuilt when the state changes
  std::shared_ptr<const geocean::render::WorldTextures> world;
  std::unique_ptr<geocean::ocean_render::OceanRenderer> renderer;
};

// Saves the GL state the ocean's draw and resource creation change, and
// restores it on scope exit (the list is in docs/PLUGIN_ABI.md).
class GlStateGuard {
 public:
  GlStateGuard() {
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
    for (int u = 0; u < kUnits; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_[u]);
    }
    glActiveTexture(GLenum(activeTexture_));
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &ssboGeneric_);
    for (int i = 0; i < kSsbos; ++i) {
      glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(i), &ssbo_[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, GLuint(i), &ssboStart_[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(i), &ssboSize_[i]);
    }
    for (int b = 0; b < kDrawBuffers; ++b) {
      blend_[b] = glIsEnabledi(GL_BLEND, GLuint(b));
      glGetIntegeri_v(GL_BLEND_SRC_RGB, GLuint(b), &blendFunc_[b][0]);
      glGetIntegeri_v(GL_BLEND_DST_RGB, GLuint(b), &blendFunc_[b][1]);
      glGetIntegeri_v(GL_BLEND_SRC_ALPHA, GLuint(b), &blendFunc_[b][2]);
      glGetIntegeri_v(GL_BLEND_DST_ALPHA, GLuint(b), &blendFunc_[b][3]);
    }
    polygonOffsetFill_ = glIsEnabled(GL_POLYGON_OFFSET_FILL);
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &offsetFactor_);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &offsetUnits_);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlignment_);
  }
  ~GlStateGuard() {
    glUseProgram(GLuint(program_));
    glBindVertexArray(GLuint(vao_));
    for (int u = 0; u < kUnits; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      glBindTexture(GL_TEXTURE_2D, GLuint(texture_[u]));
    }
    glActiveTexture(GLenum(activeTexture_));
    for (int i = 0; i < kSsbos; ++i) {
      if (ssbo_[i] != 0 && ssboSize_[i] > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, GLuint(i), GLuint(ssbo_[i]), GLintptr(ssboStart_[i]),
                          GLsizeiptr(ssboSize_[i]));
      else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(i), GLuint(ssbo_[i]));
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(ssboGeneric_));
    for (int b = 0; b < kDrawBuffers; ++b) {
      if (blend_[b])
        glEnablei(GL_BLEND, GLuint(b));
      else
        glDisablei(GL_BLEND, GLuint(b));
      glBlendFuncSeparatei(GLuint(b), GLenum(blendFunc_[b][0]), GLenum(blendFunc_[b][1]), GLenum(blendFunc_[b][2]),
                           GLenum(blendFunc_[b][3]));
    }
    if (polygonOffsetFill_)
      glEnable(GL_POLYGON_OFFSET_FILL);
    else
      glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(offsetFactor_, offsetUnits_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment_);
  }
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

 private:
  static constexpr int kUnits = 3, kSsbos = 5, kDrawBuffers = 2;  // SSBOs 3-4: the FFT tables
  GLint program_ = 0, vao_ = 0, activeTexture_ = GL_TEXTURE0, texture_[kUnits] = {}, ssboGeneric_ = 0;
  GLint ssbo_[kSsbos] = {};
  GLint64 ssboStart_[kSsbos] = {}, ssboSize_[kSsbos] = {};
  GLboolean blend_[kDrawBuffers] = {}, polygonOffsetFill_ = GL_FALSE;
  GLint blendFunc_[kDrawBuffers][4] = {};
  GLfloat offsetFactor_ = 0.0f, offsetUnits_ = 0.0f;
  GLint unpackAlignment_ = 4;
};

bool allFinite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// A host view, validated and turned into what the ocean renderer reads.
struct FrameView {
  geocean::render::ViewMatrices vm;
  geocean::render::ViewPose pose;
  geocean::render::Lighting light;
  bool reference = false;
};

FrameView frameViewOf(const geocean_view* v) {
  if (v->struct_size < sizeof(geocean_view))
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "view->struct_size " + std::to_string(v->struct_size) +
                                             " is smaller than " + std::to_string(sizeof(geocean_view)) +
                                             ": call geocean_view_init first");
  auto bad = [](const std::string& what) { fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "view->" + what); };
  if (!allFinite(v->eye_ecef_m, 3)) bad("eye_ecef_m is not finite");
  if (!allFinite(v->view_matrix, 16)) bad("view_matrix is not finite");
  if (!allFinite(v->projection_matrix, 16)) bad("projection_matrix is not finite");
  if (!std::isfinite(v->time_s)) bad("time_s " + std::to_string(v->time_s) + " is not finite");
  if (!allFinite(v->sun_dir_ecef, 3)) bad("sun_dir_ecef is not finite");
  const int32_t w = v->viewport_width_px, h = v->viewport_height_px;
  if (w < 1 || w > 16384 || h < 1 || h > 16384)
    bad("viewport " + std::to_string(w) + "x" + std::to_string(h) + " is not within 1 .. 16384");
  const glm::dvec3 sun(v->sun_dir_ecef[0], v->sun_dir_ecef[1], v->sun_dir_ecef[2]);
  if (glm::length(sun) <= 0.0) bad("sun_dir_ecef is zero");

  const double* m = v->view_matrix;  // element (r, c) at m[4c + r]
  const glm::dvec3 right(m[0], m[4], m[8]), up(m[1], m[5], m[9]), back(m[2], m[6], m[10]);
  // 1e-6: a rotation built in double or float (float rounding ~6e-8 per
  // element) passes; a scaled or skewed matrix does not.
  constexpr double kTol = 1e-6;
  if (std::abs(glm::length(right) - 1.0) > kTol || std::abs(glm::length(up) - 1.0) > kTol ||
      std::abs(glm::length(back) - 1.0) > kTol || std::abs(glm::dot(right, up)) > kTol ||
      std::abs(glm::dot(right, back)) > kTol || std::abs(glm::dot(up, back)) > kTol ||
      glm::dot(glm::cross(right, up), back) < 0.0)
    bad("view_matrix rotation is not orthonormal and right-handed");

  const double* p = v->projection_matrix;
  if (p[11] != -1.0 || p[15] != 0.0 || p[3] != 0.0 || p[7] != 0.0 || p[1] != 0.0 || p[4] != 0.0 ||
      std::abs(p[8]) > kTol || std::abs(p[9]) > kTol || !(p[0] > 0.0) || !(p[5] > 0.0))
    bad("projection_matrix is not a symmetric perspective (w = -z, no skew, positive scales)");
  const double aspect = p[5] / p[0], viewportAspect = double(w) / double(h);
  if (std::abs(aspect / viewportAspect - 1.0) > 1e-3)
    bad("projection_matrix aspect " + std::to_string(aspect) + " does not match the viewport's " +
        std::to_string(viewportAspect));

  FrameView f;
  auto& vm = f.vm;
  vm.eyeEcef = {v->eye_ecef_m[0], v->eye_ecef_m[1], v->eye_ecef_m[2]};
  vm.right = right;
  vm.up = up;
  vm.forward = -back;
  glm::dmat4 view(1.0), proj(0.0);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) view[c][r] = m[4 * c + r];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) proj[c][r] = p[4 * c + r];
  vm.nearM = p[14] != 0.0 ? std::abs(p[14]) : 1.0;
  vm.view = glm::mat4(view);
  vm.proj = glm::mat4(proj);
  vm.viewProjD = proj * view;
  vm.viewProj = glm::mat4(vm.viewProjD);
  const geocean::geo::Geodetic g = geocean::geo::fromEcef(vm.eyeEcef);
  f.pose.latDeg = g.latDeg;
  f.pose.lonDeg = g.lonDeg;
  f.pose.altM = g.heightM;
  f.pose.fovYDeg = 2.0 * std::atan(1.0 / p[5]) * 180.0 / 3.14159265358979323846;
  f.pose.width = w;
  f.pose.height = h;
  f.light.sunEcef = glm::normalize(sun);
  f.light.timeS = v->time_s;
  if (v->draw_flags & ~GEOCEAN_DRAW_REFERENCE)
    bad("draw_flags " + std::to_string(v->draw_flags) + " has bits that are not GEOCEAN_DRAW_*");
  f.reference = (v->draw_flags & GEOCEAN_DRAW_REFERENCE) != 0;
  return f;
}

// The camera fields of a geocean_view from the viewer's own matrices, in
// double (the same numbers the viewer draws with).
void fillView(geocean_view* view, const geocean::render::ViewMatrices& vm, const geocean::render::ViewPose& pose) {
  for (int i = 0; i < 3; ++i) view->eye_ecef_m[i] = vm.eyeEcef[i];
  double* m = view->view_matrix;
  std::fill(m, m + 16, 0.0);
  for (int c = 0; c < 3; ++c) {
    m[4 * c + 0] = vm.right[c];
    m[4 * c + 1] = vm.up[c];
    m[4 * c + 2] = -vm.forward[c];
  }
  m[15] = 1.0;
  double* p = view->projection_matrix;
  std::fill(p, p + 16, 0.0);
  const double f = 1.0 / std::tan(0.5 * pose.fovYDeg * 3.14159265358979323846 / 180.0);
  p[0] = f / (double(pose.width) / double(pose.height));  // as render::viewMatrices, to the last bit
  p[5] = f;
  p[11] = -1.0;      // w = -z_view
  p[14] = vm.nearM;  // reversed Z: depth = near / -z_view
  view->viewport_width_px = pose.width;
  view->viewport_height_px = pose.height;
}

}  // namespace

struct geocean_ocean {
  mutable std::mutex mutex;  // guards `snapshot` (the pointer, not its contents)
  std::shared_ptr<const Snapshot> snapshot = std::make_shared<Snapshot>();
  // Render-thread state (update/draw/release_gl never overlap, header rule).
  std::optional<FrameView> view;
  std::unique_ptr<GlResources> gl;

  std::shared_ptr<const Snapshot> current() const {
    std::lock_guard lock(mutex);
    return snapshot;
  }
  // Applies `edit` to a copy of the current snapshot and publishes it.
  // Setters are serialised so two concurrent edits cannot lose one another.
  template <class Edit>
  void update(Edit&& edit) {
    std::lock_guard editLock(editMutex);
    auto next = std::make_shared<Snapshot>(*current());
    edit(*next);
    if (next->mask || next->elevation)
      next->landSea = std::make_shared<geocean::ocean::LandSea>(next->mask, next->elevation);
    else
      next->landSea.reset();
    if (next->waves)
      next->sea = std::make_shared<geocean::waves::SeaQuery>(*next->waves, next->landSea);
    else
      next->sea.reset();
    std::lock_guard lock(mutex);
    snapshot = std::move(next);
  }

 private:
  std::mutex editMutex;
};

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
    if (ocean && ocean->gl) {
      if (currentGlContext() == ocean->gl->context)
        ocean->gl.reset();
      else
        (void)ocean->gl.release();  // no GL call without its context: the context owns them now
    }
    delete ocean;
  });
}

GEOCEAN_API geocean_status geocean_set_mask_file(geocean_ocean* ocean, const char* path, geocean_georef georef) {
  return guard("geocean_set_mask_file", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(path, "path");
    auto r = Raster::open(path, openOptions(georef));
    ocean->update([&](Snapshot& s) { s.mask = std::move(r); });
  });
}

GEOCEAN_API geocean_status geocean_set_elevation_file(geocean_ocean* ocean, const char* path,
                                                      geocean_georef georef) {
  return guard("geocean_set_elevation_file", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(path, "path");
    auto r = Raster::open(path, openOptions(georef));
    ocean->update([&](Snapshot& s) { s.elevation = std::move(r); });
  });
}

GEOCEAN_API geocean_status geocean_set_mask_pixels(geocean_ocean* ocean, const float* values, int32_t width,
                                                   int32_t height, const geocean_grid_placement* placement) {
  return guard("geocean_set_mask_pixels", [&] {
    requireNonNull(ocean, "ocean");
    auto r = fromMemory(values, width, height, placement, "<mask from memory>");
    ocean->update([&](Snapshot& s) { s.mask = std::move(r); });
  });
}

GEOCEAN_API geocean_status geocean_set_elevation_pixels(geocean_ocean* ocean, const float* values_m,
                                                        int32_t width, int32_t height,
                                                        const geocean_grid_placement* placement) {
  return guard("geocean_set_elevation_pixels", [&] {
    requireNonNull(ocean, "ocean");
    auto r = fromMemory(values_m, width, height, placement, "<elevation from memory>");
    ocean->update([&](Snapshot& s) { s.elevation = std::move(r); });
  });
}

GEOCEAN_API geocean_status geocean_set_default_world(geocean_ocean* ocean) {
  return guard("geocean_set_default_world", [&] {
    requireNonNull(ocean, "ocean");
    std::string dir;
    if (const char* env = std::getenv("GEOCEAN_DATA"); env && *env) dir = env;
    if (dir.empty()) dir = installedDataDir();
    if (dir.empty()) dir = geocean::raster::dataDir();
    auto mask = Raster::open(dir + "/landmask_5m.tif");
    auto elevation = Raster::open(dir + "/etopo_20m.tif");
    ocean->update([&](Snapshot& s) {
      s.mask = std::move(mask);
      s.elevation = std::move(elevation);
    });
  });
}

GEOCEAN_API geocean_status geocean_clear_rasters(geocean_ocean* ocean) {
  return guard("geocean_clear_rasters", [&] {
    requireNonNull(ocean, "ocean");
    ocean->update([&](Snapshot& s) {
      s.mask.reset();
      s.elevation.reset();
    });
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
    const auto snap = ocean->current();
    if (!snap->landSea)
      fail(GEOCEAN_ERROR_NOT_READY, "no mask or elevation raster: call geocean_set_mask_* or "
                                    "geocean_set_elevation_* (or geocean_set_default_world) first");
    static_assert(sizeof(geocean::ocean::Surface) == sizeof(uint8_t));
    static_assert(uint8_t(geocean::ocean::Surface::Ocean) == GEOCEAN_SURFACE_OCEAN &&
                  uint8_t(geocean::ocean::Surface::Land) == GEOCEAN_SURFACE_LAND &&
                  uint8_t(geocean::ocean::Surface::Lake) == GEOCEAN_SURFACE_LAKE);
    // Through a buffer: writing uint8_t storage through Surface lvalues would break aliasing rules.
    constexpr std::size_t kChunk = 1024;
    geocean::ocean::Surface buf[kChunk];
    for (std::size_t i = 0; i < count; i += kChunk) {
      const std::size_t n = std::min(kChunk, count - i);
      snap->landSea->classifyBatch(lat_deg + i, lon_deg + i, n, buf);
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
    const auto snap = ocean->current();
    if (!snap->elevation)
      fail(GEOCEAN_ERROR_NOT_READY, "no elevation raster: call geocean_set_elevation_file, "
                                    "geocean_set_elevation_pixels or geocean_set_default_world first");
    snap->landSea->elevationBatch(lat_deg, lon_deg, count, out_elevation_m);
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
    if (sea_state->struct_size < sizeof(geocean_sea_state))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "sea_state->struct_size " + std::to_string(sea_state->struct_size) +
                                               " is smaller than " + std::to_string(sizeof(geocean_sea_state)) +
                                               ": call geocean_sea_state_init first");
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
    std::string error;
    auto field = geocean::waves::WaveField::create(model, s, error);
    if (!field) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, error);
    auto shared = std::make_shared<const geocean::waves::WaveField>(std::move(*field));
    ocean->update([&](Snapshot& snap) {
      snap.waves = std::move(shared);
      snap.model = model;
      snap.seaState = s;
    });
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
    const auto snap = ocean->current();
    if (!snap->sea) fail(GEOCEAN_ERROR_NOT_READY, "no sea state: call geocean_set_sea_state first");
    if (count == 0) return;
    requireNonNull(lat_deg, "lat_deg");
    requireNonNull(lon_deg, "lon_deg");
    requireNonNull(out_height_m, "out_height_m");
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    // Chunks bound the result buffer; each chunk runs on all cores (TBB).
    constexpr std::size_t kChunk = 16384;
    std::vector<geocean::waves::SeaQueryResult> r(std::min(count, kChunk));
    for (std::size_t i0 = 0; i0 < count; i0 += kChunk) {
      const std::size_t n = std::min(kChunk, count - i0);
      snap->sea->queryBatch(lat_deg + i0, lon_deg + i0, &time_s, false, n, r.data());
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = i0 + k;
        const bool sea = r[k].surface == geocean::ocean::Surface::Ocean;
        out_height_m[i] = r[k].seaHeightM;
        if (out_class) out_class[i] = static_cast<uint8_t>(r[k].surface);
        if (out_normal_enu) {
          out_normal_enu[3 * i] = sea ? r[k].normalEnu.x : kNaN;
          out_normal_enu[3 * i + 1] = sea ? r[k].normalEnu.y : kNaN;
          out_normal_enu[3 * i + 2] = sea ? r[k].normalEnu.z : kNaN;
        }
      }
    }
  });
}

GEOCEAN_API geocean_status geocean_significant_wave_height(const geocean_ocean* ocean, double* out_hs_m) {
  return guard("geocean_significant_wave_height", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(out_hs_m, "out_hs_m");
    const auto snap = ocean->current();
    if (!snap->waves) fail(GEOCEAN_ERROR_NOT_READY, "no sea state: call geocean_set_sea_state first");
    *out_hs_m = snap->waves->spectrumHsM();
  });
}

GEOCEAN_API geocean_status geocean_view_init(geocean_view* view) {
  return guard("geocean_view_init", [&] {
    requireNonNull(view, "view");
    *view = geocean_view{};
    view->struct_size = sizeof(geocean_view);
    const geocean::render::ViewPose pose;  // 10,000 km over (0, 0), looking down, 1280x720, 45 deg
    fillView(view, geocean::render::viewMatrices(pose, pose.altM), pose);
    view->time_s = 0.0;
    view->sun_dir_ecef[0] = 1.0;
  });
}

GEOCEAN_API geocean_status geocean_view_from_pose(geocean_view* view, double lat_deg, double lon_deg,
                                                  double height_m, double heading_deg, double pitch_deg,
                                                  double fov_y_deg, int32_t width_px, int32_t height_px) {
  return guard("geocean_view_from_pose", [&] {
    requireNonNull(view, "view");
    auto bad = [](const char* name, double v, const char* range) {
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(name) + " " + std::to_string(v) + " is not " + range);
    };
    if (!(std::abs(lat_deg) <= 90.0)) bad("lat_deg", lat_deg, "within -90 .. 90");
    if (!std::isfinite(lon_deg)) bad("lon_deg", lon_deg, "finite");
    if (!(std::abs(height_m) < 1e9)) bad("height_m", height_m, "finite (|h| < 1e9 m)");
    if (!std::isfinite(heading_deg)) bad("heading_deg", heading_deg, "finite");
    if (!(std::abs(pitch_deg) <= 90.0)) bad("pitch_deg", pitch_deg, "within -90 .. 90");
    if (!(fov_y_deg >= 1.0 && fov_y_deg <= 170.0)) bad("fov_y_deg", fov_y_deg, "within 1 .. 170");
    if (width_px < 1 || width_px > 16384) bad("width_px", width_px, "within 1 .. 16384");
    if (height_px < 1 || height_px > 16384) bad("height_px", height_px, "within 1 .. 16384");
    geocean::render::ViewPose pose;
    pose.latDeg = lat_deg;
    pose.lonDeg = lon_deg;
    pose.altM = height_m;
    pose.headingDeg = heading_deg;
    pose.pitchDeg = pitch_deg;
    pose.fovYDeg = fov_y_deg;
    pose.width = width_px;
    pose.height = height_px;
    // Near plane from the height above the sea (the host knows no better here).
    fillView(view, geocean::render::viewMatrices(pose, height_m), pose);
  });
}

GEOCEAN_API geocean_status geocean_update(geocean_ocean* ocean, const geocean_view* view) {
  return guard("geocean_update", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(view, "view");
    ocean->view = frameViewOf(view);
  });
}

GEOCEAN_API geocean_status geocean_draw(geocean_ocean* ocean) {
  return guard("geocean_draw", [&] {
    requireNonNull(ocean, "ocean");
    void* ctx = currentGlContext();
    if (!ctx)
      fail(GEOCEAN_ERROR_NO_GL_CONTEXT,
           "no OpenGL context is current on this thread (neither EGL nor GLX): make the host's context current");
    if (!ocean->view) fail(GEOCEAN_ERROR_NOT_READY, "no view: call geocean_update first");
    const auto snap = ocean->current();
    if (!snap->waves) fail(GEOCEAN_ERROR_NOT_READY, "no sea state: call geocean_set_sea_state first");
    if (snap->model == geocean::waves::Model::NoisePaper)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "sea state model GEOCEAN_WAVES_NOISE_PAPER has no GPU form: "
                                           "draw with GEOCEAN_WAVES_NOISE, GEOCEAN_WAVES_GERSTNER or GEOCEAN_WAVES_FFT");
    if (ocean->gl && ocean->gl->context != ctx)
      fail(GEOCEAN_ERROR_GL, "the ocean's GL resources belong to another context: call geocean_release_gl "
                             "with that context current first");
    if (epoxy_gl_version() < 45 || !epoxy_is_desktop_gl())
      fail(GEOCEAN_ERROR_GL, "the current context is OpenGL " + std::to_string(epoxy_gl_version() / 10) + "." +
                                 std::to_string(epoxy_gl_version() % 10) +
                                 (epoxy_is_desktop_gl() ? "" : " ES") + "; the ocean needs desktop OpenGL 4.5");
    GlStateGuard state;
    try {
      if (!ocean->gl) {
        ocean->gl = std::make_unique<GlResources>();
        ocean->gl->context = ctx;
      }
      GlResources& gl = *ocean->gl;
      if (!gl.builtFrom || gl.builtFrom->mask != snap->mask || gl.builtFrom->elevation != snap->elevation) {
        gl.renderer.reset();
        gl.world = std::make_shared<const geocean::render::WorldTextures>(worldDataFor(*snap));
      }
      if (!gl.renderer || gl.builtFrom->waves != snap->waves) {
        geocean::ocean_render::OceanOptions o;
        o.model = snap->model;
        o.sea = snap->seaState;
        gl.renderer.reset();
        gl.renderer = std::make_unique<geocean::ocean_render::OceanRenderer>(gl.world, snap->landSea, o);
      }
      gl.builtFrom = snap;
      gl.renderer->draw(ocean->view->vm, ocean->view->pose, ocean->view->light, ocean->view->reference);
    } catch (const geocean::render::ShaderError& e) {
      fail(GEOCEAN_ERROR_GL, e.what());
    }
  });
}

GEOCEAN_API geocean_status geocean_release_gl(geocean_ocean* ocean) {
  return guard("geocean_release_gl", [&] {
    requireNonNull(ocean, "ocean");
    if (!ocean->gl) return;
    void* ctx = currentGlContext();
    if (!ctx)
      fail(GEOCEAN_ERROR_NO_GL_CONTEXT, "no OpenGL context is current on this thread: make current the context "
                                        "of the first geocean_draw");
    if (ctx != ocean->gl->context)
      fail(GEOCEAN_ERROR_GL, "the current context is not the one the ocean's GL resources were made in");
    ocean->gl.reset();
  });
}

}  // extern "C"
