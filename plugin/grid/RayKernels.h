// Batch kernels for the screen grid: the same algebra as
// geo::intersectEllipsoid, in a branch-free loop the compiler vectorises.
//
// SIMD policy: the library is compiled for the portable baseline
// (-march=x86-64-v2, see the top-level CMakeLists.txt); these kernels are
// multi-versioned with GCC target_clones (baseline, x86-64-v3 = AVX2+FMA,
// x86-64-v4 = AVX-512) and the best clone is picked once at load time by the
// ifunc resolver. FP contraction stays off (-std=c++20 implies
// -ffp-contract=off), so every clone returns bit-identical results.
#pragma once

#include <cstddef>

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
void surfaceLatLonBatch(const double eyeEcef[3], const double* rx, const double* ry, const double* rz,
                        std::size_t n, double* latDeg, double* lonDeg);

// Which clone the ifunc resolver picked on this CPU: "x86-64-v4",
// "x86-64-v3" or "baseline" (for logs and benchmark labels).
const char* kernelIsa();

}  // namespace geocean::grid
