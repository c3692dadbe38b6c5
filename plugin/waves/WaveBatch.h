// The SIMD batch form of WaveField::surfaceAt (noise, Gerstner and FFT models):
// Highway, compiled for every x86-64 target and dispatched at run time to
// the widest vectors the CPU has (AVX-512, AVX2, SSE4), 2-8 queries per
// vector in double. A second implementation of the algebra of
// shaders/waves.glsl (which is scalar GLSL), pinned to it by
// tests/waves/test_batch.cpp. Internal to plugin/waves.
#pragma once

#include "plugin/waves/WaveField.h"

#include <cstddef>
#include <cstdint>

namespace geocean::waves::batch {

// Per-octave constants of the solid noise, in the order the kernel uses them.
struct NoiseOctave {
  double row[3][3];  // M rows (lattice units per m)
  double vel[3];     // lattice units per second
  double amplitudeM;
  std::uint32_t seed;
};

// Per-component constants of the Gerstner sea.
struct GerstnerComponent {
  double source[3];  // unit ECEF
  double omega, kRef, kR, amplitudeM, phase0, choppiness;
};

// One (plane, cascade) entry of the FFT ocean (WvFftPlane without the
// per-point part): float-rounded tile axes in texels per metre, the offset
// (texels) of the plane, metres per texel, first texel of the cascade.
struct FftPlane {
  double u[3], v[3];
  double offU, offV;
  double metresPerTexel;
  int firstTexel;
};

struct Points {
  const double* latDeg;
  const double* lonDeg;
  const double* tS;
  bool timesPerPoint;
  const double* depthM;  // null: deep water everywhere
  std::size_t n;
};

void noise(const NoiseOctave* octaves, int count, const Points& p, SurfacePoint* out);
void gerstner(const GerstnerComponent* comps, int count, const Points& p, SurfacePoint* out);
// planes: kPlanes x kCascades entries (plane-major); texels: the tables at
// the one time every point of p has (p.tS[0] when !p.timesPerPoint).
void fft(const FftPlane* planes, const glm::dvec4* texels, const Points& p, SurfacePoint* out);

// Name of the instruction set the dispatch picked on this CPU ("AVX3", "AVX2", "SSE4", ...)
// and the number of doubles per vector there.
const char* targetName();
std::size_t lanes();

}  // namespace geocean::waves::batch
