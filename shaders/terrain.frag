// Terrain: Blue Marble imagery lit by the sun with relief shading from the
// elevation raster; water (coverage >= 0.5, anti-aliased over one pixel)
// shaded as distant sea; aerial perspective.
#include "geo_uv.glsl"
#include "sea_shading.glsl"

in vec3 vEyeRel;
in vec3 vNormal;
in vec2 vLonLat;
in float vHeightM;

uniform vec4 uImageryGeo;
uniform vec4 uElevationGeo;
uniform vec4 uWaterGeo;
uniform float uExaggeration;
uniform vec3 uSunDir;
uniform vec3 uEyeDir;
uniform float uEyeRadiusM;
uniform int uSeaShading;  // 0: an ocean layer covers the water
layout(binding = 0) uniform sampler2D uImagery;
layout(binding = 1) uniform sampler2D uElevation;
layout(binding = 2) uniform sampler2D uWater;

layout(location = 0) out vec4 outColor;

void main() {
  vec3 up = normalize(vNormal);
  vec3 v = normalize(-vEyeRel);
  float dist = length(vEyeRel);
  float eyeAlt = uEyeRadiusM - kEarthRadiusM;

  // Relief: the elevation gradient tilts the normal (east/north tangents).
  vec2 uvE = geoUv(vLonLat, uElevationGeo);
  vec2 texel = 1.0 / vec2(textureSize(uElevation, 0));
  float hE = texture(uElevation, uvE + vec2(texel.x, 0)).r, hW = texture(uElevation, uvE - vec2(texel.x, 0)).r;
  float hN = texture(uElevation, uvE - vec2(0, texel.y)).r, hS = texture(uElevation, uvE + vec2(0, texel.y)).r;
  float cellNS = abs(uElevationGeo.w) * texel.y * 111320.0;
  float cellEW = max(abs(uElevationGeo.z) * texel.x * 111320.0 * cos(radians(vLonLat.y)), 1.0);
  vec3 east = normalize(cross(vec3(0.0, 0.0, 1.0), up) + vec3(1e-6, 0.0, 0.0));
  vec3 north = cross(up, east);
  vec2 grad = vec2(max(hE, 0.0) - max(hW, 0.0), max(hN, 0.0) - max(hS, 0.0)) /
              (2.0 * vec2(cellEW, cellNS)) * uExaggeration;
  vec3 n = normalize(up - grad.x * east - grad.y * north);

  vec3 albedo = texture(uImagery, geoUv(vLonLat, uImageryGeo)).rgb;
  float sunMu = dot(uSunDir, up);
  vec3 sun = sunLight(sunMu);
  // Skylight fades out on the night side.
  vec3 land = albedo * (sun * max(dot(n, uSunDir), 0.0) * 1.6 + vec3(0.04, 0.045, 0.05) * smoothstep(-0.25, 0.1, sunMu));

  vec3 c = land;
  if (uSeaShading != 0) {
    // Water coverage: 0.5 is the shoreline; smooth over a pixel. Magnified:
    // B-spline (smooth shoreline); minified: the mipmapped average.
    vec2 uvW = geoUv(vLonLat, uWaterGeo);
    float texelsPerPixel = length(fwidth(uvW) * vec2(textureSize(uWater, 0)));
    float w = texelsPerPixel < 1.0 ? textureBSpline(uWater, uvW) : texture(uWater, uvW).r;
    float aa = clamp(fwidth(w) * 0.75, 1e-3, 0.5);
    float waterAmt = smoothstep(0.5 - aa, 0.5 + aa, w);
    // The 20' relief puts coastal cells above the sea: near the shore take
    // the depth from the coverage instead (about 60 m at full coverage).
    float depth = max(-texture(uElevation, uvE).r, (w - 0.5) * 120.0);
    // Distant sea: no wave geometry, the waves' slopes become roughness.
    if (waterAmt > 0.0) c = mix(land, seaColor(up, v, up, uSunDir, depth, 0.18, 0.0, eyeAlt, uEyeRadiusM), waterAmt);
  }
  c = applyHaze(c, dist, eyeAlt, max(vHeightM, 0.0), up, uSunDir);
  outColor = vec4(toDisplay(c), 1.0);
}
