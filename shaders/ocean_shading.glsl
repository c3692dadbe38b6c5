// The ocean surface's colour (display-ready), shared by ocean.frag and, for
// far open water shaded per vertex, by ocean.vert: depth colour, Fresnel
// sky, the sun's glitter from the slopes not drawn (Cox-Munk microfacets),
// whitecaps and the shore foam band of paper 000 (eq. 9-11), then the
// aerial perspective.
// Callers declare uSunDir before including this.
#define SEA_WIND_AXIS 1  // oceanColorCrest gives the wind's axis (sea_shading.glsl)
#include "sea_shading.glsl"

uniform float uTimeS;
// Whitecaps (OceanRenderer): crests above foamM (ocean.vert: the height the
// waves it draws exceed on a fraction W = 3.84e-6 U^3.41 of the sea, Monahan
// & O'Muircheartaigh 1980), blended over uFoamSoftM either side; where the
// waves have faded into roughness, that mean cover W itself.
uniform float uFoamSoftM;
uniform float uWhitecapCover;
// The wind (OceanRenderer): U10 (m/s) and the direction it blows from
// (radians from north): the glitter's Cox-Munk axes.
uniform vec2 uWind;

// Optics (OceanRenderer): the refracted bottom on or off, and the host's
// planar reflection (issue 13 item 4): sky and terrain seen by the eye
// mirrored in the tangent plane of the ellipsoid at its nadir (normal
// uNadirUp, uEyeHeightM under the eye), drawn with uReflViewProj (relative
// to the mirrored eye, uReflEyeOffset = eye - mirrored eye from the eye).
uniform int uRefraction;
uniform int uReflection;
// The refraction and crests' subsurface light on or off: fixed in the
// per-pixel programs (GEOCEAN_OPTICS_FIXED, OceanRenderer makes one per
// switch; llvmpipe runs both sides of a branch on a uniform), uniforms in
// the per-vertex far program.
#ifdef GEOCEAN_OPTICS_FIXED
#ifdef GEOCEAN_NO_REFRACTION
const bool kRefractionOn = false;
#else
const bool kRefractionOn = true;
#endif
#ifdef GEOCEAN_NO_SUBSURFACE
const bool kSubsurfaceOn = false;
#else
const bool kSubsurfaceOn = true;
#endif
#else
#define kRefractionOn (uRefraction != 0)
#define kSubsurfaceOn (uSubsurface != 0)
#endif
uniform mat4 uReflViewProj;
uniform vec3 uReflEyeOffset;
uniform vec3 uNadirUp;
uniform float uEyeHeightM;
// How far the eye moved since the map was drawn (a reused map,
// FrameSettings::reflectionEvery; 0 for a fresh one).
uniform float uReflEyeMovedM;
layout(binding = 3) uniform sampler2D uReflectionMap;
// The single plane lies d^2/2R above the sea at distance d (31 m at 20 km):
// the map is used out to kReflectionNearM and fades to the sky BRDF by
// kReflectionFarM (shaders/Shaders.h's kReflectionReachM: the host skips
// the pass for an eye higher than that, where every weight here is 0).
const float kReflectionFarM = GEOCEAN_REFLECTION_REACH_M;
const float kReflectionNearM = 0.5 * kReflectionFarM;

// The map holds display colours (toDisplay): back to linear radiance,
// saturated texels at the shoulder's 0.995.
vec3 fromDisplay(vec3 x) {
  x = min(x, vec3(0.995));
  return -log(1.0 - pow(x, vec3(2.2))) / 1.6;
}

// Paper 001's secondary reflection map (eq. 11, P = P_plane + h N): the
// point of the mirror plane under the fragment, moved along the ray its
// wave normal reflects (slopes taken relative to the local vertical, so a
// calm sea is the plane's exact mirror), projected by the mirrored camera.
// h = 3x the eye's distance: a distant object's deflection is 3/4 drawn,
// one at 3x the eye's distance behind the point exactly. rgb: linear
// radiance; a: its weight against the sky BRDF (0 outside the map, past its
// reach, towards the sun's disc, which the glitter draws, and where the
// perturbed ray dips below the horizon).
vec4 planarReflection(vec3 eyeRel, vec3 n, vec3 up, vec3 sunDir) {
#ifdef GEOCEAN_NO_REFLECTION
  return vec4(0.0);  // a program for draws without the map (OceanRenderer)
#endif
  if (uReflection == 0) return vec4(0.0);
  float above = dot(eyeRel, uNadirUp) + uEyeHeightM;
  vec3 pPlane = eyeRel - above * uNadirUp;
  float dist = length(pPlane);
  vec3 nPert = normalize(uNadirUp + (normalize(n) - normalize(up)));
  vec3 r = reflect(pPlane / max(dist, 1e-3), nPert);
  // The looked-up point is taken far beyond the eye's move, so a reused
  // map's parallax stays under a hundredth of a radian (distant terrain and
  // sky exact; nearer objects m - 1 frames late).
  vec4 clip = uReflViewProj * vec4(pPlane + max(3.0 * dist, 100.0 * uReflEyeMovedM) * r + uReflEyeOffset, 1.0);
  if (clip.w <= 0.0) return vec4(0.0);
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  float edge = smoothstep(0.0, 0.03, min(min(uv.x, 1.0 - uv.x), min(uv.y, 1.0 - uv.y)));
  float reach = 1.0 - smoothstep(kReflectionNearM, kReflectionFarM, dist);
  float disc = 1.0 - smoothstep(0.9993, 0.9996, dot(r, sunDir));
  float rising = smoothstep(-0.01, 0.0, dot(r, uNadirUp));
  float a = edge * reach * disc * rising;
  if (a <= 0.0) return vec4(0.0);
  return vec4(fromDisplay(textureLod(uReflectionMap, uv, 0.0).rgb), a);
}

// Paper 000 eq. 10: blend factor of one depth curve.
float depthCurve(float depthM, float tauMin, float tauMax) {
  return clamp((tauMin - depthM) / (tauMin - tauMax), 0.0, 1.0);
}

// Light through thin crests (issue 13 item 2): sunlight entering the back
// of a crest and scattered out of its front towards an eye that looks
// towards the sun. The approximation of Atlas (Mihelich & Tcheblokov, GDC
// 2019, the one Crest uses): H (v . -L)^4 (0.5 - 0.5 L . n)^3, H the crest's
// height over the significant amplitude Hs / 2 (a thin, high crest passes
// more light), faded out with the waves (far). kSubsurface: its radiance
// per unit sun irradiance, the sea green of light scattered in the water,
// set by eye: a crest's back lit by a sun 12 degrees high (v . -L 0.85,
// slope 0.3 to the eye, H 1/2) gets 0.036, 3x the deep body's green
// (0.0125); then Beer-Lambert's 1 m through the crest (kWaterAttenuation).
uniform float uHsM;
uniform int uSubsurface;
const vec3 kSubsurface = vec3(0.10, 0.93, 0.72);
vec3 crestSubsurface(vec3 n, vec3 v, vec3 sunDir, vec3 sun, float heightM, float far) {
  if (!kSubsurfaceOn) return vec3(0.0);
  float h = clamp(heightM / max(0.5 * uHsM, 1e-3), 0.0, 1.0) * (1.0 - far);
  float back = max(dot(v, -sunDir), 0.0), away = 0.5 - 0.5 * dot(sunDir, n);
  float back2 = back * back;
  return sun * kSubsurface * exp(-kWaterAttenuation) * (h * back2 * back2 * away * away * away * gSunVisible);
}

// The relief's depth as the optics use it. reliefFloor (OceanWorld's
// reliefUnderMaskWater, bilinear, per vertex): 1 where the relief is too
// coarse for the mask's coast (it puts the mask's water on land nearby).
// There the depth goes from the coverage's floor (what the water on the
// relief's land takes) at the relief's 0 m line to the relief's own by 20 m
// of it, so the line (straight across a 37 km ETOPO cell) draws no step in
// the sea; 20 m: where the bottom's green has faded to a tenth (Beer-Lambert
// down and up, 0.0584 /m), so the shelves that show keep their depth.
// Elsewhere (0) the relief's depth as it is.
float seaOpticsDepthM(float reliefDepthM, float reliefFloor, float w) {
  if (reliefDepthM <= 0.0) return reliefDepthM;
  float keep = mix(1.0, smoothstep(0.0, 20.0, reliefDepthM), reliefFloor);
  return mix(max(reliefDepthM, (w - 0.5) * 120.0), reliefDepthM, keep);
}

// The depth seen through the water: the relief's where it has one (the
// coverage's 60 m floor would hide every shelf); the coverage's floor
// where the relief puts the water on land (or without refraction).
float seaSeenDepthM(float reliefDepthM, float w) {
  float depth = max(reliefDepthM, (w - 0.5) * 120.0);
  return kRefractionOn && reliefDepthM > 0.0 ? reliefDepthM : depth;
}

// reliefDepthM: seaOpticsDepthM's.
// w: water coverage (0.5 = coast); far: how far the waves have faded into
// roughness (0 near, 1 far); mss: the mean square slope not in `normal`
// (ocean.vert: the spectrum's waves not drawn, and the slope the fade
// removes); crest: the whitecaps' foam (0..1); heightM: the wave height
// (the crests' subsurface light).
vec3 oceanColorCrest(vec3 eyeRel, vec3 normal, vec3 upIn, vec3 sun, vec3 hazeTr, vec3 hazeIn,
                     float reliefDepthM, float far, float mss, float crest, float w, float heightM) {
  // Depth (eq. 9's height): relief, or the coverage where the 20' relief
  // puts coastal water above sea level.
  float depth = max(reliefDepthM, (w - 0.5) * 120.0);
  vec3 up = normalize(upIn);
  vec3 v = normalize(-eyeRel);
#if WV_MODEL == 0 || WV_MODEL == 4
  // Noise, paper 002's noise: the octaves come filtered to the pixel
  // (noise_bands.glsl; ocean.frag's wv_paperNoiseFiltered).
  vec3 n = normalize(normal);
#else
  vec3 n = normalize(mix(normalize(normal), up, far * 0.7));
#endif
  // The whitecaps, and the shore band (eq. 11: water + sum f_i foam)
  // pulsing with the surf.
  float surf = 0.5 + 0.5 * sin(uTimeS * 0.9 - depth * 1.7);
  float shore = depthCurve(depth, 4.0, 0.3) * 0.55 * surf + depthCurve(depth, 1.2, 0.0) * 0.4;
  float foam = clamp(crest + shore, 0.0, 1.0);
  vec4 refl = planarReflection(eyeRel, n, up, uSunDir);
  float seen = seaSeenDepthM(reliefDepthM, w);
  vec3 east = cross(vec3(0.0, 0.0, 1.0), up);
  east = dot(east, east) > 1e-12 ? normalize(east) : vec3(0.0, 1.0, 0.0);  // at a pole any axis
  vec3 north = cross(up, east);
  vec3 windAxis = sin(uWind.y) * east + cos(uWind.y) * north;  // the sign does not matter
  vec3 c = seaColorOptics(n, v, up, uSunDir, sun, seen, mss, foam, refl, kRefractionOn, windAxis,
                          coxMunkUpwindShare(uWind.x));
  // Leaving the water through the surface (1 - Fresnel), under the foam.
  c += crestSubsurface(n, v, uSunDir, sun, heightM, far) * (1.0 - fresnelSchlick(dot(n, v))) * (1.0 - foam);
  return toDisplay(c * hazeTr + hazeIn);
}

// Noise (and far shading): whitecaps on the highest crests, above foamM.
vec3 oceanColor(vec3 eyeRel, vec3 normal, vec3 upIn, float heightM, vec3 sun, vec3 hazeTr, vec3 hazeIn,
                float reliefDepthM, float far, float mss, float foamM, float w) {
  float crest = mix(smoothstep(foamM - uFoamSoftM, foamM + uFoamSoftM, heightM), uWhitecapCover, far);
  return oceanColorCrest(eyeRel, normal, upIn, sun, hazeTr, hazeIn, reliefDepthM, far, mss, crest, w, heightM);
}
