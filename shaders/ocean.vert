// Ocean grid vertex: the eye-relative grid point (plugin/grid, made in
// double) displaced by the shared wave kernel, evaluated at its offset from
// the wave patch origin (the ground point under the eye). Octaves whose
// wavelength spans fewer than 3 grid cells are left out: they would alias,
// and the fragment shader turns them into roughness instead.
#include "waves_types.glsl"
layout(std430, binding = 0) readonly buffer WvOctaveBuffer { WvOctave wvOctaves[]; };
layout(std430, binding = 1) readonly buffer WvWaveBuffer { WvWave wvWaves[]; };
layout(std430, binding = 2) readonly buffer WvFrameBuffer { WvFrame wvFrames[]; };
#include "waves.glsl"
#include "geo_uv.glsl"

layout(location = 0) in vec3 aEyeRel;
layout(location = 1) in uint aClassFlags;
layout(location = 2) in dvec2 aLatLon;

uniform mat4 uViewProj;
uniform vec3 uEyeMinusOrigin;
uniform int uOctaveCount;
uniform int uWaveCount;
uniform float uOctaveWavelengthM[16];
uniform float uCellRadians;
uniform vec4 uElevationGeo;
layout(binding = 1) uniform sampler2D uElevation;

out vec3 vEyeRel;
out vec3 vNormal;
out vec3 vUp;
out vec2 vLonLat;
out float vHeightM;

void main() {
  vec2 lonLat = vec2(float(aLatLon.y), float(aLatLon.x));
  vec3 d = aEyeRel + uEyeMinusOrigin;
  WvFrame fr = wvFrames[0];
  vec3 up = wv_upAt(fr, d);
#ifdef GEOCEAN_BARE
  vec3 p = aEyeRel;
  vNormal = up;
  vHeightM = 0.0;
#else
  float footprint = length(aEyeRel) * uCellRadians;
  int count = 0;
  while (count < uOctaveCount && count < 16 && uOctaveWavelengthM[count] > 3.0 * footprint) ++count;
#if WV_MODEL == 1
  float elev = textureLod(uElevation, geoUv(lonLat, uElevationGeo), 0.0).r;
  float depth = elev < -500.0 ? 1e30 : max(-elev, 1.0);
  WvResult r = wv_gerstner(0, uWaveCount, d, fr, depth);
#else
  WvResult r = wv_solidNoise(0, count, d, fr);
#endif
  vec3 p = aEyeRel + r.disp.xyz;
  vNormal = r.normal.xyz;
  vHeightM = r.disp.w;
#endif
  vEyeRel = p;
  vUp = up;
  vLonLat = lonLat;
  gl_Position = uViewProj * vec4(p, 1.0);
}
