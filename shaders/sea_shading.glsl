// Shading of the sea surface, shared by the wave-grid ocean and by the
// terrain's distant water: Fresnel reflection of the sky, a water body
// colour from depth (shallow water turns turquoise, deep water dark blue),
// sun specular widened by `roughness` (distant waves become roughness
// instead of aliasing geometry), and foam.
#include "atmosphere.glsl"

float fresnelSchlick(float cosTheta) {
  float x = 1.0 - clamp(cosTheta, 0.0, 1.0), x2 = x * x;
  return 0.02 + 0.98 * x2 * x2 * x;
}

// depthM: water depth below the sea (positive). n: surface normal, v: unit
// vector from the surface towards the eye, up: local vertical; sun =
// sunLight(dot(sunDir, up)), computed once per vertex by the callers. The
// reflected sky is the one seen from near the sea (the view from orbit
// reflects the same dome).
vec3 seaColorLit(vec3 n, vec3 v, vec3 up, vec3 sunDir, vec3 sun, float depthM, float roughness, float foam) {
  float ndv = max(dot(n, v), 1e-3);
  vec3 r = reflect(-v, n);
  // Reflections from below the horizon see the sea, not the sky.
  r = normalize(r + up * max(0.0, -dot(r, up)) * 1.05);
  float F = fresnelSchlick(ndv);
  vec3 sky = skyLow(r, up, sunDir, sun);
  vec3 light = sun + vec3(0.03);
  // Beer-Lambert tint: shallow water shows the bright sea floor.
  float shallow = exp(-max(depthM, 0.0) / 12.0);
  vec3 deep = vec3(0.004, 0.025, 0.06);
  vec3 body = mix(deep, vec3(0.05, 0.28, 0.30), shallow) * (0.35 + 0.65 * max(dot(sunDir, up), 0.0)) * light;
  vec3 c = mix(body, sky, F);
  // Sun glint: normalised Blinn-Phong whose exponent falls with roughness.
  vec3 hv = normalize(sunDir + v);
  float a2 = max(roughness * roughness, 1e-4);
  float spec = pow(max(dot(n, hv), 0.0), 2.0 / a2 - 2.0) / (3.14159 * a2);
  c += sun * spec * F * 0.25 * step(0.0, dot(sunDir, n));
  vec3 foamColor = vec3(0.85, 0.9, 0.92) * (light * 0.9 + 0.1);
  return mix(c, foamColor, clamp(foam, 0.0, 1.0));
}

vec3 seaColor(vec3 n, vec3 v, vec3 up, vec3 sunDir, float depthM, float roughness, float foam) {
  return seaColorLit(n, v, up, sunDir, sunLight(dot(sunDir, up)), depthM, roughness, foam);
}
