// Normal gravity against GeographicLib's NormalGravity (the exact closed
// formula in ellipsoidal coordinates, Heiskanen & Moritz sec. 2-7) and the
// published WGS84 equatorial and polar values (NIMA TR8350.2 table 3.4).
#include "plugin/bodies/Gravity.h"

#include <GeographicLib/NormalGravity.hpp>
#include <gtest/gtest.h>

#include <cmath>

using geocean::bodies::normalGravity;

TEST(NormalGravity, PublishedEquatorAndPoleValues) {
  // TR8350.2 quotes 10 decimals; our formula reproduces them to rounding.
  EXPECT_NEAR(normalGravity(0.0, 0.0), 9.7803253359, 1e-10);
  EXPECT_NEAR(normalGravity(90.0, 0.0), 9.8321849378, 1e-10);
  EXPECT_NEAR(normalGravity(-90.0, 0.0), 9.8321849378, 1e-10);
}

TEST(NormalGravity, MatchesGeographicLibNormalGravity) {
  const auto& ref = GeographicLib::NormalGravity::WGS84();
  double worst = 0.0;
  for (double lat = -90.0; lat <= 90.0; lat += 7.5) {
    for (double h : {-100.0, 0.0, 10.0, 1000.0, 10000.0}) {
      double gy = 0.0, gz = 0.0;
      ref.Gravity(lat, h, gy, gz);
      const double magnitude = std::hypot(gy, gz);
      // TR8350.2's free-air series is second order in h but only first order
      // in the flattening in its h coefficient: against the exact formula it
      // is off by ~1.0e-10 m/s^2 per metre of height (measured: 1e-7 at 1 km,
      // 7e-7 at 10 km), 1e-9 of g over the +-100 m a floating body sees.
      const double tol = 1.2e-10 * std::abs(h) + 2e-10;
      EXPECT_NEAR(normalGravity(lat, h), magnitude, tol) << "lat " << lat << " h " << h;
      worst = std::max(worst, std::abs(normalGravity(lat, h) - magnitude) / tol);
      // Normal gravity leaves the ellipsoid normal by the plumb line's
      // curvature, ~8.3e-10 rad per metre of height (0.17" at 1 km), so
      // "along the ellipsoid normal" is right to 1e-7 rad at sea level +-100 m.
      EXPECT_LT(std::abs(gy), (8.5e-10 * std::abs(h) + 1e-15) * magnitude) << "lat " << lat << " h " << h;
    }
  }
  EXPECT_GT(worst, 0.1);  // the tolerance is not loose by orders of magnitude
}

TEST(NormalGravity, FreeAirGradientIsAbout3Point086e6) {
  // Textbook free-air gradient: 0.3086 mGal/m (3.086e-6 s^-2) at mid latitude.
  const double grad = (normalGravity(45.0, 0.0) - normalGravity(45.0, 100.0)) / 100.0;
  EXPECT_NEAR(grad, 3.086e-6, 0.005e-6);
}
