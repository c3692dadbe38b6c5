#include "plugin/bodies/Spawn.h"

#include "globe/geo/Ellipsoid.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <numbers>

namespace geocean::bodies {

BodyState restingUpright(const HullMesh& hull, double densityRatio, double latDeg, double lonDeg, double headingDeg) {
  const double rest = -hull.restingWaterlineZ(densityRatio);
  const geo::EnuFrame f = geo::enuFrame(geo::Geodetic{latDeg, lonDeg, rest});
  const double h = headingDeg * std::numbers::pi / 180.0;
  const glm::dvec3 x(std::sin(h), std::cos(h), 0.0), y(-std::cos(h), std::sin(h), 0.0), z(0, 0, 1);
  BodyState s;
  s.positionEcef = f.originEcef;
  s.orientation = glm::normalize(glm::quat_cast(glm::dmat3(f.toEcef(x), f.toEcef(y), f.toEcef(z))));
  return s;
}

}  // namespace geocean::bodies
