// The ocean surface's colour (display-ready), shared by ocean.frag and, for
// far open water shaded per vertex, by ocean.vert: depth colour, Fresnel
// sky, glint whose roughness grows with distance, crest foam and the shore
// foam band of paper 000 (eq. 9-11), then the aerial perspective.
// Callers declare uSunDir before including this.
#include "sea_shading.glsl"

uniform float uMaxVerticalM;
uniform float uTimeS;

// Paper 000 eq. 10: blend factor of one depth curve.
float depthCurve(float depthM, float tauMin, float tauMax) {
  return clamp((tauMin - depthM) / (tauMin - tauMax), 0.0, 1.0);
}

// w: water coverage (0.5 = coast); far: how far the waves have faded into
// roughness (0 near, 1 far).
vec3 oceanColor(vec3 eyeRel, vec3 normal, vec3 upIn, float heightM, vec3 sun, vec3 hazeTr, vec3 hazeIn,
                float reliefDepthM, float far, float w) {
  // Depth (eq. 9's height): relief, or the coverage where the 20' relief
  // puts coastal water above sea level.
  float depth = max(reliefDepthM, (w - 0.5) * 120.0);
  vec3 up = normalize(upIn);
  vec3 v = normalize(-eyeRel);
  vec3 n = normalize(mix(normalize(normal), up, far * 0.7));
  float roughness = mix(0.06, 0.22, far);
  // Crest foam where the surface nears its highest, and the shore band
  // (eq. 11: water + sum f_i foam) pulsing with the surf.
  float crest = smoothstep(0.55, 0.95, heightM / max(uMaxVerticalM, 1e-3)) * (1.0 - far);
  float surf = 0.5 + 0.5 * sin(uTimeS * 0.9 - depth * 1.7);
  float shore = depthCurve(depth, 4.0, 0.3) * 0.55 * surf + depthCurve(depth, 1.2, 0.0) * 0.4;
  float foam = clamp(crest * 0.7 + shore, 0.0, 1.0);
  vec3 c = seaColorLit(n, v, up, uSunDir, sun, depth, roughness, foam);
  return toDisplay(c * hazeTr + hazeIn);
}
