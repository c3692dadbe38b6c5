// Foam that floating bodies make (issue 14 item 5): the plugin's bodies
// (ABI 1.4) are passed to the ocean's draw (OceanRenderer::setWakes), so
// the sea the host's boats float on foams around them. Per body, in the
// local tangent plane, three parts, each a fraction 0..1 that ocean.frag
// takes as crest foam (the brightest of it and the whitecaps):
// - the hull's wash: a band outside the waterline ellipse (half length a,
//   half beam b) as wide as the bow wave's stagnation head U^2 / 2g
//   (capped at b), where the bow wave breaks against the hull;
// - the Kelvin arms: foam left by the breaking bow wave along the cusp
//   lines of the Kelvin wedge, arcsin(1/3) = 19.47 degrees either side of
//   the track behind the bow (deep water, Kelvin 1887; Lighthill's Waves in
//   Fluids sec. 3.10), aged by the time since the bow passed (distance
//   behind the bow / U);
// - the turbulent wake behind the stern: half width b (1 + s / L)^(1/3)
//   at s behind it (an axisymmetric turbulent wake's x^(1/3) growth,
//   Tennekes & Lumley 1972 sec. 4.2).
// Both age as exp(-age / OceanRenderer::kWakeDecayS). Foam needs speed through the water
// (uWakeEdges, OceanRenderer::kWakeBreakingFroude and kWakeStirredMps,
// chosen for the picture: the bow wave breaking with the length Froude
// number U / sqrt(g L), the stern's wake stirred with U). A body at rest,
// or drifting with the water, makes none.
#ifndef GEOCEAN_WAKE_GLSL
#define GEOCEAN_WAKE_GLSL

#define GEOCEAN_MAX_WAKES 16
uniform int uWakeCount;
uniform vec4 uWakeCentre[GEOCEAN_MAX_WAKES];  // xyz: hull centre from the eye (m), w: half length a
uniform vec4 uWakeBow[GEOCEAN_MAX_WAKES];     // xyz: the bow's direction, w: half beam b
uniform vec4 uWakeTrack[GEOCEAN_MAX_WAKES];   // xyz: horizontal direction of motion, w: speed U (m/s)
uniform vec4 uWakeEdges;  // breaking from / fully at Froude xy; stirred from / fully at zw (m/s)

const float kKelvinTan = 0.35355339;  // tan(asin(1/3)) = 1 / sqrt(8)
// OceanRenderer::kWakeDecayS (8 s, why there).
uniform float uWakeDecayS;

// Value noise over the water (2 octaves of smooth lattice noise): foam
// breaks up into patches as it fades, instead of fading as a band.
float wakeHash(ivec2 c) {
  uint h = (uint(c.x) * 0x8da6b343u) ^ (uint(c.y) * 0xd8163841u);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h) * (1.0 / 4294967295.0);
}
float wakeNoise(vec2 p) {
  vec2 i = floor(p), f = p - i, s = f * f * (3.0 - 2.0 * f);
  ivec2 c = ivec2(i);
  return mix(mix(wakeHash(c), wakeHash(c + ivec2(1, 0)), s.x), mix(wakeHash(c + ivec2(0, 1)), wakeHash(c + ivec2(1, 1)), s.x),
             s.y);
}
// Foam of strength `amount` (0..1) at a water-fixed point (m): whole from
// 2/3 up, then patches of the noise's highest values as it fades (half the
// water at 1/3), dimming below 1/2.
float wakePatches(float amount, vec2 water) {
  float n = 0.65 * wakeNoise(water * 0.5) + 0.35 * wakeNoise(water * 1.4 + 17.0);
  return min(1.0, 2.0 * amount) * smoothstep(0.9 - 1.5 * amount, 1.1 - 1.5 * amount, n);
}

// Only programs made with GEOCEAN_WAKES (OceanRenderer: frames with a
// wake) have the loop: llvmpipe runs a loop's body once even when it makes
// no iteration, so without a wake it cost every pixel an iteration.
float wakeFoam(vec3 eyeRel, vec3 up) {
  float foam = 0.0;
#ifdef GEOCEAN_WAKES
  for (int i = 0; i < uWakeCount; ++i) {
    float a = uWakeCentre[i].w, b = uWakeBow[i].w, u = uWakeTrack[i].w;
    vec3 d = eyeRel - uWakeCentre[i].xyz;
    d -= dot(d, up) * up;
    // Past 4 decay times of the wake behind the body: nothing left.
    float reach = a + 4.0 * uWakeDecayS * u + b;
    if (dot(d, d) > reach * reach) continue;
    float fr = u / sqrt(9.81 * 2.0 * a);
    float breaking = smoothstep(uWakeEdges.x, uWakeEdges.y, fr);
    float stirred = smoothstep(uWakeEdges.z, uWakeEdges.w, u);
    // The wash: outside the waterline ellipse, the distance to it to first
    // order, (g - 1) / |grad g| of g = (x/a)^2 + (y/b)^2.
    vec3 f = normalize(uWakeBow[i].xyz - dot(uWakeBow[i].xyz, up) * up);
    float hx = dot(d, f), hy = dot(d, cross(up, f));
    float g = (hx * hx) / (a * a) + (hy * hy) / (b * b);
    float grad = 2.0 * length(vec2(hx / (a * a), hy / (b * b)));
    float outside = (g - 1.0) / max(grad, 1e-6);
    float band = min(u * u / (2.0 * 9.81), b);
    if (band > 0.0) foam = max(foam, breaking * (1.0 - smoothstep(0.5 * band, band, outside)));
    // Along the track: x ahead of the centre, y across.
    vec3 t = uWakeTrack[i].xyz;
    float tx = dot(d, t), ty = abs(dot(d, cross(up, t)));
    float behindBow = a - tx;
    // The water moves past the body at U: a point fixed in the water.
    vec2 water = vec2(tx + u * uTimeS, dot(d, cross(up, t)));
    if (behindBow > 0.0 && u > 0.0) {
      float arm = behindBow * kKelvinTan;
      float armHalfWidth = 0.25 * band + 0.01 * behindBow;
      float onArm = 1.0 - smoothstep(armHalfWidth, 2.0 * armHalfWidth, abs(ty - arm));
      foam = max(foam, wakePatches(breaking * onArm * exp(-behindBow / (u * uWakeDecayS)), water));
    }
    float behindStern = -a - tx;
    if (behindStern > 0.0 && u > 0.0) {
      float halfWidth = b * pow(1.0 + behindStern / (2.0 * a), 1.0 / 3.0);
      float inWake = 1.0 - smoothstep(0.6 * halfWidth, halfWidth, ty);
      foam = max(foam, wakePatches(stirred * inWake * exp(-behindStern / (u * uWakeDecayS)), water));
    }
  }
#endif
  return foam;
}

#endif
