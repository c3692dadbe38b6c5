// Shared set-up for the bodies tests.
#pragma once

#include "globe/geo/Ellipsoid.h"
#include "plugin/bodies/RigidBody.h"

namespace geocean::bodies::test {

// A state at a geodetic point with its velocity given in local east-north-up.
inline BodyState stateAt(const geo::Geodetic& p, const glm::dvec3& velocityEnu = glm::dvec3(0.0)) {
  BodyState s;
  const geo::EnuFrame f = geo::enuFrame(p);
  s.positionEcef = f.originEcef;
  s.velocityEcef = f.toEcef(velocityEnu);
  return s;
}

}  // namespace geocean::bodies::test
