// Depth-only pass over the terrain (colour writes off): keeps the depth of
// open water that the ocean layer will cover, discards the rest (land,
// coasts, water the ocean grid may skip). The terrain's colour pass then
// fails the depth test there and does not shade what the sea covers.
#include "geo_uv.glsl"

in vec3 vEyeRel;
in vec3 vNormal;
in vec2 vLonLat;
in float vHeightM;

uniform vec4 uWaterGeo;
uniform float uOceanCellPx;       // the ocean layer's grid cell, pixels
uniform float uOceanCellRadians;  // the same as an angle
uniform float uSeaDropM;          // the terrain's water lies this far under the sea
layout(binding = 2) uniform sampler2D uWater;

void main() {
  // Only where the ocean's flat cells stay above the terrain's water (30 m
  // under the sea): their sag L^2/(4R) is under 10 m, or ocean.vert raises
  // them (elevation angle with sin >= 0.5).
  float sinElev = dot(normalize(-vEyeRel), normalize(vNormal));
  float cellM = length(vEyeRel) * uOceanCellRadians / max(sinElev, 1e-3);
  if (sinElev < 0.5 && cellM * cellM / (4.0 * 6.3e6) > 10.0) discard;
  // The ground here must lie well under the sea (the coastal ramp of
  // terrain.vert can still be above it), or the ocean would fail against it.
  if (vHeightM > -0.5 * uSeaDropM) discard;
  // One texture tap (this pass covers the whole terrain; 4 B-spline taps
  // here cost as much as the terrain's own shading).
  vec2 uvW = geoUv(vLonLat, uWaterGeo);
  float lambda = textureQueryLod(uWater, uvW).y;
  if (lambda < 0.0) {
    // Magnified: the ocean's B-spline coverage is opaque (>= 0.5 + aa, aa
    // tiny) wherever the mip-1 average over the same 4 x 4 texels is >= 0.75
    // (worst case, outer ring all land: B-spline >= 0.69); its cell is drawn
    // (the grid keeps cells within two mask cells of water).
    if (textureLod(uWater, uvW, 1.0).r < 0.75) discard;
  } else {
    // Minified: all water within one ocean cell of the pixel (the mip of
    // the footprint + log2(cell) + 1), so the grid draws this cell (its
    // corners are water) with coverage 1; at least mip 2.
    float lod = max(lambda + log2(uOceanCellPx) + 1.0, 2.0);
    if (textureLod(uWater, uvW, lod).r < 1.0) discard;
  }
}
