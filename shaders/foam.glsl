// Whitecaps of the Gerstner and FFT seas from the waves (issue 13 item 3),
// per fragment, from the shared wave kernel itself (waves.glsl) at the
// fragment's rest point: foam where the choppy map folds, i.e. where the
// Jacobian determinant of the horizontal displacement is below
// uFoamJacobian (OceanRenderer calibrates it so that the foam-covered
// fraction of the sea is Monahan & O'Muircheartaigh's W).
// Decay: the rest point is a water particle (both models are Lagrangian),
// so foam made there stays with that water and fades as exp(-age / tau)
// (Callaghan et al. 2012: individual whitecaps decay quasi-exponentially,
// tau 0.5-8 s; OceanRenderer::kFoamDecayS). The kernel is evaluated at the
// present and at FOAM_TIMES - 1 earlier times on a fixed 0.5 s grid
// (uFoamAgeS: their ages), whose wave data follow the present's in the
// buffers: copy k of the components is wvWaves[k * uWaveCount ..], of the
// FFT planes wvFftPlanes[k * 3 * uFftCascades ..] (OceanRenderer::draw).
// Callers include waves_types.glsl, declare the wave buffers, include
// waves.glsl and define FOAM_TIMES.
uniform float uFoamJacobian;
uniform float uFoamJacobianSoft;
uniform float uFoamAgeS[FOAM_TIMES];
uniform float uFoamDecayS;

// Foam of one sample: 1 below the threshold, 0 above, over +-soft.
float foamOfJacobian(float det) {
  return 1.0 - smoothstep(uFoamJacobian - uFoamJacobianSoft, uFoamJacobian + uFoamJacobianSoft, det);
}

float whitecapFoam(vec3 d, WvFrame fr, float depthM) {
  float foam = 0.0;
  for (int k = 0; k < FOAM_TIMES; ++k) {
#if WV_MODEL == 2
    WvResult r = wv_fft(k * 3 * uFftCascades, 3, uFftCascades, d, fr);
#elif defined(WV_COAST)
    WvResult r = wv_gerstnerCoast(k * uWaveCount, uWaveCount, d, fr, depthM, wvCoasts[0]);
#else
    WvResult r = wv_gerstner(k * uWaveCount, uWaveCount, d, fr, depthM);
#endif
    foam = max(foam, foamOfJacobian(r.jac.w) * exp(-uFoamAgeS[k] / uFoamDecayS));
  }
  return foam;
}
