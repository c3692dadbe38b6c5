// A perspective camera on the WGS84 globe, in double precision.
//
// The pose lives in ECEF metres (double). Nothing absolute ever reaches the
// GPU: the view matrix is a pure rotation about the eye and every position
// sent to a shader is relative to the eye (computed in double, then rounded
// to float), so precision does not depend on where on Earth the camera is.
// Thread-safety: a Camera is an immutable value; all members are const.
#pragma once

#include "globe/geo/Ellipsoid.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace geocean::camera {

// Geodetic pose. heading: clockwise from north; pitch: 0 is level, -90 looks
// straight down; roll: clockwise about the view direction.
struct GeodeticPose {
  double latDeg = 0.0;
  double lonDeg = 0.0;
  double heightM = 1000.0;  // eye height above the ellipsoid
  double headingDeg = 0.0;
  double pitchDeg = -90.0;
  double rollDeg = 0.0;
};

class Camera {
 public:
  // Throws std::invalid_argument naming the field for a non-finite pose, a
  // field of view outside (0, 180) degrees or a non-positive viewport.
  static Camera fromGeodetic(const GeodeticPose& pose, double vfovDeg, int widthPx, int heightPx);
  // forward and upHint need not be unit length; upHint must not be parallel to forward.
  static Camera fromEcef(const glm::dvec3& eyeEcef, const glm::dvec3& forward, const glm::dvec3& upHint,
                         double vfovDeg, int widthPx, int heightPx);

  const glm::dvec3& eyeEcef() const { return eye_; }
  const glm::dvec3& forward() const { return forward_; }  // unit, ECEF
  const glm::dvec3& right() const { return right_; }      // unit, ECEF
  const glm::dvec3& up() const { return up_; }            // unit, ECEF (screen up)
  double heightM() const { return heightM_; }             // eye height above the ellipsoid
  double vfovDeg() const { return vfovDeg_; }
  int widthPx() const { return width_; }
  int heightPx() const { return height_; }
  double aspect() const { return double(width_) / double(height_); }
  // tan(vfov/2) * aspect and tan(vfov/2): NDC (1, 1) maps to forward + tanX*right + tanY*up.
  double tanHalfX() const { return tanY_ * aspect(); }
  double tanHalfY() const { return tanY_; }

  // Clip planes from altitude: near is 1/10 of the eye height (at least 1 cm,
  // so a camera 1 m above the sea still sees waves 10 cm away); far reaches
  // the horizon of the ellipsoid plus the horizon of a 9 km mountain.
  double nearM() const { return nearM_; }
  double farM() const { return farM_; }

  // Unnormalised ray direction through NDC (x right, y up, both in [-1, 1]
  // on screen; values outside are allowed): forward + x tanX right + y tanY up.
  glm::dvec3 rayThroughNdc(double ndcX, double ndcY) const {
    return forward_ + (ndcX * tanHalfX()) * right_ + (ndcY * tanHalfY()) * up_;
  }
  // Unit ray direction through a pixel position: (0, 0) is the top-left corner
  // of the top-left pixel, (x + 0.5, y + 0.5) the centre of pixel (x, y).
  glm::dvec3 pixelRay(double pxX, double pxY) const;
  glm::dvec2 pixelToNdc(double pxX, double pxY) const {
    return {2.0 * pxX / width_ - 1.0, 1.0 - 2.0 * pxY / height_};
  }
  // NDC of an ECEF point; nullopt when the point is not in front of the eye.
  std::optional<glm::dvec2> projectToNdc(const glm::dvec3& ecef) const;
  // Same for a point given relative to the eye (no cancellation).
  std::optional<glm::dvec2> projectEyeRelative(const glm::dvec3& rel) const;

  // GPU matrices (OpenGL, right-handed eye space looking down -Z). The view
  // is a rotation only: apply it to eye-relative positions.
  glm::mat4 viewRotation() const;
  // Reversed-Z projection for glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE):
  // depth 1 at near, 0 at far; float depth keeps relative precision all the way.
  glm::mat4 projectionReversedZ() const;

 private:
  void finish();
  glm::dvec3 eye_{0.0}, forward_{0.0}, right_{0.0}, up_{0.0};
  double heightM_ = 0.0, vfovDeg_ = 60.0, tanY_ = 0.0, nearM_ = 0.0, farM_ = 0.0;
  int width_ = 1, height_ = 1;
};

}  // namespace geocean::camera
