#include "plugin/bodies/RigidBody.h"

#include "plugin/bodies/Validate.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace geocean::bodies {

using detail::fail;
using detail::requireFinite;
using detail::requireNonNegative;
using detail::requirePositive;

namespace {

glm::dmat3 diagonal(double a, double b, double c) {
  glm::dmat3 m(0.0);
  m[0][0] = a;
  m[1][1] = b;
  m[2][2] = c;
  return m;
}

glm::dmat3 axisymmetric(double iAxis, double iPerp, Axis axis) {
  switch (axis) {
    case Axis::X: return diagonal(iAxis, iPerp, iPerp);
    case Axis::Y: return diagonal(iPerp, iAxis, iPerp);
    case Axis::Z: break;
  }
  return diagonal(iPerp, iPerp, iAxis);
}

}  // namespace

MassProperties::MassProperties(double massKg, const glm::dmat3& inertiaBody) : mass_(massKg), inertia_(inertiaBody) {
  requirePositive("mass", massKg, "kg");
  double scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      const std::string field = "inertia[" + std::to_string(r) + "][" + std::to_string(c) + "]";
      requireFinite(field, inertiaBody[c][r], "kg m^2");
      scale = std::max(scale, std::abs(inertiaBody[c][r]));
    }
  }
  for (int c = 0; c < 3; ++c) {
    for (int r = c + 1; r < 3; ++r) {
      // Symmetric to rounding: 1e-12 of the largest entry.
      const double asym = inertiaBody[c][r] - inertiaBody[r][c];
      if (std::abs(asym) > 1e-12 * scale) {
        fail("inertia[" + std::to_string(r) + "][" + std::to_string(c) + "] - its transpose", asym, "kg m^2",
             "the inertia tensor must be symmetric");
      }
    }
  }
  // Sylvester's criterion: all leading principal minors > 0.
  const glm::dmat3& I = inertiaBody;
  const double m1 = I[0][0];
  const double m2 = I[0][0] * I[1][1] - I[1][0] * I[0][1];
  const double m3 = glm::determinant(I);
  if (!(m1 > 0.0)) fail("inertia leading minor 1", m1, "kg m^2", "the inertia tensor must be positive definite");
  if (!(m2 > 0.0)) fail("inertia leading minor 2", m2, "kg^2 m^4", "the inertia tensor must be positive definite");
  if (!(m3 > 0.0)) fail("inertia leading minor 3", m3, "kg^3 m^6", "the inertia tensor must be positive definite");
  inverseMass_ = 1.0 / massKg;
  inverseInertia_ = glm::inverse(inertiaBody);
}

MassProperties MassProperties::box(double massKg, const glm::dvec3& sizeM) {
  requirePositive("mass", massKg, "kg");
  requirePositive("box size.x", sizeM.x, "m");
  requirePositive("box size.y", sizeM.y, "m");
  requirePositive("box size.z", sizeM.z, "m");
  const glm::dvec3 s2 = sizeM * sizeM;
  const double k = massKg / 12.0;
  return {massKg, diagonal(k * (s2.y + s2.z), k * (s2.x + s2.z), k * (s2.x + s2.y))};
}

MassProperties MassProperties::solidCylinder(double massKg, double radiusM, double lengthM, Axis axis) {
  requirePositive("mass", massKg, "kg");
  requirePositive("cylinder radius", radiusM, "m");
  requirePositive("cylinder length", lengthM, "m");
  const double r2 = radiusM * radiusM;
  return {massKg, axisymmetric(massKg * r2 / 2.0, massKg * (3.0 * r2 + lengthM * lengthM) / 12.0, axis)};
}

MassProperties MassProperties::hollowCylinder(double massKg, double innerRadiusM, double outerRadiusM,
                                              double lengthM, Axis axis) {
  requirePositive("mass", massKg, "kg");
  requireNonNegative("hollow cylinder inner radius", innerRadiusM, "m");
  requirePositive("hollow cylinder outer radius", outerRadiusM, "m");
  requirePositive("hollow cylinder length", lengthM, "m");
  if (!(innerRadiusM < outerRadiusM)) {
    fail("hollow cylinder inner radius", innerRadiusM, "m", "must be < the outer radius");
  }
  const double s = innerRadiusM * innerRadiusM + outerRadiusM * outerRadiusM;
  return {massKg, axisymmetric(massKg * s / 2.0, massKg * (3.0 * s + lengthM * lengthM) / 12.0, axis)};
}

MassProperties MassProperties::isotropicFrom(const MassProperties& shape) {
  const glm::dmat3& I = shape.inertiaBody();
  const double iPe = (I[0][0] + I[1][1] + I[2][2]) / 3.0;
  return {shape.massKg(), diagonal(iPe, iPe, iPe)};
}

void validate(const BodyState& s) {
  requireFinite("position", s.positionEcef, "m");
  requireFinite("velocity", s.velocityEcef, "m/s");
  requireFinite("angular velocity", s.angularVelocityBody, "rad/s");
  const glm::dvec4 q(s.orientation.w, s.orientation.x, s.orientation.y, s.orientation.z);
  static constexpr const char* kName[4] = {"orientation.w", "orientation.x", "orientation.y", "orientation.z"};
  for (int i = 0; i < 4; ++i) requireFinite(kName[i], q[i], "");
  const double n = glm::length(q);
  if (!(std::abs(n - 1.0) <= 1e-9)) fail("orientation norm", n, "", "must be 1 (a unit quaternion)");
}

glm::dvec3 angularMomentumEcef(const BodyState& s, const MassProperties& m) {
  return s.orientation * (m.inertiaBody() * s.angularVelocityBody);
}

double rotationalEnergy(const BodyState& s, const MassProperties& m) {
  return 0.5 * glm::dot(s.angularVelocityBody, m.inertiaBody() * s.angularVelocityBody);
}

BodyState interpolate(const BodyState& a, const BodyState& b, double alpha) {
  requireFinite("interpolation alpha", alpha, "");
  BodyState r = b;
  r.positionEcef = a.positionEcef + (b.positionEcef - a.positionEcef) * alpha;
  r.orientation = glm::slerp(a.orientation, b.orientation, alpha);
  r.velocityEcef = glm::mix(a.velocityEcef, b.velocityEcef, alpha);
  r.angularVelocityBody = glm::mix(a.angularVelocityBody, b.angularVelocityBody, alpha);
  return r;
}

}  // namespace geocean::bodies
