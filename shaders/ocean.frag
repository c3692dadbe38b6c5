// Ocean surface: coverage-cut shoreline (anti-aliased), depth colour from
// the relief, Fresnel sky reflection, sun glint whose roughness grows with
// distance, crest foam and the shore foam band of paper 000 (eq. 9-11).
#include "geo_uv.glsl"
#include "sea_shading.glsl"

in vec3 vEyeRel;
in vec3 vNormal;
in vec3 vUp;
in vec2 vLonLat;
in float vHeightM;
in vec3 vSun;
in vec3 vHazeTr;
in vec3 vHazeIn;
in float vDepthM;
in float vFar;
#ifdef GEOCEAN_VERTEX_COVERAGE
in float vCoverage;
#endif

uniform vec4 uWaterGeo;
uniform vec3 uSunDir;
uniform float uMaxVerticalM;
uniform float uTimeS;
uniform int uWriteData;
layout(binding = 2) uniform sampler2D uWater;

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outData;

// Paper 000 eq. 10: blend factor of one depth curve.
float depthCurve(float depthM, float tauMin, float tauMax) {
  return clamp((tauMin - depthM) / (tauMin - tauMax), 0.0, 1.0);
}

void main() {
  // Coverage: B-spline magnified (a smooth shoreline, no 5' steps), the
  // mipmapped average minified; 0.5 is the coast, smoothed over a pixel.
#if defined(GEOCEAN_OPEN_WATER)
  // Water throughout the cell and its filters' reach (OceanRenderer).
  float w = 1.0;
#elif defined(GEOCEAN_VERTEX_COVERAGE)
  float w = vCoverage;
#else
  float w = textureBSplineAuto(uWater, geoUv(vLonLat, uWaterGeo));
#endif
  float aa = clamp(fwidth(w) * 0.75, 1e-3, 0.5);
  float alpha = smoothstep(0.5 - aa, 0.5 + aa, w);
  if (alpha <= 0.0) discard;

  // Depth (eq. 9's height): relief, or the coverage where the 20' relief
  // puts coastal water above sea level.
  float depth = max(vDepthM, (w - 0.5) * 120.0);
  vec3 up = normalize(vUp);
  vec3 v = normalize(-vEyeRel);
  float far = vFar;
  vec3 n = normalize(mix(normalize(vNormal), up, far * 0.7));
  float roughness = mix(0.06, 0.22, far);
  // Crest foam where the surface nears its highest, and the shore band
  // (eq. 11: water + sum f_i foam) pulsing with the surf.
  float crest = smoothstep(0.55, 0.95, vHeightM / max(uMaxVerticalM, 1e-3)) * (1.0 - far);
  float surf = 0.5 + 0.5 * sin(uTimeS * 0.9 - depth * 1.7);
  float shore = depthCurve(depth, 4.0, 0.3) * 0.55 * surf + depthCurve(depth, 1.2, 0.0) * 0.4;
  float foam = clamp(crest * 0.7 + shore, 0.0, 1.0);
  vec3 c = seaColorLit(n, v, up, uSunDir, vSun, depth, roughness, foam);
  outColor = vec4(toDisplay(c * vHazeTr + vHazeIn), alpha);
  outData = uWriteData != 0 ? vec4(vEyeRel, 1.0) : vec4(0.0);
}
