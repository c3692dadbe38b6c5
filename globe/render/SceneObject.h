// Objects the host draws into its scene with the terrain (the floating
// bodies): before the layers, so the ocean's depth test hides what is under
// the water and its scene copy holds them, and again in the mirrored
// reflection pass, so the sea reflects them.
#pragma once

#include "globe/camera/Camera.h"

namespace geocean::render {

class SceneObject {
 public:
  virtual ~SceneObject() = default;
  // Once per frame before anything is drawn: bring the state to the frame's time.
  virtual void update(double timeS) { (void)timeS; }
  // Into the bound framebuffer (reversed Z, GL_GREATER, depth test on).
  // mirroredFrom: `cam` is the mirror image of *mirroredFrom in the sea-level
  // plane under its eye; draw only what is above that plane.
  virtual void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
                    const camera::Camera* mirroredFrom) = 0;
  // Depth only, into the sun's shadow map (reversed Z, GL_GREATER):
  // viewProj takes positions relative to originEcef. Objects that cast no
  // shadow leave it empty.
  virtual void drawDepth(const glm::mat4& viewProj, const glm::dvec3& originEcef) { (void)viewProj, (void)originEcef; }
};

}  // namespace geocean::render
