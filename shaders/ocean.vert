// Ocean grid vertex: the eye-relative grid point (plugin/grid, made in
// double) displaced by the shared wave kernel, evaluated at its offset from
// the wave patch origin (the ground point under the eye). Octaves whose
// wavelength spans fewer than 3 grid cells are left out: they would alias,
// and the fragment shader turns them into roughness instead.
#include "waves_types.glsl"
layout(std430, binding = 0) readonly buffer WvOctaveBuffer { WvOctave wvOctaves[]; };
layout(std430, binding = 1) readonly buffer WvWaveBuffer { WvWave wvWaves[]; };
layout(std430, binding = 2) readonly buffer WvFrameBuffer { WvFrame wvFrames[]; };
#if WV_MODEL == 2
// FFT ocean (WaveField::gpuPatch: fftPlanes, fftTexels); WV_FFT is defined.
layout(std430, binding = 3) readonly buffer WvFftPlaneBuffer { WvFftPlane wvFftPlanes[]; };
layout(std430, binding = 4) readonly buffer WvFftTexelBuffer { vec4 wvFftTexels[]; };
uniform int uFftCascades;
uniform float uFftTexelM;  // the coarse cascade's texel, metres
#endif
#if WV_MODEL == 1 && defined(WV_COAST)
// Gerstner with the near-shore phase field (OceanOptions::coast, as in
// shaders/waves_eval.glsl's WV_MODEL 3): the patch's WvCoast and the field's texels.
layout(std430, binding = 3) readonly buffer WvCoastBuffer { WvCoast wvCoasts[]; };
layout(std430, binding = 4) readonly buffer WvCoastTexelBuffer { vec4 wvCoastTexels[]; };
#endif
#include "waves.glsl"
#if WV_MODEL == 4
// Paper 002's noise (OceanRenderer: the patch's WvPaper as 3 vec4).
#include "waves_paper.glsl"
uniform vec4 uPaper[3];
#endif
#if WV_MODEL == 0
#include "noise_bands.glsl"
uniform int uFragOctaves;  // the model's octaves and the detail octaves after them (OceanRenderer)
out float vHeightA;        // the height of the octaves in the vertex normal, by their weight (noise foam)
out float vCellAlongM;     // a grid cell's footprint along the view (noise_bands.glsl)
#endif
#include "geo_uv.glsl"
#include "elev_pages.glsl"
#include "atmosphere.glsl"

layout(location = 0) in vec3 aEyeRel;
layout(location = 1) in uint aClassFlags;
layout(location = 2) in dvec2 aLatLon;

uniform mat4 uViewProj;
uniform vec3 uEyeMinusOrigin;
uniform int uOctaveCount;
uniform int uWaveCount;
uniform float uOctaveWavelengthM[16];
// Mean square slope of the spectrum's waves not drawn (WaveField's
// slopeVarianceAbove): noise, [c] with c octaves kept; Gerstner and FFT,
// [0] all waves, [1] those shorter than the model's shortest.
uniform float uMssAbove[17];
// Whitecaps' crest height by octaves drawn (noise; the other models: all alike).
uniform float uFoamHeightM[17];
uniform float uCellRadians;
uniform float uRefLonDeg;  // the eye's longitude
uniform float uRefLatDeg;  // and latitude (the streamed reliefs' eye-relative texels)
uniform vec4 uElevationGeo;
uniform vec3 uSunDir;
uniform float uEyeAltM;
layout(binding = 1) uniform sampler2D uElevation;

out vec3 vEyeRel;
out vec3 vNormal;
out vec3 vUp;
out vec2 vLonLat;
out float vHeightM;
// Smooth over a cell, so computed per vertex: sunlight at the surface, the
// aerial perspective, the relief's water depth (read at the cell's
// footprint) and how far the waves have faded into roughness.
out vec3 vSun;
out vec3 vHazeTr;
out vec3 vHazeIn;
out float vDepthM;
// Where the relief is too coarse for the mask's coast (ocean_shading.glsl's
// seaOpticsDepthM), on the elevation grid's texels.
layout(binding = 8) uniform sampler2D uReliefFloor;
out float vReliefFloor;
out float vFar;
out float vMss;
out float vFoamM;
#if WV_MODEL == 1 && defined(WV_COAST)
out float vBreakFoam;  // issue 15 hook: the breaking waves' foam (wv_breakingFoam) for ocean.frag
#include "coast_bands.glsl"
#endif
#ifdef FOAM_TIMES
out vec3 vRest;  // ocean.frag's whitecaps (foam.glsl)
out float vWaveDepthM;
#endif
#ifdef GEOCEAN_FAR_SHADED
// Far open water (OceanRenderer): the waves have faded into roughness and
// nothing left varies within a cell, so the colour is made per vertex.
#include "ocean_shading.glsl"
out vec3 vColor;
#endif
#ifdef GEOCEAN_VERTEX_COVERAGE
// Cells much smaller than a water texel (OceanRenderer): the shoreline's
// B-spline is linear across them to well under a pixel, so it is read per
// vertex instead of per pixel.
uniform vec4 uWaterGeo;
layout(binding = 2) uniform sampler2D uWater;
out float vCoverage;
#endif

// Relief texels are ~37 km: the grid's level whose texel matches a cell of
// footprint m (vDepthM's read, and past the streamed reliefs).
float gridElevLod(float footprint) {
  float texelM = abs(uElevationGeo.w) / float(textureSize(uElevation, 0).y) * 111320.0;
  return max(log2(footprint / texelM), 0.0);
}

void main() {
#if WV_MODEL == 0
  vHeightA = 0.0, vCellAlongM = 1.0;
  float noiseVarUnresolved = 0.0;
#endif
  // Longitude unwrapped to within 180 degrees of the eye's, so a cell across
  // the antimeridian interpolates across it, not back through 0 (the
  // textures repeat in longitude).
  double lonD = aLatLon.y - double(uRefLonDeg);
  lonD -= 360.0 * floor((lonD + 180.0) / 360.0);
  vec2 lonLat = vec2(float(lonD + double(uRefLonDeg)), float(aLatLon.x));
  vec3 d = aEyeRel + uEyeMinusOrigin;
  WvFrame fr = wvFrames[0];
#ifdef FOAM_TIMES
  vRest = d;
  vWaveDepthM = 1e30;
#endif
  vec3 up = wv_upAt(fr, d);
#ifdef GEOCEAN_BARE
  vec3 p = aEyeRel;
  vNormal = up;
  vHeightM = 0.0;
#else
  float footprint = length(aEyeRel) * uCellRadians;
  int count = 0;
  while (count < uOctaveCount && count < 16 && uOctaveWavelengthM[count] > 3.0 * footprint) ++count;
#ifdef GEOCEAN_ELEV_PAGES
  // The streamed reliefs (elev_pages.glsl) at the cell's level, as the
  // query reads them at level 0: one read for the waves' depth and vDepthM;
  // the grid past them at vDepthM's level of detail.
  float pagedElev = elevPages(vec2(float(lonD), float(aLatLon.x - double(uRefLatDeg))), footprint, lonLat, uElevation,
                              uElevationGeo, gridElevLod(footprint));
#endif
#if WV_MODEL == 1
#ifdef GEOCEAN_ELEV_PAGES
  float elev = pagedElev;
#else
  float elev = textureLod(uElevation, geoUv(lonLat, uElevationGeo), 0.0).r;
#endif
  float depth = elev < -500.0 ? 1e30 : max(-elev, 1.0);
#ifdef FOAM_TIMES
  vWaveDepthM = depth;
#endif
#ifdef WV_COAST
  WvResult r = wv_gerstnerCoast(0, uWaveCount, d, fr, depth, wvCoasts[0]);
  vBreakFoam = wv_breakingFoam(r);
#ifndef GEOCEAN_NO_COAST_BANDS
  // Issue 15 item 4 hook: the distance bands' foam (coast_bands.glsl).
  coastBands(wv_breakingFoamMean(0, uWaveCount, d, fr, depth, wvCoasts[0]),
             footprint / max(abs(dot(normalize(aEyeRel), up)), 0.02));
#endif
#else
  WvResult r = wv_gerstner(0, uWaveCount, d, fr, depth);
#endif
  float mssDrawn = uMssAbove[0] - uMssAbove[1], mssRest = uMssAbove[1];
  vFoamM = uFoamHeightM[0];
#elif WV_MODEL == 2
  // The tables are bilinear per texel: where a grid cell spans several
  // texels of the coarse cascade the surface would alias, so displacement
  // and slope fade to the mean surface (the fragment shader's roughness
  // takes over, as for the noise octaves).
  WvResult r = wv_fft(0, 3, uFftCascades, d, fr);
  float fftKeep = 1.0 - smoothstep(0.5, 1.5, footprint / max(uFftTexelM, 1e-3));
  r.disp *= fftKeep;
  r.normal.xyz = normalize(mix(up, r.normal.xyz, fftKeep));
  // What the fade removes from the normal goes to the roughness.
  float mssDrawn = (uMssAbove[0] - uMssAbove[1]) * fftKeep * fftKeep;
  float mssRest = uMssAbove[0] - mssDrawn;
  vFoamM = uFoamHeightM[0];
#elif WV_MODEL == 4
  // The octaves longer than 3 cells, as the noise's; the rest is roughness.
  WvResult r = wv_paperNoise(0, count, d, WvPaper(uPaper[0], uPaper[1], uPaper[2]));
  float mssDrawn = uMssAbove[0] - uMssAbove[count], mssRest = uMssAbove[count];
  vFoamM = uFoamHeightM[count];
#else
  vFoamM = uFoamHeightM[count];
  // The normal: the octaves over 3-6 cells along the view
  // (noise_bands.glsl), the rest per fragment or roughness.
  float sinE = abs(dot(normalize(aEyeRel), up));
  vCellAlongM = footprint / max(sinE, 0.02);
  vec3 grad = vec3(0.0);
  vHeightA = 0.0;
  float mssRest = uMssAbove[min(uFragOctaves, 16)];
  noiseVarUnresolved = 0.0;
  // The height: wv_solidNoise's sum over the `count` octaves (its normal
  // is not used here), each octave's noise evaluated once for the height
  // and the normal: the normal's octaves are the first ones, so they add
  // to the height in the same order and with the same operations (the
  // vertex noise was up to ~40 % of the G-buffer pass, docs/PERFORMANCE.md).
  float h = 0.0;
  // The octaves in the normal (a > 0) come first, the wavelengths
  // decreasing: their noise in a loop of their own, tested at its end
  // (llvmpipe runs a masked-off branch, and a loop's body once more when
  // every vertex leaves at the top), the others' bands after it.
  int nv = min(uFragOctaves, 16), i = 0;
  float a = nv > 0 ? noiseVertexWeight(uOctaveWavelengthM[0], vCellAlongM) : 0.0;
  if (a > 0.0) do {
    mssRest += (uMssAbove[i] - uMssAbove[i + 1]) * (1.0 - a * a);
    if (i < uOctaveCount) noiseVarUnresolved += uOctaveHeightVar[i] * (1.0 - a * a);
    vec4 o = noiseOctave(i, d);
    if (i < count) h += o.x;
    grad += a * o.yzw;
    if (i < uOctaveCount) vHeightA += a * noiseCrestWeight(i) * o.x;
    ++i;
    a = i < nv ? noiseVertexWeight(uOctaveWavelengthM[i], vCellAlongM) : 0.0;
  } while (a > 0.0);
  for (int k = i; k < count; ++k) h += noiseOctave(k, d).x;
  WvResult r;
  r.disp = vec4(up * h, h);
  for (; i < nv; ++i) {
    a = noiseVertexWeight(uOctaveWavelengthM[i], vCellAlongM);
    mssRest += (uMssAbove[i] - uMssAbove[i + 1]) * (1.0 - a * a);
    if (i < uOctaveCount) noiseVarUnresolved += uOctaveHeightVar[i] * (1.0 - a * a);
  }
  r.normal.xyz = normalize(up - (grad - dot(grad, up) * up));
  float mssDrawn = 0.0;  // no pull towards the mean (ocean_shading.glsl): the weights filter
#endif
  // A flat cell between vertices on the ellipsoid sags below it, at its
  // centre, by d^2/(8R) over its diagonal d = sqrt(2) L, i.e. L^2/(4R) (L:
  // the cell's size on the ground): 38 m for the 44 km cells seen from
  // 3450 km, more than the 30 m the terrain's water lies under the sea, so
  // cell centres lost the depth test to it (the dot pattern seen from
  // orbit). Each vertex is raised by L^2/(3R) with L = footprint / sin(elevation
  // angle) where that is >= 0.5, faded out below (so the silhouette and the
  // atmosphere's limb glow stay; terrain.vert's sea proxy stops there too);
  // below a few km the raise is under 1 mm.
  float sinElev = abs(dot(normalize(aEyeRel), up));
  float cellM = footprint / max(sinElev, 0.5);
  vec3 p = aEyeRel + r.disp.xyz + up * (cellM * cellM / (3.0 * 6.3e6) * smoothstep(0.2, 0.5, sinElev));
  vNormal = r.normal.xyz;
  vHeightM = r.disp.w;
#endif
  vEyeRel = p;
  vUp = up;
#ifdef GEOCEAN_BARE
  vSun = vec3(1.0), vHazeTr = vec3(1.0), vHazeIn = vec3(0.0), vDepthM = 0.0, vFar = 0.0, vMss = 0.0, vFoamM = 0.0;
  vReliefFloor = 0.0;
#else
  vSun = sunLight(dot(uSunDir, up));
  float t = hazeAmount(length(p), uEyeAltM, 0.0);
  vHazeTr = exp(-t * vec3(1.2, 2.0, 3.6));
  vHazeIn = vec3(0.30, 0.45, 0.80) * (vSun + vec3(0.02)) * 0.3 * (1.0 - vHazeTr);
#ifdef GEOCEAN_ELEV_PAGES
  vDepthM = -pagedElev;
#else
  vDepthM = -textureLod(uElevation, geoUv(lonLat, uElevationGeo), gridElevLod(footprint)).r;
#endif
  vReliefFloor = textureLod(uReliefFloor, geoUv(lonLat, uElevationGeo), 0.0).r;
  // Distant sea: geometry fades to the mean normal, slopes to roughness.
  vFar = smoothstep(0.02, 0.5, footprint / max(uOctaveWavelengthM[0], 1e-3));
  // ocean_shading.glsl turns the drawn normal towards the mean by 0.7 far
  // (slopes x (1 - 0.7 far)): the slope variance it takes goes to roughness.
  float kept = (1.0 - 0.7 * vFar) * (1.0 - 0.7 * vFar);
  vMss = mssRest + (1.0 - kept) * mssDrawn;
#endif
  vLonLat = lonLat;
#if defined(GEOCEAN_FAR_SHADED)
  float opticsDepthM = seaOpticsDepthM(vDepthM, vReliefFloor, 1.0);  // open water: w 1
#endif
#if defined(GEOCEAN_FAR_SHADED) && WV_MODEL == 0
  vColor = oceanColorCrest(vEyeRel, vNormal, vUp, vSun, vHazeTr, vHazeIn, opticsDepthM, vFar, vMss,
                           noiseCrestFoam(vHeightA, noiseVarUnresolved, uFoamSoftM, uWhitecapCover), 1.0, vHeightM);
#elif defined(GEOCEAN_FAR_SHADED)
  vColor = oceanColor(vEyeRel, vNormal, vUp, vHeightM, vSun, vHazeTr, vHazeIn, opticsDepthM, vFar, vMss, vFoamM, 1.0);
#endif
#if defined(GEOCEAN_VERTEX_COVERAGE) && defined(GEOCEAN_WATER_PAGES)
  // A streamed mask: its finest resident level's B-spline, as the paged
  // fragments read it magnified (geo_uv.glsl waterPagesAuto).
  vCoverage = pageBSpline(lonLat, 0, uWater, uWaterGeo);
#elif defined(GEOCEAN_VERTEX_COVERAGE)
  vCoverage = textureBSplineGather(uWater, geoUv(lonLat, uWaterGeo));
#endif
  gl_Position = uViewProj * vec4(p, 1.0);
}
