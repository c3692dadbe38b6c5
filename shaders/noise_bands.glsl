// The noise sea's octaves by scale (issue 13 item 1), shared by ocean.vert
// and ocean.frag: each octave is shown where the picture resolves it and
// is roughness where it does not, its slope variance moving continuously
// between the two (uMssAbove's band, the same spectrum).
// - geometry: octaves over 3 grid cells (ocean.vert's count, as before);
// - the vertex normal: octaves over 6 cells along the view, faded in from
//   3 (noiseVertexWeight): those of the geometry, so the normal is the
//   mesh's own;
// - the fragment normal: the rest, over 2 e pixels (the pixel's longer
//   axis), faded out by e (noisePixelWeight; e = OceanOptions::
//   pixelOctaveEndPx: 2 is Nyquist, 4 leaves the lattice of even pixels
//   what is drawn, for reduced-rate shading): one
//   gradient noise per pixel and octave (the ocean's cost on llvmpipe:
//   docs/PERFORMANCE.md; a periodic 3D table of it, one texture fetch an
//   octave, tried, was slower);
// - roughness: what neither shows, (1 - w^2) of each octave's band.
// Callers include waves.glsl (wv_solidNoise) first.
#ifndef NOISE_BANDS_GLSL
#define NOISE_BANDS_GLSL

// cellAlongM: a grid cell's footprint along the view (its footprint over
// the sine of the view's elevation angle).
float noiseVertexWeight(float wavelengthM, float cellAlongM) {
  return smoothstep(3.0, 6.0, wavelengthM / max(cellAlongM, 1e-6));
}
float noisePixelWeight(float wavelengthM, float pixelM, float endPx) {
  return smoothstep(endPx, 2.0 * endPx, wavelengthM / max(pixelM, 1e-6));
}

// Octave i at d: (height, its gradient in ECEF, m/m), the body of
// wv_solidNoise's loop for one octave (the same operations); the caller
// takes the tangent part once for all octaves (wv_solidNoise's normal is
// normalize(up - tangent gradient)).
vec4 noiseOctaveOf(WvOctave o, vec3 d) {
  vec3 r0 = o.row0.xyz, r1 = o.row1.xyz, r2 = o.row2.xyz;
  vec3 q = o.fracO.xyz + vec3(dot(r0, d), dot(r1, d), dot(r2, d));
  vec3 fl = floor(q);
  vec4 n = wv_perlin3(o.cellO.xyz + ivec3(fl), q - fl, uint(o.row1.w));
  float a = o.row0.w;
  return vec4(a * n.x, a * (r0 * n.y + r1 * n.z + r2 * n.w));
}
vec4 noiseOctave(int i, vec3 d) { return noiseOctaveOf(wvOctaves[i], d); }

#ifdef NOISE_OCTAVE_TEXELS
// The same octave read through buffer textures (OceanRenderer): the
// fragments' octave index differs from pixel to pixel, and llvmpipe reads a
// buffer or a uniform array at such an index lane by lane through the
// stack, a texel fetch with one gather instruction (AVX2): the octave loop's
// cost on llvmpipe (docs/PERFORMANCE.md). uOctaveTexels: the octave SSBO
// itself as RGBA32F, 6 texels per WvOctave (row0, row1, row2, fracO, cellO
// as bits, vel); uOctaveBands: per octave (wavelength m, uMssAbove,
// uOctaveHeightVar, the sum of uOctaveHeightVar from it on), the uniform
// arrays' values.
layout(binding = 12) uniform samplerBuffer uOctaveTexels;
layout(binding = 13) uniform samplerBuffer uOctaveBands;
vec4 noiseOctaveFetched(int i, vec3 d) {
  WvOctave o;
  o.row0 = texelFetch(uOctaveTexels, 6 * i);
  o.row1 = texelFetch(uOctaveTexels, 6 * i + 1);
  o.row2 = texelFetch(uOctaveTexels, 6 * i + 2);
  o.fracO = texelFetch(uOctaveTexels, 6 * i + 3);
  o.cellO = floatBitsToInt(texelFetch(uOctaveTexels, 6 * i + 4));
  o.vel = vec4(0.0);
  return noiseOctaveOf(o, d);
}
#endif

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
