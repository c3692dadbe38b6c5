// Ray/ellipsoid intersection against the textbook closed form evaluated in
// long double (64-bit mantissa: 2^11 times finer than double).
#include "globe/geo/Ellipsoid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace geocean::geo;

namespace {
struct RefRoots {
  bool hit;
  long double t1, t2;
};

RefRoots reference(glm::dvec3 o, glm::dvec3 d) {
  const long double a = kWgs84A, b = (long double)kWgs84A * (1.0L - 1.0L / 298.257223563L);
  const long double ox = o.x / a, oy = o.y / a, oz = o.z / b;
  const long double dx = d.x / a, dy = d.y / a, dz = d.z / b;
  const long double A = dx * dx + dy * dy + dz * dz;
  const long double B = ox * dx + oy * dy + oz * dz;
  const long double C = ox * ox + oy * oy + oz * oz - 1.0L;
  const long double disc = B * B - A * C;
  if (disc < 0) return {false, 0, 0};
  const long double s = std::sqrt(disc);
  return {true, (-B - s) / A, (-B + s) / A};
}

// Height of an ECEF point above the ellipsoid, via GeographicLib (7 nm).
double heightOf(glm::dvec3 p) { return fromEcef(p).heightM; }
}  // namespace

TEST(RayEllipsoid, OneMetreAboveTheSeaHitsAtOneMetre) {
  for (double lat : {0.0, 45.0, 89.9, -60.0}) {
    for (double lon : {0.0, 179.999, -179.999, 33.3}) {
      const glm::dvec3 o = toEcef({lat, lon, 1.0});
      const RayHit h = intersectEllipsoid(o, -surfaceNormal(lat, lon));
      ASSERT_TRUE(h.hit);
      EXPECT_FALSE(h.originInside);
      EXPECT_NEAR(h.tNear, 1.0, 1e-6) << lat << "," << lon;  // GeographicLib's 7 nm + rounding
    }
  }
}

TEST(RayEllipsoid, RandomRaysMatchLongDoubleWithin1mm) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1), alt(1.0, 2e7);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 o = toEcef({90 * u(rng), 180 * u(rng), alt(rng)});
    glm::dvec3 d = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) - o / glm::length(o) * 0.9);
    const RayHit h = intersectEllipsoid(o, d);
    const RefRoots r = reference(o, d);
    if (!r.hit || r.t2 < 0) {
      EXPECT_FALSE(h.hit && r.t2 >= 0 && h.tNear > 0 && std::abs(heightOf(o + d * h.tNear)) > 1e-3);
      continue;
    }
    ++hits;
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.tNear, (double)r.t1, 1e-3);
    EXPECT_NEAR(h.tFar, (double)r.t2, 1e-3);
  }
  EXPECT_GT(hits, 1000);
}

TEST(RayEllipsoid, GrazingRaysStayWithin1mm) {
  // Rays tangent to a sphere slightly inside the ellipsoid at the clearance
  // below: the classic cancellation case (CesiumJS is off by 0.2 m here).
  for (double lat : {0.0, 30.0, 60.0, 85.0}) {
    for (double depth : {0.01, 1.0, 100.0, 1e4}) {
      const EnuFrame f = enuFrame({lat, 20.0, -depth});
      // Eye 3000 km back along the tangent line, looking north along it.
      const glm::dvec3 o = f.originEcef - f.north * 3e6;
      const RayHit h = intersectEllipsoid(o, f.north);
      const RefRoots r = reference(o, f.north);
      ASSERT_TRUE(r.hit);
      ASSERT_TRUE(h.hit);
      EXPECT_NEAR(h.tNear, (double)r.t1, 1e-3) << lat << " " << depth;
      EXPECT_NEAR(h.tFar, (double)r.t2, 1e-3) << lat << " " << depth;
      EXPECT_NEAR(heightOf(o + f.north * h.tNear), 0.0, 1e-3);
    }
  }
}

TEST(RayEllipsoid, OriginInsideGivesExitOnly) {
  const glm::dvec3 o = toEcef({10, 10, -5000});
  const glm::dvec3 d = surfaceNormal(10, 10);
  const RayHit h = intersectEllipsoid(o, d);
  ASSERT_TRUE(h.hit);
  EXPECT_TRUE(h.originInside);
  EXPECT_LT(h.tNear, 0);
  EXPECT_NEAR(h.tFirst(), 5000.0, 1e-6);
}

TEST(RayEllipsoid, MissesAndPointingAway) {
  const glm::dvec3 o = toEcef({0, 0, 1000});
  EXPECT_FALSE(intersectEllipsoid(o, surfaceNormal(0, 0)).hit);          // straight up
  EXPECT_FALSE(intersectEllipsoid(o, glm::dvec3(0, 0, 1) + surfaceNormal(0, 0) * 0.1).hit);
  EXPECT_FALSE(intersectEllipsoid(o, glm::dvec3(0)).hit);                 // degenerate direction
}

TEST(RayEllipsoid, InflatedEllipsoidAndHorizon) {
  const glm::dvec3 o = toEcef({0, 0, 100});
  const RayHit h = intersectEllipsoid(o, -surfaceNormal(0, 0), 10.0);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.tNear, 90.0, 1e-6);
  // A ray straight up misses; its horizon point lies on the surface and is
  // tangent: the eye-to-point line is perpendicular to the normal there.
  const glm::dvec3 eye = toEcef({20, 30, 5e5});
  const glm::dvec3 p = horizonPoint(eye, surfaceNormal(20, 30));
  const Geodetic g = fromEcef(p);
  EXPECT_NEAR(g.heightM, 0.0, 1e-3);
  EXPECT_NEAR(glm::dot(glm::normalize(p - eye), surfaceNormal(g.latDeg, g.lonDeg)), 0.0, 1e-6);
}
