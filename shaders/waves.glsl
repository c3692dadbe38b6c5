// The wave functions, ONE source for the CPU (plugin/waves/WaveKernel.h
// includes this file inside a C++ struct, WR = double) and the GPU (a shader
// includes waves_types.glsl, declares
//   buffer ... { WvOctave wvOctaves[]; };  buffer ... { WvWave wvWaves[]; };
// and then includes this file, WR = float). Common subset of GLSL and GLM
// only: see waves_types.glsl. Inputs are patch-relative: d = P - O (m, ECEF)
// for a patch whose per-octave / per-component data the CPU computed at O.
#ifndef WAVES_GLSL
#define WAVES_GLSL

#include "waves_types.glsl"

// ---- hashing and gradient noise ------------------------------------------

uint wv_hash(uint x) {
  // "lowbias32" integer hash (C. Wellons): good avalanche, two multiplies.
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

uint wv_hashCell3(ivec3 c, uint seed) {
  return wv_hash(seed ^ (uint(c.x) * 0x8da6b343u) ^ (uint(c.y) * 0xd8163841u) ^ (uint(c.z) * 0xcb1ab31fu));
}

// Perlin's 12 cube-edge gradients: axis 0 (s1, s2, 0), 1 (s1, 0, s2),
// 2 (0, s1, s2). Branch-free (selects by arithmetic): the hash is random, so
// branches would be mispredicted half the time on the CPU.
WR3 wv_grad3(uint h) {
  uint g = h % 12u;
  WR s1 = WR(1) - WR(2) * WR(g & 1u);
  WR s2 = WR(1) - WR(2) * WR((g >> 1) & 1u);
  uint axis = g >> 2;
  WR a0 = WR(axis == 0u), a2 = WR(axis == 2u);
  return WR3(s1 * (WR(1) - a2), s2 * a0 + s1 * a2, s2 * (WR(1) - a0));
}

// 3D gradient noise with quintic fade; returns (value, d/dx, d/dy, d/dz) in
// lattice units. `f` is the position inside `cell` (0..1).
WR4 wv_perlin3(ivec3 cell, WR3 f, uint seed) {
  WR3 u = f * f * f * (f * (f * WR(6) - WR(15)) + WR(10));
  WR3 du = WR(30) * f * f * (f * (f - WR(2)) + WR(1));
  WR3 ga = wv_grad3(wv_hashCell3(cell + ivec3(0, 0, 0), seed));
  WR3 gb = wv_grad3(wv_hashCell3(cell + ivec3(1, 0, 0), seed));
  WR3 gc = wv_grad3(wv_hashCell3(cell + ivec3(0, 1, 0), seed));
  WR3 gd = wv_grad3(wv_hashCell3(cell + ivec3(1, 1, 0), seed));
  WR3 ge = wv_grad3(wv_hashCell3(cell + ivec3(0, 0, 1), seed));
  WR3 gf = wv_grad3(wv_hashCell3(cell + ivec3(1, 0, 1), seed));
  WR3 gg = wv_grad3(wv_hashCell3(cell + ivec3(0, 1, 1), seed));
  WR3 gh = wv_grad3(wv_hashCell3(cell + ivec3(1, 1, 1), seed));
  WR va = dot(ga, f);
  WR vb = dot(gb, f - WR3(1, 0, 0));
  WR vc = dot(gc, f - WR3(0, 1, 0));
  WR vd = dot(gd, f - WR3(1, 1, 0));
  WR ve = dot(ge, f - WR3(0, 0, 1));
  WR vf = dot(gf, f - WR3(1, 0, 1));
  WR vg = dot(gg, f - WR3(0, 1, 1));
  WR vh = dot(gh, f - WR3(1, 1, 1));
  WR k1 = vb - va, k2 = vc - va, k3 = ve - va;
  WR k4 = va - vb - vc + vd, k5 = va - vc - ve + vg, k6 = va - vb - ve + vf;
  WR k7 = -va + vb + vc - vd + ve - vf - vg + vh;
  WR value = va + u.x * k1 + u.y * k2 + u.z * k3 + u.x * u.y * k4 + u.y * u.z * k5 + u.z * u.x * k6 +
             u.x * u.y * u.z * k7;
  WR3 grad = ga + u.x * (gb - ga) + u.y * (gc - ga) + u.z * (ge - ga) + u.x * u.y * (ga - gb - gc + gd) +
             u.y * u.z * (ga - gc - ge + gg) + u.z * u.x * (ga - gb - ge + gf) +
             u.x * u.y * u.z * (-ga + gb + gc - gd + ge - gf - gg + gh);
  grad += du * WR3(k1 + u.y * k4 + u.z * k6 + u.y * u.z * k7,
                   k2 + u.z * k5 + u.x * k4 + u.z * u.x * k7,
                   k3 + u.x * k6 + u.y * k5 + u.x * u.y * k7);
  return WR4(value, grad.x, grad.y, grad.z);
}

// 2D gradient noise (8 gradient directions) for the paper's model; returns
// (value, d/dx, d/dy).
WR3 wv_perlin2(ivec2 cell, WR2 f, uint seed) {
  WR2 u = f * f * f * (f * (f * WR(6) - WR(15)) + WR(10));
  WR2 du = WR(30) * f * f * (f * (f - WR(2)) + WR(1));
  WR r = WR(0.70710678118654752);
  WR2 gr[4];
  for (int i = 0; i < 4; ++i) {
    ivec2 c = cell + ivec2(i & 1, i >> 1);
    uint h = wv_hash(seed ^ (uint(c.x) * 0x8da6b343u) ^ (uint(c.y) * 0xd8163841u)) & 7u;
    WR sx = (h & 1u) != 0u ? WR(-1) : WR(1);
    WR sy = (h & 2u) != 0u ? WR(-1) : WR(1);
    gr[i] = (h & 4u) != 0u ? WR2(sx * r, sy * r) : ((h & 1u) != 0u ? WR2(WR(0), sy) : WR2(sx, WR(0)));
  }
  WR va = dot(gr[0], f);
  WR vb = dot(gr[1], f - WR2(1, 0));
  WR vc = dot(gr[2], f - WR2(0, 1));
  WR vd = dot(gr[3], f - WR2(1, 1));
  WR k1 = vb - va, k2 = vc - va, k4 = va - vb - vc + vd;
  WR value = va + u.x * k1 + u.y * k2 + u.x * u.y * k4;
  WR2 grad = gr[0] + u.x * (gr[1] - gr[0]) + u.y * (gr[2] - gr[0]) + u.x * u.y * (gr[0] - gr[1] - gr[2] + gr[3]);
  grad += du * WR2(k1 + u.y * k4, k2 + u.x * k4);
  return WR3(value, grad.x, grad.y);
}

// ---- geometry -------------------------------------------------------------

// Geodetic normal at O + d.
WR3 wv_upAt(WvFrame fr, WR3 d) { return normalize(WR3(fr.up) + WR3(fr.upScale) * d); }

// ---- model: solid fractal noise (the default) -----------------------------

// Sum of `count` octaves wvOctaves[first ..]: height along the geodetic up,
// normal from the analytic gradient, vertical velocity from the octaves'
// drift. No horizontal displacement, so the query needs no inversion.
WvResult wv_solidNoise(int first, int count, WR3 d, WvFrame fr) {
  WR h = WR(0);
  WR dhdt = WR(0);
  WR3 grad = WR3(0);
  for (int i = 0; i < count; ++i) {
    WvOctave o = wvOctaves[first + i];
    WR3 r0 = WR3(o.row0), r1 = WR3(o.row1), r2 = WR3(o.row2);
    WR3 q = WR3(o.fracO) + WR3(dot(r0, d), dot(r1, d), dot(r2, d));
    WR3 fl = floor(q);
    WR4 n = wv_perlin3(ivec3(o.cellO) + ivec3(fl), q - fl, uint(o.row1.w));
    WR a = o.row0.w;
    h += a * n.x;
    grad += a * (r0 * n.y + r1 * n.z + r2 * n.w);
    dhdt += a * (n.y * o.vel.x + n.z * o.vel.y + n.w * o.vel.z);
  }
  WR3 up = wv_upAt(fr, d);
  WR3 gs = grad - dot(grad, up) * up;
  return WvResult(WR4(up * h, h), WR4(normalize(up - gs), dhdt), WR4(0), WR4(1, 0, 1, 1));
}

// ---- linear wave theory ---------------------------------------------------

// Wave number (rad/m) from the full dispersion relation w^2 = g k tanh(k h):
// Guo (2002)'s explicit approximation (max error 0.75%) and two Newton steps.
WR wv_waveNumber(WR omega, WR depthM) {
  WR x = omega * sqrt(depthM / WR(WV_G));
  WR kh = x * x * pow(WR(1) - exp(-pow(x, WR(2.4908))), WR(-1) / WR(2.4908));
  for (int i = 0; i < 2; ++i) {
    WR t = tanh(min(kh, WR(20)));
    kh -= (kh * t - x * x) / (t + kh * (WR(1) - t * t));
  }
  return kh / depthM;
}

// ---- model: Gerstner waves on great circles --------------------------------

// First axis of the tangent frame (t1, t2 = up x t1) the Jacobian is given in:
// the first component's direction at the patch origin, made tangent at `up`.
WR3 wv_tangent1(WR3 dir0, WR3 up) { return normalize(dir0 - dot(dir0, up) * up); }

// atan(y / x) for x > 0, accurate to rounding for small angles: the phase
// multiplies it by k R ~ 1e6, and GPU atan is not that accurate.
WR wv_atan2Small(WR y, WR x) {
  WR t = y / x;
  if (abs(t) > WR(0.05)) return atan(y, x);
  WR t2 = t * t;
  // Taylor series to t^11: truncation < 0.05^13 / 13, below double rounding.
  return t * (WR(1) + t2 * (WR(-1.0 / 3.0) + t2 * (WR(0.2) + t2 * (WR(-1.0 / 7.0) + t2 * (WR(1.0 / 9.0) + t2 * WR(-1.0 / 11.0))))));
}

// The coast field of component `comp` at offset d: (phase offset, sin beta,
// 1 - cos beta, Kr - 1), bilinear between nodes; 0 outside the grid (its
// outer ring of nodes is 0, so the field is continuous there). Only where
// the includer declares `WR4 wvCoastTexels[]` and defines WV_COAST.
WR4 wv_coastSample(WvCoast co, int comp, WR3 d) {
#ifdef WV_COAST
  int n = co.cell.z;
  WR tx = co.eAxis.w + dot(WR3(co.eAxis), d), ty = co.nAxis.w + dot(WR3(co.nAxis), d);
  WR fx = floor(tx), fy = floor(ty);
  int ix = co.cell.x + int(fx), iy = co.cell.y + int(fy);
  if (ix < 0 || iy < 0 || ix >= n - 1 || iy >= n - 1) return WR4(0);
  WR ax = tx - fx, ay = ty - fy;
  int b = co.cell.w + (comp * n + iy) * n + ix;
  WR4 v00 = wvCoastTexels[b], v10 = wvCoastTexels[b + 1];
  WR4 v01 = wvCoastTexels[b + n], v11 = wvCoastTexels[b + n + 1];
  return (v00 * (WR(1) - ax) + v10 * ax) * (WR(1) - ay) + (v01 * (WR(1) - ax) + v11 * ax) * ay;
#else
  return WR4(0);
#endif
}

// One component's amplitude at depth `depth` (m, >= 0.05), shared by
// wv_gerstnerCoast (the query's surface) and wv_breakingFoamMean (its phase
// average), so the two cannot drift: shoaling Ks = sqrt(cg0 / cg) at the
// local wave number, the coast field's refraction (krM1 = Kr - 1), the
// source's taper at arc s / |P| = sRel and, with a coast field (`coast`),
// Miche's steepness limit H <= 0.142 L tanh(k h). Returns (az, tanh(k h),
// kP: the wave number of the phase, the local one with a coast field).
WR3 wv_coastAmplitude(WvWave w, WR sRel, WR krM1, WR depth, bool coast) {
  WR taper = smoothstep(WR(WV_TAPER_RAD), WR(2.0 * WV_TAPER_RAD), sRel);
  WR omega = w.phase.z;
  WR kDeep = omega * omega / WR(WV_G);
  WR th = WR(1), ks = WR(1);
  WR kP = w.extra.x;
  if (kDeep * depth < WR(WV_DEEP_KH)) {
    WR kLoc = wv_waveNumber(omega, depth);
    th = tanh(kLoc * depth);
    WR n = WR(0.5) * (WR(1) + kLoc * depth * (WR(1) - th * th) / th);
    ks = sqrt(WR(WV_G) * kLoc / (WR(2) * omega * omega * n));
    if (coast) kP = kLoc;  // the phase field's |grad psi|
  }
  WR az = w.phase.w * ks * (WR(1) + krM1) * taper;
  if (coast) az = min(az, WR(0.071 * 2.0 * WV_PI) / kP * th);
  return WR3(az, th, kP);
}

// The breaking of the crest sum (sumAz: of the components' az, sumAz2: of
// az^2) at depth `depth`, shared as wv_coastAmplitude: (sB, the factor
// that keeps the highest crest sB sumAz <= 0.39 h, i.e. H <= 0.78 h; b,
// the breaking weight: brkW, the coast field's, times the share the cap
// removes; A, the level above which eq. 6 collapses the crest).
WR3 wv_coastBreaking(WR depth, WR sumAz, WR sumAz2, WR brkW) {
  WR sB = min(WR(1), WR(0.39) * depth / max(sumAz, WR(1e-30)));
  WR b = brkW * smoothstep(WR(0), WR(0.5), WR(1) - sB);
  WR zc = sB * sumAz;
  WR A = min(WR(1.4142135623730951) * sqrt(sumAz2) * sB, WR(0.8) * zc);
  return WR3(sB, b, A);
}

// Sum of `count` components wvWaves[first ..] at depth `depthM` (m, > 0; use
// 1e30 for deep water). Each component travels along great circles away from
// its source; its local wave number follows the dispersion relation at the
// sea state's reference depth (phase) and its amplitude and orbit shape
// follow the local depth (shoaling by energy-flux conservation, elliptical
// orbits, breaking limit H/h <= 0.78).
// With a coast field (co.cell.z > 0) the phase, direction and amplitude
// take the field's corrections (depth-dependent dispersion and refraction,
// plugin/waves/CoastField.h) and the orbit's wave number is the local one;
// and the waves curl and break (paper 003 eq. 5-6) by the breaker type the
// field's beach slope gives (Iribarren number, the slab after the components):
// - eq. 5, the phase stretch: the horizontal motion takes the phase
//   psi - lc c^2, c = (1 + cos psi) / 2 (the crest, c = 1, runs ahead of the
//   trough, c = 0), lc = WV_CURL_RAD min(1, (1 - T) / T), T = tanh k h, times
//   the plunging weight: 0 in deep water, growing as depth decreases (about
//   as 1 / kh in shallow water, as the waves' asymmetry does with the Ursell
//   number; full from k h = 0.55), so crests lean forward. The map stays one-to-one (the Jacobian cap below), so the
//   surface is a height field the query inverts: a lean, not an overhang.
// - eq. 6, the collapse: where the breaking cap acts (b from 1 - sB, the
//   share of the crest the 0.78 h limit removes), z above A (the local
//   significant amplitude) falls by S (z - A)^2 b with S = 1 / (2 (zc - A)),
//   zc the highest crest there (S ~ 1/A as in the paper; b plays the
//   paper's time factor: it grows as the wave runs into shallower water).
//   Monotone in z (slope >= 1 - b), and only lowers: H <= 0.78 h holds.
// The breaking foam (wv_breakingFoam) is returned in hvel.w.
WvResult wv_gerstnerCoast(int first, int count, WR3 d, WvFrame fr, WR depthM, WvCoast co) {
  WR depth = max(depthM, WR(0.05));
  WR invR = fr.radial.w;
  WR3 n0 = WR3(fr.radial);
  WR3 v = n0 + d * invR;  // P / |O|
  WR3 ph = normalize(v);
  WR lenV = length(v);
  WR3 up = wv_upAt(fr, d);
  WR3 t1 = wv_tangent1(WR3(wvWaves[first].dirO), up);
  WR3 t2 = cross(up, t1);
  WR en = dot(d, n0) * invR;

  // (iribarren, curl weight, break weight, tan beta) of the beach here.
  WR4 brk = WR4(0);
  if (co.cell.z > 0) brk = wv_coastSample(co, count, d);
  WR z = WR(0), dzdt = WR(0), sumAz = WR(0), sumAz2 = WR(0), sumKAx = WR(0);
  WR3 hor = WR3(0), hvel = WR3(0), gradZ = WR3(0);
  WR jxx = WR(0), jxy = WR(0), jyy = WR(0);
  for (int i = 0; i < count; ++i) {
    WvWave w = wvWaves[first + i];
    WR3 g0 = WR3(w.dirO), b0 = WR3(w.binO);
    WR sO = w.dirO.w, cO = w.binO.w;
    WR eg = dot(d, g0) * invR, eb = dot(d, b0) * invR;
    // Arc from the source at P minus arc at O, with the large terms cancelled
    // analytically so it is accurate in float for small d.
    WR p = sO * (WR(1) + en) + cO * eg;
    WR s = sqrt(p * p + eb * eb);
    WR e = eb * eb / max(s + p, WR(1e-30));
    WR dTheta = wv_atan2Small(eg + cO * e, WR(1) + en + sO * e);
    WR psi = w.phase.x + w.phase.y * dTheta;
    WR4 cf = WR4(0);
    if (co.cell.z > 0) cf = wv_coastSample(co, i, d);
    psi += cf.x;
    // Reduce before sin/cos: GPU sin/cos (llvmpipe) lose accuracy for large
    // arguments (measured: 9 mm errors at |psi| ~ 2000 rad without this).
    psi -= WR(2.0 * WV_PI) * floor(psi * WR(0.5 / WV_PI) + WR(0.5));
    WR3 c = n0 * cO - g0 * sO;  // source direction
    WR3 dir = ph * dot(c, ph) - c;
    dir = normalize(dir - dot(dir, up) * up);
    // Snell turning by beta about the up axis (exact no-op where cf = 0).
    dir = dir * (WR(1) - cf.z) + cross(up, dir) * cf.y;
    WR omega = w.phase.z;
    WR3 amp = wv_coastAmplitude(w, s / lenV, cf.w, depth, co.cell.z > 0);
    WR az = amp.x, th = amp.y, kP = amp.z;
    WR ax = w.extra.y * az / th;
    WR cs = cos(psi), sn = sin(psi);
    // Eq. 5: the horizontal phase psx and d(psx)/d(psi) (exactly psi and 1 without curl).
    WR lc = WR(WV_CURL_RAD) * brk.y * min(WR(1), (WR(1) - th) / th);
    WR csx = cs, snx = sn, dsx = WR(1);
    if (lc > WR(0)) {
      WR cr = WR(0.5) * (WR(1) + cs);
      WR psx = psi - lc * cr * cr;
      csx = cos(psx);
      snx = sin(psx);
      dsx = WR(1) + lc * cr * sn;
    }
    sumAz += az;
    sumAz2 += az * az;
    // |dsx| <= 1 + 0.65 lc (max of c sin(psi) is 0.6495): the fold bound.
    sumKAx += ax * kP * (WR(1) + WR(0.65) * lc);
    z += az * cs;
    dzdt += az * omega * sn;
    gradZ -= (az * kP * sn) * dir;
    hor -= (ax * snx) * dir;
    hvel += (ax * omega * csx * dsx) * dir;
    WR gx = dot(dir, t1), gy = dot(dir, t2), cj = ax * kP * csx * dsx;
    jxx += cj * gx * gx;
    jxy += cj * gx * gy;
    jyy += cj * gy * gy;
  }
  // Breaking limit on the crest, then keep the horizontal map one-to-one
  // (Jacobian eigenvalues >= 0.1) so the surface never loops.
  WR3 brkA = wv_coastBreaking(depth, sumAz, sumAz2, brk.z);
  WR sB = brkA.x;
  WR lam = sB * min(WR(1), WR(0.9) / max(sB * sumKAx, WR(1e-30)));
  z *= sB;
  dzdt *= sB;
  gradZ *= sB;
  // Eq. 6: the collapse above A where the waves break, and their foam.
  WR foam = WR(0);
  WR b = brkA.y;
  if (b > WR(0)) {
    WR zc = sB * sumAz;
    WR A = brkA.z;
    if (z > A) {
      WR S = WR(0.5) / (zc - A);
      WR m = WR(1) - WR(2) * S * b * (z - A);
      z -= S * b * (z - A) * (z - A);
      dzdt *= m;
      gradZ *= m;
    }
    foam = b * smoothstep(WR(0), A, z);
  }
  hor *= lam;
  hvel *= lam;
  WR a11 = WR(1) - lam * jxx, a12 = -lam * jxy, a22 = WR(1) - lam * jyy;
  WR det = a11 * a22 - a12 * a12;
  WR gzx = dot(gradZ, t1), gzy = dot(gradZ, t2);
  WR sx = (a22 * gzx - a12 * gzy) / det, sy = (a11 * gzy - a12 * gzx) / det;
  WR3 nrm = normalize(up - t1 * sx - t2 * sy);
  return WvResult(WR4(hor + up * z, z), WR4(nrm, dzdt), WR4(hvel, foam), WR4(a11, a12, a22, det));
}

// Breaking foam of a wv_gerstnerCoast result, 0 .. 1: the breaking
// intensity b on the crests above the still water, full above A (0 without
// a coast field, and for the other models).
WR wv_breakingFoam(WvResult r) { return r.hvel.w; }

// Issue 15 item 4, the distance bands (paper 003's LOD; shaders/coast_bands.glsl).
// E[smoothstep(0, a, u)] for u of unit variance and excess kurtosis 24 g,
// by a Gram-Charlier density phi(u) (1 + g He4(u)): Q(a) + g He3(a) phi(a)
// above a (Abramowitz & Stegun 7.1.26 for Q, error < 1.5e-7), 16 midpoints
// from 0 to a (a smooth integrand).
WR wv_crestShare(WR a, WR g) {
  WR x = a * WR(0.7071067811865476), t = WR(1) / (WR(1) + WR(0.3275911) * x);
  WR ec = t * (WR(0.254829592) + t * (WR(-0.284496736) + t * (WR(1.421413741) + t * (WR(-1.453152027) + t * WR(1.061405429))))) * exp(-x * x);
  WR e = WR(0.5) * ec + g * (a * a * a - WR(3) * a) * WR(0.3989422804014327) * exp(WR(-0.5) * a * a);
  for (int j = 0; j < 16; ++j) {
    WR u = (WR(j) + WR(0.5)) * a / WR(16);
    WR q = u / a, u2 = u * u;
    e += q * q * (WR(3) - WR(2) * q) * WR(0.3989422804014327) * exp(WR(-0.5) * u2) *
         (WR(1) + g * (u2 * u2 - WR(6) * u2 + WR(3))) * a / WR(16);
  }
  return clamp(e, WR(0), WR(1));
}

// The breaking foam averaged over the waves' phases at offset d, for cells
// too coarse to carry the crests. The amplitudes, the breaking weight b and
// the level A are wv_gerstnerCoast's, which need no phase; the crest share
// is E[smoothstep(0, A, z)] over z = sB sum az cos(psi) with independent
// uniform phases (wv_crestShare: the sum's variance and its excess
// kurtosis, -1.5 sum az^4 / (sum az^2)^2 for cosines); exact for the
// collapse, which keeps z above A.
// m: (mean foam 0 .. 1, the amplitude-weighted local wavelength in m, b,
// A / sigma). For a foam texture with that mean: the unreduced phases (psi
// with the field's offset, continuous in d) of the 4 components of largest
// deep-water amplitude (the same everywhere) and their local amplitudes
// over sqrt(sum / 2) of their squares (so sum amp cos(phase) has unit
// variance); the texture's own crest share at A / sigma is in m's place
// only through wv_crestShare (the includer's).
struct WvBreakMean {
  WR4 m;
  WR4 phase;
  WR4 amp;
  WR shareTex;  // wv_crestShare of the 4-cosine texture at A / sigma
};
WvBreakMean wv_breakingFoamMean(int first, int count, WR3 d, WvFrame fr, WR depthM, WvCoast co) {
  WvBreakMean r;
  r.m = WR4(0);
  r.phase = WR4(0);
  r.amp = WR4(0);
  r.shareTex = WR(0);
  if (co.cell.z <= 0) return r;
  WR depth = max(depthM, WR(0.05));
  WR invR = fr.radial.w;
  WR3 n0 = WR3(fr.radial);
  WR lenV = length(n0 + d * invR);
  WR en = dot(d, n0) * invR;
  WR4 brk = wv_coastSample(co, count, d);
  WR sumAz = WR(0), sumAz2 = WR(0), sumAz4 = WR(0), sumAzK = WR(0);
  WR4 top = WR4(-1);  // deep-water amplitudes of the 4 kept, decreasing
  for (int i = 0; i < count; ++i) {
    WvWave w = wvWaves[first + i];
    WR sO = w.dirO.w, cO = w.binO.w;
    WR eg = dot(d, WR3(w.dirO)) * invR, eb = dot(d, WR3(w.binO)) * invR;
    WR p = sO * (WR(1) + en) + cO * eg;
    WR s = sqrt(p * p + eb * eb);
    WR4 cf = wv_coastSample(co, i, d);
    WR3 amp = wv_coastAmplitude(w, s / lenV, cf.w, depth, true);
    WR az = amp.x, kP = amp.z;
    sumAz += az;
    sumAz2 += az * az;
    sumAz4 += az * az * az * az;
    sumAzK += az * kP;
    // Insertion into the 4 largest by w.phase.w (ties: the first stays).
    WR a0 = w.phase.w;
    if (a0 > top.w) {
      WR e0 = eb * eb / max(s + p, WR(1e-30));
      WR psi = w.phase.x + w.phase.y * wv_atan2Small(eg + cO * e0, WR(1) + en + sO * e0) + cf.x;
      if (a0 > top.x) {
        top = WR4(a0, top.x, top.y, top.z), r.phase = WR4(psi, r.phase.x, r.phase.y, r.phase.z);
        r.amp = WR4(az, r.amp.x, r.amp.y, r.amp.z);
      } else if (a0 > top.y) {
        top = WR4(top.x, a0, top.y, top.z), r.phase = WR4(r.phase.x, psi, r.phase.y, r.phase.z);
        r.amp = WR4(r.amp.x, az, r.amp.y, r.amp.z);
      } else if (a0 > top.z) {
        top = WR4(top.x, top.y, a0, top.z), r.phase = WR4(r.phase.x, r.phase.y, psi, r.phase.z);
        r.amp = WR4(r.amp.x, r.amp.y, az, r.amp.z);
      } else {
        top.w = a0, r.phase.w = psi, r.amp.w = az;
      }
    }
  }
  WR lambda = WR(2.0 * WV_PI) * sumAz / max(sumAzK, WR(1e-30));
  WR3 brkA = wv_coastBreaking(depth, sumAz, sumAz2, brk.z);
  WR sB = brkA.x, b = brkA.y, A = brkA.z;
  r.m = WR4(0, lambda, 0, 0);
  if (b <= WR(0) || sumAz2 <= WR(0)) return r;
  WR sigma = sB * sqrt(WR(0.5) * sumAz2);
  WR a = A / sigma;
  r.m = WR4(b * wv_crestShare(a, WR(-1.5 / 24.0) * sumAz4 / (sumAz2 * sumAz2)), lambda, b, a);
  WR t2 = dot(r.amp, r.amp);
  if (t2 > WR(0)) {
    r.shareTex = wv_crestShare(a, WR(-1.5 / 24.0) * dot(r.amp * r.amp, r.amp * r.amp) / (t2 * t2));
    r.amp /= sqrt(WR(0.5) * t2);
  }
  return r;
}

// Without a coast field: each component's wave number is the reference
// depth's (the renderer's call; the query's too where no field is set).
WvResult wv_gerstner(int first, int count, WR3 d, WvFrame fr, WR depthM) {
  return wv_gerstnerCoast(first, count, d, fr, depthM, WvCoast(WR4(0), WR4(0), ivec4(0)));
}

// ---- model: FFT ocean (Tessendorf) laid on the ellipsoid triplanarly -------
// Only where the includer declares wvFftPlanes[] and wvFftTexels[] and
// defines WV_FFT (the CPU does; shaders without FFT compile as before).
#ifdef WV_FFT

WR4 wv_fftTexel(ivec4 cell, int x, int y, int j) {
  int n = cell.w;
  return wvFftTexels[(cell.z + (y & (n - 1)) * n + (x & (n - 1))) * 2 + j];
}

// Weight of the tile projected along axis component c of the up vector:
// zero below 0.5, so every point has 1 or 2 (rarely 3) planes and each plane
// is seen at most 60 degrees from its normal (bounded stretch, <= 2x).
WR wv_fftWeight(WR c) {
  WR x = max(abs(c) - WR(0.5), WR(0));
  return x * x;
}

// Axis of the Jacobian's frame for wv_fft: the ECEF axis most nearly
// horizontal at `up` (never within 54 degrees of it), made tangent.
WR3 wv_fftTangent1(WR3 up) {
  WR3 ax = abs(up);
  WR3 ref = (ax.x <= ax.y && ax.x <= ax.z) ? WR3(1, 0, 0) : (ax.y <= ax.z ? WR3(0, 1, 0) : WR3(0, 0, 1));
  return wv_tangent1(ref, up);
}

// Sum over `planes` x `cascades` entries wvFftPlanes[first ..] (plane-major).
// Fields are bilinear in each table; slopes and the choppy Jacobian are the
// exact derivatives of that bilinear surface, so the normal and the vertical
// velocity belong to exactly the surface whose height is returned (the
// tables' spectral slopes, texel part 1 xy, are there for smooth shading).
// The planes are blended with weights normalised in the square (so the
// variance, hence Hs, is the same everywhere); within a plane the cascades add.
WvResult wv_fft(int first, int planes, int cascades, WR3 d, WvFrame fr) {
  WR3 up = wv_upAt(fr, d);
  WR3 wgt = WR3(wv_fftWeight(up.x), wv_fftWeight(up.y), wv_fftWeight(up.z));
  WR norm = WR(1) / sqrt(dot(wgt, wgt));
  WR3 e1 = wv_fftTangent1(up), e2 = cross(up, e1);
  WR z = WR(0), dzdt = WR(0), g1 = WR(0), g2 = WR(0), j11 = WR(0), j12 = WR(0), j21 = WR(0), j22 = WR(0);
  WR3 hor = WR3(0), hvel = WR3(0);
  for (int p = 0; p < planes; ++p) {
    WvFftPlane p0 = wvFftPlanes[first + p * cascades];
    WR w = dot(wgt, WR3(p0.axis)) * norm;
    if (w <= WR(0)) continue;
    // Per plane: value (h, Dx, Dy, dh/dt), its u and v derivatives (per m),
    // and (., ., dDx/dt, dDy/dt).
    WR4 val = WR4(0), du = WR4(0), dv = WR4(0), vel = WR4(0);
    for (int c = 0; c < cascades; ++c) {
      WvFftPlane q = wvFftPlanes[first + p * cascades + c];
      WR tu = q.uAxis.w + dot(WR3(q.uAxis), d), tv = q.vAxis.w + dot(WR3(q.vAxis), d);
      WR fu = floor(tu), fv = floor(tv);
      int ix = q.cell.x + int(fu), iy = q.cell.y + int(fv);
      WR fx = tu - fu, fy = tv - fv, perM = WR(1) / q.axis.w;
      WR4 a = wv_fftTexel(q.cell, ix, iy, 0), b = wv_fftTexel(q.cell, ix + 1, iy, 0);
      WR4 cc = wv_fftTexel(q.cell, ix, iy + 1, 0), e = wv_fftTexel(q.cell, ix + 1, iy + 1, 0);
      val += (a * (WR(1) - fx) + b * fx) * (WR(1) - fy) + (cc * (WR(1) - fx) + e * fx) * fy;
      du += ((b - a) * (WR(1) - fy) + (e - cc) * fy) * perM;
      dv += ((cc - a) * (WR(1) - fx) + (e - b) * fx) * perM;
      WR4 va = wv_fftTexel(q.cell, ix, iy, 1), vb = wv_fftTexel(q.cell, ix + 1, iy, 1);
      WR4 vc = wv_fftTexel(q.cell, ix, iy + 1, 1), ve = wv_fftTexel(q.cell, ix + 1, iy + 1, 1);
      vel += (va * (WR(1) - fx) + vb * fx) * (WR(1) - fy) + (vc * (WR(1) - fx) + ve * fx) * fy;
    }
    // Unit axes from the first cascade (every cascade shares the plane's
    // axes); m: gradients of the tile coordinates u, v in the frame (e1, e2).
    WR3 ua = WR3(p0.uAxis) * p0.axis.w, va3 = WR3(p0.vAxis) * p0.axis.w;
    WR m11 = dot(ua, e1), m12 = dot(va3, e1), m21 = dot(ua, e2), m22 = dot(va3, e2);
    z += w * val.x;
    dzdt += w * val.w;
    hor += w * (val.y * ua + val.z * va3);
    hvel += w * (vel.z * ua + vel.w * va3);
    g1 += w * (du.x * m11 + dv.x * m12);
    g2 += w * (du.x * m21 + dv.x * m22);
    // d(horizontal map)/d(e1, e2) = m J m^T, J = d(Dx, Dy)/d(u, v).
    WR b11 = du.y * m11 + dv.y * m12, b12 = du.y * m21 + dv.y * m22;  // (J m^T) row 1
    WR b21 = du.z * m11 + dv.z * m12, b22 = du.z * m21 + dv.z * m22;  // (J m^T) row 2
    j11 += w * (m11 * b11 + m12 * b21);
    j12 += w * (m11 * b12 + m12 * b22);
    j21 += w * (m21 * b11 + m22 * b21);
    j22 += w * (m21 * b12 + m22 * b22);
  }
  hor -= dot(hor, up) * up;
  hvel -= dot(hvel, up) * up;
  // The displaced surface's slope: A^-T grad h, A = I + dH/dx (frame e1, e2).
  WR a11 = WR(1) + j11, a22 = WR(1) + j22;
  WR det = a11 * a22 - j12 * j21;
  WR s1 = (a22 * g1 - j21 * g2) / det, s2 = (a11 * g2 - j12 * g1) / det;
  // jac: symmetrised (it only sets the speed of the query's Newton steps).
  WR js = WR(0.5) * (j12 + j21);
  return WvResult(WR4(hor + up * z, z), WR4(normalize(up - s1 * e1 - s2 * e2), dzdt), WR4(hvel, WR(0)),
                  WR4(a11, js, a22, a11 * a22 - js * js));
}

// The choppy map's Jacobian determinant det(I + dD/dx) for whitecaps
// (shaders/foam.glsl; WaveField::foldJacobian). wv_fft's exact derivatives
// of the bilinear tables jump at every texel edge, so a fold threshold drew
// the coarse cascade's texels as blocks; here the derivatives are central
// differences at the texels, interpolated bilinearly: continuous.
WR2 wv_fftChop(ivec4 cell, int x, int y) {
  WR4 t = wv_fftTexel(cell, x, y, 0);
  return WR2(t.y, t.z);
}

WR wv_fftFold(int first, int planes, int cascades, WR3 d, WvFrame fr) {
  WR3 up = wv_upAt(fr, d);
  WR3 wgt = WR3(wv_fftWeight(up.x), wv_fftWeight(up.y), wv_fftWeight(up.z));
  WR norm = WR(1) / sqrt(dot(wgt, wgt));
  WR3 e1 = wv_fftTangent1(up), e2 = cross(up, e1);
  WR j11 = WR(0), j12 = WR(0), j21 = WR(0), j22 = WR(0);
  for (int p = 0; p < planes; ++p) {
    WvFftPlane p0 = wvFftPlanes[first + p * cascades];
    WR w = dot(wgt, WR3(p0.axis)) * norm;
    if (w <= WR(0)) continue;
    WR2 du = WR2(0), dv = WR2(0);  // d(Dx, Dy)/du and /dv, per m
    for (int c = 0; c < cascades; ++c) {
      WvFftPlane q = wvFftPlanes[first + p * cascades + c];
      WR tu = q.uAxis.w + dot(WR3(q.uAxis), d), tv = q.vAxis.w + dot(WR3(q.vAxis), d);
      WR fu = floor(tu), fv = floor(tv);
      int ix = q.cell.x + int(fu), iy = q.cell.y + int(fv);
      WR fx = tu - fu, fy = tv - fv, halfPerM = WR(0.5) / q.axis.w;
      WR2 a = wv_fftChop(q.cell, ix, iy), b = wv_fftChop(q.cell, ix + 1, iy);
      WR2 cc = wv_fftChop(q.cell, ix, iy + 1), e = wv_fftChop(q.cell, ix + 1, iy + 1);
      WR2 du00 = b - wv_fftChop(q.cell, ix - 1, iy), du10 = wv_fftChop(q.cell, ix + 2, iy) - a;
      WR2 du01 = e - wv_fftChop(q.cell, ix - 1, iy + 1), du11 = wv_fftChop(q.cell, ix + 2, iy + 1) - cc;
      WR2 dv00 = cc - wv_fftChop(q.cell, ix, iy - 1), dv10 = e - wv_fftChop(q.cell, ix + 1, iy - 1);
      WR2 dv01 = wv_fftChop(q.cell, ix, iy + 2) - a, dv11 = wv_fftChop(q.cell, ix + 1, iy + 2) - b;
      du += ((du00 * (WR(1) - fx) + du10 * fx) * (WR(1) - fy) + (du01 * (WR(1) - fx) + du11 * fx) * fy) * halfPerM;
      dv += ((dv00 * (WR(1) - fx) + dv10 * fx) * (WR(1) - fy) + (dv01 * (WR(1) - fx) + dv11 * fx) * fy) * halfPerM;
    }
    WR3 ua = WR3(p0.uAxis) * p0.axis.w, va3 = WR3(p0.vAxis) * p0.axis.w;
    WR m11 = dot(ua, e1), m12 = dot(va3, e1), m21 = dot(ua, e2), m22 = dot(va3, e2);
    WR b11 = du.x * m11 + dv.x * m12, b12 = du.x * m21 + dv.x * m22;
    WR b21 = du.y * m11 + dv.y * m12, b22 = du.y * m21 + dv.y * m22;
    j11 += w * (m11 * b11 + m12 * b21);
    j12 += w * (m11 * b12 + m12 * b22);
    j21 += w * (m21 * b11 + m22 * b21);
    j22 += w * (m21 * b12 + m22 * b22);
  }
  return (WR(1) + j11) * (WR(1) + j22) - j12 * j21;
}

#endif  // WV_FFT

// ---- the detail normal layer (issue 13 item 2) -----------------------------

// Waves shorter than the model draws, as a shading normal only (no height,
// so the query is unchanged: plugin/waves/README.md). `count` plane waves of
// the spectrum's short band, per wave (WaveField's detailPatch, at the patch
// origin O): wvDetail[2 i] = (k g: the wave vector, ECEF, rad/m; a k: the
// slope amplitude), wvDetail[2 i + 1] = (phase at O and the frame's time,
// wavelength m, 0, 0); ordered by wavelength, longest first. The
// great-circle wave's phase at O + d is taken to first order (its
// curvature, k |d|^2 / 2R, is < 0.01 rad wherever the fade keeps the wave).
// Returns the height's gradient (ECEF, m/m) of the waves whose wavelength
// is over 4 pixels (footprintM each), faded out by 2 pixels, and in w their
// slope variance (the fade's keep^2 a^2 k^2 / 2), which the caller takes
// from the roughness.
// Only where the includer declares `WR4 wvDetail[]` and defines WV_DETAIL.
#ifdef WV_DETAIL
WR4 wv_detailSlope(int count, WR3 d, WR footprintM) {
  WR3 grad = WR3(0);
  WR kept = WR(0);
  for (int i = 0; i < count; ++i) {
    WR4 kv = wvDetail[2 * i], ph = wvDetail[2 * i + 1];
    WR keep = smoothstep(WR(2), WR(4), ph.y / max(footprintM, WR(1e-6)));
    if (keep <= WR(0)) break;  // shorter waves follow
    WR s = kv.w * keep;
    grad -= WR3(kv) * (s / length(WR3(kv)) * sin(ph.x + dot(WR3(kv), d)));
    kept += WR(0.5) * s * s;
  }
  return WR4(grad, kept);
}
#endif

#endif
