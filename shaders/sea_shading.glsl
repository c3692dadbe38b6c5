// Shading of the sea surface, shared by the wave-grid ocean and by the
// terrain's distant water: Fresnel reflection of the sky, a water body
// colour from depth (shallow water turns turquoise, deep water dark blue),
// sun specular widened by `roughness` (distant waves become roughness
// instead of aliasing geometry), and foam.
#include "atmosphere.glsl"

float fresnelSchlick(float cosTheta) {
  return 0.02 + 0.98 * pow(1.0 - clamp(cosTheta, 0.0, 1.0), 5.0);
}

// depthM: water depth below the sea (positive). n: surface normal, v: unit
// vector from the surface towards the eye, up: local vertical.
vec3 seaColor(vec3 n, vec3 v, vec3 up, vec3 sunDir, float depthM, float roughness, float foam,
              float eyeAltM, float eyeRadiusM) {
  float ndv = max(dot(n, v), 1e-3);
  vec3 r = reflect(-v, n);
  // Reflections from below the horizon see the sea, not the sky.
  r = normalize(r + up * max(0.0, -dot(r, up)) * 1.05);
  float F = fresnelSchlick(ndv);
  vec3 sky = skyRadiance(r, up, sunDir, min(eyeAltM, 20000.0), eyeRadiusM, 0.0);
  vec3 light = sunLight(dot(sunDir, up)) + vec3(0.03);
  // Beer-Lambert tint: shallow water shows the bright sea floor.
  float shallow = exp(-max(depthM, 0.0) / 12.0);
  vec3 deep = vec3(0.004, 0.025, 0.06);
  vec3 body = mix(deep, vec3(0.05, 0.28, 0.30), shallow) * (0.35 + 0.65 * max(dot(sunDir, up), 0.0)) * light;
  vec3 c = mix(body, sky, F);
  // Sun glint: normalised Blinn-Phong whose exponent falls with roughness.
  vec3 hv = normalize(sunDir + v);
  float a2 = roughness * roughness;
  float spec = pow(max(dot(n, hv), 0.0), 2.0 / max(a2, 1e-4) - 2.0) / (3.14159 * max(a2, 1e-4));
  c += sunLight(dot(sunDir, up)) * spec * F * 0.25 * step(0.0, dot(sunDir, n));
  vec3 foamColor = vec3(0.85, 0.9, 0.92) * (light * 0.9 + 0.1);
  return mix(c, foamColor, clamp(foam, 0.0, 1.0));
}
