// Issue 15 item 4: the breaking foam of the distance bands per fragment
// (coast_bands.glsl says which band is which).
#ifdef GEOCEAN_NO_COAST_BANDS
float coastBandFoam(float nearFoam, vec3 eyeRel) { return nearFoam; }
#else
in vec4 vBreakBand;
in vec4 vBreakPhase;
in vec4 vBreakAmp;
in float vBreakLambdaM;
uniform int uCoastBandMode;  // coast_bands.glsl's (3, 4: the middle->far fade's ends, for tests)

// nearFoam: the vertex's wv_breakingFoam; eyeRel: the fragment's position.
float coastBandFoam(float nearFoam, vec3 eyeRel) {
  if (vBreakBand.x <= 0.0) return nearFoam;
  float u = dot(vBreakAmp, cos(vBreakPhase));
  float tex = vBreakBand.z * smoothstep(0.0, vBreakBand.y, u);
  // The texture's crests fade into their mean as a pixel (the longer axis
  // of its footprint: the grazing stretch counts) nears the wavelength.
  float pixelM = max(length(dFdx(eyeRel)), length(dFdy(eyeRel)));
  float fade = smoothstep(0.25, 1.0, pixelM / max(vBreakLambdaM, 1e-3));
  if (uCoastBandMode >= 3) fade = uCoastBandMode == 3 ? 0.0 : 1.0;
  float far = mix(tex, vBreakBand.w, fade);
  return mix(nearFoam, far, vBreakBand.x);
}
#endif
