// A scripted flight from orbit to a few metres above the sea: the altitude
// falls geometrically (constant speed in log altitude, so it feels the same
// at every scale, with eased ends), the distance still to go along the
// ground track shrinks with the altitude (ending over the target), and the view tilts from straight down to just below the
// horizon in the last kilometres.
#pragma once

#include "globe/camera/Camera.h"

namespace geocean::render {

struct FlightPlan {
  double fromLatDeg = 0.0, fromLonDeg = 0.0, fromAltM = 2.0e7;
  double toLatDeg = 0.0, toLonDeg = 0.0, toAltM = 2.0;
  double headingDeg = 0.0;
  double finalPitchDeg = -8.0;
};

// Pose at progress s in [0, 1] (clamped); keeps fov/size from `base`.
camera::ViewPose flightPose(const FlightPlan& plan, double s, const camera::ViewPose& base);

}  // namespace geocean::render
