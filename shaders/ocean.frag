// Ocean surface: coverage-cut shoreline (anti-aliased), depth colour from
// the relief, Fresnel sky reflection, Cox-Munk sun glitter from the slopes
// not drawn, whitecaps and the shore foam band of paper 000 (eq. 9-11).
#include "geo_uv.glsl"

// Deferred shading (the noise sea, OceanRenderer): GEOCEAN_GBUFFER writes
// what the shading reads per pixel from the grid's triangles, and
// GEOCEAN_DEFERRED shades it in one pass over the tiles with sea. llvmpipe shades 4 x 4
// pixel blocks whole, so the grid's 32-pixel triangles ran the shading for
// ~2 lanes a pixel (docs/PERFORMANCE.md); the values and arithmetic are
// the forward pass's.
#ifdef GEOCEAN_DEFERRED
#define VARYING  // filled from the G-buffer at the start of main
#else
#define VARYING in
#endif
#if (defined(GEOCEAN_GBUFFER) || defined(GEOCEAN_DEFERRED)) && (WV_MODEL != 0 || defined(GEOCEAN_FAR_SHADED))
#error "the deferred ocean is the noise sea's per-pixel programs only"
#endif
VARYING vec3 vEyeRel;
VARYING vec3 vNormal;
VARYING vec3 vUp;
VARYING vec2 vLonLat;
VARYING float vHeightM;
VARYING vec3 vSun;
VARYING vec3 vHazeTr;
VARYING vec3 vHazeIn;
VARYING float vDepthM;
VARYING float vReliefFloor;  // ocean.vert; 0 in the resolve (the G-buffer's depth has it)
VARYING float vFar;
VARYING float vMss;
VARYING float vFoamM;
#ifdef GEOCEAN_VERTEX_COVERAGE
in float vCoverage;
#endif
#ifdef GEOCEAN_FAR_SHADED
in vec3 vColor;  // far open water: shaded per vertex (OceanRenderer)
#endif
#if WV_MODEL == 1 && defined(WV_COAST) && !defined(GEOCEAN_BARE)
in float vBreakFoam;  // issue 15 hook (ocean.vert): breaking foam, added to the crest foam below
#define GEOCEAN_BREAK_FOAM 1
#include "coast_bands_frag.glsl"  // issue 15 item 4: the distance bands (coastBandFoam)
#endif
#ifdef FOAM_TIMES
// Whitecaps from the Jacobian per fragment (Gerstner, FFT): the rest point
// (offset from the wave patch origin: linear across a cell, so exact) and
// the water depth the vertex used.
in vec3 vRest;
in float vWaveDepthM;
#endif
#ifndef GEOCEAN_FAR_SHADED
// The detail normal layer (waves.glsl's wv_detailSlope; OceanRenderer).
#define WV_DETAIL 1
uniform vec4 wvDetail[64];
uniform int uDetailCount;
uniform vec3 uEyeMinusOrigin;
#include "waves_types.glsl"
layout(std430, binding = 0) readonly buffer WvOctaveBuffer { WvOctave wvOctaves[]; };
layout(std430, binding = 1) readonly buffer WvWaveBuffer { WvWave wvWaves[]; };
layout(std430, binding = 2) readonly buffer WvFrameBuffer { WvFrame wvFrames[]; };
uniform int uWaveCount;
#if WV_MODEL == 2
layout(std430, binding = 3) readonly buffer WvFftPlaneBuffer { WvFftPlane wvFftPlanes[]; };
layout(std430, binding = 4) readonly buffer WvFftTexelBuffer { vec4 wvFftTexels[]; };
uniform int uFftCascades;
#endif
#if WV_MODEL == 1 && defined(WV_COAST)
layout(std430, binding = 3) readonly buffer WvCoastBuffer { WvCoast wvCoasts[]; };
layout(std430, binding = 4) readonly buffer WvCoastTexelBuffer { vec4 wvCoastTexels[]; };
#endif
#include "waves.glsl"
#if WV_MODEL == 4
// Paper 002's noise per fragment (OceanRenderer: uPaper as ocean.vert's).
#include "waves_paper.glsl"
uniform vec4 uPaper[3];
uniform int uOctaveCount;
uniform float uOctaveWavelengthM[16];
uniform float uMssAbove[17];
uniform float uFoamHeightM[17];
#endif
#if WV_MODEL == 0
#define NOISE_OCTAVE_TEXELS 1
#include "noise_bands.glsl"
uniform int uFragOctaves;
uniform float uPixelOctaveEndPx;  // OceanOptions::pixelOctaveEndPx
uniform int uOctaveCount;
uniform float uOctaveWavelengthM[16];
uniform float uMssAbove[17];
VARYING float vHeightA;
VARYING float vCellAlongM;
#endif
#ifdef FOAM_TIMES
#include "foam.glsl"
#endif
#ifdef GEOCEAN_FRAGMENT_NORMAL
uniform int uFragmentNormal;  // OceanRenderer::setFragmentNormal
#endif
#endif

uniform vec4 uWaterGeo;
uniform vec3 uSunDir;
uniform int uWriteData;
layout(binding = 2) uniform sampler2D uWater;

#ifdef GEOCEAN_GBUFFER
// eyeRel, alpha | normal (octahedral), height, cell along the view |
// relief depth, vertex octaves' crest height, footprint, coverage. The terms
// smooth over a cell (up, sun, haze, far) are made again per pixel by the
// shading pass: each target costs ~6-10 ms a frame to write on llvmpipe.
layout(location = 0) out vec4 outG0;
layout(location = 1) out vec4 outG1;
layout(location = 2) out vec4 outG2;
// Which 8 x 8 pixel tiles have sea to shade (OceanRenderer draws the
// shading pass over those alone: llvmpipe runs the whole shading for a
// block whose pixels all discard). Tested early, so hidden sea marks none.
layout(early_fragment_tests) in;
layout(binding = 7, r8ui) uniform writeonly uimage2D uGTiles;
#else
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outData;
#endif
#ifdef GEOCEAN_DEFERRED
// The G-buffer (units 15-17), in the framebuffer's pixels.
layout(binding = 15) uniform sampler2D uG0;
layout(binding = 16) uniform sampler2D uG1;
layout(binding = 17) uniform sampler2D uG2;
#endif
#if defined(GEOCEAN_GBUFFER) || defined(GEOCEAN_DEFERRED)
// A direction as 2 floats (octahedral; the shading normalises what it reads).
vec2 octEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * s;
}
vec3 octDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * s;
  return n;
}
#endif
#ifdef GEOCEAN_DEFERRED
// ocean.vert's, for the terms it makes per vertex, made here per pixel.
uniform float uCellRadians;
uniform float uEyeAltM;
#endif
#include "ocean_shading.glsl"
#ifndef GEOCEAN_FAR_SHADED
#include "wake.glsl"
#include "shadow.glsl"
#endif

void main() {
#ifdef GEOCEAN_DEFERRED
#ifdef GEOCEAN_COARSE
  // Reduced rate (OceanRenderer, ocean_resolve.frag): a half-size target,
  // each texel the exact shading of the framebuffer pixel 2 x its own.
  ivec2 px = ivec2(gl_FragCoord.xy) * 2;
#else
  ivec2 px = ivec2(gl_FragCoord.xy);
#endif
  vec4 g0 = texelFetch(uG0, px, 0);
  float alpha = g0.w;
  if (alpha <= 0.0) discard;  // no sea drawn at this pixel (cleared to 0)
  vec4 g1 = texelFetch(uG1, px, 0), g2 = texelFetch(uG2, px, 0);
  vEyeRel = g0.xyz, vNormal = octDecode(g1.xy), vHeightM = g1.z, vCellAlongM = g1.w, vDepthM = g2.x, vHeightA = g2.y;
  vReliefFloor = 0.0;
  float w = g2.w;
  // What ocean.vert makes per vertex and the grid interpolates, at the
  // pixel (the same formulas: they vary little over a cell, so the
  // picture moves by rounding; docs/PERFORMANCE.md).
  vUp = wv_upAt(wvFrames[0], vEyeRel + uEyeMinusOrigin);
  vSun = sunLight(dot(uSunDir, vUp));
  vHazeTr = exp(-hazeAmount(length(vEyeRel), uEyeAltM, 0.0) * vec3(1.2, 2.0, 3.6));
  vHazeIn = vec3(0.30, 0.45, 0.80) * (vSun + vec3(0.02)) * 0.3 * (1.0 - vHazeTr);
  vec3 restRel = vEyeRel - vUp * vHeightM;
  float cellFootprint = length(restRel) * uCellRadians;
  vFar = smoothstep(0.02, 0.5, cellFootprint / max(uOctaveWavelengthM[0], 1e-3));
  vLonLat = vec2(0.0), vMss = 0.0, vFoamM = 0.0;  // not read by the noise sea's shading
#else
  // Coverage: B-spline magnified (a smooth shoreline, no 5' steps), the
  // mipmapped average minified; 0.5 is the coast, smoothed over a pixel.
#if defined(GEOCEAN_OPEN_WATER) || defined(GEOCEAN_FAR_SHADED)
  // Water throughout the cell and its filters' reach (OceanRenderer).
  float w = 1.0;
#elif defined(GEOCEAN_VERTEX_COVERAGE)
  float w = vCoverage;
#elif defined(GEOCEAN_WATER_PAGES)
  float w = waterPagesAuto(vLonLat, uWater, uWaterGeo);  // a streamed mask (plugin/render/WaterPages)
#else
  float w = textureBSplineAuto(uWater, geoUv(vLonLat, uWaterGeo));
#endif
  float aa = clamp(fwidth(w) * 0.75, 1e-3, 0.5);
  float alpha = smoothstep(0.5 - aa, 0.5 + aa, w);
  if (alpha <= 0.0) discard;
#endif
#ifdef GEOCEAN_GBUFFER
  outG0 = vec4(vEyeRel, alpha), outG1 = vec4(octEncode(vNormal), vHeightM, vCellAlongM);
  outG2 = vec4(seaOpticsDepthM(vDepthM, vReliefFloor, w), vHeightA, max(length(dFdx(vEyeRel)), length(dFdy(vEyeRel))),
               w);
  imageStore(uGTiles, ivec2(gl_FragCoord.xy) / 8, uvec4(1u));
#elif defined(GEOCEAN_FAR_SHADED)
  outColor = vec4(vColor, alpha);
#else
  // The floating bodies' foam (wake.glsl) joins the crests' foam.
  float wake = wakeFoam(vEyeRel, normalize(vUp));
#if defined(FOAM_TIMES)
  // The kernel is evaluated per fragment, so the folds stay resolved while
  // a pixel (1/8 of the cell's footprint) is under half the shortest wave
  // (peak / 16: vFar ~0.25); the mean cover takes over by vFar 0.75.
  float far = smoothstep(0.25, 0.75, vFar);
  vec3 fragNormal = vNormal;
  float crest = far < 1.0 ? whitecapFoam(vRest, wvFrames[0], vWaveDepthM, fragNormal) : 0.0;
  crest = mix(crest, uWhitecapCover, far);
#ifdef GEOCEAN_BREAK_FOAM
  crest = max(crest, coastBandFoam(vBreakFoam, vEyeRel));
#endif
#elif defined(GEOCEAN_BREAK_FOAM)
  // Issue 15 hook: oceanColor's crest foam, and the breaking waves' on top.
  float crest = max(mix(smoothstep(vFoamM - uFoamSoftM, vFoamM + uFoamSoftM, vHeightM), uWhitecapCover, vFar), coastBandFoam(vBreakFoam, vEyeRel));
#elif WV_MODEL == 0
  float crest = 0.0;  // below, with the octaves
#else
  // oceanColor's crest foam.
  float crest = mix(smoothstep(vFoamM - uFoamSoftM, vFoamM + uFoamSoftM, vHeightM), uWhitecapCover, vFar);
#endif
  // The detail layer's slopes (waves under a pixel's 2 x footprint drop
  // out) join the drawn normal and leave the roughness; oceanColorCrest
  // turns normals towards the mean by 0.7 far, so that share of them stays
  // roughness.
  vec3 up = normalize(vUp);
#ifdef GEOCEAN_DEFERRED
  float footprint = g2.z;  // the grid pass's derivatives
#else
  float footprint = max(length(dFdx(vEyeRel)), length(dFdy(vEyeRel)));
#endif
#if WV_MODEL == 0
  // The noise sea's octaves not in the vertex normal, down to
  // uPixelOctaveEndPx pixels, at the fragment's rest point (the
  // displacement is vertical), and the roughness of what is shown neither
  // way (noise_bands.glsl).
  WvFrame fr0 = wvFrames[0];
  vec3 d = vEyeRel - up * vHeightM + uEyeMinusOrigin;
  vec3 upD = wv_upAt(fr0, d);
  vec3 nv = normalize(vNormal);
  vec3 grad = upD - nv / dot(nv, upD), gAdd = vec3(0.0);
  float hRes = vHeightA, varU = 0.0;
  // Only the octaves between the vertex normal's (a < 1 from 6 cells) and
  // the pixel's (f > 0 down to uPixelOctaveEndPx) are visited: the wavelengths
  // halve, so the first is found by a logarithm; before it every octave is
  // shown whole, after it none (the spectrum from there is roughness).
  int n = min(uFragOctaves, 16);
  // The octave index differs between pixels: the octaves' data come as
  // texel fetches (noiseOctaveFetched, uOctaveBands), the same values.
  int i = clamp(int(floor(log2(uOctaveWavelengthM[0] / (6.0 * vCellAlongM)))) + 1, 0, n);
  float mss = 0.0;
  vec4 band = texelFetch(uOctaveBands, i);
#ifdef GEOCEAN_NO_PIXEL_OCTAVES
  // No pixel of the view is under 1 / uPixelOctaveEndPx of the longest
  // octave (OceanRenderer's bound): every f below is 0, so the loop and
  // the slopes it adds are left out (llvmpipe would run the loop's body
  // once, masked), and the trailing loop's sum is read whole
  // (OceanRenderer: the same float sum).
  mss += band.y;
  varU = band.w;
  vec3 nrm = normalize(upD - grad);
#else
  // A do-while tested at the end: llvmpipe runs a loop's body once more,
  // masked, when every pixel leaves it at the top (an octave's noise).
  float f = i < n ? noisePixelWeight(band.x, footprint, uPixelOctaveEndPx) : 0.0;
  if (f > 0.0) do {
    float a = noiseVertexWeight(band.x, vCellAlongM);
    float shown = max(a, f);
    vec4 next = texelFetch(uOctaveBands, i + 1);
    mss += (band.y - next.y) * (1.0 - shown * shown);
    if (i < uOctaveCount) varU += band.z * (1.0 - shown * shown);
    if (f > a) {
      vec4 o = noiseOctaveFetched(i, d);
      gAdd += (f - a) * o.yzw;
      if (i < uOctaveCount) hRes += (f - a) * noiseCrestWeight(i) * o.x;
    }
    band = next;
    ++i;
    f = i < n ? noisePixelWeight(band.x, footprint, uPixelOctaveEndPx) : 0.0;
  } while (f > 0.0);
  mss += band.y;
  for (int k = i; k < uOctaveCount && k < 16; ++k) varU += texelFetch(uOctaveBands, k).z;
  gAdd -= dot(gAdd, upD) * upD;
  // The octaves added here replace roughness that is Cox & Munk's
  // anisotropic: their isotropic slopes are stretched along the wind by
  // the upwind share (total variance kept), as the roughness's.
  vec3 eastD = cross(vec3(0.0, 0.0, 1.0), upD);
  eastD = dot(eastD, eastD) > 1e-12 ? normalize(eastD) : vec3(0.0, 1.0, 0.0);
  vec3 windD = sin(uWind.y) * eastD + cos(uWind.y) * cross(upD, eastD);
  float share = coxMunkUpwindShare(uWind.x);
  float along = dot(gAdd, windD);
  grad += windD * along * sqrt(2.0 * share) + (gAdd - windD * along) * sqrt(2.0 * (1.0 - share));
  vec3 nrm = normalize(upD - grad);
#endif
  crest = noiseCrestFoam(hRes, varU, uFoamSoftM, uWhitecapCover);
#else
  vec3 nDrawn = normalize(vNormal);
#if defined(GEOCEAN_FRAGMENT_NORMAL) && defined(FOAM_TIMES)
  // The kernel's normal at the fragment's rest point (the whitecaps' present
  // sample, so no extra evaluation) where the whitecaps resolve the waves,
  // the vertices' as they fade (far): the middle band's coarse cells
  // (OceanOptions::coarseMiddle) would otherwise interpolate the normal
  // over twice the vertex spacing and soften the sea. uFragmentNormal 0
  // (tests): the vertices' alone.
  if (uFragmentNormal != 0) nDrawn = normalize(mix(fragNormal, nDrawn, far));
#endif
  float mssDrawn = vMss;
  float farKeep = (1.0 - 0.7 * vFar) * (1.0 - 0.7 * vFar);
#if WV_MODEL == 4
  // Paper 002's noise: its octaves down to 2 pixels at the fragment's rest
  // point (the displacement is vertical), not only the vertex's over 3
  // cells; the roughness keeps the rest. Filtered to the pixel, so no pull
  // to the mean far away (ocean_shading.glsl, as the noise's).
  WvResult rp = wv_paperNoiseFiltered(0, uOctaveCount, vEyeRel - up * vHeightM + uEyeMinusOrigin,
                                      WvPaper(uPaper[0], uPaper[1], uPaper[2]), footprint);
  nDrawn = rp.normal.xyz;
  int kept = 0;  // octaves at least half kept: their crest level (OceanRenderer's uFoamHeightM)
  mssDrawn = uMssAbove[min(uOctaveCount, 16)];
  for (int i = 0; i < uOctaveCount && i < 16; ++i) {
    float k = smoothstep(2.0, 4.0, uOctaveWavelengthM[i] / footprint);
    mssDrawn += (uMssAbove[i] - uMssAbove[i + 1]) * (1.0 - k * k);
    kept += k >= 0.5 ? 1 : 0;
  }
  farKeep = 1.0;
  float foamM = uFoamHeightM[kept];
  crest = mix(smoothstep(foamM - uFoamSoftM, foamM + uFoamSoftM, rp.disp.w), uWhitecapCover, vFar);
#endif
  vec4 detail = wv_detailSlope(uDetailCount, vEyeRel + uEyeMinusOrigin, footprint);
  vec3 nrm = normalize(nDrawn - (detail.xyz - up * dot(detail.xyz, up)));
  float mss = max(mssDrawn - detail.w * farKeep, 0.0);
#endif
  // The sun's shadow (shadow.glsl): its direct light removed, or paper 001's
  // darkening of the pixel by 0.5.
  float sunVis = sunVisibility(vEyeRel);
  gSunVisible = uShadow == 2 ? 1.0 : sunVis;
  vec3 col = oceanColorCrest(vEyeRel, nrm, vUp, vSun, vHazeTr, vHazeIn, seaOpticsDepthM(vDepthM, vReliefFloor, w), vFar,
                             mss, max(crest, wake), w, vHeightM);
  outColor = vec4(uShadow == 2 ? col * mix(0.5, 1.0, sunVis) : col, alpha);
#endif
#ifndef GEOCEAN_GBUFFER
  // 2 (tests): the water depth drawn (vDepthM) and the depth seen through
  // it (seaSeenDepthM), w 2 where the sea drew.
  outData = uWriteData == 2 ? vec4(vDepthM, seaSeenDepthM(seaOpticsDepthM(vDepthM, vReliefFloor, w), w), 0.0, 2.0)
          : uWriteData != 0 ? vec4(vEyeRel, 1.0) : vec4(0.0);
#endif
}
