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

camera::ViewPose flightPose(const FlightPlan& plan, double s, const camera::ViewPose& base) {
  s = std::clamp(s, 0.0, 1.0);
  camera::ViewPose p = base;
  // Altitude: log-linear with eased ends.
  const double la = std::log(plan.fromAltM), lb = std::log(plan.toAltM);
  p.altM = std::exp(la + (lb - la) * smooth(s));
  // Ground track: along the great circle, the angle still to go shrinks with
  // the altitude, r = omega f(alt) / f(alt0) with f(h) = h / (h + k): the
  // whole distance at the start, about the altitude itself near the end, so
  // the last kilometres are flown over the target, not over whatever lies
  // 50 km before it (the Strait's approach crossed Cadiz province there).
  // Horizontal speed is proportional to altitude, as in Google Earth.
  const glm::dvec3 a = geo::surfaceNormal(plan.fromLatDeg, plan.fromLonDeg);
  const glm::dvec3 b = geo::surfaceNormal(plan.toLatDeg, plan.toLonDeg);
  const double omega = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  const double k = std::max(2.0 * omega * geo::kWgs84A, 1.0);
  const auto f = [k](double h) { return h / (h + k); };
  const double rest = omega * f(p.altM) / f(plan.fromAltM);
  glm::dvec3 dir = b;
  if (omega > 1e-12)
    dir = (std::sin(rest) * a + std::sin(omega - rest) * b) / std::sin(omega);
  // dir is a surface normal: its geodetic latitude is asin(z) (not the
  // geocentric one of the point a * dir).
  dir = glm::normalize(dir);
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  p.latDeg = s < 1.0 ? std::asin(std::clamp(dir.z, -1.0, 1.0)) * kRadToDeg : plan.toLatDeg;
  p.lonDeg = s < 1.0 ? std::atan2(dir.y, dir.x) * kRadToDeg : plan.toLonDeg;
  // Tilt towards the horizon below 20 km, fully tilted at the end.
  const double tilt = smooth((std::log(2.0e4) - std::log(p.altM)) / (std::log(2.0e4) - lb));
  p.pitchDeg = -90.0 + (90.0 + plan.finalPitchDeg) * tilt;
  p.headingDeg = plan.headingDeg;
  return p;
}

}  // namespace geocean::render
