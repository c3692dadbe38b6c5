// Terrain tile vertex: tile-relative ellipsoid point + height along the
// normal; the tile centre's offset from the eye is added as a uniform made
// in double on the CPU, so this stays precise at 1 m from the surface.
#include "geo_uv.glsl"

layout(location = 0) in vec3 aLocal;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aLonLat;
layout(location = 3) in float aSkirt;

uniform mat4 uViewProj;
uniform vec3 uTileOffset;
uniform float uSkirtM;
uniform float uExaggeration;
uniform float uSeaDropM;
uniform vec4 uElevationGeo;
uniform vec4 uWaterGeo;
layout(binding = 1) uniform sampler2D uElevation;
layout(binding = 2) uniform sampler2D uWater;

out vec3 vEyeRel;
out vec3 vNormal;
out vec2 vLonLat;
out float vHeightM;

void main() {
#ifdef GEOCEAN_BARE
  float h = -uSkirtM * aSkirt;
#else
  float elev = textureLod(uElevation, geoUv(aLonLat, uElevationGeo), 0.0).r;
  vec2 uvW = geoUv(aLonLat, uWaterGeo);
  // The fragment shaders draw the shoreline at B-spline coverage 0.5; the
  // ground must already be under the sea wherever that can be water, or it
  // hides the wave grid (seen 2 m above the Strait of Gibraltar).
  float water = max(textureLod(uWater, uvW, 0.0).r, textureBSpline(uWater, uvW));
  // Land never dips below the sea, water areas sit under the wave grid.
  float land = max(elev, 0.0) * uExaggeration;
  float h = mix(land, -uSeaDropM, smoothstep(0.3, 0.45, water)) - uSkirtM * aSkirt;
#endif
  vec3 p = uTileOffset + aLocal + aNormal * h;
  vEyeRel = p;
  vNormal = aNormal;
  vLonLat = aLonLat;
  vHeightM = h;
  gl_Position = uViewProj * vec4(p, 1.0);
}
