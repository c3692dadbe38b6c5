// Compute stage that builds the coast field's island table on the GPU, one
// invocation per node (the same function the CPU build runs: coast_islands.glsl).
// Buffers: 0 node elevation (float), 1 per component (travel x, y, omega, 0),
// 2 the table (out), 5 the land nodes' summed-area table (int), 6 the shadow weight (out). Uniforms: node count per side, components, cell (m),
// occlusion radius (nodes).
layout(local_size_x = 8, local_size_y = 8) in;

#include "waves_types.glsl"

// waves.glsl's arrays, unused here (the table only needs wv_waveNumber).
layout(std430, binding = 3) readonly buffer WvOctaveBuffer { WvOctave wvOctaves[]; };
layout(std430, binding = 4) readonly buffer WvWaveBuffer { WvWave wvWaves[]; };
#include "waves.glsl"

layout(std430, binding = 0) readonly buffer WvIslandElevBuffer { float wvIslandElev[]; };
layout(std430, binding = 1) readonly buffer WvIslandCompBuffer { vec4 wvIslandComps[]; };
layout(std430, binding = 2) writeonly buffer WvIslandTableBuffer { vec4 wvIslandTable[]; };
layout(std430, binding = 5) readonly buffer WvIslandSatBuffer { int wvIslandLandSat[]; };
layout(std430, binding = 6) writeonly buffer WvIslandShadowBuffer { float wvIslandShadow[]; };
uniform int uNodes;
uniform int uComps;
uniform float uCellM;
uniform float uRadiusCells;

#include "coast_islands.glsl"

void main() {
  ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
  if (ij.x >= uNodes || ij.y >= uNodes) return;
  wv_islandNode(uNodes, ij.x, ij.y, uComps, uCellM, uRadiusCells);
}
