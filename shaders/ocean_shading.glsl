// The ocean surface's colour (display-ready), shared by ocean.frag and, for
// far open water shaded per vertex, by ocean.vert: depth colour, Fresnel
// sky, the sun's glitter from the slopes not drawn (Cox-Munk microfacets),
// whitecaps and the shore foam band of paper 000 (eq. 9-11), then the
// aerial perspective.
// Callers declare uSunDir before including this.
#include "sea_shading.glsl"

uniform float uTimeS;
// Whitecaps (OceanRenderer): crests above foamM (ocean.vert: the height the
// waves it draws exceed on a fraction W = 3.84e-6 U^3.41 of the sea, Monahan
// & O'Muircheartaigh 1980), blended over uFoamSoftM either side; where the
// waves have faded into roughness, that mean cover W itself.
uniform float uFoamSoftM;
uniform float uWhitecapCover;

// Paper 000 eq. 10: blend factor of one depth curve.
float depthCurve(float depthM, float tauMin, float tauMax) {
  return clamp((tauMin - depthM) / (tauMin - tauMax), 0.0, 1.0);
}

// w: water coverage (0.5 = coast); far: how far the waves have faded into
// roughness (0 near, 1 far); mss: the mean square slope not in `normal`
// (ocean.vert: the spectrum's waves not drawn, and the slope the fade removes).
vec3 oceanColor(vec3 eyeRel, vec3 normal, vec3 upIn, float heightM, vec3 sun, vec3 hazeTr, vec3 hazeIn,
                float reliefDepthM, float far, float mss, float foamM, float w) {
  // Depth (eq. 9's height): relief, or the coverage where the 20' relief
  // puts coastal water above sea level.
  float depth = max(reliefDepthM, (w - 0.5) * 120.0);
  vec3 up = normalize(upIn);
  vec3 v = normalize(-eyeRel);
  vec3 n = normalize(mix(normalize(normal), up, far * 0.7));
  // Whitecaps on the highest crests, and the shore band (eq. 11: water +
  // sum f_i foam) pulsing with the surf.
  float crest = mix(smoothstep(foamM - uFoamSoftM, foamM + uFoamSoftM, heightM), uWhitecapCover, far);
  float surf = 0.5 + 0.5 * sin(uTimeS * 0.9 - depth * 1.7);
  float shore = depthCurve(depth, 4.0, 0.3) * 0.55 * surf + depthCurve(depth, 1.2, 0.0) * 0.4;
  float foam = clamp(crest + shore, 0.0, 1.0);
  vec3 c = seaColorMss(n, v, up, uSunDir, sun, depth, mss, foam);
  return toDisplay(c * hazeTr + hazeIn);
}
