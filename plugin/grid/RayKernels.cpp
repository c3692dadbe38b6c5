#include "plugin/grid/RayKernels.h"

#include "globe/geo/Ellipsoid.h"
#include "plugin/grid/ScreenGrid.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cmath>
#include <limits>

#include <immintrin.h>


// One attribute for every hot loop: baseline clone plus AVX2 and AVX-512.
#define GEOCEAN_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))

namespace geocean::grid {

// GCC names the x86-64 levels in __builtin_cpu_supports; Clang before 16
// does not (the libFuzzer build, tests/fuzz), so there they are spelled as
// the levels' features that Clang 14 can test (x86-64 psABI; it cannot
// test MOVBE, LZCNT or F16C, which every AVX2 + FMA + BMI2 CPU has).
#if defined(__clang__) && __clang_major__ < 16
#define GEOCEAN_CPU_V3                                                                                     \
  (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") && \
   __builtin_cpu_supports("fma"))
#define GEOCEAN_CPU_V4                                                                                           \
  (GEOCEAN_CPU_V3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&                 \
   __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
#else
#define GEOCEAN_CPU_V3 __builtin_cpu_supports("x86-64-v3")
#define GEOCEAN_CPU_V4 __builtin_cpu_supports("x86-64-v4")
#endif

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kPiO2 = 1.57079632679489661923;
constexpr double kPiO4 = 0.78539816339744830962;

// atan(num / den) for 0 <= num <= den, den > 0, branch-free so it vectorises.
// Above tan(pi/8) it uses atan(z) = pi/4 + atan((z - 1) / (z + 1)), with
// (z - 1) / (z + 1) = (num - den) / (num + den): one division either way,
// |reduced argument x| <= tan(pi/8).
//
// atan(x) = x + x s P(s) / Q(s), s = x^2 <= tan^2(pi/8): a rational minimax
// of type (3, 3) fitted for this interval (Remez in binary128, relative error
// of atan): |error| <= 3.8e-16 |atan(x)| <= 1.6e-16 rad before rounding.
// Cephes' (4, 5) rational, used before, is fitted for |x| <= 0.66; on
// |x| <= tan(pi/8) the (3, 3) type is enough, with 6 fewer FP operations.
// With the rounding of x, of the evaluation and of the octant constants the
// kernel stays within 1e-15 rad (6e-14 deg, 6 nm on the Earth) of the exact
// atan2 of its double inputs (test_ray_kernels: SurfaceLatLonMatchesLongDouble),
// far inside the grid's 1e-11 deg. Cephes' extra low-order bits of pi/4
// (6e-17 rad) are left out.
//
// Divisions stay (A/B in one in-L1 micro-benchmark, 2026-11-30, AVX-512
// clone): FP operations, not the divider, set the pace here. A
// division-free degree-8 minimax polynomial with one division per vertex
// shared by lat and lon took 2.46 ns/vertex against Cephes' 2.26 (4
// divisions); sharing this rational's divisions between lat and lon
// (1/(q_lat q_lon), 1/(den_lat den_lon)) was 3-6% slower again; this kernel
// takes 2.00 unfused, 1.58 with FMA (surfaceLatLonBatch).
// a * b + c: fused (one rounding) in the AVX2/AVX-512 lat/lon kernels, two
// roundings in the portable one (see surfaceLatLonBatch).
template <bool kFma>
inline double mulAdd(double a, double b, double c) {
  if constexpr (kFma) {
    return std::fma(a, b, c);
  } else {
    return a * b + c;
  }
}

template <bool kFma>
inline double atanRatio(double num, double den) {
  const bool big = num > 0.41421356237309504880 * den;
  const double x = (big ? num - den : num) / (big ? num + den : den);
  const double base = big ? kPiO4 : 0.0;
  const double s = x * x;
  const double p = mulAdd<kFma>(mulAdd<kFma>(mulAdd<kFma>(-6.920989678749491547243e-03, s, -7.291123710112603693934e-01), s,
                                             -2.888934599523784514341e+00),
                                s, -2.483581327415647086051e+00);
  const double q = mulAdd<kFma>(mulAdd<kFma>(s + 6.876511270586865033462e+00, s, 1.313725018722962112606e+01), s,
                                7.450743982251262162723e+00);
  return base + mulAdd<kFma>(x, s * p / q, x);
}

// atan2 for any signs, branch-free; signed zeros as std::atan2 (atan2(+-0, +0)
// = +-0, atan2(+-0, -0) = +-pi); NaN in, NaN out (the comparisons keep a NaN
// in num or den, and the division passes it on).
template <bool kFma>
inline double atan2Fast(double y, double x) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool swap = ay > ax;
  const double num = swap ? ax : ay;
  // den = 0 only when both are 0: the smallest normal keeps the ratio 0.
  const double den = std::max(swap ? ay : ax, 2.2250738585072014e-308);
  double r = atanRatio<kFma>(num, den);
  r = swap ? kPiO2 - r : r;
  // The sign bit, not x < 0: x = -0 gives pi as std::atan2 (std::signbit
  // does not vectorise with GCC 12).
  r = std::bit_cast<std::int64_t>(x) < 0 ? kPi - r : r;
  return std::copysign(r, y);
}

// atan2(y, x) for x >= 0 (the latitude: x is a distance from the axis).
template <bool kFma>
inline double atan2PosX(double y, double x) {
  const double ay = std::fabs(y);
  const bool swap = ay > x;
  const double num = swap ? x : ay;
  const double den = std::max(swap ? ay : x, 2.2250738585072014e-308);
  double r = atanRatio<kFma>(num, den);
  r = swap ? kPiO2 - r : r;
  return std::copysign(r, y);
}

template <bool kFma>
inline void latLonLoop(const double eye[3], const double* __restrict rx, const double* __restrict ry,
                       const double* __restrict rz, std::size_t n, double* __restrict latDeg,
                       double* __restrict lonDeg) {
  // On the surface, tan(geodetic lat) = z / ((1 - e^2) p) exactly.
  constexpr double e2c = (1.0 - geo::kWgs84F) * (1.0 - geo::kWgs84F);  // 1 - e^2 = (b/a)^2
  constexpr double toDeg = 180.0 / kPi;
  const double ex = eye[0], ey = eye[1], ez = eye[2];
  for (std::size_t i = 0; i < n; ++i) {
    const double x = ex + rx[i], y = ey + ry[i], z = ez + rz[i];
    const double p = std::sqrt(mulAdd<kFma>(x, x, y * y));
    latDeg[i] = atan2PosX<kFma>(z, e2c * p) * toDeg;
    lonDeg[i] = atan2Fast<kFma>(y, x) * toDeg;
  }
}

// c ? a : b without a branch.
inline double sel(bool c, double a, double b) {
  const std::uint64_t m = std::uint64_t(0) - std::uint64_t(c);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & m) | (std::bit_cast<std::uint64_t>(b) & ~m));
}
inline std::uint8_t sel8(bool c, std::uint8_t a, std::uint8_t b) {
  const std::uint8_t m = std::uint8_t(0u - unsigned(c));
  return std::uint8_t((a & m) | (b & ~m));
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
void surfaceHitsRow(const double eye[3], const double F[3], const double R[3], const double U[3], double x0,
                    double dx, double y, std::size_t n, double* __restrict tOut, double* __restrict rx,
                    double* __restrict ry, double* __restrict rz) {
  const EllipsoidRays e(eye, 0.0);
  const double bx = F[0] + y * U[0], by = F[1] + y * U[1], bz = F[2] + y * U[2];
  const double R0 = R[0], R1 = R[1], R2 = R[2];
  for (std::size_t i = 0; i < n; ++i) {
    const double x = x0 + double(int(i)) * dx;
    const double dxi = bx + x * R0, dyi = by + x * R1, dzi = bz + x * R2;  // as rayRow
    const double t = e.t(dxi, dyi, dzi);
    tOut[i] = t;
    rx[i] = t * dxi;
    ry[i] = t * dyi;
    rz[i] = t * dzi;
  }
}

GEOCEAN_CLONES
std::size_t horizonRow(const double F[3], const double R[3], const double U[3], double x0, double dx, double y,
                       std::size_t n, bool borderRow, const LimbCandidates& c, const double* __restrict t,
                       double* __restrict rx, double* __restrict ry, double* __restrict rz,
                       double* __restrict latDeg, double* __restrict lonDeg, std::uint8_t* __restrict surface,
                       std::uint8_t* __restrict unresolved) {
  const double bx = F[0] + y * U[0], by = F[1] + y * U[1], bz = F[2] + y * U[2];
  const double R0 = R[0], R1 = R[1], R2 = R[2];
  const double* __restrict c0x = c.colDir[0][0];
  const double* __restrict c0y = c.colDir[0][1];
  const double* __restrict c0z = c.colDir[0][2];
  const double* __restrict c1x = c.colDir[1][0];
  const double* __restrict c1y = c.colDir[1][1];
  const double* __restrict c1z = c.colDir[1][2];
  const double r0x = c.rowDir[0][0], r0y = c.rowDir[0][1], r0z = c.rowDir[0][2];
  const double r1x = c.rowDir[1][0], r1y = c.rowDir[1][1], r1z = c.rowDir[1][2];
  // Every load unconditional, every choice a select: the loop vectorises.
  const double* __restrict p0x = c.colRel[0][0];
  const double* __restrict p0y = c.colRel[0][1];
  const double* __restrict p0z = c.colRel[0][2];
  const double* __restrict p1x = c.colRel[1][0];
  const double* __restrict p1y = c.colRel[1][1];
  const double* __restrict p1z = c.colRel[1][2];
  const double* __restrict la0 = c.colLat[0];
  const double* __restrict la1 = c.colLat[1];
  const double* __restrict lo0 = c.colLon[0];
  const double* __restrict lo1 = c.colLon[1];
  const std::uint8_t* __restrict s0 = c.colSurface[0];
  const std::uint8_t* __restrict s1 = c.colSurface[1];
  const double q0x = c.rowRel[0][0], q0y = c.rowRel[0][1], q0z = c.rowRel[0][2];
  const double q1x = c.rowRel[1][0], q1y = c.rowRel[1][1], q1z = c.rowRel[1][2];
  const double rla0 = c.rowLat[0], rla1 = c.rowLat[1], rlo0 = c.rowLon[0], rlo1 = c.rowLon[1];
  const std::uint8_t rs0 = c.rowSurface[0], rs1 = c.rowSurface[1];
  // Blocks of kBlock lanes in two loops: the doubles (choice and position,
  // lat, lon), then the bytes (class, unresolved) from the choice code. In
  // one loop the byte arrays set GCC's vector factor to 64 lanes (eight zmm
  // of every double), which spilled registers (~22 instructions per lane).
  constexpr std::size_t kBlock = 256;
  // 0: hit, kept; 1, 2: column candidate 0, 1; 3, 4: row candidate 0, 1; 5: none.
  alignas(64) std::int64_t code[kBlock];
  std::size_t left = 0;
  for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
    const std::size_t m = std::min(kBlock, n - i0);
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = i0 + k;
      const double x = x0 + double(int(i)) * dx;
      const double dxi = bx + x * R0, dyi = by + x * R1, dzi = bz + x * R2;
      const double d0 = c0x[i] * dxi + c0y[i] * dyi + c0z[i] * dzi, d1 = c1x[i] * dxi + c1y[i] * dyi + c1z[i] * dzi;
      const double e0 = r0x * dxi + r0y * dyi + r0z * dzi, e1 = r1x * dxi + r1y * dyi + r1z * dzi;
      // Within a line the second point wins only if strictly better (and > 0).
      const bool col1 = d1 > (d0 > 0.0 ? d0 : 0.0), row1 = e1 > (e0 > 0.0 ? e0 : 0.0);
      const double colDot = d0 > d1 ? d0 : d1, rowDot = e0 > e1 ? e0 : e1;
      const bool borderCol = (i == 0) | (i + 1 == n);
      const bool colPos = colDot > 0.0, rowPos = rowDot > 0.0, colNearer = colDot >= rowDot;
      const bool preferCol = (borderCol & colPos) | (!borderCol & borderRow & !rowPos) |
                             (!borderCol & !borderRow & colNearer);
      const bool useCol = preferCol & colPos;
      const bool useRow = !useCol & rowPos;
      const bool miss = t[i] != t[i];
      // Bitwise selects: GCC turns `c ? a[i] : b[i]` into a load from a
      // selected address, which it cannot vectorise.
      const double cx = sel(col1, p1x[i], p0x[i]), cy = sel(col1, p1y[i], p0y[i]), cz = sel(col1, p1z[i], p0z[i]);
      const double cla = sel(col1, la1[i], la0[i]), clo = sel(col1, lo1[i], lo0[i]);
      const double qx = sel(row1, q1x, q0x), qy = sel(row1, q1y, q0y), qz = sel(row1, q1z, q0z);
      const double qla = sel(row1, rla1, rla0), qlo = sel(row1, rlo1, rlo0);
      rx[i] = sel(miss, sel(useCol, cx, qx), rx[i]);
      ry[i] = sel(miss, sel(useCol, cy, qy), ry[i]);
      rz[i] = sel(miss, sel(useCol, cz, qz), rz[i]);
      latDeg[i] = sel(miss, sel(useCol, cla, qla), latDeg[i]);
      lonDeg[i] = sel(miss, sel(useCol, clo, qlo), lonDeg[i]);
      // Arithmetic, not ?: on constants (GCC leaves those as branches here).
      const std::int64_t none = std::int64_t(!useCol & !useRow);
      const std::int64_t choice = std::int64_t(useCol) * (1 + std::int64_t(col1)) +
                                  std::int64_t(useRow) * (3 + std::int64_t(row1)) + 5 * none;
      code[k] = std::int64_t(miss) * choice;
    }
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = i0 + k;
      const std::int64_t ch = code[k];
      const std::uint8_t col = sel8(ch == 2, s1[i], s0[i]), row = sel8(ch == 4, rs1, rs0);
      surface[i] = sel8(ch == 0 || ch == 5, surface[i], sel8(ch <= 2, col, row));
      unresolved[i] = std::uint8_t(ch == 5);
      left += ch == 5;
    }
  }
  return left;
}

GEOCEAN_CLONES
void rayRow(const double F[3], const double R[3], const double U[3], double x0, double dx, double y, std::size_t n,
            double* __restrict dirX, double* __restrict dirY, double* __restrict dirZ) {
  const double bx = F[0] + y * U[0], by = F[1] + y * U[1], bz = F[2] + y * U[2];
  for (std::size_t i = 0; i < n; ++i) {
    const double x = x0 + double(int(i)) * dx;
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

namespace {
// The vertex as four 64-bit words { x | y << 32, z | (surface | flags << 8) << 32, lat, lon }
// (little endian): GCC vectorises this as an interleaving store, where the
// field-by-field struct write was eight scalar stores per vertex.
using Word = std::uint64_t __attribute__((may_alias));
inline void packWords(const double* __restrict t, const double* __restrict rx, const double* __restrict ry,
                      const double* __restrict rz, const double* __restrict latDeg, const double* __restrict lonDeg,
                      const std::uint8_t* __restrict surface, double x0, double dx, std::uint32_t rowFlag,
                      std::size_t i0, std::size_t n, Word* __restrict o) {
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = i0 + k;
    const double x = x0 + double(int(i)) * dx;
    const std::uint32_t flags = (t[i] != t[i] ? std::uint32_t(kVertexHorizon) : 0u) |
                                (std::fabs(x) > 1.0 ? std::uint32_t(kVertexOffscreen) : 0u) | rowFlag;
    const std::uint32_t word = std::uint32_t(surface[i]) | flags << 8;  // reserved = 0
    const auto bits = [](double v) { return std::uint64_t(std::bit_cast<std::uint32_t>(float(v))); };
    o[4 * k] = bits(rx[i]) | bits(ry[i]) << 32;
    o[4 * k + 1] = bits(rz[i]) | std::uint64_t(word) << 32;
    o[4 * k + 2] = std::bit_cast<std::uint64_t>(latDeg[i]);
    o[4 * k + 3] = std::bit_cast<std::uint64_t>(lonDeg[i]);
  }
}

// packWords for 8 vertices at a time with AVX-512 permutes (GCC's own
// vectorisation of the interleave is a long chain of lane extracts and
// inserts). Same conversions (round to nearest float), same words.
// GCC 12 reports its own _mm512_undefined_* placeholders in the conversion
// intrinsics as maybe-uninitialized (a known false positive).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw")))
void packWordsAvx512(const double* __restrict t, const double* __restrict rx, const double* __restrict ry,
                     const double* __restrict rz, const double* __restrict latDeg, const double* __restrict lonDeg,
                     const std::uint8_t* __restrict surface, double x0, double dx, std::uint32_t rowFlag,
                     std::size_t i0, std::size_t n, Word* __restrict o) {
  const __m256i iota = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m512i order = _mm512_setr_epi64(0, 1, 4, 5, 2, 3, 6, 7);
  const __m512i zipLo = _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11), zipHi = _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15);
  const __m512i pairLo = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11), pairHi = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
  const __m256i horizon = _mm256_set1_epi32(int(kVertexHorizon) << 8), off = _mm256_set1_epi32(int(kVertexOffscreen) << 8);
  const __m256i rowBits = _mm256_set1_epi32(int(rowFlag << 8));
  const __m512d one = _mm512_set1_pd(1.0), vx0 = _mm512_set1_pd(x0), vdx = _mm512_set1_pd(dx);
  std::size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    const std::size_t i = i0 + k;
    const __m512d tv = _mm512_loadu_pd(t + i);
    const __mmask8 nan = _mm512_cmp_pd_mask(tv, tv, _CMP_UNORD_Q);
    const __m512d xv = _mm512_add_pd(vx0, _mm512_mul_pd(_mm512_cvtepi32_pd(_mm256_add_epi32(_mm256_set1_epi32(int(i)), iota)), vdx));
    const __mmask8 offscreen = _mm512_cmp_pd_mask(_mm512_abs_pd(xv), one, _CMP_GT_OQ);
    __m256i word = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(surface + i)));
    word = _mm256_or_si256(word, rowBits);
    word = _mm256_mask_or_epi32(word, nan, word, horizon);
    word = _mm256_mask_or_epi32(word, offscreen, word, off);
    const __m256 fx = _mm512_cvtpd_ps(_mm512_loadu_pd(rx + i)), fy = _mm512_cvtpd_ps(_mm512_loadu_pd(ry + i));
    const __m256 fz = _mm512_cvtpd_ps(_mm512_loadu_pd(rz + i)), fw = _mm256_castsi256_ps(word);
    // 64-bit words a_k | b_k << 32, k = 0..7 in order.
#define GEOCEAN_PAIRS(a, b)                                                                              \
  _mm512_permutexvar_pd(order, _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(_mm256_unpacklo_ps(a, b))), \
                                                  _mm256_castps_pd(_mm256_unpackhi_ps(a, b)), 1))
    const __m512d xy = GEOCEAN_PAIRS(fx, fy), zw = GEOCEAN_PAIRS(fz, fw);
#undef GEOCEAN_PAIRS
    const __m512d la = _mm512_loadu_pd(latDeg + i), lo = _mm512_loadu_pd(lonDeg + i);
    const __m512d aLo = _mm512_permutex2var_pd(xy, zipLo, zw), aHi = _mm512_permutex2var_pd(xy, zipHi, zw);
    const __m512d bLo = _mm512_permutex2var_pd(la, zipLo, lo), bHi = _mm512_permutex2var_pd(la, zipHi, lo);
    double* dst = reinterpret_cast<double*>(o + 4 * k);
    _mm512_storeu_pd(dst, _mm512_permutex2var_pd(aLo, pairLo, bLo));
    _mm512_storeu_pd(dst + 8, _mm512_permutex2var_pd(aLo, pairHi, bLo));
    _mm512_storeu_pd(dst + 16, _mm512_permutex2var_pd(aHi, pairLo, bHi));
    _mm512_storeu_pd(dst + 24, _mm512_permutex2var_pd(aHi, pairHi, bHi));
  }
  if (k < n) packWords(t, rx, ry, rz, latDeg, lonDeg, surface, x0, dx, rowFlag, i0 + k, n - k, o + 4 * k);
}
#pragma GCC diagnostic pop
}  // namespace

void packRow(const double* __restrict t, const double* __restrict rx, const double* __restrict ry,
             const double* __restrict rz, const double* __restrict latDeg, const double* __restrict lonDeg,
             const std::uint8_t* __restrict surface, double x0, double dx, bool rowOffscreen, std::size_t n,
             GridVertex* __restrict out, bool streamOut) {
  static_assert(offsetof(GridVertex, eyeRelM) == 0 && offsetof(GridVertex, surface) == 12 &&
                offsetof(GridVertex, flags) == 13 && offsetof(GridVertex, latDeg) == 16 &&
                offsetof(GridVertex, lonDeg) == 24);
  const std::uint32_t rowFlag = rowOffscreen ? std::uint32_t(kVertexOffscreen) : 0u;
  // Packing straight into the buffer with plain stores (micro-benchmark, min
  // of 100, 512 x 512 rows into 8 MB: AVX-512 0.20 ms plain vs 0.45 ms
  // streamed; 1024 x 1024: 2.4 vs 3.1 ms; GCC's interleave: 0.29 vs
  // 0.47 ms at 8 MB, but 2.7 vs 2.0 ms at 32 MB, beyond the cache).
  static const bool avx512 = GEOCEAN_CPU_V4;
  if (avx512) {
    packWordsAvx512(t, rx, ry, rz, latDeg, lonDeg, surface, x0, dx, rowFlag, 0, n, reinterpret_cast<Word*>(out));
    return;
  }
  packRowPortable(t, rx, ry, rz, latDeg, lonDeg, surface, x0, dx, rowOffscreen, n, out, streamOut);
}

void prefetchPackRow(GridVertex* out, std::size_t n, bool streamOut) {
  static const bool avx512 = GEOCEAN_CPU_V4;  // packRow's choice
  if (streamOut && !avx512) return;
  const auto* p = reinterpret_cast<const char*>(out);
  for (std::size_t b = 0; b < n * sizeof(GridVertex); b += 64) __builtin_prefetch(p + b, 1, 3);
}

GEOCEAN_CLONES
void packRowPortable(const double* __restrict t, const double* __restrict rx, const double* __restrict ry,
                     const double* __restrict rz, const double* __restrict latDeg, const double* __restrict lonDeg,
                     const std::uint8_t* __restrict surface, double x0, double dx, bool rowOffscreen, std::size_t n,
                     GridVertex* __restrict out, bool streamOut) {
  const std::uint32_t rowFlag = rowOffscreen ? std::uint32_t(kVertexOffscreen) : 0u;
  if (!streamOut || reinterpret_cast<std::uintptr_t>(out) % 16 != 0) {
    packWords(t, rx, ry, rz, latDeg, lonDeg, surface, x0, dx, rowFlag, 0, n, reinterpret_cast<Word*>(out));
    return;
  }
  // Packed in L1 blocks, then streamed (non-temporal) to the buffer: beyond
  // the cache, plain stores would first read every line (twice the memory
  // traffic). SSE2 streams: in every clone.
  constexpr std::size_t kBlock = 64;
  alignas(64) std::uint64_t stage[4 * kBlock];
  auto* dst = reinterpret_cast<__m128i*>(out);
  for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
    const std::size_t m = std::min(kBlock, n - i0);
    packWords(t, rx, ry, rz, latDeg, lonDeg, surface, x0, dx, rowFlag, i0, m, stage);
    const auto* src = reinterpret_cast<const __m128i*>(stage);
    for (std::size_t k = 0; k < 2 * m; ++k) _mm_stream_si128(dst + 2 * i0 + k, _mm_load_si128(src + k));
  }
  _mm_sfence();  // the streamed stores are visible before the row is used
}

namespace {
// The lat/lon kernel's clones, dispatched by hand (not target_clones) so that
// only the FMA-capable ones fuse: GCC's -ffp-contract is per file, and std::fma
// in the baseline would be a library call per operation.
__attribute__((target("arch=x86-64-v4"))) void latLonV4(const double eye[3], const double* rx, const double* ry,
                                                         const double* rz, std::size_t n, double* lat, double* lon) {
  latLonLoop<true>(eye, rx, ry, rz, n, lat, lon);
}
__attribute__((target("arch=x86-64-v3"))) void latLonV3(const double eye[3], const double* rx, const double* ry,
                                                         const double* rz, std::size_t n, double* lat, double* lon) {
  latLonLoop<true>(eye, rx, ry, rz, n, lat, lon);
}
}  // namespace

// FMA in the AVX2 and AVX-512 paths (7 fused operations per vertex: the
// rational's Horner steps, its last step and x^2 + y^2): 20 % faster kernel,
// 11 % on the 512^2 build (8-run A/B). Fused and unfused results differ by a few ulp
// (test_latlon_paths: FmaWithinTwoUlpOfPortable, within 6e-14 deg; both stay within
// the 1e-13 deg of SurfaceLatLonMatchesLongDouble), so the lat/lon of the
// baseline path is no longer bit-identical to the AVX2/AVX-512 paths; those
// two are (std::fma is exact, the same operations fuse in both).
void surfaceLatLonBatch(const double eye[3], const double* __restrict rx, const double* __restrict ry,
                        const double* __restrict rz, std::size_t n, double* __restrict latDeg,
                        double* __restrict lonDeg) {
  static const int isa = GEOCEAN_CPU_V4 ? 4 : GEOCEAN_CPU_V3 ? 3 : 2;
  if (isa == 4) {
    latLonV4(eye, rx, ry, rz, n, latDeg, lonDeg);
  } else if (isa == 3) {
    latLonV3(eye, rx, ry, rz, n, latDeg, lonDeg);
  } else {
    surfaceLatLonBatchPortable(eye, rx, ry, rz, n, latDeg, lonDeg);
  }
}

// The unfused kernel: what CPUs without FMA run (GEOCEAN_CLONES still gives
// it SSE/AVX widths where they exist).
GEOCEAN_CLONES
void surfaceLatLonBatchPortable(const double eye[3], const double* __restrict rx, const double* __restrict ry,
                                const double* __restrict rz, std::size_t n, double* __restrict latDeg,
                                double* __restrict lonDeg) {
  latLonLoop<false>(eye, rx, ry, rz, n, latDeg, lonDeg);
}

GEOCEAN_CLONES
std::size_t landCellRow(const std::uint8_t* __restrict below, const std::uint8_t* __restrict above,
                        std::uint8_t land, std::size_t cols, std::uint8_t* __restrict skip) {
  std::size_t count = 0;
  for (std::size_t i = 0; i + 1 < cols; ++i) {
    const std::uint8_t s =
        std::uint8_t((below[i] == land) & (below[i + 1] == land) & (above[i] == land) & (above[i + 1] == land));
    skip[i] = s;
    count += s;
  }
  return count;
}

GEOCEAN_CLONES
std::size_t countNan(const double* __restrict v, std::size_t n) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) k += v[i] != v[i];
  return k;
}

const char* kernelIsa() {
  __builtin_cpu_init();
  if (GEOCEAN_CPU_V4) return "x86-64-v4";
  if (GEOCEAN_CPU_V3) return "x86-64-v3";
  return "baseline";
}

}  // namespace geocean::grid
