// Geodesy against independent references: PROJ's cs2cs for geodetic->ECEF,
// GeographicLib's CartConvert tool for local east-north-up coordinates.
#include "globe/geo/Ellipsoid.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

using namespace geocean::geo;
using geocean::test::haveTool;
using geocean::test::run;

namespace {
const std::vector<Geodetic> kPoints = {
    {0, 0, 0},          {90, 0, 0},           {-90, 0, 0},          {90, 137, 1234.5},
    {0, 180, 0},        {0, -180, 0},         {12.5, 179.9999999, 10}, {-33.9, 151.5, -420},
    {51.4779, -0.0015, 46}, {89.999, -179.5, 8848}, {-89.9999, 45, -10}, {36.1, -5.35, 2e7},
    {-45.123456789, -179.999999, 35786e3},
};
}  // namespace

TEST(Ellipsoid, EcefMatchesProjCs2csWithin1mm) {
  if (!haveTool("cs2cs")) GTEST_SKIP() << "cs2cs (Debian proj-bin) not installed";
  std::ostringstream in;
  in.precision(17);
  for (const auto& p : kPoints) in << p.lonDeg << ' ' << p.latDeg << ' ' << p.heightM << '\n';
  auto r = run("cs2cs -f %.6f +proj=longlat +datum=WGS84 +to +proj=geocent +datum=WGS84", in.str());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::istringstream out(r.out);
  for (const auto& p : kPoints) {
    glm::dvec3 ref;
    ASSERT_TRUE(out >> ref.x >> ref.y >> ref.z);
    const glm::dvec3 ours = toEcef(p);
    // Tolerance: the 1 mm; cs2cs prints to 1 um.
    EXPECT_NEAR(ours.x, ref.x, 1e-3) << p.latDeg << "," << p.lonDeg;
    EXPECT_NEAR(ours.y, ref.y, 1e-3) << p.latDeg << "," << p.lonDeg;
    EXPECT_NEAR(ours.z, ref.z, 1e-3) << p.latDeg << "," << p.lonDeg;
  }
}

TEST(Ellipsoid, RoundTripIsExactToNanometres) {
  for (const auto& p : kPoints) {
    const Geodetic g = fromEcef(toEcef(p));
    // GeographicLib bounds Reverse's error by 7 nm: well under 1e-9 degrees.
    EXPECT_NEAR(g.latDeg, p.latDeg, 1e-9);
    if (std::abs(p.latDeg) < 89.9999) {
      EXPECT_NEAR(std::remainder(g.lonDeg - p.lonDeg, 360.0), 0.0, 1e-9);
    }
    EXPECT_NEAR(g.heightM, p.heightM, 1e-6);
    EXPECT_GE(g.lonDeg, -180.0);
    EXPECT_LT(g.lonDeg, 180.0);
  }
}

TEST(Ellipsoid, EnuMatchesCartConvert) {
  if (!haveTool("CartConvert")) GTEST_SKIP() << "CartConvert (Debian geographiclib-tools) not installed";
  const Geodetic origin{47.7, -87.5, 183};
  const std::vector<Geodetic> pts = {{47.71, -87.49, 200}, {47.5, -87.9, 0}, {48.7, -86.0, 5000}};
  std::ostringstream in;
  in.precision(17);
  for (const auto& p : pts) in << p.latDeg << ' ' << p.lonDeg << ' ' << p.heightM << '\n';
  auto r = run("CartConvert -p 9 -l 47.7 -87.5 183", in.str());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::istringstream out(r.out);
  const EnuFrame f = enuFrame(origin);
  for (const auto& p : pts) {
    glm::dvec3 ref;
    ASSERT_TRUE(out >> ref.x >> ref.y >> ref.z);
    const glm::dvec3 ours = f.toLocal(toEcef(p) - f.originEcef);
    EXPECT_NEAR(glm::length(ours - ref), 0.0, 1e-6);  // both are exact to rounding
  }
}

TEST(Ellipsoid, NormalIsGradientDirection) {
  // The geodetic normal is parallel to the gradient (x/a^2, y/a^2, z/b^2).
  for (const auto& p : kPoints) {
    const glm::dvec3 e = toEcef({p.latDeg, p.lonDeg, 0});
    const glm::dvec3 g = glm::normalize(glm::dvec3(e.x / (kWgs84A * kWgs84A), e.y / (kWgs84A * kWgs84A),
                                                   e.z / (kWgs84B * kWgs84B)));
    EXPECT_NEAR(glm::length(g - surfaceNormal(p.latDeg, p.lonDeg)), 0.0, 1e-12);
    const EnuFrame f = enuFrame(p);
    EXPECT_NEAR(glm::dot(f.east, f.north), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(glm::cross(f.east, f.north) - f.up), 0.0, 1e-15);
  }
}

TEST(Ellipsoid, WrapLongitude) {
  EXPECT_EQ(wrapLonDeg(180.0), -180.0);
  EXPECT_EQ(wrapLonDeg(-180.0), -180.0);
  EXPECT_DOUBLE_EQ(wrapLonDeg(190.0), -170.0);
  EXPECT_DOUBLE_EQ(wrapLonDeg(-190.0), 170.0);
  EXPECT_DOUBLE_EQ(wrapLonDeg(720.5), 0.5);
}
