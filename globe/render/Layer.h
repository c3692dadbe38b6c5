// The host/layer contract: what a layer drawn over the terrain (the ocean
// plugin, or any other) tells the host, and what the host gives it. The
// host never assumes what a layer covers: it asks.
#pragma once

#include "globe/camera/Camera.h"
#include "shaders/Shaders.h"

#include <epoxy/gl.h>

namespace geocean::render {

// What the host runs for a layer before its draw (LayerInfo::wants bits).
enum LayerInput : unsigned {
  kLayerWantsReflection = 1u,  // sky and terrain mirrored in the sea-level plane under the eye
  kLayerWantsSceneCopy = 2u,   // a copy of the scene's colour and depth so far (refraction)
  kLayerWantsShadowMap = 4u,   // the sun's depth map of terrain and scene objects near the eye
};

// The sun's shadow map (issue 13 item 6): an orthographic depth pass along
// the sun over the sea the eye sees out to a reach that grows with the eye's
// height above the surface, kShadowReachPerHeight x it, within
// kShadowReachMinM..kShadowReachMaxM; no pass for an eye higher than the
// largest reach (no sea point within it), for the sun below the horizon or
// when nothing can cast onto the region (all open water, no scene object).
constexpr double kShadowReachPerHeight = 30.0;
constexpr double kShadowReachMinM = 500.0;
constexpr double kShadowReachMaxM = 5000.0;
// The map's side (texels): over a 5 km reach about 3.7 m a texel (a 12 m
// boat's shadow 3 texels wide), 0.4 m for an eye 17 m up.
constexpr int kShadowMapSize = 2048;

// What the water does in shadow: the sun's direct light removed (glitter,
// sun-lit body, subsurface and foam; the sky's light stays), or paper 001's
// darkening of the shadowed pixel by m = 0.5.
enum class ShadowModel { Physical, Paper };
// The sun's specular on the water: the microfacet glitter (Cox-Munk
// slopes), or paper 001's Phong term (eq. 19).
enum class SunModel { Microfacet, Phong };

// The reach of a reflection: layers use the mirrored pass's map only for
// points within this distance of the eye (the ocean fades it out from half
// of it: ocean_shading.glsl's kReflectionFarM, the same constant). No point
// of the sea is nearer than the eye's height, so above it the host skips the
// pass (from orbit it cost a third of the frame on llvmpipe and drew nothing
// the sea shows).
constexpr double kReflectionReachM = shaders::kReflectionReachM;

struct LayerInfo {
  // The layer draws water opaquely where coversOpaquely() says so: the
  // terrain may leave those tiles out.
  bool opaqueWater = false;
  double cellPx = 0.0;  // the layer's grid cell on screen, pixels (0: none)
  unsigned wants = 0;   // LayerInput bits
};

// Filled by the host for the inputs a layer asked for (0 where not asked).
struct LayerInputs {
  GLuint reflectionColor = 0;  // RGBA8, reflectionCamera's size (FrameSettings::reflectionSize)
  GLuint sceneColor = 0;       // RGBA8 copy of the colour attachment 0 after the terrain
  GLuint sceneDepth = 0;       // DEPTH32F copy (reversed Z: 0 far, 1 at the near plane)
  // The mirrored camera the reflection was drawn with (valid with
  // reflectionColor): project a mirrored point with its gpu() matrices.
  camera::Camera reflectionCamera = camera::Camera::fromView({});
  // The frame's optics switch (--no-refraction): whether the layer draws
  // what is seen through its water. (--no-reflections: the host makes no
  // reflection, reflectionColor is 0.)
  bool refraction = true;
  // The sun's shadow map (kLayerWantsShadowMap; 0: none this frame):
  // DEPTH32F, reversed (1 nearest the sun), shadowSize square;
  // shadowMatrix maps a position relative to shadowOriginEcef to clip
  // space (x, y in -1..1 over the map, z its depth); the map covers the sea
  // out to shadowReachM from that origin (the eye).
  GLuint shadowDepth = 0;
  int shadowSize = 0;
  glm::dmat4 shadowMatrix{1.0};
  glm::dvec3 shadowOriginEcef{0.0};
  double shadowReachM = 0.0;
  // The frame's light options (--shadow-model, --sun-model).
  ShadowModel shadowModel = ShadowModel::Physical;
  SunModel sunModel = SunModel::Microfacet;
};

class Layer {
 public:
  virtual ~Layer() = default;
  virtual const char* name() const = 0;
  virtual LayerInfo info() const { return {}; }
  // True when the layer draws every pixel over the geographic rectangle
  // opaquely, for pixels whose footprint on the surface there is up to
  // pixelFootprintM metres (only asked of layers with info().opaqueWater).
  virtual bool coversOpaquely(double lat0Deg, double lat1Deg, double lon0Deg, double lon1Deg,
                              double pixelFootprintM) const {
    (void)lat0Deg, (void)lat1Deg, (void)lon0Deg, (void)lon1Deg, (void)pixelFootprintM;
    return false;
  }
  // Draws into the bound framebuffer (reversed Z, GL_GREATER). `bare`:
  // trivial shaders, the reference draw for frame-time ratios.
  virtual void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
                    const LayerInputs& inputs) = 0;
};

}  // namespace geocean::render
