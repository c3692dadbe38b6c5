// Shading of the sea surface, shared by the wave-grid ocean and by the
// terrain's distant water: Fresnel reflection of the sky, a water body
// colour from depth (shallow water turns turquoise, deep water dark blue),
// sun glitter from the slope variance of the waves not drawn (Cox-Munk
// microfacets), and foam.
#include "atmosphere.glsl"

float fresnelSchlick(float cosTheta) {
  float x = 1.0 - clamp(cosTheta, 0.0, 1.0), x2 = x * x;
  return 0.02 + 0.98 * x2 * x2 * x;
}

// The sun's irradiance at normal incidence, in the sky model's radiance
// units: the scene's own sun, the one that lights the sea body, foam and the
// host's terrain. (A real clear sky's zenith is ~0.04 / sr of the sun's
// irradiance, against skyLow's 0.22 that would be 5.5: the glitter tail from
// 50 km then greys the sea past the host's land, see plugin/render/README.md.)
const float kSunIrradiance = 1.0;
// The sun's angular radius (4.65 mrad): a facet tilt of half of it still
// reflects the disc, so the disc widens the slope distribution by (r/2)^2.
const float kSunDiscMss = 0.0000054;

// The share of the sun's direct light that reaches the point (shadow.glsl;
// the ocean sets it per fragment, 1 elsewhere): glitter, the sun-lit body
// and foam; the sky's light stays.
float gSunVisible = 1.0;
// The sun's specular: 0 the microfacet glitter (default), 1 paper 001's
// Phong term (eq. 19), exponent uPhongExponent (0: 1 / (2 mss), the lobe of
// the same slopes: facets tilted by b reflect the ray by 2b, so Beckmann's
// exp(-b^2 / mss) is exp(-phi^2 / (4 mss)) and cos^n(phi) ~ exp(-n phi^2 / 2)).
uniform int uSunPhong;
uniform float uPhongExponent;

// Fresnel reflectance of sea water (n = 1.34), unpolarised, exact: the
// glitter is seen at 50-80 degrees of incidence, where Schlick's form is
// 10-15 % high.
float fresnelWater(float cosI) {
  float c = clamp(cosI, 1e-3, 1.0);
  float cosT = sqrt(1.0 - (1.0 - c * c) / (1.34 * 1.34));
  float rs = (c - 1.34 * cosT) / (c + 1.34 * cosT), rp = (cosT - 1.34 * c) / (cosT + 1.34 * c);
  return 0.5 * (rs * rs + rp * rp);
}

// Smith shadowing for Gaussian (Beckmann) slopes of mean square slope mss,
// Walter et al. (2007)'s rational form of Lambda.
float smithLambda(float cosT, float mss) {
  float a = cosT / (sqrt(mss * max(1.0 - cosT * cosT, 1e-6)));
  return a >= 1.6 ? 0.0 : (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}

// Water seen through the surface (issue 13 item 5): light from the sun
// down to a bottom depthM below and back up along the view ray refracted
// by Snell's law (n = 1.34), attenuated per channel by Beer-Lambert over
// that optical path: c = a + b of pure sea water at 650, 550 and 450 nm,
// absorption a from Pope & Fry (1997; 0.340, 0.0565, 0.0092 /m) and
// scattering b from Morel (1974; 0.0009, 0.0019, 0.0045 /m). What the bottom
// does not send back the column does: the water's own (deep) colour.
const vec3 kWaterAttenuation = vec3(0.3409, 0.0584, 0.0137);
const vec3 kBottomAlbedo = vec3(0.50, 0.47, 0.40);  // bright carbonate sand
const float kWaterIndex = 1.34;

// The per-channel transmittance of the path down to depthM and back to the
// surface along the view (n, v: surface normal and the direction to the eye).
vec3 waterPathTransmittance(vec3 n, vec3 v, vec3 up, vec3 sunDir, float depthM) {
  float muV = max(-dot(refract(-v, n, 1.0 / kWaterIndex), up), 0.05);
  float sunUp = clamp(dot(sunDir, up), 0.0, 1.0);
  float sinS = sqrt(1.0 - sunUp * sunUp) / kWaterIndex;
  float muS = sqrt(1.0 - sinS * sinS);
  return exp(-kWaterAttenuation * max(depthM, 0.0) * (1.0 / muS + 1.0 / muV));
}

// Cox & Munk (1954)'s slopes are wider along the wind than across it:
// upwind variance 3.16e-3 U, crosswind 0.003 + 1.92e-3 U (U at ~10 m). The
// upwind share of the mean square slope, 0.5 without a wind axis.
float coxMunkUpwindShare(float u10) {
  float up = 3.16e-3 * u10, cross = 0.003 + 1.92e-3 * u10;
  return up / (up + cross);
}

// The Beckmann mean square slope (alpha^2, the isotropic form's mss) seen
// along the tangent direction d, for slope variances alphaU^2 / 2 and
// alphaC^2 / 2 along tu and tc.
float mssAlong(vec3 d, vec3 n, vec3 tu, vec3 tc, float aU, float aC) {
  vec2 t = vec2(dot(d, tu), dot(d, tc));
  float l2 = dot(t, t);
  if (l2 < 1e-12) return 0.5 * (aU + aC);
  return (aU * t.x * t.x + aC * t.y * t.y) / l2;
}

// sky: the reflected radiance (skyLow along the reflected ray, or the
// planar reflection where the ocean has one); refraction: the bottom through
// the water (else the old depth tint, the terrain's distant sea keeps it).
// windAxis: the wind's direction in the tangent plane and upShare its
// share of mss (coxMunkUpwindShare); upShare 0.5: isotropic.
vec3 seaColorOptics(vec3 n, vec3 v, vec3 up, vec3 sunDir, vec3 sun, float depthM, float mss, float foam,
                    vec4 reflected, bool refraction, vec3 windAxis, float upShare) {
  float ndv = max(dot(n, v), 1e-3);
  vec3 r = reflect(-v, n);
  // Reflections from below the horizon see the sea, not the sky.
  r = normalize(r + up * max(0.0, -dot(r, up)) * 1.05);
  float F = fresnelSchlick(ndv);
  vec3 sky = skyLow(r, up, sunDir, sun);
  if (reflected.a > 0.0) sky = mix(sky, reflected.rgb, reflected.a);
  vec3 light = sun * gSunVisible + vec3(0.03);
  vec3 deep = vec3(0.004, 0.025, 0.06);
  float lit = 0.35 + 0.65 * max(dot(sunDir, up), 0.0);
  vec3 body;
  if (refraction) {
    // The bottom lit by the sun through the surface (Fresnel) and the sky,
    // its radiance divided by n^2 leaving the water.
    float sunUp = max(dot(sunDir, up), 0.0);
    vec3 e = sun * (sunUp * (1.0 - fresnelWater(sunUp)) * gSunVisible) + vec3(0.03);
    vec3 bottom = kBottomAlbedo / 3.14159265 * e / (kWaterIndex * kWaterIndex);
    body = mix(deep * lit * light, bottom, waterPathTransmittance(n, v, up, sunDir, depthM));
  } else {
    // Beer-Lambert tint: shallow water shows the bright sea floor.
    float shallow = exp(-max(depthM, 0.0) / 12.0);
    body = mix(deep, vec3(0.05, 0.28, 0.30), shallow) * lit * light;
  }
  vec3 c = mix(body, sky, F);
  // Sun glitter (Cox & Munk 1954; Bruneton et al. 2010, eq. 13): facets of
  // Gaussian slopes that mirror the sun into the eye, L = E F(v.h) p(slope)
  // G / (4 n.v (n.h)^4), p the Beckmann density of mean square slope mss.
  float m = max(mss, 1e-4) + kSunDiscMss;
  vec3 h = normalize(sunDir + v);
#ifdef GEOCEAN_OPTICS_FIXED
  // The ocean's per-pixel programs are made per model (OceanRenderer):
  // llvmpipe runs both sides of a branch on a uniform.
#ifdef GEOCEAN_SUN_PHONG
  const bool phong = true;
#else
  const bool phong = false;
#endif
#else
  bool phong = uSunPhong != 0;
#endif
  if (phong) {
    // Paper 001 eq. 19's I_s = k_s I cos^n(phi), phi between the mirrored
    // view ray and the sun; k_s = F (n + 2) / 2 pi (normalised: the lobe
    // keeps the reflected energy F E whatever n).
    float e = uPhongExponent > 0.0 ? uPhongExponent : 0.5 / m;
    float cosPhi = max(dot(reflect(-v, n), sunDir), 0.0);
    c += kSunIrradiance * sun * gSunVisible * (fresnelWater(ndv) * (e + 2.0) / 6.2831853 * pow(cosPhi, e)) *
         step(0.0, dot(n, sunDir));
  } else {
  float ndh = max(dot(n, h), 1e-3), ndl = dot(n, sunDir);
  float ndh2 = ndh * ndh;
  float D, G;
#ifdef SEA_WIND_AXIS
  // Every caller gives the wind's axis (ocean_shading.glsl): the anisotropic
  // form alone, which at a share of 0.5 is the isotropic one (llvmpipe runs
  // both sides of a branch that is not known when compiling).
  const bool isotropic = false;
#else
  bool isotropic = upShare == 0.5;
#endif
  if (isotropic) {
    D = exp((ndh2 - 1.0) / (ndh2 * m)) / (3.14159265 * m * ndh2 * ndh2);
    G = 1.0 / (1.0 + smithLambda(ndv, m) + smithLambda(max(ndl, 1e-3), m));
  } else {
    // Anisotropic Beckmann: alpha^2 = 2 x the slope variance along each
    // axis (the sun's disc widens both alike), Smith's Lambda with the
    // alpha^2 along the view's and the sun's azimuths.
    vec3 tu = windAxis - n * dot(windAxis, n);
    tu = dot(tu, tu) > 1e-12 ? normalize(tu) : normalize(cross(n, abs(n.z) < 0.9 ? vec3(0, 0, 1) : vec3(1, 0, 0)));
    vec3 tc = cross(n, tu);
    float m0 = max(mss, 1e-4);
    float aU = 2.0 * m0 * upShare + kSunDiscMss, aC = 2.0 * m0 * (1.0 - upShare) + kSunDiscMss;
    float su = dot(h, tu) / ndh, sc = dot(h, tc) / ndh;
    D = exp(-(su * su / aU + sc * sc / aC)) / (3.14159265 * sqrt(aU * aC) * ndh2 * ndh2);
    G = 1.0 / (1.0 + smithLambda(ndv, mssAlong(v, n, tu, tc, aU, aC)) +
               smithLambda(max(ndl, 1e-3), mssAlong(sunDir, n, tu, tc, aU, aC)));
  }
  c += kSunIrradiance * sun * gSunVisible * (fresnelWater(dot(v, h)) * D * G / (4.0 * ndv)) * step(0.0, ndl);
  }
  vec3 foamColor = vec3(0.85, 0.9, 0.92) * (light * 0.9 + 0.1);
  return mix(c, foamColor, clamp(foam, 0.0, 1.0));
}

// depthM: water depth below the sea (positive). n: surface normal of the
// waves drawn, v: unit vector from the surface towards the eye, up: local
// vertical; sun = sunLight(dot(sunDir, up)), computed once per vertex by the
// callers. mss: mean square slope of the waves not drawn (their microfacets,
// about n). The reflected sky is the one seen from near the sea (the view
// from orbit reflects the same dome).
vec3 seaColorMss(vec3 n, vec3 v, vec3 up, vec3 sunDir, vec3 sun, float depthM, float mss, float foam) {
  return seaColorOptics(n, v, up, sunDir, sun, depthM, mss, foam, vec4(0.0), false, vec3(0.0), 0.5);
}

// The terrain's distant sea gives a roughness; its mean square slope is
// roughness^2 (Beckmann).
vec3 seaColorLit(vec3 n, vec3 v, vec3 up, vec3 sunDir, vec3 sun, float depthM, float roughness, float foam) {
  return seaColorMss(n, v, up, sunDir, sun, depthM, roughness * roughness, foam);
}

vec3 seaColor(vec3 n, vec3 v, vec3 up, vec3 sunDir, float depthM, float roughness, float foam) {
  return seaColorLit(n, v, up, sunDir, sunLight(dot(sunDir, up)), depthM, roughness, foam);
}
