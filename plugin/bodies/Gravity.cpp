#include "plugin/bodies/Gravity.h"

#include "globe/geo/Ellipsoid.h"

#include <cmath>
#include <numbers>

namespace geocean::bodies {

namespace {
constexpr double kA = geo::kWgs84A, kB = geo::kWgs84B, kF = geo::kWgs84F;
constexpr double kE2 = kF * (2.0 - kF);
// Somigliana's constant k = b gamma_p / (a gamma_e) - 1.
constexpr double kSomigliana = kB * kGammaPole / (kA * kGammaEquator) - 1.0;
// m = omega^2 a^2 b / GM.
constexpr double kM = kWgs84Omega * kWgs84Omega * kA * kA * kB / kWgs84Gm;
}  // namespace

double normalGravity(double latDeg, double heightM) {
  const double s = std::sin(latDeg * (std::numbers::pi / 180.0));
  const double s2 = s * s;
  const double surface = kGammaEquator * (1.0 + kSomigliana * s2) / std::sqrt(1.0 - kE2 * s2);
  const double h = heightM;
  return surface * (1.0 - 2.0 / kA * (1.0 + kF + kM - 2.0 * kF * s2) * h + 3.0 / (kA * kA) * h * h);
}

}  // namespace geocean::bodies
