// One frame of the globe: sky, terrain (with distant sea), then any extra
// layers (the wave-grid ocean from plugin/render) — into whatever
// framebuffer is bound, from whatever context is current (EGL headless or
// a GLFW window). Reversed Z: depth cleared to 0, GL_GREATER, float depth.
#pragma once

#include "globe/gl/Framebuffer.h"
#include "globe/gl/GlProgram.h"
#include "globe/render/Layer.h"
#include "globe/render/SceneObject.h"
#include "globe/render/Terrain.h"
#include "globe/camera/Camera.h"
#include "globe/render/WorldTextures.h"

#include <memory>
#include <optional>
#include <vector>

namespace geocean::render {

struct FrameTimes {
  double skyMs = 0.0, terrainMs = 0.0, layersMs = 0.0, totalMs = 0.0;
  // Process CPU time (all threads, llvmpipe's rasteriser threads included)
  // per pass; with `timed` it is the pass's own work, and unlike wall time
  // it does not grow when other processes share the cores.
  double skyCpuMs = 0.0, terrainCpuMs = 0.0, layersCpuMs = 0.0, totalCpuMs = 0.0;
  // The mirrored pass of a reflection alone (part of layers*Ms; 0 when the
  // map was reused or not wanted).
  double reflectionMs = 0.0, reflectionCpuMs = 0.0;
  // The sun's shadow map pass alone (part of layers*Ms; 0 when skipped).
  double shadowMs = 0.0, shadowCpuMs = 0.0;
  TerrainStats terrain;
  bool reflectionDrawn = false;  // the mirrored pass ran this frame (not reused)
  bool shadowDrawn = false;      // the shadow map pass ran this frame
};

struct FrameSettings {
  double timeS = 0.0;
  glm::dvec3 sunEcef{1.0, 0.0, 0.0};
  bool bare = false;   // trivial shaders: the reference draw for frame-time ratios
  bool timed = false;  // glFinish between passes so each pass is timed alone
  // Optics (issue 13): the mirrored pass for layers that want a reflection
  // (--no-reflections: none made), and the view through the water.
  bool reflections = true;
  bool refraction = true;
  // The mirrored pass's map: its longer side in pixels, the viewport's
  // aspect kept (paper 001's 512, 1024, 2048); 0: the viewport's size.
  int reflectionSize = 0;
  // Paper 001 reuses its reflection map for m frames: the mirrored pass runs
  // on every reflectionEvery-th frame, the others read the last map through
  // the camera it was drawn with (so it stays where it was in the world; what
  // moved since is m - 1 frames late). 1: every frame.
  int reflectionEvery = 1;
  // The sun's shadows on the water (issue 13 item 6; --no-shadows,
  // --shadow-model) and its specular (--sun-model), for layers that want them.
  bool shadows = true;
  ShadowModel shadowModel = ShadowModel::Physical;
  SunModel sunModel = SunModel::Microfacet;
};

// The sun's shadow map's view for a camera (Layer.h's reach and rules):
// false when no pass is needed (sun below the horizon at the nadir, eye
// above the largest reach). matrix: positions relative to the eye -> clip
// (x, y in -1..1, z 0..1 reversed: 1 nearest the sun); reachM: the sea
// covered, from the eye; region: the covered sea's geodetic rectangle
// (lat0, lat1, lon0, lon1) widened by what a 1 km high caster's shadow spans.
struct ShadowView {
  glm::dmat4 matrix{1.0};
  double reachM = 0.0;
  double region[4] = {0.0, 0.0, 0.0, 0.0};
};
bool shadowView(const camera::Camera& cam, const glm::dvec3& sunEcef, ShadowView& out);

class GlobeRenderer {
 public:
  GlobeRenderer(std::shared_ptr<const WorldTextures> world, TerrainOptions terrain = {});
  ~GlobeRenderer();
  GlobeRenderer(const GlobeRenderer&) = delete;
  GlobeRenderer& operator=(const GlobeRenderer&) = delete;
  void addLayer(std::shared_ptr<Layer> layer) { layers_.push_back(std::move(layer)); }
  // Drawn after the terrain in the main and the mirrored pass (SceneObject.h).
  void addSceneObject(std::shared_ptr<SceneObject> object) { objects_.push_back(std::move(object)); }

  // Height of the eye above the terrain or sea under it (for the near plane).
  double altitudeAboveSurfaceM(const camera::ViewPose& pose) const;
  // The camera a frame of this pose is drawn with (near plane from the
  // altitude above the surface).
  camera::Camera camera(const camera::ViewPose& pose) const;

  FrameTimes render(const camera::ViewPose& pose, const FrameSettings& settings);

  const WorldTextures& world() const { return *world_; }
  TerrainRenderer& terrain() { return terrain_; }

 private:
  std::shared_ptr<const WorldTextures> world_;
  TerrainRenderer terrain_;
  // Draws sky and terrain (no layers) into the bound framebuffer; with
  // mirroredFrom, `cam` is its mirror image and only terrain above the sea
  // is drawn (the reflection pass).
  void drawScene(const camera::Camera& cam, const camera::Lighting& light, const FrameSettings& settings,
                 FrameTimes& t, const Layer* waterLayer, SeaShading sea,
                 const camera::Camera* mirroredFrom = nullptr);
  // The inputs the layers asked for (LayerInfo::wants), made after the terrain.
  void makeLayerInputs(const camera::Camera& cam, const camera::Lighting& light, const FrameSettings& settings,
                       unsigned wants, LayerInputs& in, FrameTimes& t);

  gl::GlProgram sky_;
  GLuint emptyVao_ = 0;
  // The layers' inputs (made on first need, per size).
  gl::TextureTarget sceneCopy_, reflection_;
  // The sun's depth map (made on first need).
  GLuint shadowFbo_ = 0, shadowDepth_ = 0;
  bool settingsTimed_ = false;
  void makeShadowMap(const camera::Camera& cam, const camera::Lighting& light, const Layer* waterLayer,
                     LayerInputs& in, FrameTimes& t);
  // The last mirrored pass (FrameSettings::reflectionEvery): its camera
  // (and so the map's size) and the frames since; a change of
  // reflectionEvery starts a new cycle (the next frame draws).
  std::optional<camera::Camera> reflectionCamera_;
  int reflectionAge_ = 0, reflectionEvery_ = 1;
  std::vector<std::shared_ptr<Layer>> layers_;
  std::vector<std::shared_ptr<SceneObject>> objects_;
};

}  // namespace geocean::render
