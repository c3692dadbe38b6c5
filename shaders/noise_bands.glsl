// The noise sea's octaves by scale (issue 13 item 1), shared by ocean.vert
// and ocean.frag: each octave is shown where the picture resolves it and
// is roughness where it does not, its slope variance moving continuously
// between the two (uMssAbove's band, the same spectrum).
// - geometry: octaves over 3 grid cells (ocean.vert's count, as before);
// - the vertex normal: octaves over 12 cells along the view (12 vertices a
//   wavelength: linear interpolation of their normals is smooth), faded in
//   from 6 (noiseVertexWeight);
// - the fragment normal: the rest, over 4 pixels (the pixel's longer axis),
//   faded out by 2 (Nyquist), as the detail layer (noisePixelWeight);
// - roughness: what neither shows, (1 - w^2) of each octave's band.
// Callers include waves.glsl (wv_solidNoise) first.
#ifndef NOISE_BANDS_GLSL
#define NOISE_BANDS_GLSL

// cellAlongM: a grid cell's footprint along the view (its footprint over
// the sine of the view's elevation angle).
float noiseVertexWeight(float wavelengthM, float cellAlongM) {
  return smoothstep(6.0, 12.0, wavelengthM / max(cellAlongM, 1e-6));
}
float noisePixelWeight(float wavelengthM, float pixelM) {
  return smoothstep(2.0, 4.0, wavelengthM / max(pixelM, 1e-6));
}

// The tangent gradient of octaves [first, first + count) at d (zero for
// none): wv_solidNoise's normal is normalize(up - g).
vec3 noiseGradient(int first, int count, vec3 d, WvFrame fr, vec3 up, out float heightM) {
  heightM = 0.0;
  if (count <= 0) return vec3(0.0);
  WvResult r = wv_solidNoise(first, count, d, fr);
  heightM = r.disp.w;
  return up - r.normal.xyz / dot(r.normal.xyz, up);
}

// Whitecaps of the noise sea: where the crest field, the model's octave
// heights weighted by 2^(3i/4) (noiseCrestWeight: the shorter crests break
// the long waves' tops into patches a fraction of their size), is above
// uCrestM, the level it exceeds on Monahan's fraction W of the sea
// (OceanRenderer). The octaves a pixel does not resolve, a share u of
// the field's variance (varUnresolved over uCrestVar), leave the pixel's
// crests unknown: the pixel takes (1 - u) of the resolved field's crests,
// above uCrestM sqrt(1 - u) (the same quantile of a field of that
// variance), and u of the mean cover W. So the cover stays W at every
// distance, each patch fades into the mean as it becomes smaller than a
// pixel (no sparkle) and far away the sea has W evenly. The edge: a
// logistic (the normal CDF's form within 0.01) over 0.15 of the field's
// standard deviation (a soft rim, set by eye on the matrix's 30 m views;
// fwidth of the field, tried, steps at triangle edges) or softM if wider.
uniform float uCrestM;
uniform float uCrestVar;
uniform float uOctaveHeightVar[16];
float noiseCrestWeight(int i) { return exp2(0.75 * float(i)); }
float noiseCrestFoam(float heightM, float varUnresolved, float softM, float cover) {
  softM = max(softM, 0.3 * sqrt(uCrestVar));
  float u = clamp(varUnresolved / max(uCrestVar, 1e-12), 0.0, 1.0);
  float edge = 1.0 / (1.0 + exp(-1.702 * (heightM - uCrestM * sqrt(1.0 - u)) / max(softM, 1e-6)));
  return mix(edge, cover, u);
}
#endif
