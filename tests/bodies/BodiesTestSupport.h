// Shared set-up for the bodies tests.
#pragma once

#include "globe/geo/Ellipsoid.h"
#include "plugin/bodies/RigidBody.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <numbers>

namespace geocean::bodies::test {

// A state at a geodetic point with its velocity given in local east-north-up.
inline BodyState stateAt(const geo::Geodetic& p, const glm::dvec3& velocityEnu = glm::dvec3(0.0)) {
  BodyState s;
  const geo::EnuFrame f = geo::enuFrame(p);
  s.positionEcef = f.originEcef;
  s.velocityEcef = f.toEcef(velocityEnu);
  return s;
}

// Body x east, y north, z up, then rotated by roll (about x), then pitch
// (about y) in the body (degrees): body -> ECEF.
inline glm::dquat orientationAt(const geo::Geodetic& p, double rollDeg = 0.0, double pitchDeg = 0.0) {
  const glm::dquat enu = glm::quat_cast(geo::enuFrame(p).rotation());
  const double d = std::numbers::pi / 180.0;
  const glm::dquat pitch = glm::angleAxis(pitchDeg * d, glm::dvec3(0, 1, 0));
  const glm::dquat roll = glm::angleAxis(rollDeg * d, glm::dvec3(1, 0, 0));
  return glm::normalize(enu * pitch * roll);
}

// Roll and pitch (degrees) of a body's axes relative to the local up.
inline double rollDeg(const BodyState& s, const geo::EnuFrame& f) {
  const glm::dvec3 y = f.toLocal(s.bodyToEcef({0, 1, 0})), z = f.toLocal(s.bodyToEcef({0, 0, 1}));
  return std::atan2(y.z, z.z) * 180.0 / std::numbers::pi;
}

}  // namespace geocean::bodies::test
