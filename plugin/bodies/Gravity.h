// WGS84 normal gravity: the attraction of the reference ellipsoid plus the
// centrifugal acceleration of the Earth's rotation, along the ellipsoid normal.
#pragma once

namespace geocean::bodies {

// WGS84 constants (NIMA TR8350.2, 3rd ed., tables 3.1 and 3.4).
inline constexpr double kWgs84Gm = 3986004.418e8;          // m^3/s^2
inline constexpr double kWgs84Omega = 7292115.0e-11;       // rad/s
inline constexpr double kGammaEquator = 9.7803253359;      // m/s^2
inline constexpr double kGammaPole = 9.8321849378;         // m/s^2

// Magnitude of normal gravity (m/s^2) at geodetic latitude latDeg and height
// heightM above the ellipsoid: Somigliana's closed formula on the ellipsoid
// (TR8350.2 eq. 4-1) times the second-order free-air correction (eq. 4-3),
// which TR8350.2 gives for heights near the surface: against the exact
// ellipsoidal formula (GeographicLib::NormalGravity) it is off by ~1e-10
// m/s^2 per metre of height, 1e-9 of g within +-100 m (tests/bodies).
double normalGravity(double latDeg, double heightM);

}  // namespace geocean::bodies
