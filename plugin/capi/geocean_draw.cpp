// The C ABI's drawing half (ABI 1.1): the host's view, the ocean's GL
// resources in the host's context, draw and release.
#include "plugin/capi/CapiSupport.h"

#include "globe/render/GlProgram.h"
#include "globe/render/WorldTextures.h"
#include "plugin/render/OceanRenderer.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

using namespace geocean::capi;

namespace {

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

namespace geocean::capi {
struct DrawState {
  std::optional<FrameView> view;
  std::unique_ptr<GlResources> gl;
};
void DrawStateDeleter::operator()(DrawState* d) const { delete d; }
void releaseDrawState(std::unique_ptr<DrawState, DrawStateDeleter>& d) {
  if (d && d->gl) {
    if (currentGlContext() == d->gl->context)
      d->gl.reset();
    else
      (void)d->gl.release();  // no GL call without its context: the context owns them now
  }
  d.reset();
}
}  // namespace geocean::capi

namespace {
DrawState& drawState(geocean_ocean* ocean) {
  if (!ocean->draw) ocean->draw.reset(new DrawState);
  return *ocean->draw;
}
}  // namespace

extern "C" {

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
    drawState(ocean).view = frameViewOf(view);
  });
}

GEOCEAN_API geocean_status geocean_draw(geocean_ocean* ocean) {
  return guard("geocean_draw", [&] {
    requireNonNull(ocean, "ocean");
    DrawState& ds = drawState(ocean);
    void* ctx = currentGlContext();
    if (!ctx)
      fail(GEOCEAN_ERROR_NO_GL_CONTEXT,
           "no OpenGL context is current on this thread (neither EGL nor GLX): make the host's context current");
    if (!ds.view) fail(GEOCEAN_ERROR_NOT_READY, "no view: call geocean_update first");
    const auto snap = ocean->current();
    if (!snap->waves) fail(GEOCEAN_ERROR_NOT_READY, "no sea state: call geocean_set_sea_state first");
    if (snap->model == geocean::waves::Model::NoisePaper)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "sea state model GEOCEAN_WAVES_NOISE_PAPER has no GPU form: "
                                           "draw with GEOCEAN_WAVES_NOISE, GEOCEAN_WAVES_GERSTNER or GEOCEAN_WAVES_FFT");
    if (ds.gl && ds.gl->context != ctx)
      fail(GEOCEAN_ERROR_GL, "the ocean's GL resources belong to another context: call geocean_release_gl "
                             "with that context current first");
    if (epoxy_gl_version() < 45 || !epoxy_is_desktop_gl())
      fail(GEOCEAN_ERROR_GL, "the current context is OpenGL " + std::to_string(epoxy_gl_version() / 10) + "." +
                                 std::to_string(epoxy_gl_version() % 10) +
                                 (epoxy_is_desktop_gl() ? "" : " ES") + "; the ocean needs desktop OpenGL 4.5");
    GlStateGuard state;
    try {
      if (!ds.gl) {
        ds.gl = std::make_unique<GlResources>();
        ds.gl->context = ctx;
      }
      GlResources& gl = *ds.gl;
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
      gl.renderer->draw(ds.view->vm, ds.view->pose, ds.view->light, ds.view->reference);
    } catch (const geocean::render::ShaderError& e) {
      fail(GEOCEAN_ERROR_GL, e.what());
    }
  });
}

GEOCEAN_API geocean_status geocean_release_gl(geocean_ocean* ocean) {
  return guard("geocean_release_gl", [&] {
    requireNonNull(ocean, "ocean");
    if (!ocean->draw || !ocean->draw->gl) return;
    void* ctx = currentGlContext();
    if (!ctx)
      fail(GEOCEAN_ERROR_NO_GL_CONTEXT, "no OpenGL context is current on this thread: make current the context "
                                        "of the first geocean_draw");
    if (ctx != ocean->draw->gl->context)
      fail(GEOCEAN_ERROR_GL, "the current context is not the one the ocean's GL resources were made in");
    ocean->draw->gl.reset();
  });
}

}  // extern "C"
