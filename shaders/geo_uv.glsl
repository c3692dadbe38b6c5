// lon/lat in degrees -> texture coordinates of a global equirectangular
// raster described by geo = (originLonDeg, originLatDeg, lonSpanDeg, latSpanDeg).
vec2 geoUv(vec2 lonLatDeg, vec4 geo) {
  return vec2((lonLatDeg.x - geo.x) / geo.z, (lonLatDeg.y - geo.y) / geo.w);
}

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
