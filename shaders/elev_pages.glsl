// The ocean's water depth from the streamed reliefs (issues 12 and 15):
// the host terrain's elevation layers (world::streamedElevationLayers, 1 to
// 4, GEOCEAN_ELEV_PAGES n) in the ocean's own tile pools with a page table
// each (plugin/render/ElevationPages). As the query
// (LayerStack::elevationBatch, raster::Raster::sampleBilinear) and the
// terrain (geo_uv.glsl eLayer): the first layer whose nearest texel lies
// inside it and whose 4 bilinear texels (clamped or wrapped into the level)
// have any data answers, with the bilinear mean of those that have; the
// ocean's elevation grid past the last. At level 0 that is the query's
// value; a cell wider than a texel reads the pyramid level whose texel
// matches it (levels are means of 2 x 2 texels), the finest resident from
// there up.
// Texel positions are eye-relative: the CPU splits a reference point's
// level-0 position (double) into an integer texel and a fraction, and a
// vertex adds its offset from the reference, so a 1" texel is read at
// 179.99 E as at 0 E (float longitudes near 180 are 1.7 m apart).
// Vertex stage; pools on units 25 + k, page tables on 29 + k.
#ifdef GEOCEAN_ELEV_PAGES
layout(binding = 25) uniform sampler2DArray uEPagePool0;
layout(binding = 29) uniform isampler2D uEPageTable0;
#if GEOCEAN_ELEV_PAGES > 1
layout(binding = 26) uniform sampler2DArray uEPagePool1;
layout(binding = 30) uniform isampler2D uEPageTable1;
#endif
#if GEOCEAN_ELEV_PAGES > 2
layout(binding = 27) uniform sampler2DArray uEPagePool2;
layout(binding = 31) uniform isampler2D uEPageTable2;
#endif
#if GEOCEAN_ELEV_PAGES > 3
layout(binding = 28) uniform sampler2DArray uEPagePool3;
layout(binding = 32) uniform isampler2D uEPageTable3;
#endif
uniform int uEPageTop[4];         // the top level (one tile)
uniform ivec4 uEPageLevel[96];    // per layer 24 levels: width, height (texels), tiles across, first table row
uniform ivec2 uEPageTile[4];      // tile size, 1 if longitude wraps
uniform ivec2 uEPageRefTexel[4];  // the reference's level-0 position (texel edges at integers): integer part
uniform vec2 uEPageRefFrac[4];    // and fraction
uniform vec2 uEPageStep[4];       // level-0 texel: lon step, lat step (degrees)
uniform float uEPageRefOff[4];    // the reference's longitude in the layer minus the layer's centre (degrees)

ivec4 epLevel(int k, int l) { return uEPageLevel[k * 24 + l]; }

int epTable(int k, ivec2 at) {
#if GEOCEAN_ELEV_PAGES > 1
  if (k == 1) return texelFetch(uEPageTable1, at, 0).r;
#endif
#if GEOCEAN_ELEV_PAGES > 2
  if (k == 2) return texelFetch(uEPageTable2, at, 0).r;
#endif
#if GEOCEAN_ELEV_PAGES > 3
  if (k == 3) return texelFetch(uEPageTable3, at, 0).r;
#endif
  return texelFetch(uEPageTable0, at, 0).r;
}

float epPool(int k, ivec3 at) {
#if GEOCEAN_ELEV_PAGES > 1
  if (k == 1) return texelFetch(uEPagePool1, at, 0).r;
#endif
#if GEOCEAN_ELEV_PAGES > 2
  if (k == 2) return texelFetch(uEPagePool2, at, 0).r;
#endif
#if GEOCEAN_ELEV_PAGES > 3
  if (k == 3) return texelFetch(uEPagePool3, at, 0).r;
#endif
  return texelFetch(uEPagePool0, at, 0).r;
}

// Texel g of level l wrapped (global) or clamped into the level (as
// raster::Raster::sampleBilinear and geo_uv.glsl blockTexel).
ivec2 epWrap(int k, int l, ivec2 g) {
  ivec4 L = epLevel(k, l);
  g.x = uEPageTile[k].y != 0 ? ((g.x % L.x) + L.x) % L.x : clamp(g.x, 0, L.x - 1);
  g.y = clamp(g.y, 0, L.y - 1);
  return g;
}

int epSlot(int k, int l, ivec2 g) {  // g wrapped
  ivec2 t = g / uEPageTile[k].x;
  return epTable(k, ivec2(t.x, epLevel(k, l).w + t.y));
}

// Layer k's level-l position of a point rel (degrees: longitude, latitude
// from the reference) as an integer texel i and a fraction f (texel
// centres at integers). Exact to float's precision of rel/step however far
// the point is from longitude 0.
void epPos(int k, int l, vec2 rel, out ivec2 i, out vec2 f) {
  if (uEPageTile[k].y == 0) {  // regional: the longitude nearest the layer's centre (raster::lonNear)
    float c = uEPageRefOff[k] + rel.x;
    rel.x += c > 180.0 ? -360.0 : c < -180.0 ? 360.0 : 0.0;
  }
  ivec2 I = uEPageRefTexel[k];
  ivec2 Il = I >> l;  // arithmetic shift: floor division by 2^l
  vec2 q = (vec2(I - (Il << l)) + uEPageRefFrac[k] + rel / uEPageStep[k]) / float(1 << l) - 0.5;
  vec2 fl = floor(q);
  i = Il + ivec2(fl);
  f = q - fl;
}

// True when the tiles of layer k's 2 x 2 texels from i at level l are resident.
bool epResident(int k, int l, ivec2 i) {
  ivec2 a = epWrap(k, l, i), b = epWrap(k, l, i + 1);
  return epSlot(k, l, a) >= 0 && epSlot(k, l, b) >= 0 && epSlot(k, l, ivec2(a.x, b.y)) >= 0 &&
         epSlot(k, l, ivec2(b.x, a.y)) >= 0;
}

// The level whose texel (its latitude step, 111,320 m a degree) is about a
// cell of footprintM (ElevationPages::request asks for the same).
int epWant(int k, float footprintM) {
  return max(int(floor(log2(max(footprintM, 1e-6) / (abs(uEPageStep[k].y) * 111320.0)))), 0);
}

// Layer k at rel for a cell of footprintM, at its finest resident level
// from epWant: false where it has no data (its nearest texel past a
// regional layer's edge, or none of the 4 texels with data), else v, the
// bilinear mean of those with data.
bool epLayer(int k, vec2 rel, float footprintM, out float v) {
  v = 0.0;
  int top = uEPageTop[k];
  int l = min(epWant(k, footprintM), top);
  ivec2 i;
  vec2 f;
  epPos(k, l, rel, i, f);
  for (; l < top && !epResident(k, l, i);) {
    ++l;
    epPos(k, l, rel, i, f);
  }
  ivec4 L = epLevel(k, l);
  ivec2 n = i + ivec2(greaterThanEqual(f, vec2(0.5)));  // the nearest texel
  if (uEPageTile[k].y == 0 && (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, L.xy)))) return false;
  // Latitude clamped into the level (Raster::sampleBilinear's y clamp).
  if (i.y < 0) i.y = 0, f.y = 0.0;
  if (i.y >= L.y - 1) i.y = L.y - 1, f.y = 0.0;
  int T = uEPageTile[k].x;
  float s = 0.0, ws = 0.0;
  for (int q = 0; q < 4; ++q) {
    ivec2 g = epWrap(k, l, i + ivec2(q & 1, q >> 1));
    float t = epPool(k, ivec3(g - (g / T) * T + 1, epSlot(k, l, g)));  // + 1: the tile's border
    float w = ((q & 1) != 0 ? f.x : 1.0 - f.x) * ((q >> 1) != 0 ? f.y : 1.0 - f.y);
    if (!isnan(t)) s += w * t, ws += w;
  }
  v = s / max(ws, 1e-30);
  return ws > 0.0;
}

// The relief's elevation (m) at rel (degrees from the reference) for a
// cell of footprintM; the grid (at lonLat, level of detail gridLod) where
// no layer has data. Each layer spelled out: a constant index selects its
// pool and table.
float elevPages(vec2 rel, float footprintM, vec2 lonLat, sampler2D grid, vec4 gridGeo, float gridLod) {
  float v;
  if (epLayer(0, rel, footprintM, v)) return v;
#if GEOCEAN_ELEV_PAGES > 1
  if (epLayer(1, rel, footprintM, v)) return v;
#endif
#if GEOCEAN_ELEV_PAGES > 2
  if (epLayer(2, rel, footprintM, v)) return v;
#endif
#if GEOCEAN_ELEV_PAGES > 3
  if (epLayer(3, rel, footprintM, v)) return v;
#endif
  return textureLod(grid, geoUv(lonLat, gridGeo), gridLod).r;
}
#endif
