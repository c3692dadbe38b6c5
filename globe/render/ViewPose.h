// The renderer's view: a geodetic pose and a reversed-Z perspective. Kept
// private to globe/render until globe/camera lands; everything that reaches
// the GPU is relative to the eye (positions are eye-relative floats made in
// double), so the depth scheme and float precision hold from 20,000 km to 1 m.
#pragma once

#include "globe/geo/Ellipsoid.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace geocean::render {

struct ViewPose {
  double latDeg = 0.0, lonDeg = 0.0, altM = 1.0e7;  // eye, altitude above the ellipsoid
  double headingDeg = 0.0;  // 0 north, 90 east
  double pitchDeg = -90.0;  // 0 horizontal, -90 straight down
  double fovYDeg = 45.0;
  int width = 1280, height = 720;
};

struct ViewMatrices {
  glm::dvec3 eyeEcef{0.0};
  glm::dvec3 forward{0.0}, right{0.0}, up{0.0};  // ECEF unit vectors
  double nearM = 1.0;
  glm::mat4 view{1.0f};      // eye-relative ECEF -> view space (rotation only)
  glm::mat4 proj{1.0f};      // reversed-Z, infinite far, clip-control [0, 1]
  glm::mat4 viewProj{1.0f};  // proj * view
  glm::dmat4 viewProjD{1.0}; // the same in double, for CPU projection and culling
};

// Near plane from the altitude above the highest terrain we can meet: small
// enough to keep waves 1 m below the eye, large enough to spare float depth.
double nearPlaneM(double altAboveSurfaceM);

ViewMatrices viewMatrices(const ViewPose& pose, double altAboveSurfaceM);

// Screen pixel (x right, y down, pixel centres at +0.5) -> unit ray direction in ECEF.
glm::dvec3 pixelRay(const ViewMatrices& vm, const ViewPose& pose, double px, double py);

}  // namespace geocean::render
