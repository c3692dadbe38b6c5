#include "plugin/grid/RayKernels.h"

#include "globe/geo/Ellipsoid.h"
#include "plugin/grid/ScreenGrid.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cmath>
#include <limits>

#include <immintrin.h>

// One attribute for every hot loop: baseline clone plus AVX2 and AVX-512.
#define GEOCEAN_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))

namespace geocean::grid {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kPiO2 = 1.57079632679489661923;
constexpr double kPiO4 = 0.78539816339744830962;
constexpr double kMoreBits = 6.123233995736765886130e-17;  // pi/2 - double(pi/2)

// atan(num / den) for 0 <= num <= den, den > 0: Cephes' rational
// approximation (max relative error ~2e-16), branch-free so it vectorises.
// Above 0.66 it uses atan(z) = pi/4 + atan((z - 1) / (z + 1)), with
// (z - 1) / (z + 1) = (num - den) / (num + den): one division either way.
inline double atanRatio(double num, double den) {
  const bool big = num > 0.66 * den;
  const double x = (big ? num - den : num) / (big ? num + den : den);
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
  const double num = swap ? ax : ay;
  // den = 0 only when both are 0: the smallest normal keeps the ratio 0.
  const double den = std::max(swap ? ay : ax, 2.2250738585072014e-308);
  double r = atanRatio(num, den);
  r = swap ? (kPiO2 - r) + kMoreBits : r;
  r = x < 0.0 ? (kPi - r) + 2.0 * kMoreBits : r;
  return std::copysign(r, y) + 0.0 * (x + y);  // NaN in, NaN out
}

// The per-ray algebra of geo::intersectEllipsoid for a shared origin.
struct EllipsoidRays {
  double ox, oy, oz, C, bx, by, bz, wa, wb, waa, wab;
  bool inside;
  EllipsoidRays(const double eye[3], double offsetM) {
    const double a = geo::kWgs84A + offsetM, b = geo::kWgs84B + offsetM;
    wa = 1.0 / (a * a), wb = 1.0 / (b * b);
    ox = eye[0], oy = eye[1], oz = eye[2];
    const double sx = ox / a, sy = oy / a, sz = oz / b;
    C = sx * sx + sy * sy + sz * sz - 1.0;  // shared by every ray
    inside = C < 0.0;
    bx = wa * ox, by = wa * oy, bz = wb * oz;
    waa = wa * wa, wab = wa * wb;
  }
  double t(double x, double y, double z) const {
    const double A = wa * (x * x + y * y) + wb * z * z;
    const double B = bx * x + by * y + bz * z;
    // Lagrange's identity: B^2 - A C = A - |o x d|_w^2 (no cancellation in C).
    const double cxy = ox * y - oy * x, cxz = ox * z - oz * x, cyz = oy * z - oz * y;
    const double disc = A - (waa * cxy * cxy + wab * (cxz * cxz + cyz * cyz));
    const double s = std::sqrt(disc > 0.0 ? disc : 0.0);
    const double q = -(B + std::copysign(s, B));
    const double t1 = q / A, t2 = C / q;
    const double tn = t1 < t2 ? t1 : t2, tf = t1 < t2 ? t2 : t1;
    const double tt = inside ? tf : tn;
    return (disc >= 0.0 && tf >= 0.0) ? tt : std::numeric_limits<double>::quiet_NaN();
  }
};
}  // namespace

GEOCEAN_CLONES
void intersectEllipsoidBatch(const double eye[3], const double* __restrict dx, const double* __restrict dy,
                             const double* __restrict dz, std::size_t n, double offsetM,
                             double* __restrict tOut) {
  const EllipsoidRays e(eye, offsetM);
  for (std::size_t i = 0; i < n; ++i) tOut[i] = e.t(dx[i], dy[i], dz[i]);
}

GEOCEAN_CLONES
void surfaceHitsBatch(const double eye[3], const double* __restrict dx, const double* __restrict dy,
                      const double* __restrict dz, std::size_t n, double* __restrict tOut, double* __restrict rx,
                      double* __restrict ry, double* __restrict rz) {
  const EllipsoidRays e(eye, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = e.t(dx[i], dy[i], dz[i]);
    tOut[i] = t;
    rx[i] = t * dx[i];
    ry[i] = t * dy[i];
    rz[i] = t * dz[i];
  }
}

GEOCEAN_CLONES
void rayRow(const double F[3], const double R[3], const double U[3], double x0, double dx, double y, std::size_t n,
            double* __restrict dirX, double* __restrict dirY, double* __restrict dirZ) {
  const double bx = F[0] + y * U[0], by = F[1] + y * U[1], bz = F[2] + y * U[2];
  for (std::size_t i = 0; i < n; ++i) {
    const double x = x0 + double(i) * dx;
    dirX[i] = bx + x * R[0];
    dirY[i] = by + x * R[1];
    dirZ[i] = bz + x * R[2];
  }
}

GEOCEAN_CLONES
void ispgBatch(const double eye[3], const double N[3], double H, double farM, const double* __restrict dx,
               const double* __restrict dy, const double* __restrict dz, std::size_t n, double* __restrict tOut,
               double* __restrict rx, double* __restrict ry, double* __restrict rz) {
  const double ia2 = 1.0 / (geo::kWgs84A * geo::kWgs84A), ib2 = 1.0 / (geo::kWgs84B * geo::kWgs84B);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = dx[i], y = dy[i], z = dz[i];
    const double dn = x * N[0] + y * N[1] + z * N[2];
    const double len = std::sqrt(x * x + y * y + z * z);
    const double tp = -H / (dn < 0.0 ? dn : -1.0);
    const bool onPlane = dn < 0.0 && tp * len < farM;
    // Otherwise: the far point of the plane in the ray's horizontal direction.
    const double hx = x - dn * N[0], hy = y - dn * N[1], hz = z - dn * N[2];
    const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    const double hs = farM / (hl > 0.0 ? hl : 1.0);
    const double px = onPlane ? x * tp : hx * hs - H * N[0];
    const double py = onPlane ? y * tp : hy * hs - H * N[1];
    const double pz = onPlane ? z * tp : hz * hs - H * N[2];
    // Radial map from the Earth's centre: X_s = X / |X|_w.
    const double X = eye[0] + px, Y = eye[1] + py, Z = eye[2] + pz;
    const double w = 1.0 / std::sqrt((X * X + Y * Y) * ia2 + Z * Z * ib2);
    rx[i] = X * w - eye[0];
    ry[i] = Y * w - eye[1];
    rz[i] = Z * w - eye[2];
    tOut[i] = 1.0;
  }
}

GEOCEAN_CLONES
void packRow(const double* __restrict t, const double* __restrict rx, const double* __restrict ry,
             const double* __restrict rz, const double* __restrict latDeg, const double* __restrict lonDeg,
             const std::uint8_t* __restrict surface, double x0, double dx, bool rowOffscreen, std::size_t n,
             GridVertex* __restrict out) {
  // Two 16-byte stores per vertex (field by field it was eight, and stores
  // were the limit): { x, y, z, surface | flags << 8 } and { lat, lon }.
  static_assert(offsetof(GridVertex, surface) == 12 && offsetof(GridVertex, latDeg) == 16);
  // Streaming (non-temporal) stores when 16-byte aligned (malloc's
  // alignment): the buffer is written once and read by the upload, so
  // reading each line into the cache first (plain stores) only doubles the
  // memory traffic.
  const bool aligned = reinterpret_cast<std::uintptr_t>(out) % 16 == 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = x0 + double(i) * dx;
    const unsigned flags = (t[i] != t[i] ? kVertexHorizon : 0) | ((rowOffscreen || std::fabs(x) > 1.0) ? kVertexOffscreen : 0);
    const std::uint32_t word = std::uint32_t(surface[i]) | flags << 8;  // little endian: surface, flags, reserved = 0
    const __m128 pos = _mm_setr_ps(float(rx[i]), float(ry[i]), float(rz[i]), std::bit_cast<float>(word));
    auto* dst = reinterpret_cast<char*>(out + i);
    if (aligned) {
      _mm_stream_ps(reinterpret_cast<float*>(dst), pos);
      _mm_stream_pd(reinterpret_cast<double*>(dst + 16), _mm_setr_pd(latDeg[i], lonDeg[i]));
    } else {
      _mm_storeu_ps(reinterpret_cast<float*>(dst), pos);
      _mm_storeu_pd(reinterpret_cast<double*>(dst + 16), _mm_setr_pd(latDeg[i], lonDeg[i]));
    }
  }
  _mm_sfence();  // the streamed stores are visible before the row is used
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

GEOCEAN_CLONES
void landCellRow(const std::uint8_t* __restrict below, const std::uint8_t* __restrict above, std::uint8_t land,
                 std::size_t cols, std::uint8_t* __restrict skip) {
  for (std::size_t i = 0; i + 1 < cols; ++i)
    skip[i] = std::uint8_t((below[i] == land) & (below[i + 1] == land) & (above[i] == land) & (above[i + 1] == land));
}

GEOCEAN_CLONES
std::size_t countNan(const double* __restrict v, std::size_t n) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) k += v[i] != v[i];
  return k;
}

const char* kernelIsa() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return "x86-64-v4";
  if (__builtin_cpu_supports("x86-64-v3")) return "x86-64-v3";
  return "baseline";
}

}  // namespace geocean::grid
