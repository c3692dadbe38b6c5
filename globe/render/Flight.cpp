#include "globe/render/Flight.h"

#include <algorithm>
#include <cmath>

namespace geocean::render {

namespace {
double smooth(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
}  // namespace

ViewPose flightPose(const FlightPlan& plan, double s, const ViewPose& base) {
  s = std::clamp(s, 0.0, 1.0);
  ViewPose p = base;
  // Ground track: a great circle between the two surface normals, done by s = 0.6.
  const glm::dvec3 a = geo::surfaceNormal(plan.fromLatDeg, plan.fromLonDeg);
  const glm::dvec3 b = geo::surfaceNormal(plan.toLatDeg, plan.toLonDeg);
  const double omega = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  const double track = smooth(s / 0.6);
  glm::dvec3 dir = b;
  if (omega > 1e-12 && track < 1.0)
    dir = (std::sin((1.0 - track) * omega) * a + std::sin(track * omega) * b) / std::sin(omega);
  const geo::Geodetic g = geo::fromEcef(glm::normalize(dir) * geo::kWgs84A);
  p.latDeg = track < 1.0 ? g.latDeg : plan.toLatDeg;
  p.lonDeg = track < 1.0 ? g.lonDeg : plan.toLonDeg;
  // Altitude: log-linear with eased ends.
  const double la = std::log(plan.fromAltM), lb = std::log(plan.toAltM);
  p.altM = std::exp(la + (lb - la) * smooth(s));
  // Tilt towards the horizon below 20 km, fully tilted at the end.
  const double tilt = smooth((std::log(2.0e4) - std::log(p.altM)) / (std::log(2.0e4) - lb));
  p.pitchDeg = -90.0 + (90.0 + plan.finalPitchDeg) * tilt;
  p.headingDeg = plan.headingDeg;
  return p;
}

}  // namespace geocean::render
