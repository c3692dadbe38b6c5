// Compute stage that evaluates the wave kernel at a batch of points: the GPU
// side of tests/waves/test_gpu_parity.cpp, and a GPU batch evaluator.
// Assemble with shaders::assemble("waves_eval.glsl", {"WV_MODEL 0"}) (0 solid
// noise, 1 Gerstner, 2 FFT: index.z = cascades, 3 Gerstner with a coast field,
// 4 paper 002's noise: one WvPaper per patch). Buffers: see the bindings below; uniform uCount.
layout(local_size_x = 64) in;

#include "waves_types.glsl"

struct WvPoint {
  vec4 d;       // xyz: offset from the patch origin (m, ECEF), w: water depth (m)
  ivec4 index;  // x: patch (frame), y: first octave/wave, z: count
};

layout(std430, binding = 0) readonly buffer WvOctaveBuffer { WvOctave wvOctaves[]; };
layout(std430, binding = 1) readonly buffer WvWaveBuffer { WvWave wvWaves[]; };
layout(std430, binding = 2) readonly buffer WvFrameBuffer { WvFrame wvFrames[]; };
layout(std430, binding = 3) readonly buffer WvPointBuffer { WvPoint wvPoints[]; };
layout(std430, binding = 4) writeonly buffer WvResultBuffer { WvResult wvResults[]; };
layout(std430, binding = 5) readonly buffer WvFftPlaneBuffer { WvFftPlane wvFftPlanes[]; };
layout(std430, binding = 6) readonly buffer WvFftTexelBuffer { vec4 wvFftTexels[]; };
uniform uint uCount;

#if WV_MODEL == 3
// Gerstner with a coast field (plugin/waves/CoastField.h): one WvCoast per patch.
#define WV_COAST 1
layout(std430, binding = 7) readonly buffer WvCoastTexelBuffer { vec4 wvCoastTexels[]; };
layout(std430, binding = 8) readonly buffer WvCoastBuffer { WvCoast wvCoasts[]; };
#endif

#define WV_FFT 1
#include "waves.glsl"
#if WV_MODEL == 4
#include "waves_paper.glsl"
layout(std430, binding = 7) readonly buffer WvPaperBuffer { WvPaper wvPapers[]; };
#endif

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  WvPoint p = wvPoints[i];
  WvFrame fr = wvFrames[p.index.x];
#if WV_MODEL == 4
  wvResults[i] = wv_paperNoise(p.index.y, p.index.z, p.d.xyz, wvPapers[p.index.x]);
#elif WV_MODEL == 3
  wvResults[i] = wv_gerstnerCoast(p.index.y, p.index.z, p.d.xyz, fr, p.d.w, wvCoasts[p.index.x]);
#elif WV_MODEL == 2
  wvResults[i] = wv_fft(p.index.y, 3, p.index.z, p.d.xyz, fr);
#elif WV_MODEL == 1
  wvResults[i] = wv_gerstner(p.index.y, p.index.z, p.d.xyz, fr, p.d.w);
#else
  wvResults[i] = wv_solidNoise(p.index.y, p.index.z, p.d.xyz, fr);
#endif
}
