// Where a body starts: upright, at rest, floating at its still-water draft.
// One function for `geocean float`, the C ABI and the viewer's boats, so
// they start the same bodies from the same numbers.
#pragma once

#include "plugin/bodies/Hull.h"
#include "plugin/bodies/RigidBody.h"

namespace geocean::bodies {

// The hull upright at (lat, lon), its centre of mass -restingWaterlineZ
// above the ellipsoid (the still-water draft of a body of densityRatio =
// rho_body / rho_water), bow towards headingDeg (clockwise from north), at rest.
BodyState restingUpright(const HullMesh& hull, double densityRatio, double latDeg, double lonDeg, double headingDeg);

}  // namespace geocean::bodies
