// Issue 15 item 4: paper 003's distance bands for the breaking waves, on the
// screen grid (Gerstner with a coast field; ocean.vert computes, ocean.frag
// draws through coast_bands_frag.glsl). Measured against the local
// wavelength lambda of the breaking sea (wv_breakingFoamMean's: shorter in
// shallow water than offshore):
//   near,   grid cell along the view < lambda / 8: the kernel's breaking
//           foam on the drawn crests (wv_breakingFoam per vertex: eight
//           vertices a wave carry its crest and collapse);
//   middle, cell > lambda / 3 (cross-faded from lambda / 8): a foam texture
//           per fragment, b smoothstep(0, A, sigma u) with u the 4 strongest
//           components' cosines at their own phases (a height texture moved
//           along the crest lines: refracted, at the waves' speed), scaled so
//           that its mean is the kernel's phase-averaged foam;
//   far,    a pixel along the view > lambda (faded from lambda / 4): that
//           mean itself (wv_breakingFoamMean), the surf zone's foam where the
//           coast field breaks the waves, i.e. on the weather side.
// Every band has the near band's mean, so the fades change no mean (the
// band-edge test, tests/render/test_coast_bands.cpp). Only the foam changes:
// heights and normals stay wv_gerstnerCoast's, the query's function (item 5).
// uCoastBandMode (OceanRenderer::setCoastBands, for tests): 0 the bands by
// distance, 1 the near band everywhere, 2 the middle/far bands everywhere,
// 3 the middle band's texture everywhere (no fade to the far band's mean),
// 4 the far band's mean everywhere.
// GEOCEAN_NO_COAST_BANDS (OceanOptions::coastBands false): none of it.
#ifndef GEOCEAN_NO_COAST_BANDS
uniform int uCoastBandMode;
out vec4 vBreakBand;   // (near -> middle weight, A / sigma, texture scale, mean foam)
out vec4 vBreakPhase;  // the 4 components' unreduced phases (linear across a cell)
out vec4 vBreakAmp;    // their amplitudes, sum amp cos(phase) of unit variance
out float vBreakLambdaM;

void coastBands(WvBreakMean m, float cellAlongM) {
  float w = smoothstep(0.125, 0.333, cellAlongM / max(m.m.y, 1e-3));
  if (uCoastBandMode != 0) w = uCoastBandMode == 1 ? 0.0 : 1.0;
  vBreakBand = vec4(w, max(m.m.w, 1e-3), m.shareTex > 0.0 ? m.m.x / m.shareTex : 0.0, m.m.x);
  vBreakPhase = m.phase;
  vBreakAmp = m.amp;
  vBreakLambdaM = m.m.y;
}
#endif
