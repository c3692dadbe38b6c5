#include "plugin/grid/RayKernels.h"

#include "globe/geo/Ellipsoid.h"

#include <cmath>
#include <limits>

// One attribute for every hot loop: baseline clone plus AVX2 and AVX-512.
#define GEOCEAN_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))

namespace geocean::grid {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kPiO2 = 1.57079632679489661923;
constexpr double kPiO4 = 0.78539816339744830962;
constexpr double kMoreBits = 6.123233995736765886130e-17;  // pi/2 - double(pi/2)

// atan(z) for z in [0, 1], Cephes' rational approximation (max relative
// error ~2e-16 on that range), written without branches so it vectorises.
inline double atanUnit(double z) {
  const bool big = z > 0.66;
  const double x = big ? (z - 1.0) / (z + 1.0) : z;
  const double base = big ? kPiO4 : 0.0;
  const double more = big ? 0.5 * kMoreBits : 0.0;
  const double zz = x * x;
  const double p = (((-8.750608600031904122785e-1 * zz - 1.615753718733365076637e1) * zz -
                     7.500855792314704667340e1) * zz - 1.228866684490136173410e2) * zz -
                   6.485021904942025371773e1;
  const double q = ((((zz + 2.485846490142306297962e1) * zz + 1.650270098316988542046e2) * zz +
                     4.328810604912902668951e2) * zz + 4.853903996359136964868e2) * zz +
                   1.945506571482613964425e2;
  return base + (x * (zz * p / q) + more + x);
}

// atan2 for any signs, branch-free; atan2(0, 0) = 0.
inline double atan2Fast(double y, double x) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool swap = ay > ax;
  const double num = swap ? ax : ay, den = swap ? ay : ax;
  const double z = den > 0.0 ? num / den : 0.0;
  double r = atanUnit(z);
  r = swap ? (kPiO2 - r) + kMoreBits : r;
  r = x < 0.0 ? (kPi - r) + 2.0 * kMoreBits : r;
  return std::copysign(r, y) + 0.0 * (x + y);  // NaN in, NaN out
}
}  // namespace

GEOCEAN_CLONES
void intersectEllipsoidBatch(const double eye[3], const double* __restrict dx, const double* __restrict dy,
                             const double* __restrict dz, std::size_t n, double offsetM,
                             double* __restrict tOut) {
  const double a = geo::kWgs84A + offsetM, b = geo::kWgs84B + offsetM;
  const double wa = 1.0 / (a * a), wb = 1.0 / (b * b);
  const double ox = eye[0], oy = eye[1], oz = eye[2];
  const double sx = ox / a, sy = oy / a, sz = oz / b;
  const double C = sx * sx + sy * sy + sz * sz - 1.0;  // shared by every ray
  const bool inside = C < 0.0;
  const double bx = wa * ox, by = wa * oy, bz = wb * oz;
  const double waa = wa * wa, wab = wa * wb;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i) {
    const double x = dx[i], y = dy[i], z = dz[i];
    const double A = wa * (x * x + y * y) + wb * z * z;
    const double B = bx * x + by * y + bz * z;
    // Lagrange's identity: B^2 - A C = A - |o x d|_w^2 (no cancellation in C).
    const double cxy = ox * y - oy * x, cxz = ox * z - oz * x, cyz = oy * z - oz * y;
    const double disc = A - (waa * cxy * cxy + wab * (cxz * cxz + cyz * cyz));
    const double s = std::sqrt(disc > 0.0 ? disc : 0.0);
    const double q = -(B + std::copysign(s, B));
    const double t1 = q / A, t2 = C / q;
    const double tn = t1 < t2 ? t1 : t2, tf = t1 < t2 ? t2 : t1;
    const double t = inside ? tf : tn;
    tOut[i] = (disc >= 0.0 && tf >= 0.0) ? t : nan;
  }
}

GEOCEAN_CLONES
void surfaceLatLonBatch(const double eye[3], const double* __restrict rx, const double* __restrict ry,
                        const double* __restrict rz, std::size_t n, double* __restrict latDeg,
                        double* __restrict lonDeg) {
  // On the surface, tan(geodetic lat) = z / ((1 - e^2) p) exactly.
  constexpr double e2c = (1.0 - geo::kWgs84F) * (1.0 - geo::kWgs84F);  // 1 - e^2 = (b/a)^2
  constexpr double toDeg = 180.0 / kPi;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = eye[0] + rx[i], y = eye[1] + ry[i], z = eye[2] + rz[i];
    const double p = std::sqrt(x * x + y * y);
    latDeg[i] = atan2Fast(z, e2c * p) * toDeg;
    lonDeg[i] = atan2Fast(y, x) * toDeg;
  }
}

const char* kernelIsa() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return "x86-64-v4";
  if (__builtin_cpu_supports("x86-64-v3")) return "x86-64-v3";
  return "baseline";
}

}  // namespace geocean::grid
