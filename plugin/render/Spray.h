#pragma once
// Issue 15 item 4: the near band's breaking spray (paper 003): point sprites
// thrown where the coast field breaks the waves, near the eye only, drawn by
// OceanRenderer after the sea (shaders/spray.vert says how they move). A
// function of the time and the wave patch alone: no particle state, so
// every frame is reproducible.
#include "globe/camera/Camera.h"
#include "globe/gl/GlProgram.h"

#include <glm/glm.hpp>

namespace geocean::ocean_render {

class Spray {
 public:
  // Sites along a side of the lattice, and their spacing (m): 160 x 1.25 m
  // reaches past where a cluster is a pixel at 384 px (spray.vert's fade).
  static constexpr int kSites = 160;
  static constexpr double kSpacingM = 1.25;

  Spray();  // compiles shaders/spray.{vert,frag} (Gerstner with a coast field)
  // Draws with the ocean's wave SSBOs (bindings 0-4) and the elevation on
  // unit 1 bound: the patch at `originEcef` (ground under the eye) at timeS.
  void draw(const camera::Camera& cam, const glm::dvec3& originEcef, double originLatDeg, double originLonDeg,
            double timeS, int waveCount, const glm::vec4& elevationGeo, const glm::dvec3& sunEcef) const;
  ~Spray();
  Spray(const Spray&) = delete;
  Spray& operator=(const Spray&) = delete;
  // The context is gone: forget the GL names without GL calls.
  void abandon() { program_.abandon(), vao_ = 0; }

 private:
  gl::GlProgram program_;
  GLuint vao_ = 0;
};

}  // namespace geocean::ocean_render
