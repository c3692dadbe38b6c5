// Batch kernels for the screen grid: the same algebra as
// geo::intersectEllipsoid, in a branch-free loop the compiler vectorises.
//
// SIMD policy: the library is compiled for the portable baseline
// (-march=x86-64-v2, see the top-level CMakeLists.txt); these kernels are
// multi-versioned with GCC target_clones (baseline, x86-64-v3 = AVX2+FMA,
// x86-64-v4 = AVX-512) and the best clone is picked once at load time by the
// ifunc resolver. FP contraction is off (-ffp-contract=off on the target),
// so every clone returns bit-identical results, except surfaceLatLonBatch:
// explicit FMA on AVX2/AVX-512 (dispatched by hand, 20 % faster kernel),
// within 6e-14 deg of the portable path. packRow also has an AVX-512
// intrinsics path chosen at run time (no arithmetic, same bytes; tested
// against packRowPortable).
#pragma once

#include <cstddef>
#include <cstdint>

namespace geocean::grid {

// First intersection (t >= 0) of rays eye + t d with the WGS84 ellipsoid
// inflated by offsetM, for n directions in SoA form (need not be unit: t is
// in units of each direction's length). Misses give NaN. From an eye inside
// the surface the exit root is returned. Accuracy: within 1 mm of
// geo::intersectEllipsoid except for rays within ~1e-4 rad of grazing,
// where t moves along the tangent line (the point stays on the surface).
void intersectEllipsoidBatch(const double eyeEcef[3], const double* dx, const double* dy, const double* dz,
                             std::size_t n, double offsetM, double* tOut);

// Geodetic latitude/longitude (degrees) of n points ON the WGS84 ellipsoid
// (eye + t d with t from intersectEllipsoidBatch, given eye-relative as
// rx, ry, rz): closed form, exact for points on the surface. NaN in, NaN out.
// With FMA on CPUs that have it (AVX2/AVX-512): within 6e-14 deg of the
// portable kernel, not bit-identical to it (see RayKernels.cpp).
void surfaceLatLonBatch(const double eyeEcef[3], const double* rx, const double* ry, const double* rz,
                        std::size_t n, double* latDeg, double* lonDeg);
// surfaceLatLonBatch without FMA (what CPUs without FMA run).
void surfaceLatLonBatchPortable(const double eyeEcef[3], const double* rx, const double* ry, const double* rz,
                                std::size_t n, double* latDeg, double* lonDeg);

struct GridVertex;

// Unnormalised ray directions F + (x0 + i dx) R + y U for i in [0, n): one
// grid row (R, U already scaled by tan(fov/2)).
void rayRow(const double F[3], const double R[3], const double U[3], double x0, double dx, double y, std::size_t n,
            double* dirX, double* dirY, double* dirZ);

// rayRow fused with intersectEllipsoidBatch (offset 0) and the eye-relative
// hit point r = t d (NaN on a miss): the same directions (same arithmetic)
// in one pass, without storing them.
void surfaceHitsRow(const double eyeEcef[3], const double F[3], const double R[3], const double U[3], double x0,
                    double dx, double y, std::size_t n, double* tOut, double* rx, double* ry, double* rz);

// Limb (horizon) candidates for the missed rays of one grid row: two per
// grid column (arrays indexed by column) and two of the row's own line.
// A candidate that does not exist has direction 0 (its dot is never > 0).
struct LimbCandidates {
  const double* colDir[2][3];  // unit directions from the eye
  const double* colRel[2][3];  // eye-relative positions
  const double* colLat[2];
  const double* colLon[2];
  const std::uint8_t* colSurface[2];
  double rowDir[2][3], rowRel[2][3], rowLat[2], rowLon[2];
  std::uint8_t rowSurface[2];
};

// For every i in [0, n) whose t is NaN (a miss): the limb candidate for
// ray rayRow(i) -- the column's (i = 0 or n - 1: column first), the row's
// (borderRow: row first), else whichever is closest in direction (ties:
// the column) -- written to rx, ry, rz, lat, lon, surface. Lanes with no
// candidate in front of the ray get unresolved[i] = 1 (else 0) for the
// caller's fallback; returns how many.
std::size_t horizonRow(const double F[3], const double R[3], const double U[3], double x0, double dx, double y,
                       std::size_t n, bool borderRow, const LimbCandidates& c, const double* t, double* rx,
                       double* ry, double* rz, double* latDeg, double* lonDeg, std::uint8_t* surface,
                       std::uint8_t* unresolved);

// ISPG (paper 000 eq. 5, 7, 8) on WGS84: hit of each ray with the plane of
// normal N at height H below the eye (or, past farM, the far point in the
// plane's direction), mapped radially from the Earth's centre onto the
// ellipsoid; eye-relative output, t set to 1 (ISPG never misses).
void ispgBatch(const double eyeEcef[3], const double N[3], double H, double farM, const double* dx,
               const double* dy, const double* dz, std::size_t n, double* tOut, double* rx, double* ry, double* rz);

// Packs one row into GridVertex (float eye-relative position, class,
// flags: horizon where t is NaN, offscreen where |x0 + i dx| > 1 or rowOffscreen).
// streamOut: non-temporal stores for a buffer larger than the cache
// (measured here: plain stores win while the buffer fits in L3, 2.3x at
// 8 MB; streaming wins beyond it, except on the AVX-512 path, which always
// uses plain 64-byte stores).
void packRow(const double* t, const double* rx, const double* ry, const double* rz, const double* latDeg,
             const double* lonDeg, const std::uint8_t* surface, double x0, double dx, bool rowOffscreen,
             std::size_t n, GridVertex* out, bool streamOut = false);
// packRow without the AVX-512 path (what packRow runs on other CPUs).
void packRowPortable(const double* t, const double* rx, const double* ry, const double* rz, const double* latDeg,
                     const double* lonDeg, const std::uint8_t* surface, double x0, double dx, bool rowOffscreen,
                     std::size_t n, GridVertex* out, bool streamOut);

// Prefetches (for writing) the n vertices packRow(..., out, streamOut) will
// store with plain stores; nothing when it streams them. 512^2 build 5 %
// faster (8-run A/B, 2026-11-30): the 8 MB vertex buffer lives in L3, and
// packRow stalled on the lines it writes.
void prefetchPackRow(GridVertex* out, std::size_t n, bool streamOut);

// skip[i] = 1 where below[i], below[i + 1], above[i], above[i + 1] all
// equal `land`, else 0, for i in [0, cols - 1): one row of cell flags.
// Returns the number of skipped cells.
std::size_t landCellRow(const std::uint8_t* below, const std::uint8_t* above, std::uint8_t land, std::size_t cols,
                 std::uint8_t* skip);

// Number of NaNs in v[0, n).
std::size_t countNan(const double* v, std::size_t n);

// Which clone the ifunc resolver picked on this CPU: "x86-64-v4",
// "x86-64-v3" or "baseline" (for logs and benchmark labels).
const char* kernelIsa();

}  // namespace geocean::grid
