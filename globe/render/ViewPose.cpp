#include "globe/render/ViewPose.h"

#include <algorithm>
#include <cmath>

namespace geocean::render {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

double nearPlaneM(double altAboveSurfaceM) {
  // Reversed Z with a float buffer keeps ~24 bits of relative precision at
  // every distance, so the near plane only has to stay in front of the
  // nearest geometry: 1/4 of the height above the sea, within [2 cm, 50 km].
  return std::clamp(0.25 * std::abs(altAboveSurfaceM), 0.02, 5.0e4);
}

ViewMatrices viewMatrices(const ViewPose& pose, double altAboveSurfaceM) {
  ViewMatrices vm;
  const geo::EnuFrame enu = geo::enuFrame({pose.latDeg, pose.lonDeg, pose.altM});
  vm.eyeEcef = enu.originEcef;
  const double h = pose.headingDeg * kDeg, p = pose.pitchDeg * kDeg;
  vm.forward = enu.toEcef({std::cos(p) * std::sin(h), std::cos(p) * std::cos(h), std::sin(p)});
  vm.right = enu.toEcef({std::cos(h), -std::sin(h), 0.0});
  vm.up = glm::cross(vm.right, vm.forward);
  vm.nearM = nearPlaneM(altAboveSurfaceM);

  glm::dmat4 view(1.0);
  for (int c = 0; c < 3; ++c) {
    view[c][0] = vm.right[c];
    view[c][1] = vm.up[c];
    view[c][2] = -vm.forward[c];
  }
  const double f = 1.0 / std::tan(0.5 * pose.fovYDeg * kDeg);
  const double aspect = double(pose.width) / double(pose.height);
  glm::dmat4 proj(0.0);
  proj[0][0] = f / aspect;
  proj[1][1] = f;
  proj[2][3] = -1.0;       // w = -z_view
  proj[3][2] = vm.nearM;   // z = near  ->  depth = near / -z_view: 1 at near, 0 at infinity
  vm.view = glm::mat4(view);
  vm.proj = glm::mat4(proj);
  vm.viewProjD = proj * view;
  vm.viewProj = glm::mat4(vm.viewProjD);
  return vm;
}

glm::dvec3 pixelRay(const ViewMatrices& vm, const ViewPose& pose, double px, double py) {
  const double f = std::tan(0.5 * pose.fovYDeg * kDeg);
  const double aspect = double(pose.width) / double(pose.height);
  const double nx = (2.0 * px / pose.width - 1.0) * f * aspect;
  const double ny = (1.0 - 2.0 * py / pose.height) * f;
  return glm::normalize(vm.forward + nx * vm.right + ny * vm.up);
}

}  // namespace geocean::render
