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
// Between the samples the determinant is interpolated in time (cubic
// Hermite, centred-difference tangents): a fold travels a few metres in
// 0.5 s, more than it is wide, so the samples alone left the trail as
// separate copies of the fold (stripes near the eye). The foam of a step is
// taken at the cubic's minimum (a root of its derivative: a brief fold is
// never missed) and at FOAM_SUB points (a long fold's youngest foam, within
// exp(0.5 s / FOAM_SUB / tau), 6 %). At a fixed particle the determinant is
// a sum of the components' sinusoids in time, periods >= 1.5 s for the
// waves that fold, i.e. >= 3 samples a period: the cubic follows them.
// Callers include waves_types.glsl, declare the wave buffers, include
// waves.glsl and define FOAM_TIMES and FOAM_SUB.
uniform float uFoamJacobian;
uniform float uFoamJacobianSoft;
uniform float uFoamAgeS[FOAM_TIMES];
uniform float uFoamDecayS;

// Foam of one sample: 1 below the threshold, 0 above, over +-soft.
float foamOfJacobian(float det) {
  return 1.0 - smoothstep(uFoamJacobian - uFoamJacobianSoft, uFoamJacobian + uFoamJacobianSoft, det);
}

float foldAt(int k, vec3 d, WvFrame fr, float depthM) {
#if WV_MODEL == 2
  return wv_fftFold(k * 3 * uFftCascades, 3, uFftCascades, d, fr);
#elif defined(WV_COAST)
  return wv_gerstnerCoast(k * uWaveCount, uWaveCount, d, fr, depthM, wvCoasts[0]).jac.w;
#else
  return wv_gerstner(k * uWaveCount, uWaveCount, d, fr, depthM).jac.w;
#endif
}

// The foam of step [a0, a0 + h] inside it (the ends are samples, counted
// by the caller), the determinant p(u) = ((c3 u + c2) u + c1) u + p0.
float foamInStep(float p0, float c1, float c2, float c3, float a0, float h) {
  float foam = 0.0;
  for (int s = 1; s < FOAM_SUB; ++s) {
    float u = float(s) / float(FOAM_SUB);
    foam = max(foam, foamOfJacobian(((c3 * u + c2) * u + c1) * u + p0) * exp(-(a0 + u * h) / uFoamDecayS));
  }
  float disc = c2 * c2 - 3.0 * c3 * c1;
  if (disc < 0.0) return foam;  // monotone: no minimum inside
  float sq = sqrt(disc);
  vec2 r = abs(c3) > 1e-6 ? vec2(-c2 - sq, -c2 + sq) / (3.0 * c3) : vec2(abs(c2) > 1e-6 ? -c1 / (2.0 * c2) : -1.0);
  for (int i = 0; i < 2; ++i)
    if (r[i] > 0.0 && r[i] < 1.0) {
      float j = ((c3 * r[i] + c2) * r[i] + c1) * r[i] + p0;
      foam = max(foam, foamOfJacobian(j) * exp(-(a0 + r[i] * h) / uFoamDecayS));
    }
  return foam;
}

// OceanRenderer::foamOf is this in double (the calibration's copy).
// normal0: the present sample's surface normal (copy 0 is the present), for
// ocean.frag's per-fragment normal (GEOCEAN_FRAGMENT_NORMAL); the compiler
// drops its arithmetic where the caller does not read it.
float whitecapFoam(vec3 d, WvFrame fr, float depthM, out vec3 normal0) {
  float det[FOAM_TIMES];
#if WV_MODEL == 1
#ifdef WV_COAST
  WvResult r0 = wv_gerstnerCoast(0, uWaveCount, d, fr, depthM, wvCoasts[0]);
#else
  WvResult r0 = wv_gerstner(0, uWaveCount, d, fr, depthM);
#endif
  det[0] = r0.jac.w;
  normal0 = r0.normal.xyz;
#else
  det[0] = foldAt(0, d, fr, depthM);
  normal0 = vec3(0.0);
#endif
  for (int k = 1; k < FOAM_TIMES; ++k) det[k] = foldAt(k, d, fr, depthM);
  float foam = 0.0;
  for (int k = 0; k < FOAM_TIMES; ++k) foam = max(foam, foamOfJacobian(det[k]) * exp(-uFoamAgeS[k] / uFoamDecayS));
  for (int k = 0; k + 1 < FOAM_TIMES; ++k) {
    float a0 = uFoamAgeS[k], a1 = uFoamAgeS[k + 1], h = a1 - a0;
    float m0 = k > 0 ? (det[k + 1] - det[k - 1]) / (a1 - uFoamAgeS[k - 1]) : (det[k + 1] - det[k]) / h;
    float m1 = k + 2 < FOAM_TIMES ? (det[k + 2] - det[k]) / (uFoamAgeS[k + 2] - a0) : (det[k + 1] - det[k]) / h;
    // Hermite in powers of u = (age - a0) / h.
    float p0 = det[k], p1 = det[k + 1];
    float c3 = 2.0 * p0 + h * m0 - 2.0 * p1 + h * m1, c2 = 3.0 * (p1 - p0) - 2.0 * h * m0 - h * m1;
    foam = max(foam, foamInStep(p0, h * m0, c2, c3, a0, h));
  }
  return foam;
}
