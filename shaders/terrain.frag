// Terrain: Blue Marble imagery lit by the sun with relief shading from the
// elevation raster; water (coverage >= 0.5, anti-aliased over one pixel)
// shaded as distant sea; aerial perspective. The smooth terms (relief
// normal, sunlight, haze) come interpolated from the vertex shader.
#include "geo_uv.glsl"
#include "atmosphere.glsl"

in vec3 vEyeRel;
in vec3 vNormal;
in vec2 vLonLat;
in vec3 vRelief;
in vec3 vSun;
in vec3 vHazeTr;
in vec3 vHazeIn;
in float vDepthM;
in vec3 vSeaColor;
in float vWater;

uniform vec4 uImageryGeo;
uniform vec4 uWaterGeo;
uniform vec3 uSunDir;
uniform int uSeaShading;  // 0: no sea shading; 1: water shaded as distant sea
layout(binding = 0) uniform sampler2D uImagery;
layout(binding = 2) uniform sampler2D uWater;
// The user's imagery layers (--imagery), first on top: premultiplied sRGB,
// alpha 0 where a layer has no data or outside it (its border). Four named
// samplers, not an array: llvmpipe's LLVM 15 crashed compiling the indexed
// array in the streamed-water variant. Their count is the program's
// (TerrainRenderer): llvmpipe runs both sides of a branch on a uniform, so
// an uncalled layer still cost every pixel its textureGrad.
#ifndef GEOCEAN_IMAGERY_LAYERS
#define GEOCEAN_IMAGERY_LAYERS 0
#endif
uniform vec4 uImageryLayerGeo[4];
layout(binding = 8) uniform sampler2D uImageryLayer0;
layout(binding = 9) uniform sampler2D uImageryLayer1;
layout(binding = 10) uniform sampler2D uImageryLayer2;
layout(binding = 11) uniform sampler2D uImageryLayer3;

// Layer `geo` over `below`. Longitude is taken relative to the layer's
// centre in [-180, 180): a layer across the antimeridian works and the wrap
// falls opposite the layer (outside it). The gradients come from the
// unwrapped coordinates, so the wrap never changes the mip level.
vec3 overImagery(sampler2D tex, vec4 geo, vec3 below) {
  vec2 uv = geoUv(vLonLat, geo);
  float d = vLonLat.x - (geo.x + 0.5 * geo.z);
  d -= 360.0 * floor(d / 360.0 + 0.5);
  vec4 s = textureGrad(tex, vec2(0.5 + d / geo.z, uv.y), dFdx(uv), dFdy(uv));
  return below * (1.0 - s.a) + s.rgb;
}

layout(location = 0) out vec4 outColor;

void main() {
  vec3 up = normalize(vNormal);
  vec3 albedo = texture(uImagery, geoUv(vLonLat, uImageryGeo)).rgb;
#if GEOCEAN_IMAGERY_LAYERS > 3
  albedo = overImagery(uImageryLayer3, uImageryLayerGeo[3], albedo);
#endif
#if GEOCEAN_IMAGERY_LAYERS > 2
  albedo = overImagery(uImageryLayer2, uImageryLayerGeo[2], albedo);
#endif
#if GEOCEAN_IMAGERY_LAYERS > 1
  albedo = overImagery(uImageryLayer1, uImageryLayerGeo[1], albedo);
#endif
#if GEOCEAN_IMAGERY_LAYERS > 0
  albedo = overImagery(uImageryLayer0, uImageryLayerGeo[0], albedo);
#endif
  float sunMu = dot(uSunDir, up);
  // Skylight fades out on the night side.
  vec3 c = albedo * (vSun * max(dot(normalize(vRelief), uSunDir), 0.0) * 1.6 +
                     vec3(0.04, 0.045, 0.05) * smoothstep(-0.25, 0.1, sunMu));
#ifdef GEOCEAN_UNDER_OCEAN
  // The ocean layer draws open water and the anti-aliased shoreline over
  // this; terrain water shows only where the ocean's coverage fades (the
  // limb, the coast's one-pixel edge), so per-vertex coverage is enough and
  // spares every terrain pixel the B-spline (on llvmpipe a third of the
  // terrain's cost).
  c = mix(c, vSeaColor, smoothstep(0.4, 0.6, vWater));
#elif !defined(GEOCEAN_NO_SEA_SHADING)
  // Not in the mirrored pass (GEOCEAN_NO_SEA_SHADING: uSeaShading is 0
  // there, and llvmpipe ran the streamed coverage's B-spline per pixel anyway).
  if (uSeaShading != 0) {
    // Water coverage: 0.5 is the shoreline; smooth over a pixel (B-spline
    // magnified, the mipmapped average minified).
    float w;
#ifdef GEOCEAN_WATER_TILES
    // A uniform branch (per terrain tile): derivatives stay defined.
    if (waterTilesDrawn()) w = waterTilesAuto(vLonLat, uWater, uWaterGeo);
    else
#endif
    w = textureBSplineAuto(uWater, geoUv(vLonLat, uWaterGeo));
    float aa = clamp(fwidth(w) * 0.75, 1e-3, 0.5);
    float waterAmt = smoothstep(0.5 - aa, 0.5 + aa, w);
    // Distant sea (no wave geometry, slopes as roughness), shaded per vertex.
    c = mix(c, vSeaColor, waterAmt);
  }
#endif
  outColor = vec4(toDisplay(c * vHazeTr + vHazeIn), 1.0);
}
