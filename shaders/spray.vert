// Issue 15 item 4: the near band's breaking spray (paper 003), one point
// sprite a lattice site (plugin/render/Spray.cpp). A pure function of the
// time and the coast field, no state kept between frames: site s (a
// lattice fixed to the ground, uStepM apart, N x N around the eye's nadir)
// throws a droplet cluster every kSprayPeriodS, at its own hashed offset.
// At age a the cluster rides with the crest (the shallow-water celerity
// sqrt(g h) along the waves' particle velocity there) and flies up at v0,
// falling under gravity: it is drawn over the surface at its present rest
// point q, a height v0 a - g a^2 / 2, where wv_gerstnerCoast says the
// crest at q is breaking now (wv_breakingFoam): the crest the cluster left.
#include "waves_types.glsl"
layout(std430, binding = 0) readonly buffer WvOctaveBuffer { WvOctave wvOctaves[]; };
layout(std430, binding = 1) readonly buffer WvWaveBuffer { WvWave wvWaves[]; };
layout(std430, binding = 2) readonly buffer WvFrameBuffer { WvFrame wvFrames[]; };
layout(std430, binding = 3) readonly buffer WvCoastBuffer { WvCoast wvCoasts[]; };
layout(std430, binding = 4) readonly buffer WvCoastTexelBuffer { vec4 wvCoastTexels[]; };
#include "waves.glsl"
#include "atmosphere.glsl"

uniform mat4 uViewProj;
uniform vec3 uEyeMinusOrigin;
uniform int uWaveCount;
uniform vec3 uSunDir;
uniform float uTimeS;       // the time mod 3600 s (a whole number of periods)
uniform int uSprayN;        // sites along a side
uniform ivec2 uSprayBase;   // the first site's lattice indices (lon in [0, uSprayLonSites), lat)
uniform int uSprayLonSites; // sites round a parallel: lon indices are taken modulo it
uniform vec2 uSprayFrac;    // the nadir's offset into its lattice cell (0 .. 1)
uniform vec2 uSprayCellM;   // a lattice cell east, north (m)
uniform vec2 uSprayCellUv;  // the same in the elevation's texture coordinates
uniform vec2 uOriginUv;     // the nadir (patch origin) there (exact: made in double)
uniform vec3 uEast, uNorth; // unit ECEF at the nadir
uniform float uPxPerRad;    // viewport pixels per radian
uniform float uEyeAltM;     // the eye's height (the haze's, as the sea's)
layout(binding = 1) uniform sampler2D uElevation;

out float vAlpha;
out vec3 vColor;

const float kSprayPeriodS = 1.0;  // a cluster's life: the longest flight, 2 v0 / g
const float kSprayM = 0.6;        // a cluster's size

uint sprayHash(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
float sprayUnit(uint h) { return float(h >> 8) / 16777216.0; }

void main() {
  vAlpha = 0.0;
  vColor = vec3(0.0);
  gl_PointSize = 1.0;
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // culled unless drawn below
  int i = gl_VertexID % uSprayN, j = gl_VertexID / uSprayN;
  ivec2 site = uSprayBase + ivec2(i, j);
  // A whole number of sites round the parallel (Spray.cpp, which gives the
  // base in [0, uSprayLonSites)), so index x and x + uSprayLonSites are one
  // site: the seed does not jump where the nadir's longitude wraps at 180.
  if (site.x >= uSprayLonSites) site.x -= uSprayLonSites;
  uint h0 = sprayHash(uint(site.x) * 73856093u ^ uint(site.y) * 19349663u);
  float cyc = uTimeS / kSprayPeriodS + sprayUnit(h0);
  uint h1 = sprayHash(h0 ^ uint(int(floor(cyc))) * 83492791u);
  float age = fract(cyc) * kSprayPeriodS;
  // Launch speed: the longest flight is the period.
  float v0 = 0.5 * WV_G * kSprayPeriodS * mix(0.45, 1.0, sprayUnit(sprayHash(h1 ^ 0x9e3779b9u)));
  float height = v0 * age - 0.5 * WV_G * age * age;
  if (height <= 0.0) return;
  vec2 jit = vec2(sprayUnit(h1), sprayUnit(sprayHash(h1)));
  vec2 cells = vec2(i, j) + jit - uSprayFrac - 0.5 * float(uSprayN);
  // Offsets from the nadir's coordinates: float longitudes next to 180 deg
  // are 1.7 m apart, which moved the depth read from frame to frame.
  float elev = textureLod(uElevation, uOriginUv + cells * uSprayCellUv, 0.0).r;
  if (elev >= 0.0) return;  // land
  float depth = max(-elev, 1.0);
  WvFrame fr = wvFrames[0];
  vec3 dE = uEast * (cells.x * uSprayCellM.x) + uNorth * (cells.y * uSprayCellM.y);
  WvResult re = wv_gerstnerCoast(0, uWaveCount, dE, fr, depth, wvCoasts[0]);
  float hv = length(re.hvel.xyz);
  if (hv < 1e-4) return;
  // The crest's path since the launch: at the celerity, capped where the
  // depth read is not the breaker's (kh no longer small).
  vec3 q = dE + re.hvel.xyz / hv * min(sqrt(WV_G * depth), 8.0) * age;
  WvResult r = wv_gerstnerCoast(0, uWaveCount, q, fr, depth, wvCoasts[0]);
  float foam = wv_breakingFoam(r);
  if (foam <= 0.05) return;
  vec3 up = wv_upAt(fr, q);
  vec3 p = q - uEyeMinusOrigin + r.disp.xyz + up * height;
  float dist = length(p);
  float px = kSprayM * uPxPerRad / max(dist, 1e-3);
  // The near band: clusters under ~1 pixel fade out (the bands' foam
  // carries the surf further away).
  float near = smoothstep(0.8, 1.6, px);
  if (near <= 0.0) return;
  gl_PointSize = clamp(px, 1.0, 64.0);
  // Thin as the cluster rises and spreads, and where the breaking is weak.
  vAlpha = near * smoothstep(0.05, 0.5, foam) * (1.0 - age / kSprayPeriodS) * 0.8;
  vec3 sunDir = normalize(uSunDir);
  float sun = max(dot(up, sunDir), 0.0);
  vec3 white = vec3(0.92, 0.95, 0.97) * (0.35 + 0.65 * sun);  // display colour without haze
  // The sea's aerial perspective at this distance (ocean.vert's, in linear
  // radiance, then toDisplay as the sea's colour): a far breaker's spray
  // fades into the haze as the sea behind it does, not glowing white.
  vec3 lin = -log(1.0 - pow(min(white, vec3(0.995)), vec3(2.2))) / 1.6;  // toDisplay's inverse
  vec3 tr = exp(-hazeAmount(dist, uEyeAltM, 0.0) * vec3(1.2, 2.0, 3.6));
  vColor = toDisplay(lin * tr + vec3(0.30, 0.45, 0.80) * (sunLight(dot(sunDir, up)) + vec3(0.02)) * 0.3 * (1.0 - tr));
  gl_Position = uViewProj * vec4(p, 1.0);
}
