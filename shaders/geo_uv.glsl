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

#ifdef GEOCEAN_FRAGMENT_STAGE
// The same 4 taps with the implicit level of detail (fragment shaders only):
// magnified it is the B-spline above; minified each tap reads the mipmap
// within 1.5 texels of the others, so it is the mipmapped average.
float textureBSplineAuto(sampler2D tex, vec2 uv) {
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
  // One level for all four taps, from the derivatives of uv itself (the taps'
  // own coordinates jump across texel boundaries).
  vec2 dx = dFdx(uv), dy = dFdy(uv);
  float a = textureGrad(tex, vec2(h0.x, h0.y), dx, dy).r, b = textureGrad(tex, vec2(h1.x, h0.y), dx, dy).r;
  float c = textureGrad(tex, vec2(h0.x, h1.y), dx, dy).r, d = textureGrad(tex, vec2(h1.x, h1.y), dx, dy).r;
  return mix(mix(a, b, g1.x), mix(c, d, g1.x), g1.y);
}
#endif
