// The shared wave source (shaders/waves_types.glsl + shaders/waves.glsl +
// shaders/waves_paper.glsl)
// compiled as C++ through GLM, which names its types and functions after
// GLSL. Two instantiations:
//  - kd: WR = double, the functions too: the CPU query path.
//  - kf: WR = float, the types only: the exact std430 layout uploaded to the
//    GPU (static_asserted below), so the GPU structs are written once.
// Internal to plugin/waves and its tests; users see WaveField.h.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

namespace geocean::waves {

namespace kd {
using uint = std::uint32_t;
using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
// Using-declarations (not a using-directive) so that unqualified calls in the
// shared code can never pick ::abs(int) and friends from the C library.
using glm::abs;
using glm::ceil;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::floor;
using glm::length;
using glm::max;
using glm::min;
using glm::normalize;
using glm::pow;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
using glm::tanh;

#define WV_CPU 1
#define WV_FFT 1
#define WV_COAST 1
#define WV_DETAIL 1
#define WR double
#define WR2 glm::dvec2
#define WR3 glm::dvec3
#define WR4 glm::dvec4
#include "shaders/waves_types.glsl"
#define WV_PAPER_TYPES_ONLY 1
#include "shaders/waves_paper.glsl"
#undef WV_PAPER_TYPES_ONLY

// The GLSL functions become members so that they see the patch arrays under
// the same names the shader's SSBOs have.
struct Kernel {
  const WvOctave* wvOctaves = nullptr;
  const WvWave* wvWaves = nullptr;
  const WvFftPlane* wvFftPlanes = nullptr;
  const WR4* wvFftTexels = nullptr;
  const WR4* wvCoastTexels = nullptr;
  // The island table's build (shaders/coast_islands.glsl, CoastField.cpp).
  const WR* wvIslandElev = nullptr;
  const int* wvIslandLandSat = nullptr;
  const WR4* wvIslandComps = nullptr;
  WR4* wvIslandTable = nullptr;
  WR* wvIslandShadow = nullptr;
  // The detail normal layer's patch (WaveField.h, detailPatch): 2 per wave.
  const WR4* wvDetail = nullptr;
#include "shaders/waves.glsl"
#include "shaders/waves_paper.glsl"
#include "shaders/coast_islands.glsl"
};
#undef WR
#undef WR2
#undef WR3
#undef WR4
#undef WAVES_TYPES_GLSL
#undef WAVES_GLSL
#undef WAVES_PAPER_TYPES
#undef WAVES_PAPER_GLSL
#undef COAST_ISLANDS_GLSL
}  // namespace kd

namespace kf {
using glm::ivec4;
#define WR float
#define WR2 glm::vec2
#define WR3 glm::vec3
#define WR4 glm::vec4
#include "shaders/waves_types.glsl"
#define WV_PAPER_TYPES_ONLY 1
#include "shaders/waves_paper.glsl"
#undef WV_PAPER_TYPES_ONLY
#undef WR
#undef WR2
#undef WR3
#undef WR4
#undef WAVES_TYPES_GLSL
#undef WAVES_PAPER_TYPES
#undef WV_CPU
#undef WV_FFT
#undef WV_COAST

// std430 layout of the GPU structs: every member is a 16-byte vec4/ivec4.
static_assert(sizeof(WvFrame) == 48 && alignof(WvFrame) <= 16);
static_assert(sizeof(WvOctave) == 96 && offsetof(WvOctave, cellO) == 64);
static_assert(sizeof(WvWave) == 64 && offsetof(WvWave, phase) == 32);
static_assert(sizeof(WvResult) == 64);
static_assert(sizeof(WvCoast) == 48 && offsetof(WvCoast, cell) == 32);
static_assert(sizeof(WvFftPlane) == 64 && offsetof(WvFftPlane, cell) == 48);
static_assert(sizeof(WvPaper) == 48 && offsetof(WvPaper, trig) == 32);
}  // namespace kf

}  // namespace geocean::waves
