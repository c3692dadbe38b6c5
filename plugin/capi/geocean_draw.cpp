// The C ABI's drawing half (ABI 1.1): the host's view, the ocean's GL
// resources in the host's context, draw and release.
#include "plugin/capi/CapiSupport.h"

#include "globe/gl/GlProgram.h"
#include "plugin/render/OceanRenderer.h"
#include "plugin/render/OceanWorld.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
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

// The GL resources of one ocean, in the context current at their creation.
struct GlResources {
  void* context = nullptr;
  std::shared_ptr<const Snapshot> builtFrom;  // rebuilt when the state changes
  std::unique_ptr<geocean::ocean_render::OceanRenderer> renderer;
  // A labelled buffer in the same context: a context destroyed and a new
  // one made at the same handle (EGL and GLX reuse freed addresses) is told
  // apart by it, instead of drawing with names that died with the old one
  // (or that the host's new objects now own).
  GLuint sentinel = 0;
  std::string label;
  explicit GlResources(void* ctx) : context(ctx), label("geocean ocean " + std::to_string(reinterpret_cast<std::uintptr_t>(this))) {
    glCreateBuffers(1, &sentinel);
    glObjectLabel(GL_BUFFER, sentinel, GLsizei(label.size()), label.c_str());
  }
  ~GlResources() {
    renderer.reset();
    if (sentinel) glDeleteBuffers(1, &sentinel);
  }
  GlResources(const GlResources&) = delete;
  GlResources& operator=(const GlResources&) = delete;
  // With `context` current: are these names still this context's?
  bool alive() const {
    if (!sentinel || !glIsBuffer(sentinel)) return false;
    char got[64] = {};
    GLsizei n = 0;
    glGetObjectLabel(GL_BUFFER, sentinel, GLsizei(sizeof got), &n, got);
    return label == std::string(got, std::size_t(std::max<GLsizei>(n, 0)));
  }
  // Without their context: forget the names (no GL call can reach them).
  void abandon() {
    if (renderer) renderer->abandonGl();
    sentinel = 0;
  }
};

// The ocean's world grids (CPU) for a snapshot's rasters: its textures and
// its answer to "do you cover this opaquely" come from them.
// Keyed by the snapshot's land/sea, which is rebuilt whenever a raster, a
// layer or the mask encoding changes.
struct WorldCache {
  std::shared_ptr<const geocean::ocean::LandSea> landSea;
  std::shared_ptr<const Raster> mask, elevation;
  std::shared_ptr<const geocean::world::WorldGrids> grids;
  // A layer's streamed mask (the host terrain's rule and pyramid), or null.
  std::shared_ptr<const geocean::raster::TilePyramid> waterTiles;
  std::vector<std::shared_ptr<const geocean::raster::TilePyramid>> waterTilesBelow;  // several streamed masks
  // The streamed reliefs (the host terrain's): the water depth drawn.
  std::vector<std::shared_ptr<const geocean::raster::TilePyramid>> elevationTiles;
  const geocean::world::WorldGrids& of(const Snapshot& snap) {
    if (!grids || landSea != snap.landSea || mask != snap.mask || elevation != snap.elevation) {
      waterTilesBelow = geocean::ocean_render::oceanWaterTileLayers(snap.landSea.get(), snap.mask);
      waterTiles = waterTilesBelow.empty() ? nullptr : waterTilesBelow.front();
      if (!waterTilesBelow.empty()) waterTilesBelow.erase(waterTilesBelow.begin());
      elevationTiles = geocean::ocean_render::oceanElevationTileLayers(snap.landSea.get(), snap.elevation);
      grids = geocean::ocean_render::oceanWorld(snap.mask, snap.elevation, snap.landSea.get(), snap.maskEncoding,
                                                waterTiles.get());
      landSea = snap.landSea;
      mask = snap.mask;
      elevation = snap.elevation;
    }
    return *grids;
  }
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
    // Units 6 (2D array) and 7 (2D): a streamed mask's tile pool and page table.
    glActiveTexture(GL_TEXTURE6);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &pageTextures_[0]);
    glActiveTexture(GL_TEXTURE7);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &pageTextures_[1]);
    // Unit 14 (2D): the sun's shadow map (ABI 1.8; its sampler binding is put back by the draw).
    glActiveTexture(GL_TEXTURE14);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &shadowTexture_);
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
    glActiveTexture(GL_TEXTURE6);
    glBindTexture(GL_TEXTURE_2D_ARRAY, GLuint(pageTextures_[0]));
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, GLuint(pageTextures_[1]));
    glActiveTexture(GL_TEXTURE14);
    glBindTexture(GL_TEXTURE_2D, GLuint(shadowTexture_));
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
  static constexpr int kUnits = 4, kSsbos = 5, kDrawBuffers = 2;  // SSBOs 3-4: the FFT tables
  GLint program_ = 0, vao_ = 0, activeTexture_ = GL_TEXTURE0, texture_[kUnits] = {}, ssboGeneric_ = 0;
  GLint ssbo_[kSsbos] = {}, pageTextures_[2] = {}, shadowTexture_ = 0;
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
  geocean::camera::Camera cam;
  geocean::camera::Lighting light{};
  bool reference = false;
  bool refraction = true;
  bool completeTiles = false;
  bool ispg = false;
  bool followCoast = false;
  bool sunPhong = false;     // GEOCEAN_DRAW_SUN_PHONG (ABI 1.8)
  bool shadowPaper = false;  // GEOCEAN_DRAW_SHADOW_PAPER (ABI 1.8)
};

// geocean_layer_inputs as 1.2-1.7 hosts know it (up to reflection_view),
// and with ABI 1.8's shadow map.
constexpr std::size_t kLayerInputsSize12 = offsetof(geocean_layer_inputs, reflection_view) + sizeof(geocean_view);
constexpr std::size_t kLayerInputsSize18 = sizeof(geocean_layer_inputs);

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
  requireTimeInRange(v->time_s, "view->time_s");
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

  glm::dmat4 proj(0.0);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) proj[c][r] = p[4 * c + r];
  FrameView f{geocean::camera::Camera::fromHost({v->eye_ecef_m[0], v->eye_ecef_m[1], v->eye_ecef_m[2]}, -back, right,
                                                 up, proj, w, h)};
  f.light.sunEcef = glm::normalize(sun);
  f.light.timeS = v->time_s;
  if (v->draw_flags & ~(GEOCEAN_DRAW_REFERENCE | GEOCEAN_DRAW_NO_REFRACTION | GEOCEAN_DRAW_COMPLETE_TILES |
                        GEOCEAN_DRAW_FOLLOW_COAST | GEOCEAN_DRAW_GRID_ISPG | GEOCEAN_DRAW_SUN_PHONG |
                        GEOCEAN_DRAW_SHADOW_PAPER))
    bad("draw_flags " + std::to_string(v->draw_flags) + " has bits that are not GEOCEAN_DRAW_*");
  f.reference = (v->draw_flags & GEOCEAN_DRAW_REFERENCE) != 0;
  f.refraction = (v->draw_flags & GEOCEAN_DRAW_NO_REFRACTION) == 0;
  f.completeTiles = (v->draw_flags & GEOCEAN_DRAW_COMPLETE_TILES) != 0;
  f.ispg = (v->draw_flags & GEOCEAN_DRAW_GRID_ISPG) != 0;
  f.followCoast = (v->draw_flags & GEOCEAN_DRAW_FOLLOW_COAST) != 0;
  f.sunPhong = (v->draw_flags & GEOCEAN_DRAW_SUN_PHONG) != 0;
  f.shadowPaper = (v->draw_flags & GEOCEAN_DRAW_SHADOW_PAPER) != 0;
  return f;
}

// The camera fields of a geocean_view from a camera, in double (the same
// numbers the viewer draws with).
void fillView(geocean_view* view, const geocean::camera::Camera& cam) {
  for (int i = 0; i < 3; ++i) view->eye_ecef_m[i] = cam.eyeEcef()[i];
  double* m = view->view_matrix;
  std::fill(m, m + 16, 0.0);
  for (int c = 0; c < 3; ++c) {
    m[4 * c + 0] = cam.right()[c];
    m[4 * c + 1] = cam.up()[c];
    m[4 * c + 2] = -cam.forward()[c];
  }
  m[15] = 1.0;
  const glm::dmat4& proj = cam.gpu().projD;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) view->projection_matrix[4 * c + r] = proj[c][r];
  view->viewport_width_px = cam.widthPx();
  view->viewport_height_px = cam.heightPx();
}

}  // namespace

namespace geocean::capi {
struct DrawState {
  std::optional<FrameView> view;
  // The host's extra inputs for the next draws (geocean_set_layer_inputs).
  std::optional<geocean_layer_inputs> inputs;
  std::optional<geocean::camera::Camera> reflectionCamera;  // of inputs->reflection_view
  std::unique_ptr<GlResources> gl;
  WorldCache world;
};
void DrawStateDeleter::operator()(DrawState* d) const { delete d; }
void releaseDrawState(std::unique_ptr<DrawState, DrawStateDeleter>& d) {
  // Without their context, the GL names are left to it (no GL call can
  // reach them); the CPU side (grids, grid frame, wave tables) is freed.
  if (d && d->gl && (currentGlContext() != d->gl->context || !d->gl->alive())) d->gl->abandon();
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
    const geocean::camera::ViewPose pose;  // 10,000 km over (0, 0), looking down, 1280x720, 45 deg
    fillView(view, geocean::camera::Camera::fromView(pose));
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
    geocean::camera::ViewPose pose;
    pose.latDeg = lat_deg;
    pose.lonDeg = lon_deg;
    pose.altM = height_m;
    pose.headingDeg = heading_deg;
    pose.pitchDeg = pitch_deg;
    pose.fovYDeg = fov_y_deg;
    pose.width = width_px;
    pose.height = height_px;
    // Near plane from the height above the sea (the host knows no better here).
    fillView(view, geocean::camera::Camera::fromView(pose));
  });
}

GEOCEAN_API geocean_status geocean_update(geocean_ocean* ocean, const geocean_view* view) {
  return guard("geocean_update", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(view, "view");
    DrawState& ds = drawState(ocean);
    ds.view = frameViewOf(view);
    // At the frame's start, so its queries and its draw see one region.
    if (ds.view->followCoast) ocean->core.followCoastRegion(ds.view->cam.latDeg(), ds.view->cam.lonDeg());
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
    if (ds.gl && ds.gl->context != ctx)
      fail(GEOCEAN_ERROR_GL, "the ocean's GL resources belong to another context: call geocean_release_gl "
                             "with that context current first");
    if (ds.gl && !ds.gl->alive()) {
      // The same handle, but not the context the names were made in: that
      // one was destroyed (its names with it). Made anew below.
      ds.gl->abandon();
      ds.gl.reset();
    }
    if (epoxy_gl_version() < 45 || !epoxy_is_desktop_gl())
      fail(GEOCEAN_ERROR_GL, "the current context is OpenGL " + std::to_string(epoxy_gl_version() / 10) + "." +
                                 std::to_string(epoxy_gl_version() % 10) +
                                 (epoxy_is_desktop_gl() ? "" : " ES") + "; the ocean needs desktop OpenGL 4.5");
    GlStateGuard state;
    try {
      if (!ds.gl) ds.gl = std::make_unique<GlResources>(ctx);
      GlResources& gl = *ds.gl;
      const bool sameWorld = gl.renderer && gl.builtFrom->landSea == snap->landSea &&
                             gl.builtFrom->mask == snap->mask && gl.builtFrom->elevation == snap->elevation;
      // A followed coast region's swap changes only the coast texels.
      if (!sameWorld || (gl.builtFrom->waves != snap->waves && !gl.renderer->swapCoast(snap->waves))) {
        ds.world.of(*snap);
        geocean::ocean_render::OceanOptions o;
        o.model = snap->model;
        o.sea = snap->seaState;
        o.coast = snap->waves->coastFieldShared();  // Ocean::setCoastRegion: the query's near-shore field
        o.waves = snap->waves;  // the query's field: its FFT tables are built once for both
        o.waterTiles = ds.world.waterTiles;
        o.waterTilesBelow = ds.world.waterTilesBelow;
        o.elevationTiles = ds.world.elevationTiles;
        gl.renderer.reset();
        gl.renderer = std::make_unique<geocean::ocean_render::OceanRenderer>(ds.world.grids, snap->landSea, o);
      }
      gl.builtFrom = snap;
      geocean::ocean_render::OceanInputs oi;
      if (ds.inputs && ds.inputs->reflection_color_texture && ds.reflectionCamera) {
        oi.reflectionColor = ds.inputs->reflection_color_texture;
        oi.reflectionCamera = ds.reflectionCamera;
      }
      oi.refraction = ds.view->refraction;
      oi.sunPhong = ds.view->sunPhong;
      oi.shadowPaper = ds.view->shadowPaper;
      if (ds.inputs && ds.inputs->struct_size >= kLayerInputsSize18 && ds.inputs->shadow_depth_texture) {
        const geocean_layer_inputs& in = *ds.inputs;
        oi.shadowDepth = in.shadow_depth_texture;
        oi.shadowSize = int(in.shadow_size_px);
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) oi.shadowMatrix[c][r] = in.shadow_matrix[4 * c + r];
        oi.shadowOriginEcef = {in.shadow_origin_ecef_m[0], in.shadow_origin_ecef_m[1], in.shadow_origin_ecef_m[2]};
        oi.shadowReachM = in.shadow_reach_m;
      }
      gl.renderer->setInputs(oi);
      std::vector<geocean::ocean_render::Wake> wakes;
      {
        std::lock_guard lock(ocean->bodySetsMutex);
        for (const geocean_bodies* b : ocean->bodySets) appendWakes(*b, wakes);
      }
      gl.renderer->setWakes(std::move(wakes));
      gl.renderer->setCompleteTiles(ds.view->completeTiles);
      gl.renderer->setGridMode(ds.view->ispg ? geocean::grid::GridMode::Ispg : geocean::grid::GridMode::Direct);
      gl.renderer->draw(ds.view->cam, ds.view->light, ds.view->reference);
    } catch (const geocean::gl::ShaderError& e) {
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
    if (!ocean->draw->gl->alive()) ocean->draw->gl->abandon();  // their context was destroyed: nothing to delete
    ocean->draw->gl.reset();
  });
}

GEOCEAN_API geocean_status geocean_get_layer_info(const geocean_ocean* ocean, geocean_layer_info* out) {
  return guard("geocean_get_layer_info", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(out, "out");
    if (out->struct_size < sizeof(geocean_layer_info))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "out->struct_size " + std::to_string(out->struct_size) +
                                               " is smaller than " + std::to_string(sizeof(geocean_layer_info)));
    // The reflection of sky and terrain (item 4 of issue 13); refraction reads
    // the ocean's own relief, not the scene copy.
    out->flags = GEOCEAN_LAYER_OPAQUE_WATER | GEOCEAN_LAYER_WANTS_REFLECTION | GEOCEAN_LAYER_WANTS_SHADOW_MAP;
    out->cell_px = geocean::ocean_render::OceanOptions{}.cellPx;
  });
}

GEOCEAN_API geocean_status geocean_covers_opaquely(geocean_ocean* ocean, double lat0_deg, double lat1_deg,
                                                   double lon0_deg, double lon1_deg, double pixel_footprint_m,
                                                   int32_t* out_covers) {
  return guard("geocean_covers_opaquely", [&] {
    requireNonNull(ocean, "ocean");
    requireNonNull(out_covers, "out_covers");
    const double v[] = {lat0_deg, lat1_deg, lon0_deg, lon1_deg, pixel_footprint_m};
    static constexpr const char* kNames[] = {"lat0_deg", "lat1_deg", "lon0_deg", "lon1_deg", "pixel_footprint_m"};
    for (int i = 0; i < 5; ++i)
      if (!std::isfinite(v[i]))
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(kNames[i]) + " " + std::to_string(v[i]) + " is not finite");
    if (!(pixel_footprint_m > 0.0))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
           "pixel_footprint_m " + std::to_string(pixel_footprint_m) + " is not > 0");
    *out_covers = 0;
    const auto snap = ocean->current();
    if (!snap->mask && !snap->elevation) return;
    WorldCache& world = drawState(ocean).world;
    const auto& grids = world.of(*snap);
    // A regional streamed mask: the grids' water index is the layers' below it.
    if (world.waterTiles && !geocean::ocean_render::waterIndexFollowsTiles(grids, *world.waterTiles)) return;
    *out_covers = geocean::ocean_render::coversOpaquely(grids, geocean::ocean_render::OceanOptions{}.cellPx, lat0_deg,
                                                        lat1_deg, lon0_deg, lon1_deg, pixel_footprint_m,
                                                        world.waterTiles != nullptr)
                      ? 1
                      : 0;
  });
}

GEOCEAN_API geocean_status geocean_set_layer_inputs(geocean_ocean* ocean, const geocean_layer_inputs* inputs) {
  return guard("geocean_set_layer_inputs", [&] {
    requireNonNull(ocean, "ocean");
    DrawState& ds = drawState(ocean);
    if (!inputs) {
      ds.inputs.reset();
      ds.reflectionCamera.reset();
      return;
    }
    // A 1.2-1.7 host's struct ends at reflection_view: only that much is read.
    if (inputs->struct_size < kLayerInputsSize12)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "inputs->struct_size " + std::to_string(inputs->struct_size) +
                                               " is smaller than " + std::to_string(kLayerInputsSize12));
    geocean_layer_inputs in{};
    std::memcpy(&in, inputs, std::min<std::size_t>(inputs->struct_size, sizeof in));
    in.struct_size = uint32_t(std::min<std::size_t>(inputs->struct_size, sizeof in));
    const bool has18 = in.struct_size >= kLayerInputsSize18;
    const std::pair<uint32_t, const char*> names[] = {{in.reflection_color_texture, "reflection_color_texture"},
                                                      {in.scene_color_texture, "scene_color_texture"},
                                                      {in.scene_depth_texture, "scene_depth_texture"},
                                                      {has18 ? in.shadow_depth_texture : 0u, "shadow_depth_texture"}};
    for (const auto& [name, field] : names) {
      if (name == 0) continue;
      if (!currentGlContext())
        fail(GEOCEAN_ERROR_NO_GL_CONTEXT, std::string("inputs->") + field + " is set but no GL context is current");
      if (!glIsTexture(name))
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
             std::string("inputs->") + field + " " + std::to_string(name) + " is not a texture of the current context");
    }
    if (has18 && in.shadow_depth_texture) {
      if (!(in.shadow_size_px >= 1 && in.shadow_size_px <= 16384))
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
             "inputs->shadow_size_px " + std::to_string(in.shadow_size_px) + " is not in 1..16384");
      for (int i = 0; i < 16; ++i)
        if (!std::isfinite(in.shadow_matrix[i]))
          fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "inputs->shadow_matrix[" + std::to_string(i) + "] is not finite");
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite(in.shadow_origin_ecef_m[i]))
          fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
               "inputs->shadow_origin_ecef_m[" + std::to_string(i) + "] is not finite");
      if (!(in.shadow_reach_m >= 0.0 && std::isfinite(in.shadow_reach_m)))
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
             "inputs->shadow_reach_m " + std::to_string(in.shadow_reach_m) + " is not finite and >= 0");
    }
    std::optional<geocean::camera::Camera> mirrored;
    if (in.reflection_color_texture) mirrored = frameViewOf(&in.reflection_view).cam;  // validates it
    ds.inputs = in;
    ds.reflectionCamera = mirrored;
  });
}

}  // extern "C"
