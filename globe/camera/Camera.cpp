#include "globe/camera/Camera.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geocean::camera {

namespace {
constexpr double kPi = 3.14159265358979323846;
double rad(double deg) { return deg * (kPi / 180.0); }

void checkFinite(double v, const char* field) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string("camera: ") + field + " is not finite");
}
void checkView(double vfovDeg, int w, int h) {
  checkFinite(vfovDeg, "vertical field of view");
  if (!(vfovDeg > 0.0 && vfovDeg < 180.0))
    throw std::invalid_argument("camera: vertical field of view " + std::to_string(vfovDeg) +
                                " deg is outside (0, 180)");
  if (w <= 0 || h <= 0)
    throw std::invalid_argument("camera: viewport " + std::to_string(w) + "x" + std::to_string(h) +
                                " must be positive");
}
// Distance from a point at height h to its horizon on a sphere of radius r.
double horizonDistance(double r, double h) { return std::sqrt(std::max(0.0, h * (2.0 * r + h))); }
}  // namespace

double nearPlaneM(double altAboveSurfaceM) { return std::clamp(0.1 * std::abs(altAboveSurfaceM), 0.01, 5.0e4); }

Camera Camera::fromGeodetic(ViewPose pose, double vfovDeg, int w, int h, double altAboveSurfaceM) {
  pose.fovYDeg = vfovDeg;
  pose.width = w;
  pose.height = h;
  return fromView(pose, altAboveSurfaceM);
}

Camera Camera::fromView(const ViewPose& p, double altAboveSurfaceM) {
  const double vfovDeg = p.fovYDeg;
  const int w = p.width, h = p.height;
  checkFinite(p.latDeg, "latitude");
  checkFinite(p.lonDeg, "longitude");
  checkFinite(p.altM, "height");
  checkFinite(p.headingDeg, "heading");
  checkFinite(p.pitchDeg, "pitch");
  checkFinite(p.rollDeg, "roll");
  if (std::abs(p.latDeg) > 90.0)
    throw std::invalid_argument("camera: latitude " + std::to_string(p.latDeg) + " is outside [-90, 90]");
  checkView(vfovDeg, w, h);
  const geo::EnuFrame f = geo::enuFrame({p.latDeg, p.lonDeg, p.altM});
  const double ch = std::cos(rad(p.headingDeg)), sh = std::sin(rad(p.headingDeg));
  const double cp = std::cos(rad(p.pitchDeg)), sp = std::sin(rad(p.pitchDeg));
  Camera c;
  c.eye_ = f.originEcef;
  c.forward_ = f.toEcef({cp * sh, cp * ch, sp});
  const glm::dvec3 right0 = f.toEcef({ch, -sh, 0.0});
  const glm::dvec3 up0 = glm::cross(right0, c.forward_);
  const double cr = std::cos(rad(p.rollDeg)), sr = std::sin(rad(p.rollDeg));
  c.right_ = cr * right0 - sr * up0;
  c.up_ = sr * right0 + cr * up0;
  c.vfovDeg_ = vfovDeg;
  c.width_ = w;
  c.height_ = h;
  c.heightM_ = p.altM;
  c.latDeg_ = p.latDeg;
  c.lonDeg_ = p.lonDeg;
  c.finish(altAboveSurfaceM);
  return c;
}

Camera Camera::fromEcef(const glm::dvec3& eye, const glm::dvec3& forward, const glm::dvec3& upHint,
                        double vfovDeg, int w, int h, double altAboveSurfaceM) {
  checkFinite(eye.x + eye.y + eye.z, "eye position");
  checkView(vfovDeg, w, h);
  Camera c;
  c.eye_ = eye;
  const double fl = glm::length(forward);
  if (!(fl > 0.0) || !std::isfinite(fl)) throw std::invalid_argument("camera: forward direction is zero or not finite");
  c.forward_ = forward / fl;
  glm::dvec3 r = glm::cross(c.forward_, upHint);
  const double rl = glm::length(r);
  if (!(rl > 1e-12)) throw std::invalid_argument("camera: up hint is parallel to the forward direction");
  c.right_ = r / rl;
  c.up_ = glm::cross(c.right_, c.forward_);
  c.lensAtEye(vfovDeg, w, h);
  c.finish(altAboveSurfaceM);
  return c;
}

void Camera::lensAtEye(double vfovDeg, int w, int h) {
  vfovDeg_ = vfovDeg;
  width_ = w;
  height_ = h;
  const geo::Geodetic g = geo::fromEcef(eye_);
  heightM_ = g.heightM;
  latDeg_ = g.latDeg;
  lonDeg_ = g.lonDeg;
}

Camera Camera::fromHost(const glm::dvec3& eye, const glm::dvec3& forward, const glm::dvec3& right,
                        const glm::dvec3& up, const glm::dmat4& proj, int w, int h) {
  const double vfov = 2.0 * std::atan(1.0 / proj[1][1]) * 180.0 / kPi;
  checkFinite(eye.x + eye.y + eye.z, "eye position");
  checkView(vfov, w, h);
  Camera c;
  c.eye_ = eye;
  c.forward_ = forward;
  c.right_ = right;
  c.up_ = up;
  c.lensAtEye(vfov, w, h);
  c.finish(std::numeric_limits<double>::quiet_NaN());
  c.nearM_ = proj[3][2] != 0.0 ? std::abs(proj[3][2]) : 1.0;
  c.setGpu(proj);
  return c;
}

void Camera::finish(double altAboveSurfaceM) {
  tanY_ = std::tan(rad(vfovDeg_) * 0.5);
  const double h = std::max(heightM_, 0.0);
  nearM_ = nearPlaneM(std::isnan(altAboveSurfaceM) ? h : altAboveSurfaceM);
  // Horizon of the sea plus the horizon of the highest terrain (9 km), with
  // a 1 % margin; at least 10 km so an eye near the surface sees to its horizon.
  farM_ = std::max(1e4, 1.01 * (horizonDistance(geo::kWgs84A, h) + horizonDistance(geo::kWgs84A, 9000.0)));
  // The renderers' projection, in double.
  const double f = 1.0 / std::tan(0.5 * vfovDeg_ * (kPi / 180.0));
  const double aspect = double(width_) / double(height_);
  glm::dmat4 proj(0.0);
  proj[0][0] = f / aspect;
  proj[1][1] = f;
  proj[2][3] = -1.0;    // w = -z_view
  proj[3][2] = nearM_;  // z = near  ->  depth = near / -z_view: 1 at near, 0 at infinity
  setGpu(proj);
}

void Camera::setGpu(const glm::dmat4& proj) {
  glm::dmat4 view(1.0);
  for (int i = 0; i < 3; ++i) {
    view[i][0] = right_[i];
    view[i][1] = up_[i];
    view[i][2] = -forward_[i];
  }
  gpu_.view = glm::mat4(view);
  gpu_.proj = glm::mat4(proj);
  gpu_.projD = proj;
  gpu_.viewProjD = proj * view;
  gpu_.viewProj = glm::mat4(gpu_.viewProjD);
}

glm::dvec3 Camera::pixelRay(double x, double y) const {
  const glm::dvec2 n = pixelToNdc(x, y);
  return glm::normalize(rayThroughNdc(n.x, n.y));
}

std::optional<glm::dvec2> Camera::projectEyeRelative(const glm::dvec3& rel) const {
  const double z = glm::dot(rel, forward_);
  if (!(z > 0.0)) return std::nullopt;
  return glm::dvec2(glm::dot(rel, right_) / (z * tanHalfX()), glm::dot(rel, up_) / (z * tanHalfY()));
}

std::optional<glm::dvec2> Camera::projectToNdc(const glm::dvec3& ecef) const {
  return projectEyeRelative(ecef - eye_);
}

glm::mat4 Camera::viewRotation() const {
  // Rows: right, up, -forward (eye looks down -Z).
  glm::dmat4 v(1.0);
  for (int i = 0; i < 3; ++i) {
    v[i][0] = right_[i];
    v[i][1] = up_[i];
    v[i][2] = -forward_[i];
  }
  return glm::mat4(v);
}

glm::mat4 Camera::projectionReversedZ() const {
  const double n = nearM_, f = farM_;
  glm::dmat4 p(0.0);
  p[0][0] = 1.0 / tanHalfX();
  p[1][1] = 1.0 / tanHalfY();
  // z_clip = n f / (f - n) + z_eye n / (f - n) ... with w_clip = -z_eye:
  // depth = z_clip / w_clip is 1 at z_eye = -n and 0 at z_eye = -f.
  p[2][2] = n / (f - n);
  p[3][2] = f * n / (f - n);
  p[2][3] = -1.0;
  return glm::mat4(p);
}

}  // namespace geocean::camera
