// Depth-only pass over the terrain (colour writes off): keeps the depth of
// open water that the ocean layer will cover, discards the rest (land,
// coasts, water the ocean grid may skip). The terrain's colour pass then
// fails the depth test there and does not shade what the sea covers.
#include "geo_uv.glsl"

in vec3 vEyeRel;
in vec3 vNormal;
in vec2 vLonLat;

uniform vec4 uWaterGeo;
uniform float uOceanCellPx;       // the ocean layer's grid cell, pixels
uniform float uOceanCellRadians;  // the same as an angle
layout(binding = 2) uniform sampler2D uWater;

void main() {
  // Only where the ocean's flat cells stay above the terrain's water (30 m
  // under the sea): their sag L^2/(4R) is under 10 m, or ocean.vert raises
  // them (elevation angle with sin >= 0.5).
  float sinElev = dot(normalize(-vEyeRel), normalize(vNormal));
  float cellM = length(vEyeRel) * uOceanCellRadians / max(sinElev, 1e-3);
  if (sinElev < 0.5 && cellM * cellM / (4.0 * 6.3e6) > 10.0) discard;
  // All water within the B-spline's reach (2 texels: mip 2 at least) and
  // within one ocean cell of the pixel (the mip of the pixel's footprint +
  // log2(cell) + 1): the ocean grid draws the cells here (their corners are
  // water) with coverage 1.
  vec2 uvW = geoUv(vLonLat, uWaterGeo);
  float lod = max(textureQueryLod(uWater, uvW).y + log2(uOceanCellPx) + 1.0, 2.0);
  if (textureLod(uWater, uvW, lod).r < 1.0) discard;
}
