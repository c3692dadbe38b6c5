#include "globe/geo/Ellipsoid.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Math.hpp>

#include <cmath>

namespace geocean::geo {

namespace {
const GeographicLib::Geocentric& wgs84() { return GeographicLib::Geocentric::WGS84(); }

// a*b - c*d with one rounding error (Kahan's algorithm with FMA).
double diffOfProducts(double a, double b, double c, double d) {
  const double cd = c * d;
  const double err = std::fma(-c, d, cd);
  const double dop = std::fma(a, b, -cd);
  return dop + err;
}
}  // namespace

glm::dvec3 EnuFrame::toLocal(const glm::dvec3& v) const {
  return {glm::dot(v, east), glm::dot(v, north), glm::dot(v, up)};
}
glm::dvec3 EnuFrame::toEcef(const glm::dvec3& v) const { return east * v.x + north * v.y + up * v.z; }
glm::dmat3 EnuFrame::rotation() const { return glm::dmat3(east, north, up); }

double wrapLonDeg(double lonDeg) {
  double r = std::remainder(lonDeg, 360.0);  // exact, in [-180, 180]
  if (r >= 180.0) r -= 360.0;
  return r;
}

glm::dvec3 toEcef(const Geodetic& p) {
  glm::dvec3 r;
  wgs84().Forward(p.latDeg, p.lonDeg, p.heightM, r.x, r.y, r.z);
  return r;
}

Geodetic fromEcef(const glm::dvec3& e) {
  Geodetic g;
  wgs84().Reverse(e.x, e.y, e.z, g.latDeg, g.lonDeg, g.heightM);
  g.lonDeg = wrapLonDeg(g.lonDeg);
  return g;
}

glm::dvec3 surfaceNormal(double latDeg, double lonDeg) {
  double sphi, cphi, slam, clam;
  GeographicLib::Math::sincosd(latDeg, sphi, cphi);
  GeographicLib::Math::sincosd(lonDeg, slam, clam);
  return {cphi * clam, cphi * slam, sphi};
}

EnuFrame enuFrame(const Geodetic& p) {
  double sphi, cphi, slam, clam;
  GeographicLib::Math::sincosd(p.latDeg, sphi, cphi);
  GeographicLib::Math::sincosd(p.lonDeg, slam, clam);
  EnuFrame f;
  f.originEcef = toEcef(p);
  f.east = {-slam, clam, 0.0};
  f.north = {-sphi * clam, -sphi * slam, cphi};
  f.up = {cphi * clam, cphi * slam, sphi};
  return f;
}

RayHit intersectEllipsoid(const glm::dvec3& o, const glm::dvec3& d, double offsetM) {
  const double a = kWgs84A + offsetM, b = kWgs84B + offsetM;
  const double wa = 1.0 / (a * a), wb = 1.0 / (b * b);
  // Quadratic A t^2 + 2 B t + C = 0 in the metric diag(wa, wa, wb).
  const double A = wa * (d.x * d.x + d.y * d.y) + wb * d.z * d.z;
  const double B = wa * (o.x * d.x + o.y * d.y) + wb * o.z * d.z;
  // C = |o|_w^2 - 1, evaluated as sum of (o_i/a_i - 1)(o_i/a_i + 1)-free form:
  // scale first so the subtraction of 1 happens on O(1) numbers.
  const double sx = o.x / a, sy = o.y / a, sz = o.z / b;
  const double C = std::fma(sx, sx, std::fma(sy, sy, std::fma(sz, sz, -1.0)));
  // Lagrange: B^2 - A C = A - |o x d|_w^2, with each cross term from diffOfProducts.
  const double cxy = diffOfProducts(o.x, d.y, o.y, d.x);
  const double cxz = diffOfProducts(o.x, d.z, o.z, d.x);
  const double cyz = diffOfProducts(o.y, d.z, o.z, d.y);
  const double cross2 = wa * wa * cxy * cxy + wa * wb * (cxz * cxz + cyz * cyz);
  const double disc = A - cross2;

  RayHit h;
  h.originInside = C < 0.0;
  if (!(A > 0.0) || disc < 0.0) return h;
  const double s = std::sqrt(disc);
  const double q = -(B + std::copysign(s, B));
  double t1 = q / A;
  double t2 = (q != 0.0) ? C / q : -B / A;
  if (t1 > t2) std::swap(t1, t2);
  h.tNear = t1;
  h.tFar = t2;
  h.hit = t2 >= 0.0;
  return h;
}

glm::dvec3 horizonPoint(const glm::dvec3& eye, const glm::dvec3& dir, double offsetM) {
  const double a = kWgs84A + offsetM, b = kWgs84B + offsetM;
  const glm::dvec3 scale{1.0 / a, 1.0 / a, 1.0 / b};
  const glm::dvec3 e = eye * scale, dv = dir * scale;
  const double r = glm::length(e);
  const glm::dvec3 u = e / r;
  glm::dvec3 v = dv - glm::dot(dv, u) * u;
  double vl = glm::length(v);
  if (!(vl > 1e-300)) {  // looking straight at or away from the centre
    v = std::abs(u.z) < 0.9 ? glm::cross(u, glm::dvec3(0, 0, 1)) : glm::cross(u, glm::dvec3(1, 0, 0));
    vl = glm::length(v);
  }
  v /= vl;
  const double cosA = 1.0 / std::max(r, 1.0);
  const glm::dvec3 p = u * cosA + v * std::sqrt(std::max(0.0, 1.0 - cosA * cosA));
  return p / scale;
}

}  // namespace geocean::geo
