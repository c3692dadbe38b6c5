// lon/lat in degrees -> texture coordinates of a global equirectangular
// raster described by geo = (originLonDeg, originLatDeg, lonSpanDeg, latSpanDeg).
vec2 geoUv(vec2 lonLatDeg, vec4 geo) {
  return vec2((lonLatDeg.x - geo.x) / geo.z, (lonLatDeg.y - geo.y) / geo.w);
}

// lonDeg + 360 k nearest centreDeg (raster::lonNear): a regional layer
// across 180 deg (179.5 .. 180.5) reads -179.9 as 180.1, its own longitude.
// Near the layer the sum is exact (both in [128, 256), 360 a multiple of
// their ulp); within 180 deg of the centre it adds 0.
float lonNear(float lonDeg, float centreDeg) { return lonDeg + 360.0 * roundEven((centreDeg - lonDeg) / 360.0); }

// Cubic B-spline filtered sample from 4 bilinear fetches (Sigg & Hadwiger,
// GPU Gems 2 ch. 20). Binary masks filtered this way have a smooth 0.5
// contour instead of the bilinear filter's staircase of rounded cells.
float textureBSpline(sampler2D tex, vec2 uv) {
  vec2 size = vec2(textureSize(tex, 0));
  vec2 p = uv * size - 0.5;
  vec2 f = fract(p);
  vec2 f2 = f * f, f3 = f2 * f;
  vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0;
  vec2 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
  vec2 w2 = (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0;
  vec2 w3 = f3 / 6.0;
  vec2 g0 = w0 + w1, g1 = w2 + w3;
  vec2 h0 = (w1 / g0 - 1.0 + floor(p) + 0.5) / size;
  vec2 h1 = (w3 / g1 + 1.0 + floor(p) + 0.5) / size;
  float a = textureLod(tex, vec2(h0.x, h0.y), 0.0).r, b = textureLod(tex, vec2(h1.x, h0.y), 0.0).r;
  float c = textureLod(tex, vec2(h0.x, h1.y), 0.0).r, d = textureLod(tex, vec2(h1.x, h1.y), 0.0).r;
  return mix(mix(a, b, g1.x), mix(c, d, g1.x), g1.y);
}

// The same B-spline from the 16 texels themselves (4 textureGather), with
// the weights in float: the filtering unit's bilinear weights have only 8
// bits of subtexel precision (llvmpipe, and GPUs alike), so the 4-tap form
// is a staircase of 1/256-texel steps, 36 m for the 5' mask: magnified, its
// 0.5 contour showed as steps along the ocean's shoreline. Any stage.
float textureBSplineGather(sampler2D tex, vec2 uv) {
  vec2 size = vec2(textureSize(tex, 0));
  vec2 p = uv * size - 0.5;
  vec2 i = floor(p);
  vec2 f = p - i;
  vec2 f2 = f * f, f3 = f2 * f;
  vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0;
  vec2 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
  vec2 w2 = (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0;
  vec2 w3 = f3 / 6.0;
  // A gather at the corner (a + 1, b + 1) returns texels x: (a, b+1),
  // y: (a+1, b+1), z: (a+1, b), w: (a, b).
  vec4 g00 = textureGather(tex, (i + vec2(0.0, 0.0)) / size, 0);
  vec4 g10 = textureGather(tex, (i + vec2(2.0, 0.0)) / size, 0);
  vec4 g01 = textureGather(tex, (i + vec2(0.0, 2.0)) / size, 0);
  vec4 g11 = textureGather(tex, (i + vec2(2.0, 2.0)) / size, 0);
  return dot(g00, vec4(w0.x * w1.y, w1.x * w1.y, w1.x * w0.y, w0.x * w0.y)) +
         dot(g10, vec4(w2.x * w1.y, w3.x * w1.y, w3.x * w0.y, w2.x * w0.y)) +
         dot(g01, vec4(w0.x * w3.y, w1.x * w3.y, w1.x * w2.y, w0.x * w2.y)) +
         dot(g11, vec4(w2.x * w3.y, w3.x * w3.y, w3.x * w2.y, w2.x * w2.y));
}

#ifdef GEOCEAN_FRAGMENT_STAGE
// Magnified: the float-weight B-spline; minified: the mipmapped average
// (implicit level of detail). Fragment shaders only.
float textureBSplineAuto(sampler2D tex, vec2 uv) {
  float b = textureBSplineGather(tex, uv);
  float texelsPerPixel = length(fwidth(uv) * vec2(textureSize(tex, 0)));
  return texelsPerPixel < 1.0 ? b : texture(tex, uv).r;
}
#endif

// The four cubic B-spline weights of taps -1, 0, 1, 2 at fraction f (the
// same expressions the 4 x 4 coverage reads of the tiles and pages use).
vec4 bsplineWeights4(float f) {
  float f2 = f * f, f3 = f2 * f;
  return vec4((1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0, (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0,
              (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0, f3 / 6.0);
}

// True when the 4 x 4 texels round p (a level's texel coordinates, centres
// at integers) all lie past the edge of a regional level of size `size`:
// no texel of the layer is within a filter's reach, the grid answers alone.
bool levelClear(vec2 p, ivec2 size) {
  ivec2 i = ivec2(floor(p));
  return any(lessThan(i + 2, ivec2(0))) || any(greaterThanEqual(i - 1, size));
}

// Streamed levels' texel indices without integer division: llvmpipe has
// no SIMD one on x86 (each lane's is a scalar instruction, dozens per
// pixel or vertex). The wrap as ((x % w) + w) % w by a float floor, exact
// for |x| < 2^22 ((x + 0.5) / w lies at least 0.5 / w from an integer, far
// above float division's error).
int texelWrap(int x, int w) { return x - w * int(floor((float(x) + 0.5) / float(w))); }
ivec4 texelWrap(ivec4 x, int w) { return x - w * ivec4(floor((vec4(x) + 0.5) / float(w))); }

#if defined(GEOCEAN_WATER_TILES) || defined(GEOCEAN_ELEVATION_TILES)
// Texel g of a streamed level (host tiles: water or elevation) in its 2 x 2
// block of pool layers: (x, y) in the tile with its border, and the layer.
// g comes back wrapped or clamped into the level.
ivec3 blockTexel(inout ivec2 g, ivec3 level, ivec4 block, ivec4 slots) {
  int w = level.x;
  g.x = level.z != 0 ? texelWrap(g.x, w) : clamp(g.x, 0, w - 1);
  g.y = clamp(g.y, 0, level.y - 1);
  int T = block.w;
  ivec2 t = g >> findMSB(T);  // T a power of two, g >= 0
  int dx = t.x - block.x;
  if (dx < 0) dx += block.z;  // wrapped past the antimeridian
  int dy = t.y - block.y;
  // Outside the block (not reached: the level is chosen so the tile and the
  // filter's reach fit in it): its nearest edge texel, from the border.
  ivec2 local = g & (T - 1);
  if (dx < 0 || dx > 1) {
    local.x = dx < 0 ? -1 : T;
    dx = clamp(dx, 0, 1);
  }
  if (dy < 0 || dy > 1) {
    local.y = dy < 0 ? -1 : T;
    dy = clamp(dy, 0, 1);
  }
  int layer = dy == 0 ? (dx == 0 ? slots.x : slots.y) : (dx == 0 ? slots.z : slots.w);
  return ivec3(local + 1, layer);  // + 1: the tile's border
}
#endif

#ifdef GEOCEAN_WATER_TILES
// Water coverage streamed as pyramid tiles (globe/render/TilePool): the
// terrain tile being drawn lies inside a 2 x 2 block of tiles of one level,
// resident in layers of a texture array; texels are fetched and filtered
// here (the same B-spline weights as textureBSplineGather, in float).
layout(binding = 5) uniform sampler2DArray uWaterPool;
uniform ivec4 uWaterSlots;    // layers of the block: (x0 y0, x1 y0, x0 y1, x1 y1)
uniform ivec4 uWaterBlock;    // first tile (x, y), tiles across the level, tile size
uniform ivec3 uWaterLevel;    // level width and height in texels; 1 if longitude wraps
uniform vec4 uWaterLevelGeo;  // origin lon, origin lat, lon step, lat step of a level texel

// A regional layer (GEOCEAN_WATER_REGIONAL; a global one's programs are
// exactly as before): a terrain tile clear of it draws the water grid
// alone (TerrainRenderer::bindBlock sets no slots, -1), exactly as without
// tiles; inside the block, texels past the layer's edge and its nodata
// (NaN) take the grid's coverage at the texel's centre (one bilinear
// fetch: only texels within the B-spline's reach of the edge, or nodata,
// ever need it), so the coast runs on into the grid's without a gap.
#ifdef GEOCEAN_WATER_TILES_LAYERS
// Several streamed masks on the terrain (world::streamedWaterLayers, 2 to
// 4), in answer order: layer 0 is uWater* above, layer k >= 1 element
// k - 1 of the uWaterB* arrays (its pool on unit 15 + k, its 2 x 2 block as
// layer 0's; slots -1 where the terrain tile is clear of it). As the ocean's pages (waterPagesChain):
// the first layer with a texel of its own within the filter's reach draws
// the point; its texels past its edge or without data (NaN) take the next
// layers' texel at the pixel (one lookup a pixel), the grid past the last.
layout(binding = 16) uniform sampler2DArray uWaterPoolB1;
#if GEOCEAN_WATER_TILES_LAYERS > 2
layout(binding = 17) uniform sampler2DArray uWaterPoolB2;
#endif
#if GEOCEAN_WATER_TILES_LAYERS > 3
layout(binding = 18) uniform sampler2DArray uWaterPoolB3;
#endif
uniform ivec4 uWaterBSlots[3], uWaterBBlock[3];
uniform ivec3 uWaterBLevel[3];
uniform vec4 uWaterBLevelGeo[3];

// Only the pool's fetch is spelled out per layer (a constant index selects one sampler).
ivec4 wSlots(int k) { return k == 0 ? uWaterSlots : uWaterBSlots[k - 1]; }
ivec4 wBlock(int k) { return k == 0 ? uWaterBlock : uWaterBBlock[k - 1]; }
ivec3 wLevel(int k) { return k == 0 ? uWaterLevel : uWaterBLevel[k - 1]; }
vec4 wGeo(int k) { return k == 0 ? uWaterLevelGeo : uWaterBLevelGeo[k - 1]; }
float wFetch(int k, ivec3 at) {
#if GEOCEAN_WATER_TILES_LAYERS > 2
  if (k == 2) return texelFetch(uWaterPoolB2, at, 0).r;
#endif
#if GEOCEAN_WATER_TILES_LAYERS > 3
  if (k == 3) return texelFetch(uWaterPoolB3, at, 0).r;
#endif
  return k == 1 ? texelFetch(uWaterPoolB1, at, 0).r : texelFetch(uWaterPool, at, 0).r;
}

bool wDrawn(int k) { return wSlots(k).x >= 0; }

// Continuous texel coordinates of layer k's bound level (waterTexelPos).
vec2 wPos(int k, vec2 lonLatDeg) {
  vec4 G = wGeo(k);
  ivec3 L = wLevel(k);
  if (L.z == 0) lonLatDeg.x = lonNear(lonLatDeg.x, G.x + 0.5 * float(L.x) * G.z);
  return vec2((lonLatDeg.x - G.x) / G.z, (lonLatDeg.y - G.y) / G.w) - 0.5;
}

// Texel g of layer k: true, with v, inside the level and not NaN.
bool wOwn(int k, ivec2 g, out float v) {
  v = 0.0;
  ivec3 L = wLevel(k);
  if (L.z == 0 && (any(lessThan(g, ivec2(0))) || any(greaterThanEqual(g, L.xy)))) return false;
  v = wFetch(k, blockTexel(g, L, wBlock(k), wSlots(k)));
  return !isnan(v);
}

// The layers from j on at lon/lat c: the first whose texel there has
// data, else the grid's. Spelled out per layer (a constant index selects
// one pool; a loop's made llvmpipe fetch from each).
float wBelow(int j, vec2 c, sampler2D grid, vec4 gridGeo) {
  float v;
  if (j <= 1 && wDrawn(1) && wOwn(1, ivec2(floor(wPos(1, c) + 0.5)), v)) return v;
#if GEOCEAN_WATER_TILES_LAYERS > 2
  if (j <= 2 && wDrawn(2) && wOwn(2, ivec2(floor(wPos(2, c) + 0.5)), v)) return v;
#endif
#if GEOCEAN_WATER_TILES_LAYERS > 3
  if (j <= 3 && wDrawn(3) && wOwn(3, ivec2(floor(wPos(3, c) + 0.5)), v)) return v;
#endif
  return textureLod(grid, geoUv(c, gridGeo), 0.0).r;
}

// Texel g of layer k, or `below` (the layers' below at the pixel: one
// lookup a pixel, as the ocean's chTexel).
float wTexel(int k, ivec2 g, float below, inout bool own) {
  float v;
  if (wOwn(k, g, v)) {
    own = true;
    return v;
  }
  return below;
}

// Layer k drawn here: bound and a texel within the filter's reach.
bool wReaches(int k, vec2 p) { return wDrawn(k) && (wLevel(k).z != 0 || !levelClear(p, wLevel(k).xy)); }

float wLayerBSpline(int k, vec2 p, float below, inout bool own) {
  vec2 i = floor(p);
  vec2 f = p - i;
  vec4 wx = bsplineWeights4(f.x), wy = bsplineWeights4(f.y);
  ivec2 g = ivec2(i) - 1;
  float s = 0.0;
  for (int y = 0; y < 4; ++y) {
    vec4 row = vec4(wTexel(k, g + ivec2(0, y), below, own), wTexel(k, g + ivec2(1, y), below, own),
                    wTexel(k, g + ivec2(2, y), below, own), wTexel(k, g + ivec2(3, y), below, own));
    s += wy[y] * dot(row, wx);
  }
  return s;
}

float wLayerBilinear(int k, vec2 p, float below, inout bool own) {
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 g = ivec2(i);
  return mix(mix(wTexel(k, g, below, own), wTexel(k, g + ivec2(1, 0), below, own), f.x),
             mix(wTexel(k, g + ivec2(0, 1), below, own), wTexel(k, g + ivec2(1, 1), below, own), f.x), f.y);
}

// Each layer spelled out: W_LAYER(K, EVAL) tries layer K with EVAL
// (wLayerBSpline or wLayerBilinear) and returns when it has a texel of its own.
#define W_LAYER(K, EVAL)                                              \
  {                                                                   \
    vec2 p = wPos(K, lonLatDeg);                                      \
    if (wReaches(K, p)) {                                             \
      float below = wBelow(K + 1, lonLatDeg, grid, gridGeo);          \
      bool own = false;                                               \
      float v = EVAL(K, p, below, own);                               \
      if (own) return v;                                              \
    }                                                                 \
  }
#if GEOCEAN_WATER_TILES_LAYERS > 3
#define W_LAYERS(EVAL) W_LAYER(0, EVAL) W_LAYER(1, EVAL) W_LAYER(2, EVAL) W_LAYER(3, EVAL)
#elif GEOCEAN_WATER_TILES_LAYERS > 2
#define W_LAYERS(EVAL) W_LAYER(0, EVAL) W_LAYER(1, EVAL) W_LAYER(2, EVAL)
#else
#define W_LAYERS(EVAL) W_LAYER(0, EVAL) W_LAYER(1, EVAL)
#endif

float wChainBSpline(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
  W_LAYERS(wLayerBSpline)
  return textureBSplineGather(grid, geoUv(lonLatDeg, gridGeo));
}

float wChainBilinear(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
  W_LAYERS(wLayerBilinear)
  return textureLod(grid, geoUv(lonLatDeg, gridGeo), 0.0).r;
}

#ifdef GEOCEAN_FRAGMENT_STAGE
// waterTilesAuto over the layers (derivatives before any branch).
float wChainAuto(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
  vec2 uvW = geoUv(lonLatDeg, gridGeo);
  vec2 dx = dFdx(uvW), dy = dFdy(uvW);
  float tpp[GEOCEAN_WATER_TILES_LAYERS];
  for (int k = 0; k < GEOCEAN_WATER_TILES_LAYERS; ++k) tpp[k] = length(fwidth(wPos(k, lonLatDeg)));
#undef W_LAYER
#define W_LAYER(K, EVAL)                                                                               \
  {                                                                                                    \
    vec2 p = wPos(K, lonLatDeg);                                                                       \
    if (wReaches(K, p)) {                                                                              \
      float below = wBelow(K + 1, lonLatDeg, grid, gridGeo);                                           \
      bool own = false;                                                                                \
      float v = tpp[K] < 1.0 ? wLayerBSpline(K, p, below, own) : wLayerBilinear(K, p, below, own);     \
      if (own) return v;                                                                               \
    }                                                                                                  \
  }
  W_LAYERS(unused)
  float gridTpp = length((abs(dx) + abs(dy)) * vec2(textureSize(grid, 0)));
  return gridTpp < 1.0 ? textureBSplineGather(grid, uvW) : textureGrad(grid, uvW, dx, dy).r;
}
#endif
#undef W_LAYERS
#undef W_LAYER
#endif

bool waterTilesDrawn() {
#ifdef GEOCEAN_WATER_TILES_LAYERS
  for (int k = 0; k < GEOCEAN_WATER_TILES_LAYERS; ++k)
    if (wDrawn(k)) return true;
  return false;
#endif
#ifdef GEOCEAN_WATER_REGIONAL
  return uWaterSlots.x >= 0;
#else
  return true;
#endif
}

float waterTexel(ivec2 g, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_WATER_REGIONAL
  ivec2 g0 = g;
  bool outside = any(lessThan(g, ivec2(0))) || any(greaterThanEqual(g, uWaterLevel.xy));
  float v = outside ? 0.0 : texelFetch(uWaterPool, blockTexel(g, uWaterLevel, uWaterBlock, uWaterSlots), 0).r;
  if (outside || isnan(v)) {
    vec2 c = uWaterLevelGeo.xy + (vec2(g0) + 0.5) * uWaterLevelGeo.zw;
    v = textureLod(grid, geoUv(c, gridGeo), 0.0).r;
  }
  return v;
#else
  return texelFetch(uWaterPool, blockTexel(g, uWaterLevel, uWaterBlock, uWaterSlots), 0).r;
#endif
}

// Continuous level texel coordinates with texel centres at integers.
vec2 waterTexelPos(vec2 lonLatDeg) {
#ifdef GEOCEAN_WATER_REGIONAL
  lonLatDeg.x = lonNear(lonLatDeg.x, uWaterLevelGeo.x + 0.5 * float(uWaterLevel.x) * uWaterLevelGeo.z);
#endif
  return vec2((lonLatDeg.x - uWaterLevelGeo.x) / uWaterLevelGeo.z, (lonLatDeg.y - uWaterLevelGeo.y) / uWaterLevelGeo.w) - 0.5;
}

bool waterTilesClear(vec2 p) {
#ifdef GEOCEAN_WATER_REGIONAL
  return levelClear(p, uWaterLevel.xy);
#else
  return false;
#endif
}

float waterTilesBilinear(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_WATER_TILES_LAYERS
  return wChainBilinear(lonLatDeg, grid, gridGeo);
#endif
  vec2 p = waterTexelPos(lonLatDeg);
  if (waterTilesClear(p)) return textureLod(grid, geoUv(lonLatDeg, gridGeo), 0.0).r;
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 g = ivec2(i);
  return mix(mix(waterTexel(g, grid, gridGeo), waterTexel(g + ivec2(1, 0), grid, gridGeo), f.x),
             mix(waterTexel(g + ivec2(0, 1), grid, gridGeo), waterTexel(g + ivec2(1, 1), grid, gridGeo), f.x), f.y);
}

float waterTilesBSpline(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_WATER_TILES_LAYERS
  return wChainBSpline(lonLatDeg, grid, gridGeo);
#endif
  vec2 p = waterTexelPos(lonLatDeg);
  if (waterTilesClear(p)) return textureBSplineGather(grid, geoUv(lonLatDeg, gridGeo));
  vec2 i = floor(p);
  vec2 f = p - i;
  vec4 wx = bsplineWeights4(f.x), wy = bsplineWeights4(f.y);
  ivec2 g = ivec2(i) - 1;
  float s = 0.0;
  for (int y = 0; y < 4; ++y) {
    vec4 row = vec4(waterTexel(g + ivec2(0, y), grid, gridGeo), waterTexel(g + ivec2(1, y), grid, gridGeo),
                    waterTexel(g + ivec2(2, y), grid, gridGeo), waterTexel(g + ivec2(3, y), grid, gridGeo));
    s += wy[y] * dot(row, wx);
  }
  return s;
}

#ifdef GEOCEAN_FRAGMENT_STAGE
// Magnified: the B-spline; minified: bilinear at the level the terrain tile
// chose (its texels are at most about a pixel: the tile's cells are).
float waterTilesAuto(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_WATER_TILES_LAYERS
  return wChainAuto(lonLatDeg, grid, gridGeo);
#endif
  vec2 p = waterTexelPos(lonLatDeg);
  float texelsPerPixel = length(fwidth(p));
#ifdef GEOCEAN_WATER_REGIONAL
  {  // derivatives before the branch
    vec2 uvW = geoUv(lonLatDeg, gridGeo);
    vec2 dx = dFdx(uvW), dy = dFdy(uvW);
    if (levelClear(p, uWaterLevel.xy)) {  // the grid as textureBSplineAuto draws it
      float gridTpp = length((abs(dx) + abs(dy)) * vec2(textureSize(grid, 0)));
      return gridTpp < 1.0 ? textureBSplineGather(grid, uvW) : textureGrad(grid, uvW, dx, dy).r;
    }
  }
#endif
  return texelsPerPixel < 1.0 ? waterTilesBSpline(lonLatDeg, grid, gridGeo) : waterTilesBilinear(lonLatDeg, grid, gridGeo);
}
#endif
#endif

#ifdef GEOCEAN_ELEVATION_TILES
// Elevation streamed as pyramid tiles (WorldTextures::elevationTiles), the
// same 2 x 2 block of one level per terrain tile as the water's
// (TerrainRenderer::bindBlock); NaN texels (no data in the raster) take the
// elevation grid's value at the texel's centre: the layers below.
layout(binding = 4) uniform sampler2DArray uElevPool;
uniform ivec4 uElevSlots;
uniform ivec4 uElevBlock;
uniform ivec3 uElevLevel;
uniform vec4 uElevLevelGeo;

#ifdef GEOCEAN_ELEVATION_TILES_LAYERS
// Several streamed reliefs (world::streamedElevationLayers, 2 to 4), in
// answer order: layer 0 is uElev* above, layer k >= 1 element k - 1 of the
// uElevB* arrays (its pool on unit 18 + k, its 2 x 2 block as layer 0's,
// slots -1 where the terrain tile is clear of it). As the query
// (LayerStack::elevationBatch, raster::Raster::sampleBilinear): the first
// layer whose nearest texel lies inside it and whose 4 bilinear texels
// (clamped to its edge) have any data answers, with the bilinear mean of
// those that have; the grid past the last. Only the pool's fetch is
// spelled out per layer (a constant index selects one sampler).
layout(binding = 19) uniform sampler2DArray uElevPoolB1;
#if GEOCEAN_ELEVATION_TILES_LAYERS > 2
layout(binding = 20) uniform sampler2DArray uElevPoolB2;
#endif
#if GEOCEAN_ELEVATION_TILES_LAYERS > 3
layout(binding = 21) uniform sampler2DArray uElevPoolB3;
#endif
uniform ivec4 uElevBSlots[3], uElevBBlock[3];
uniform ivec3 uElevBLevel[3];
uniform vec4 uElevBLevelGeo[3];

ivec4 eSlots(int k) { return k == 0 ? uElevSlots : uElevBSlots[k - 1]; }
ivec4 eBlock(int k) { return k == 0 ? uElevBlock : uElevBBlock[k - 1]; }
ivec3 eLevel(int k) { return k == 0 ? uElevLevel : uElevBLevel[k - 1]; }
vec4 eGeo(int k) { return k == 0 ? uElevLevelGeo : uElevBLevelGeo[k - 1]; }
float eFetch(int k, ivec3 at) {
  if (k == 0) return texelFetch(uElevPool, at, 0).r;
#if GEOCEAN_ELEVATION_TILES_LAYERS > 2
  if (k == 2) return texelFetch(uElevPoolB2, at, 0).r;
#endif
#if GEOCEAN_ELEVATION_TILES_LAYERS > 3
  if (k == 3) return texelFetch(uElevPoolB3, at, 0).r;
#endif
  return texelFetch(uElevPoolB1, at, 0).r;
}

// Layer k's bilinear sample at lon/lat (v): false where it has no data.
bool eLayer(int k, vec2 lonLatDeg, out float v) {
  v = 0.0;
  ivec4 S = eSlots(k);
  if (S.x < 0) return false;
  vec4 G = eGeo(k);
  ivec3 L = eLevel(k);
  if (L.z == 0) lonLatDeg.x = lonNear(lonLatDeg.x, G.x + 0.5 * float(L.x) * G.z);
  vec2 p = vec2((lonLatDeg.x - G.x) / G.z, (lonLatDeg.y - G.y) / G.w) - 0.5;
  ivec2 n = ivec2(floor(p + 0.5));  // the nearest texel: past a regional layer's edge it has no data
  if (L.z == 0 && (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, L.xy)))) return false;
  p.y = clamp(p.y, 0.0, float(L.y - 1));
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec4 B = eBlock(k);
  float s = 0.0, ws = 0.0;
  for (int q = 0; q < 4; ++q) {
    ivec2 g = ivec2(i) + ivec2(q & 1, q >> 1);
    float t = eFetch(k, blockTexel(g, L, B, S));  // clamped or wrapped into the level
    float w = ((q & 1) != 0 ? f.x : 1.0 - f.x) * ((q >> 1) != 0 ? f.y : 1.0 - f.y);
    if (!isnan(t)) s += w * t, ws += w;
  }
  v = s / ws;
  return ws > 0.0;
}

bool eDrawn(int k) { return eSlots(k).x >= 0; }

float elevChain(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
  float v;
  if (eLayer(0, lonLatDeg, v)) return v;
  if (eLayer(1, lonLatDeg, v)) return v;
#if GEOCEAN_ELEVATION_TILES_LAYERS > 2
  if (eLayer(2, lonLatDeg, v)) return v;
#endif
#if GEOCEAN_ELEVATION_TILES_LAYERS > 3
  if (eLayer(3, lonLatDeg, v)) return v;
#endif
  return textureLod(grid, geoUv(lonLatDeg, gridGeo), 0.0).r;
}
#endif

// A regional layer (GEOCEAN_ELEVATION_REGIONAL): texels past its edge are
// the grid's too; a terrain tile clear of it draws the grid alone (no
// slots, -1).
bool elevTilesDrawn() {
#ifdef GEOCEAN_ELEVATION_TILES_LAYERS
  for (int k = 0; k < GEOCEAN_ELEVATION_TILES_LAYERS; ++k)
    if (eDrawn(k)) return true;
  return false;
#endif
#ifdef GEOCEAN_ELEVATION_REGIONAL
  return uElevSlots.x >= 0;
#else
  return true;
#endif
}

float elevTexel(ivec2 g, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_ELEVATION_REGIONAL
  bool outside = any(lessThan(g, ivec2(0))) || any(greaterThanEqual(g, uElevLevel.xy));
#else
  const bool outside = false;
#endif
  float v = outside ? 0.0 : texelFetch(uElevPool, blockTexel(g, uElevLevel, uElevBlock, uElevSlots), 0).r;
  if (outside || isnan(v)) {
    vec2 c = vec2(uElevLevelGeo.x + (float(g.x) + 0.5) * uElevLevelGeo.z, uElevLevelGeo.y + (float(g.y) + 0.5) * uElevLevelGeo.w);
    v = textureLod(grid, geoUv(c, gridGeo), 0.0).r;
  }
  return v;
}

// The texel (degrees, lon and lat) of the streamed level drawn: the first
// layer's bound one (for the relief's gradient).
vec2 elevTilesStep() {
#ifdef GEOCEAN_ELEVATION_TILES_LAYERS
  for (int k = 0; k < GEOCEAN_ELEVATION_TILES_LAYERS; ++k)
    if (eDrawn(k)) return abs(eGeo(k).zw);
#endif
  return abs(uElevLevelGeo.zw);
}

// Bilinear elevation (m) at lon/lat from the streamed level.
float elevTiles(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_ELEVATION_TILES_LAYERS
  return elevChain(lonLatDeg, grid, gridGeo);
#endif
  vec2 lonLatE = lonLatDeg;  // the grid's longitude stays as it came
#ifdef GEOCEAN_ELEVATION_REGIONAL
  lonLatE.x = lonNear(lonLatDeg.x, uElevLevelGeo.x + 0.5 * float(uElevLevel.x) * uElevLevelGeo.z);
#endif
  vec2 p = vec2((lonLatE.x - uElevLevelGeo.x) / uElevLevelGeo.z, (lonLatE.y - uElevLevelGeo.y) / uElevLevelGeo.w) - 0.5;
#ifdef GEOCEAN_ELEVATION_REGIONAL
  if (levelClear(p, uElevLevel.xy)) return textureLod(grid, geoUv(lonLatDeg, gridGeo), 0.0).r;
#endif
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 g = ivec2(i);
  return mix(mix(elevTexel(g, grid, gridGeo), elevTexel(g + ivec2(1, 0), grid, gridGeo), f.x),
             mix(elevTexel(g + ivec2(0, 1), grid, gridGeo), elevTexel(g + ivec2(1, 1), grid, gridGeo), f.x), f.y);
}
#endif

#ifdef GEOCEAN_WATER_PAGES
// Water coverage streamed as pyramid tiles for a draw that spans the view
// (the ocean, plugin/render/WaterPages): a page table holds, for every tile
// of every level, its layer in the pool (-1: not resident). A sample takes
// the finest resident level from the one asked for up; the top tile is
// always resident. The B-spline's weights are textureBSplineGather's, so at
// level 0 the coverage is world::coverageClassAt's on the mask's own cells.
layout(binding = 6) uniform sampler2DArray uPagePool;
layout(binding = 7) uniform isampler2D uPageTable;
uniform int uPageTop;            // the top level (one tile)
uniform ivec4 uPageLevel[24];    // per level: width, height (texels), tiles across, first row in the table
uniform vec4 uPageGeo;           // level 0: origin lon, origin lat, lon step, lat step (degrees)
uniform ivec2 uPageTile;         // tile size, 1 if longitude wraps

// The tile size is a power of two (raster::TilePyramid): shifts and masks.
int pageShift() { return findMSB(uPageTile.x); }

ivec2 pageWrap(int level, ivec2 g) {
  ivec4 L = uPageLevel[level];
  g.x = uPageTile.y != 0 ? texelWrap(g.x, L.x) : clamp(g.x, 0, L.x - 1);
  g.y = clamp(g.y, 0, L.y - 1);
  return g;
}

int pageSlot(int level, ivec2 g) {  // g wrapped
  ivec2 t = g >> pageShift();
  return texelFetch(uPageTable, ivec2(t.x, uPageLevel[level].w + t.y), 0).r;
}

// A regional pyramid (uPageTile.y 0): past its edge and at its nodata
// (NaN) the ocean's water grid answers, its B-spline at the texel's centre
// (the layers below, as the query's).
// (GEOCEAN_WATER_PAGES_REGIONAL; a global pyramid's program is as before.)
float pageTexel(int level, ivec2 g, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_WATER_PAGES_REGIONAL
  bool outside = any(lessThan(g, ivec2(0))) || any(greaterThanEqual(g, uPageLevel[level].xy));
  ivec2 w = pageWrap(level, g);
  int T = uPageTile.x;
  float v = outside ? 0.0 : texelFetch(uPagePool, ivec3((w & (T - 1)) + 1, pageSlot(level, w)), 0).r;  // + 1: the tile's border
  if (outside || isnan(v)) {
    vec2 c = uPageGeo.xy + (vec2(g) + 0.5) * float(1 << level) * uPageGeo.zw;
    v = textureLod(grid, geoUv(c, gridGeo), 0.0).r;  // one fetch: see waterTexel
  }
  return v;
#else
  g = pageWrap(level, g);
  int T = uPageTile.x;
  return texelFetch(uPagePool, ivec3((g & (T - 1)) + 1, pageSlot(level, g)), 0).r;  // + 1: the tile's border
#endif
}

// Continuous texel coordinates of a level, texel centres at integers.
vec2 pagePos(vec2 lonLatDeg, int level) {
#ifdef GEOCEAN_WATER_PAGES_REGIONAL
  lonLatDeg.x = lonNear(lonLatDeg.x, uPageGeo.x + 0.5 * float(uPageLevel[0].x) * uPageGeo.z);
#endif
  return vec2((lonLatDeg.x - uPageGeo.x) / uPageGeo.z, (lonLatDeg.y - uPageGeo.y) / uPageGeo.w) / float(1 << level) -
         0.5;
}

// The finest level from `want` up whose tiles under the 4 x 4 texels at
// lonLat are all resident; s: the slots of those corner texels' tiles
// (x0 y0, x1 y0, x0 y1, x1 y1), which pageTexels4 reads again no more.
int pageLevelSlots(vec2 lonLatDeg, int want, out ivec4 s) {
  for (int l = want; l <= uPageTop; ++l) {
    ivec2 i = ivec2(floor(pagePos(lonLatDeg, l)));
    ivec2 a = pageWrap(l, i - 1), b = pageWrap(l, i + 2);
    s = ivec4(pageSlot(l, a), pageSlot(l, ivec2(b.x, a.y)), pageSlot(l, ivec2(a.x, b.y)), pageSlot(l, b));
    if (l == uPageTop || all(greaterThanEqual(s, ivec4(0)))) return l;  // the top tile is pinned
  }
  return uPageTop;
}
int pageLevel(vec2 lonLatDeg, int want) {
  ivec4 s;
  return pageLevelSlots(lonLatDeg, want, s);
}

#ifndef GEOCEAN_WATER_PAGES_REGIONAL
// Where a global pyramid's 4 x 4 texels from g lie: each one's place in
// its tile (lx, ly; + 1: the tile's border) and which of the corner
// texels' tiles holds it (first column's, first row's). The texels lie in
// at most 2 x 2 tiles (T >= 4), those corner tiles, whose slots s
// pageLevelSlots found resident (x0 y0, x1 y0, x0 y1, x1 y1).
struct PageBlock {
  ivec4 lx, ly;
  bvec4 firstX, firstY;
};
PageBlock pageBlock(int level, ivec2 g) {
  ivec4 L = uPageLevel[level];
  int T = uPageTile.x;
  ivec4 xs = ivec4(g.x) + ivec4(0, 1, 2, 3), ys = clamp(ivec4(g.y) + ivec4(0, 1, 2, 3), ivec4(0), ivec4(L.y - 1));
  xs = uPageTile.y != 0 ? texelWrap(xs, L.x) : clamp(xs, ivec4(0), ivec4(L.x - 1));  // pageWrap's
  ivec4 tx = xs >> pageShift(), ty = ys >> pageShift();
  PageBlock b;
  b.lx = (xs & (T - 1)) + 1, b.ly = (ys & (T - 1)) + 1;
  b.firstX = equal(tx, ivec4(tx.x)), b.firstY = equal(ty, ivec4(ty.x));
  return b;
}
// Texel (x, y) of the block.
float pageBlockTexel(PageBlock b, ivec4 s, int x, int y) {
  int a = b.firstY[y] ? s.x : s.z, c = b.firstY[y] ? s.y : s.w;
  return texelFetch(uPagePool, ivec3(b.lx[x], b.ly[y], b.firstX[x] ? a : c), 0).r;
}

// The block's 16 texels (r[y][x], pageTexel's values one by one), without
// a branch: llvmpipe runs both sides of one, so a fast path for a block
// inside one tile beside a texel-by-texel fallback cost every pixel both
// (49 fetches; docs/PERFORMANCE.md).
void pageTexels4(int level, ivec2 g, ivec4 s, out vec4 r[4]) {
  PageBlock b = pageBlock(level, g);
  for (int y = 0; y < 4; ++y)
    r[y] = vec4(pageBlockTexel(b, s, 0, y), pageBlockTexel(b, s, 1, y), pageBlockTexel(b, s, 2, y),
                pageBlockTexel(b, s, 3, y));
}

// The B-spline of the 4 x 4 texels about p's cell, and the bilinear of its
// middle 2 x 2 (f: p's fraction in the cell).
float pageBSplineOf(vec4 r[4], vec2 f) {
  vec4 wx = bsplineWeights4(f.x), wy = bsplineWeights4(f.y);
  float s = 0.0;
  for (int y = 0; y < 4; ++y) s += wy[y] * dot(r[y], wx);
  return s;
}
float pageBilinearOf(vec4 r[4], vec2 f) { return mix(mix(r[1].y, r[1].z, f.x), mix(r[2].y, r[2].z, f.x), f.y); }

#ifdef GEOCEAN_WATER_PAGES_MINIFIED
// Cells whose every fragment reads the pages minified (OceanRenderer's
// partitionCells bounds the texels per pixel from the cell's corners): the
// bilinear's middle 2 x 2 of pageTexels4's block alone, fetched the same
// way (the same values, the same arithmetic: 4 pool fetches for 16).
float pageBilinearMinified(int level, ivec2 g, ivec4 s, vec2 f) {
  PageBlock b = pageBlock(level, g);
  vec2 r0 = vec2(pageBlockTexel(b, s, 1, 1), pageBlockTexel(b, s, 2, 1));
  vec2 r1 = vec2(pageBlockTexel(b, s, 1, 2), pageBlockTexel(b, s, 2, 2));
  return mix(mix(r0.x, r0.y, f.x), mix(r1.x, r1.y, f.x), f.y);
}
#endif
#endif

// The B-spline at the finest resident level from `want` up (pageLevel's).
float pageBSpline(vec2 lonLatDeg, int want, sampler2D grid, vec4 gridGeo) {
#ifndef GEOCEAN_WATER_PAGES_REGIONAL
  ivec4 slots;
  int level = pageLevelSlots(lonLatDeg, want, slots);
#else
  int level = pageLevel(lonLatDeg, want);
#endif
  vec2 p = pagePos(lonLatDeg, level);
  vec2 i = floor(p);
  vec2 f = p - i;
#ifndef GEOCEAN_WATER_PAGES_REGIONAL
  vec4 r[4];
  pageTexels4(level, ivec2(i) - 1, slots, r);
  return pageBSplineOf(r, f);
#else
  vec4 wx = bsplineWeights4(f.x), wy = bsplineWeights4(f.y);
  ivec2 g = ivec2(i) - 1;
  float s = 0.0;
  for (int y = 0; y < 4; ++y) {
    vec4 row = vec4(pageTexel(level, g + ivec2(0, y), grid, gridGeo), pageTexel(level, g + ivec2(1, y), grid, gridGeo),
                    pageTexel(level, g + ivec2(2, y), grid, gridGeo), pageTexel(level, g + ivec2(3, y), grid, gridGeo));
    s += wy[y] * dot(row, wx);
  }
  return s;
#endif
}

#ifdef GEOCEAN_WATER_PAGES_REGIONAL
float pageBilinear(vec2 lonLatDeg, int level, sampler2D grid, vec4 gridGeo) {
  vec2 p = pagePos(lonLatDeg, level);
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 g = ivec2(i);
  return mix(mix(pageTexel(level, g, grid, gridGeo), pageTexel(level, g + ivec2(1, 0), grid, gridGeo), f.x),
             mix(pageTexel(level, g + ivec2(0, 1), grid, gridGeo), pageTexel(level, g + ivec2(1, 1), grid, gridGeo), f.x),
             f.y);
}
#endif

#ifdef GEOCEAN_WATER_PAGES_LAYERS
// Several streamed masks (WaterPages, world::streamedWaterLayers: 2 to 4),
// in answer order: layer 0 is uPage* above, layer k >= 1 element k - 1 of
// the uPageB* arrays, its pool on unit 8 + k, its page table on 21 + k.
// A point is drawn from the first layer with data within its filter's
// reach: that layer's B-spline (or bilinear) over its own texels, where a
// texel past its edge or without data (NaN) takes the next layers' value
// at the pixel (the first with data there, else the grid's: one lookup a
// pixel, not one a texel as a single layer's grid fetch; llvmpipe ran
// those under lane masks for every texel). So where a layer answers the query
// (its nearest cell has data) and its 4 x 4 cells all have data, the drawn
// coverage is the query's; the layers below answer where it has none.
layout(binding = 9) uniform sampler2DArray uPagePool1;
layout(binding = 22) uniform isampler2D uPageTable1;
#if GEOCEAN_WATER_PAGES_LAYERS > 2
layout(binding = 10) uniform sampler2DArray uPagePool2;
layout(binding = 23) uniform isampler2D uPageTable2;
#endif
#if GEOCEAN_WATER_PAGES_LAYERS > 3
layout(binding = 11) uniform sampler2DArray uPagePool3;
layout(binding = 24) uniform isampler2D uPageTable3;
#endif
uniform int uPageBTop[3];
uniform ivec4 uPageBLevel[72];  // per layer 24 levels, as uPageLevel
uniform vec4 uPageBGeo[3];
uniform ivec2 uPageBTile[3];

int chTop(int k) { return k == 0 ? uPageTop : uPageBTop[k - 1]; }
ivec4 chLevel(int k, int l) { return k == 0 ? uPageLevel[l] : uPageBLevel[(k - 1) * 24 + l]; }
vec4 chGeo(int k) { return k == 0 ? uPageGeo : uPageBGeo[k - 1]; }
ivec2 chTile(int k) { return k == 0 ? uPageTile : uPageBTile[k - 1]; }

int chTable(int k, ivec2 at) {
  if (k == 0) return texelFetch(uPageTable, at, 0).r;
#if GEOCEAN_WATER_PAGES_LAYERS > 2
  if (k == 2) return texelFetch(uPageTable2, at, 0).r;
#endif
#if GEOCEAN_WATER_PAGES_LAYERS > 3
  if (k == 3) return texelFetch(uPageTable3, at, 0).r;
#endif
  return texelFetch(uPageTable1, at, 0).r;
}

float chPool(int k, ivec3 at) {
  if (k == 0) return texelFetch(uPagePool, at, 0).r;
#if GEOCEAN_WATER_PAGES_LAYERS > 2
  if (k == 2) return texelFetch(uPagePool2, at, 0).r;
#endif
#if GEOCEAN_WATER_PAGES_LAYERS > 3
  if (k == 3) return texelFetch(uPagePool3, at, 0).r;
#endif
  return texelFetch(uPagePool1, at, 0).r;
}

ivec2 chWrap(int k, int level, ivec2 g) {  // as pageWrap
  ivec4 L = chLevel(k, level);
  g.x = chTile(k).y != 0 ? ((g.x % L.x) + L.x) % L.x : clamp(g.x, 0, L.x - 1);
  g.y = clamp(g.y, 0, L.y - 1);
  return g;
}

int chSlot(int k, int level, ivec2 g) {  // g wrapped
  ivec2 t = g / chTile(k).x;
  return chTable(k, ivec2(t.x, chLevel(k, level).w + t.y));
}

// Continuous texel coordinates of a level, texel centres at integers (pagePos).
vec2 chPos(int k, vec2 lonLatDeg, int level) {
  vec4 G = chGeo(k);
  if (chTile(k).y == 0) lonLatDeg.x = lonNear(lonLatDeg.x, G.x + 0.5 * float(chLevel(k, 0).x) * G.z);
  return vec2((lonLatDeg.x - G.x) / G.z, (lonLatDeg.y - G.y) / G.w) / float(1 << level) - 0.5;
}

// g inside the level (wrapped for a global layer); false past a regional one's edge.
bool chInside(int k, int level, inout ivec2 g) {
  if (chTile(k).y != 0) {
    g = chWrap(k, level, g);
    return true;
  }
  return all(greaterThanEqual(g, ivec2(0))) && all(lessThan(g, chLevel(k, level).xy));
}

// The layers from j on at lon/lat c: the first whose texel there (at its
// finest resident level) has data, else the grid's coverage (one fetch,
// as pageTexel's).
// Layer k's texel at lon/lat c at its finest resident level: `has` when
// inside it and with data.
float chAt(int k, vec2 c, out bool has) {
  has = false;
  int top = chTop(k), T = chTile(k).x;
  for (int l = 0; l <= top; ++l) {
    ivec2 g = ivec2(floor(chPos(k, c, l) + 0.5));
    if (!chInside(k, l, g)) break;  // past its edge: the next layer
    int s = chSlot(k, l, g);
    if (s < 0) continue;  // not resident: its parent
    float v = chPool(k, ivec3(g - (g / T) * T + 1, s));
    has = !isnan(v);  // NaN: no data here, the next layer
    return v;
  }
  return 0.0;
}

// The layers from j on at lon/lat c: the first whose texel there (at its
// finest resident level) has data, else the grid's coverage (one fetch,
// as pageTexel's). Spelled out per layer: a constant layer index selects
// one pool and table (a loop's index made llvmpipe fetch from each).
float chBelow(int j, vec2 c, sampler2D grid, vec4 gridGeo) {
  bool has;
  float v;
  if (j <= 1) {
    v = chAt(1, c, has);
    if (has) return v;
  }
#if GEOCEAN_WATER_PAGES_LAYERS > 2
  if (j <= 2) {
    v = chAt(2, c, has);
    if (has) return v;
  }
#endif
#if GEOCEAN_WATER_PAGES_LAYERS > 3
  if (j <= 3) {
    v = chAt(3, c, has);
    if (has) return v;
  }
#endif
  return textureLod(grid, geoUv(c, gridGeo), 0.0).r;
}

// Texel g of layer k's level, or `below` (the layers' below at the
// pixel); `own` set when it is the layer's own.
float chTexel(int k, int level, ivec2 g, float below, inout bool own) {
  ivec2 w = g;
  if (chInside(k, level, w)) {
    int T = chTile(k).x;
    float v = chPool(k, ivec3(w - (w / T) * T + 1, chSlot(k, level, w)));
    if (!isnan(v)) {
      own = true;
      return v;
    }
  }
  return below;
}

// The finest level from `want` up whose tiles under the 4 x 4 texels at
// lonLat are all resident (pageLevel).
int chResidentLevel(int k, vec2 lonLatDeg, int want) {
  int top = chTop(k);
  for (int l = want; l < top; ++l) {
    ivec2 i = ivec2(floor(chPos(k, lonLatDeg, l)));
    ivec2 a = chWrap(k, l, i - 1), b = chWrap(k, l, i + 2);
    if (chSlot(k, l, a) >= 0 && chSlot(k, l, b) >= 0 && chSlot(k, l, ivec2(a.x, b.y)) >= 0 &&
        chSlot(k, l, ivec2(b.x, a.y)) >= 0)
      return l;
  }
  return top;
}

float chBSpline(int k, vec2 lonLatDeg, int level, float below, inout bool own) {
  vec2 p = chPos(k, lonLatDeg, level);
  vec2 i = floor(p);
  vec2 f = p - i;
  vec4 wx = bsplineWeights4(f.x), wy = bsplineWeights4(f.y);
  ivec2 g = ivec2(i) - 1;
  float s = 0.0;
  for (int y = 0; y < 4; ++y) {
    vec4 row = vec4(chTexel(k, level, g + ivec2(0, y), below, own), chTexel(k, level, g + ivec2(1, y), below, own),
                    chTexel(k, level, g + ivec2(2, y), below, own), chTexel(k, level, g + ivec2(3, y), below, own));
    s += wy[y] * dot(row, wx);
  }
  return s;
}

float chBilinear(int k, vec2 lonLatDeg, int level, float below, inout bool own) {
  vec2 p = chPos(k, lonLatDeg, level);
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 g = ivec2(i);
  return mix(mix(chTexel(k, level, g, below, own), chTexel(k, level, g + ivec2(1, 0), below, own), f.x),
             mix(chTexel(k, level, g + ivec2(0, 1), below, own), chTexel(k, level, g + ivec2(1, 1), below, own), f.x),
             f.y);
}

#ifdef GEOCEAN_FRAGMENT_STAGE
// waterPagesAuto over the layers: the first with a texel of its own within
// the filter's reach, at its level for the pixel; else the grid alone.
float waterPagesChain(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
  vec2 uvW = geoUv(lonLatDeg, gridGeo);
  vec2 dx = dFdx(uvW), dy = dFdy(uvW);
  // Derivatives before any branch; each layer spelled out (CH_LAYER): a
  // constant index selects its own pool and table.
  float tpp[GEOCEAN_WATER_PAGES_LAYERS];
  for (int k = 0; k < GEOCEAN_WATER_PAGES_LAYERS; ++k) tpp[k] = length(fwidth(chPos(k, lonLatDeg, 0)));
#define CH_LAYER(K)                                                                                 \
  {                                                                                                 \
    int want = tpp[K] < 1.0 ? 0 : min(int(floor(log2(tpp[K]))), chTop(K));                         \
    if (chTile(K).y != 0 || !levelClear(chPos(K, lonLatDeg, want), chLevel(K, want).xy)) {          \
      int l = chResidentLevel(K, lonLatDeg, want);                                                  \
      float below = chBelow(K + 1, lonLatDeg, grid, gridGeo);                                       \
      bool own = false;                                                                             \
      float v = tpp[K] < 1.0 ? chBSpline(K, lonLatDeg, l, below, own)                               \
                             : chBilinear(K, lonLatDeg, l, below, own);                             \
      if (own) return v;                                                                            \
    }                                                                                               \
  }
  CH_LAYER(0)
  CH_LAYER(1)
#if GEOCEAN_WATER_PAGES_LAYERS > 2
  CH_LAYER(2)
#endif
#if GEOCEAN_WATER_PAGES_LAYERS > 3
  CH_LAYER(3)
#endif
#undef CH_LAYER
  float texelsPerPixel = length((abs(dx) + abs(dy)) * vec2(textureSize(grid, 0)));
  return texelsPerPixel < 1.0 ? textureBSplineGather(grid, uvW) : textureGrad(grid, uvW, dx, dy).r;
}
#endif
#endif

#ifdef GEOCEAN_FRAGMENT_STAGE
// Magnified: the B-spline of level 0 (or the finest resident); minified:
// bilinear at the level whose texel is about the pixel (the pyramid's
// levels are means of 2 x 2 texels: a mipmap), as textureBSplineAuto.
// grid (uWaterGeo): the ocean's water grid. Where no texel of a regional
// pyramid's level is within the filter's reach, the grid alone, as
// textureBSplineAuto draws it (derivatives taken before the branch).
float waterPagesAuto(vec2 lonLatDeg, sampler2D grid, vec4 gridGeo) {
#ifdef GEOCEAN_WATER_PAGES_LAYERS
  return waterPagesChain(lonLatDeg, grid, gridGeo);
#endif
  float tpp = length(fwidth(pagePos(lonLatDeg, 0)));
  int want = tpp < 1.0 ? 0 : min(int(floor(log2(tpp))), uPageTop);
#ifdef GEOCEAN_WATER_PAGES_REGIONAL
  vec2 uvW = geoUv(lonLatDeg, gridGeo);
  vec2 dx = dFdx(uvW), dy = dFdy(uvW);
  {
    if (levelClear(pagePos(lonLatDeg, want), uPageLevel[want].xy)) {
      float texelsPerPixel = length((abs(dx) + abs(dy)) * vec2(textureSize(grid, 0)));
      return texelsPerPixel < 1.0 ? textureBSplineGather(grid, uvW) : textureGrad(grid, uvW, dx, dy).r;
    }
  }
#endif
#ifdef GEOCEAN_WATER_PAGES_REGIONAL
  int l = pageLevel(lonLatDeg, want);
  return tpp < 1.0 ? pageBSpline(lonLatDeg, want, grid, gridGeo) : pageBilinear(lonLatDeg, l, grid, gridGeo);
#else
  // One set of texels for either filter (the bilinear's are the B-spline's
  // middle four at the same level).
  ivec4 slots;
  int l = pageLevelSlots(lonLatDeg, want, slots);
  vec2 p = pagePos(lonLatDeg, l);
  vec2 i = floor(p);
#ifdef GEOCEAN_WATER_PAGES_MINIFIED
  return pageBilinearMinified(l, ivec2(i) - 1, slots, p - i);
#endif
  vec4 r[4];
  pageTexels4(l, ivec2(i) - 1, slots, r);
  return tpp < 1.0 ? pageBSplineOf(r, p - i) : pageBilinearOf(r, p - i);
#endif
}
#endif
#endif
