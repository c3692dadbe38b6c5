// A small analytic sky shared by the sky pass, the terrain haze and the
// sea's reflection: a Rayleigh-blue dome with a horizon haze and a Mie glow
// round the sun near the ground, the blue limb of the atmosphere from space.
// All colours linear.
const float kEarthRadiusM = 6371000.0;
const float kHazeScaleM = 8000.0;

// Sunlight reaching the ground for a sun `sunMu` = cos(zenith angle): redder
// and dimmer towards the horizon, zero below it.
vec3 sunLight(float sunMu) {
  // Kasten-Young air mass; its base is clamped so the night side (where the
  // smoothstep below is 0) gives 0, not 0 * NaN.
  float m = 1.0 / max(sunMu + 0.15 * pow(max(93.885 - degrees(acos(clamp(sunMu, -1.0, 1.0))), 1e-3), -1.253), 0.02);
  vec3 tau = vec3(0.0065, 0.015, 0.036) * m;  // extinction per air mass (R, G, B)
  return exp(-tau) * smoothstep(-0.05, 0.05, sunMu);
}

// Sky radiance seen along `dir` from an eye at `eyeAltM` with local up `up`;
// discScale 0 leaves out the sun's disc (reflections add their own glint).
// The sky near the ground (dome + horizon haze + sun glow, no disc) seen
// along `dir`; sun = sunLight(dot(sunDir, up)), which callers compute once
// (per vertex) and share.
vec3 skyLow(vec3 dir, vec3 up, vec3 sunDir, vec3 sun) {
  float mu = dot(dir, up);
  float sunMu = dot(sunDir, up);
  float cosSun = dot(dir, sunDir);
  vec3 light = sun + vec3(0.02);
  float h1 = 1.0 - max(mu, 0.0), h2 = h1 * h1;
  float h = h2 * h2 * h1;  // (1 - mu)^5
  vec3 zenith = vec3(0.10, 0.25, 0.65);
  vec3 horizon = vec3(0.55, 0.65, 0.80);
  vec3 ground = mix(zenith, horizon, h);
  float x = 1.0001 - 0.92 * cosSun;
  float mie = 0.08 * inversesqrt(x) / x * 0.02;  // 0.08 / x^1.5 * 0.02
  return ground * light * smoothstep(-0.3, 0.1, sunMu) + mie * light;
}

// The same with sun = sunLight(dot(sunDir, up)) given (constant over a
// view: the sky pass computes it per vertex).
vec3 skyRadianceLit(vec3 dir, vec3 up, vec3 sunDir, float eyeAltM, float eyeRadiusM, float discScale, vec3 sun) {
  float mu = dot(dir, up);
  float cosSun = dot(dir, sunDir);
  vec3 light = sun + vec3(0.02);
  vec3 lowSky = skyLow(dir, up, sunDir, sun);
  lowSky += discScale * vec3(18.0) * sun * smoothstep(0.9996, 0.99985, cosSun);  // the disc
  // From space: black, with the limb glowing where the ray grazes the air.
  float closest = mu < 0.0 ? eyeRadiusM * sqrt(max(1.0 - mu * mu, 0.0)) : eyeRadiusM;
  float limb = exp(-max(closest - kEarthRadiusM, 0.0) / 25000.0);
  vec3 space = vec3(0.25, 0.45, 1.0) * limb * light * 0.9;
  return mix(lowSky, space, smoothstep(30000.0, 200000.0, eyeAltM));
}

vec3 skyRadiance(vec3 dir, vec3 up, vec3 sunDir, float eyeAltM, float eyeRadiusM, float discScale) {
  return skyRadianceLit(dir, up, sunDir, eyeAltM, eyeRadiusM, discScale, sunLight(dot(sunDir, up)));
}

vec3 skyColor(vec3 dir, vec3 up, vec3 sunDir, float eyeAltM, float eyeRadiusM) {
  return skyRadiance(dir, up, sunDir, eyeAltM, eyeRadiusM, 1.0);
}

// Aerial perspective: optical depth of an exponential atmosphere along a
// straight path of length `distM` between heights hEye and hPoint, with a
// sea-level extinction of 1/(80 km).
float hazeAmount(float distM, float hEyeM, float hPointM) {
  float a = exp(-max(hPointM, 0.0) / kHazeScaleM), b = exp(-max(hEyeM, 0.0) / kHazeScaleM);
  float dh = max(hEyeM, 0.0) - max(hPointM, 0.0);
  float mean = abs(dh) > 1.0 ? kHazeScaleM * (a - b) / dh : a;
  return 1.0 - exp(-distM * mean / 80000.0);
}

// Extinction and blue in-scattering over a path (Rayleigh: blue scatters
// about 5x more than red).
vec3 applyHaze(vec3 c, float distM, float hEyeM, float hPointM, vec3 up, vec3 sunDir) {
  float t = hazeAmount(distM, hEyeM, hPointM);
  vec3 tr = exp(-t * vec3(1.2, 2.0, 3.6));
  vec3 inscatter = vec3(0.30, 0.45, 0.80) * (sunLight(dot(sunDir, up)) + vec3(0.02)) * 0.3;
  return c * tr + inscatter * (1.0 - tr);
}

// Linear colour -> display: exposure, a soft shoulder, sRGB-ish gamma.
vec3 toDisplay(vec3 c) {
  c = 1.0 - exp(-c * 1.6);
  return pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2));
}
