// WGS84 geodesy: the single place Geocean talks to GeographicLib.
// All angles in degrees, lengths in metres, everything in double.
#pragma once

#include <glm/vec3.hpp>
#include <glm/mat3x3.hpp>

namespace geocean::geo {

// WGS84 defining constants (NIMA TR8350.2).
inline constexpr double kWgs84A = 6378137.0;                  // semi-major axis, m
inline constexpr double kWgs84F = 1.0 / 298.257223563;        // flattening
inline constexpr double kWgs84B = kWgs84A * (1.0 - kWgs84F);  // semi-minor axis, m

struct Geodetic {
  double latDeg = 0.0;   // [-90, 90]
  double lonDeg = 0.0;   // any; normalised to [-180, 180) on output
  double heightM = 0.0;  // above the ellipsoid
};

// Local east-north-up frame at a geodetic point; columns are unit vectors in ECEF.
struct EnuFrame {
  glm::dvec3 originEcef{0.0};
  glm::dvec3 east{0.0}, north{0.0}, up{0.0};
  // ECEF direction -> ENU components, and back.
  glm::dvec3 toLocal(const glm::dvec3& ecefVector) const;
  glm::dvec3 toEcef(const glm::dvec3& enuVector) const;
  // 3x3 with columns east, north, up (local -> ECEF rotation).
  glm::dmat3 rotation() const;
};

// Geodetic -> ECEF. Accuracy: GeographicLib's Geocentric, exact to rounding.
glm::dvec3 toEcef(const Geodetic& p);
// ECEF -> geodetic. GeographicLib documents the error as bounded by 7 nm
// for points within ~5000 km of the surface.
Geodetic fromEcef(const glm::dvec3& ecef);

// Outward geodetic surface normal (the "up" of the ENU frame).
glm::dvec3 surfaceNormal(double latDeg, double lonDeg);
EnuFrame enuFrame(const Geodetic& p);

// Wrap a longitude into [-180, 180).
double wrapLonDeg(double lonDeg);

// Result of intersecting a ray with an ellipsoid of the WGS84 shape, inflated
// by `offsetM` along both axes (a + offset, b + offset). t is in units of the
// direction's length (metres for a unit direction).
struct RayHit {
  bool hit = false;           // the ray (t >= 0) meets the surface
  bool originInside = false;  // origin strictly inside the surface
  double tNear = 0.0;         // entry root (negative when the origin is inside)
  double tFar = 0.0;          // exit root
  // First intersection at t >= 0: tNear, or tFar from inside.
  double tFirst() const { return originInside ? tFar : tNear; }
};

// Double-precision ray/ellipsoid intersection. The discriminant uses
// Lagrange's identity (B^2 - AC = A - |o x d|_w^2) and the small root uses
// t = C / q, so there is no catastrophic cancellation for origins close to
// the surface or for grazing rays; see tests/geo/test_ray_ellipsoid.cpp.
RayHit intersectEllipsoid(const glm::dvec3& originEcef, const glm::dvec3& dir,
                          double offsetM = 0.0);

// The point on the horizon of an eye (outside the ellipsoid) closest in
// direction to `dir`: used for rays that miss so that grids have no holes.
glm::dvec3 horizonPoint(const glm::dvec3& eyeEcef, const glm::dvec3& dir, double offsetM = 0.0);

}  // namespace geocean::geo
