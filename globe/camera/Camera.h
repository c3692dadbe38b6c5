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

#include <limits>
#include <optional>

namespace geocean::camera {

// The pose applications edit (flights, the CLI, the viewer, tests): the
// eye, where it looks, and the lens. Camera::fromView turns it into the one
// camera. heading: clockwise from north; pitch: 0 is level, -90 looks
// straight down; roll: clockwise about the view direction.
struct ViewPose {
  double latDeg = 0.0, lonDeg = 0.0, altM = 1.0e7;  // eye, altitude above the ellipsoid
  double headingDeg = 0.0;  // 0 north, 90 east
  double pitchDeg = -90.0;  // 0 horizontal, -90 straight down
  double rollDeg = 0.0;
  double fovYDeg = 45.0;
  int width = 1280, height = 720;
};

// The near plane for an eye this high above the nearest surface under it:
// 1/10 of it, within [1 cm, 50 km]. Small enough that a camera 1 m above
// the sea still sees waves 10 cm away; reversed Z with float depth keeps
// ~24 bits of relative precision at every distance, so nothing needs it
// pushed further out.
double nearPlaneM(double altAboveSurfaceM);

// The GPU's matrices for eye-relative positions (rotation-only view,
// reversed-Z projection with an infinite far plane, clip control [0, 1]).
struct GpuMatrices {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::mat4 viewProj{1.0f};   // proj * view
  glm::dmat4 projD{1.0};      // the projection in double (what the ABI passes)
  glm::dmat4 viewProjD{1.0};  // proj * view in double, for CPU projection and culling
};

// Sunlight and the clock of a frame.
struct Lighting {
  glm::dvec3 sunEcef{1.0, 0.0, 0.0};  // unit vector towards the sun
  double timeS = 0.0;
};

class Camera {
 public:
  // Throws std::invalid_argument naming the field for a non-finite pose, a
  // field of view outside (0, 180) degrees or a non-positive viewport.
  // altAboveSurfaceM: the eye's height above the terrain or sea under it,
  // for the near plane (NaN: the height above the ellipsoid).
  static Camera fromView(const ViewPose& pose, double altAboveSurfaceM = std::numeric_limits<double>::quiet_NaN());
  // The same with the lens given apart (the pose's fov and size ignored).
  static Camera fromGeodetic(ViewPose pose, double vfovDeg, int widthPx, int heightPx,
                             double altAboveSurfaceM = std::numeric_limits<double>::quiet_NaN());
  // forward and upHint need not be unit length; upHint must not be parallel to forward.
  static Camera fromEcef(const glm::dvec3& eyeEcef, const glm::dvec3& forward, const glm::dvec3& upHint,
                         double vfovDeg, int widthPx, int heightPx,
                         double altAboveSurfaceM = std::numeric_limits<double>::quiet_NaN());

  // A host engine's camera taken as it is: its orthonormal basis and its
  // reversed-Z projection (w = -z; near = proj[3][2]; vertical fov from
  // proj[1][1]), so a plugin draws with exactly the host's matrices.
  static Camera fromHost(const glm::dvec3& eyeEcef, const glm::dvec3& forward, const glm::dvec3& right,
                         const glm::dvec3& up, const glm::dmat4& projection, int widthPx, int heightPx);

  const glm::dvec3& eyeEcef() const { return eye_; }
  const glm::dvec3& forward() const { return forward_; }  // unit, ECEF
  const glm::dvec3& right() const { return right_; }      // unit, ECEF
  const glm::dvec3& up() const { return up_; }            // unit, ECEF (screen up)
  double heightM() const { return heightM_; }             // eye height above the ellipsoid
  double latDeg() const { return latDeg_; }               // eye, geodetic
  double lonDeg() const { return lonDeg_; }
  double vfovDeg() const { return vfovDeg_; }
  int widthPx() const { return width_; }
  int heightPx() const { return height_; }
  double aspect() const { return double(width_) / double(height_); }
  // tan(vfov/2) * aspect and tan(vfov/2): NDC (1, 1) maps to forward + tanX*right + tanY*up.
  double tanHalfX() const { return tanY_ * aspect(); }
  double tanHalfY() const { return tanY_; }

  // Clip planes from altitude: near by nearPlaneM (from the height above the
  // surface when given, else above the ellipsoid); far reaches the horizon
  // of the ellipsoid plus the horizon of a 9 km mountain (ISPG's reach and
  // projectionReversedZ; the renderers' projection has no far plane).
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
  // What the renderers, the host and the plugin ABI draw with: reversed Z,
  // infinite far plane, near = nearM() (depth = near / distance).
  const GpuMatrices& gpu() const { return gpu_; }

 private:
  void finish(double altAboveSurfaceM);
  void lensAtEye(double vfovDeg, int widthPx, int heightPx);  // and the eye's geodetic position
  void setGpu(const glm::dmat4& projection);                  // the view from the basis
  glm::dvec3 eye_{0.0}, forward_{0.0}, right_{0.0}, up_{0.0};
  double heightM_ = 0.0, latDeg_ = 0.0, lonDeg_ = 0.0, vfovDeg_ = 60.0, tanY_ = 0.0, nearM_ = 0.0, farM_ = 0.0;
  GpuMatrices gpu_;
  int width_ = 1, height_ = 1;
};

}  // namespace geocean::camera
