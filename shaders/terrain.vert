// Terrain tile vertex: tile-relative ellipsoid point + height along the
// normal; the tile centre's offset from the eye is added as a uniform made
// in double on the CPU, so this stays precise at 1 m from the surface.
// Everything smooth over a cell is computed here, not per fragment: the
// relief normal (the 20' relief is no finer than the tiles' cells), the
// sunlight reaching the ground and the aerial perspective.
#include "geo_uv.glsl"
#include "sea_shading.glsl"

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
uniform vec3 uSunDir;
uniform float uEyeRadiusM;
layout(binding = 1) uniform sampler2D uElevation;
layout(binding = 2) uniform sampler2D uWater;

out vec3 vEyeRel;
out vec3 vNormal;
out vec2 vLonLat;
out vec3 vRelief;   // lit normal (relief-tilted)
out vec3 vSun;      // sunlight reaching the ground
out vec3 vHazeTr;   // aerial perspective: transmittance
out vec3 vHazeIn;   //                     in-scattered light
out float vDepthM;  // water depth from the relief (positive below the sea)
out float vHeightM; // height of this surface above the ellipsoid
out vec3 vSeaColor; // the distant sea's colour here (smooth: up, view, sun, depth)
out float vWater;   // water coverage at the vertex (B-spline, 0.5 = shore)

void main() {
#ifdef GEOCEAN_BARE
  float h = -uSkirtM * aSkirt;
#else
  vec2 uvE = geoUv(aLonLat, uElevationGeo);
  float elev;
#ifdef GEOCEAN_ELEVATION_TILES
  if (elevTilesDrawn()) elev = elevTiles(aLonLat, uElevation, uElevationGeo);
  else
#endif
  elev = textureLod(uElevation, uvE, 0.0).r;
  // The fragment shaders draw the shoreline at B-spline coverage 0.5; the
  // ground must already be under the sea wherever that can be water, or it
  // hides the wave grid (seen 2 m above the Strait of Gibraltar).
  float waterBSpline, water;
#ifdef GEOCEAN_WATER_TILES
  if (waterTilesDrawn()) {
    waterBSpline = waterTilesBSpline(aLonLat, uWater, uWaterGeo);
    water = max(waterTilesBilinear(aLonLat, uWater, uWaterGeo), waterBSpline);
  } else
#endif
  {  // the grid alone (no tiles, or a terrain tile clear of a regional layer)
    vec2 uvW = geoUv(aLonLat, uWaterGeo);
    waterBSpline = textureBSpline(uWater, uvW);
    water = max(textureLod(uWater, uvW, 0.0).r, waterBSpline);
  }
  // Land never dips below the sea, water areas sit under the wave grid.
  float land = max(elev, 0.0) * uExaggeration;
  float h = mix(land, -uSeaDropM, smoothstep(0.3, 0.45, water)) - uSkirtM * aSkirt;
#endif
  vec3 p = uTileOffset + aLocal + aNormal * h;
  vEyeRel = p;
  vNormal = aNormal;
  vLonLat = aLonLat;
  vHeightM = h;
#if defined(GEOCEAN_BARE) || defined(GEOCEAN_DEPTH_ONLY)  // the sun's depth map: the relief's height alone
  vRelief = aNormal, vSun = vec3(1.0), vHazeTr = vec3(1.0), vHazeIn = vec3(0.0), vDepthM = 0.0, vSeaColor = vec3(0.0), vWater = 0.0;
#else
  // Relief: the elevation gradient tilts the normal (east/north tangents).
  float hE, hW, hN, hS, cellNS, cellEW;
#ifdef GEOCEAN_ELEVATION_TILES
  if (elevTilesDrawn()) {
    // One texel of the streamed level either side.
    vec2 st = elevTilesStep();
    hE = elevTiles(aLonLat + vec2(st.x, 0.0), uElevation, uElevationGeo);
    hW = elevTiles(aLonLat - vec2(st.x, 0.0), uElevation, uElevationGeo);
    hN = elevTiles(aLonLat + vec2(0.0, st.y), uElevation, uElevationGeo);
    hS = elevTiles(aLonLat - vec2(0.0, st.y), uElevation, uElevationGeo);
    cellNS = st.y * 111320.0;
    cellEW = max(st.x * 111320.0 * cos(radians(aLonLat.y)), 1.0);
  } else
#endif
  {
    vec2 texel = 1.0 / vec2(textureSize(uElevation, 0));
    hE = textureLod(uElevation, uvE + vec2(texel.x, 0), 0.0).r, hW = textureLod(uElevation, uvE - vec2(texel.x, 0), 0.0).r;
    hN = textureLod(uElevation, uvE - vec2(0, texel.y), 0.0).r, hS = textureLod(uElevation, uvE + vec2(0, texel.y), 0.0).r;
    cellNS = abs(uElevationGeo.w) * texel.y * 111320.0;
    cellEW = max(abs(uElevationGeo.z) * texel.x * 111320.0 * cos(radians(aLonLat.y)), 1.0);
  }
  vec3 up = aNormal;
  vec3 east = normalize(cross(vec3(0.0, 0.0, 1.0), up) + vec3(1e-6, 0.0, 0.0));
  vec3 north = cross(up, east);
  vec2 grad = vec2(max(hE, 0.0) - max(hW, 0.0), max(hN, 0.0) - max(hS, 0.0)) /
              (2.0 * vec2(cellEW, cellNS)) * uExaggeration;
  vRelief = normalize(up - grad.x * east - grad.y * north);
  vSun = sunLight(dot(uSunDir, up));
  float eyeAlt = uEyeRadiusM - kEarthRadiusM;
  float t = hazeAmount(length(p), eyeAlt, max(h, 0.0));
  vHazeTr = exp(-t * vec3(1.2, 2.0, 3.6));
  vHazeIn = vec3(0.30, 0.45, 0.80) * (vSun + vec3(0.02)) * 0.3 * (1.0 - vHazeTr);
  vDepthM = -elev;
  vWater = waterBSpline;  // the shoreline's own filter
  // The 20' relief puts coastal cells above the sea: near the shore take the
  // depth from the coverage instead (about 60 m at full coverage). Per
  // vertex: on llvmpipe this shading per terrain pixel cost more than the
  // imagery, and its inputs vary over a cell no faster than the haze.
#ifdef GEOCEAN_NO_SEA_SHADING
  vSeaColor = vec3(0.0);  // not read (terrain.frag)
#else
  float depth = max(vDepthM, (water - 0.5) * 120.0);
  vSeaColor = seaColorLit(up, normalize(-p), up, uSunDir, vSun, depth, 0.18, 0.0);
#endif
#endif
#ifdef GEOCEAN_CLIP_SEA
  // The mirrored pass of a reflection: only what stands above the sea is
  // reflected (water areas lie 30 m under it, skirts hang below).
  gl_ClipDistance[0] = h + 0.5;
#endif
  gl_Position = uViewProj * vec4(p, 1.0);
}
