// Paper 002's model ("noise-paper", eq. 4-5), ONE source for the CPU query
// (plugin/waves/WaveKernel.h, WR = double) and the GPU (ocean.vert,
// waves_eval.glsl; WR = float): 2D fractal noise at
//   (x, y) = R (lambda cos(phi), phi),  R = the mean radius, lambda in [-pi, pi),
// height along the geodetic up. lambda wraps at +-180 degrees, so x jumps
// by 2 pi R cos(phi) there: the model's seam, drawn as the query computes it.
//
// Patch-relative as the other models: per octave the CPU reduces, in
// double, the lattice coordinate at the origin O (integer cell + fraction,
// for O's lambda and for lambda - / + 2 pi, the other side of the seam); the
// kernel adds only f R (lambda cos(phi) - lambda0 cos(phi0), phi - phi0),
// with the longitude and latitude differences taken from d = P - O without
// subtracting large numbers (below). P must lie on the ellipsoid (rest
// points do): the latitude is atan(z / ((1 - e^2) rho)) there.
// Include after waves.glsl (wv_perlin2); `#define WV_PAPER_TYPES_ONLY`
// before including it gives the struct alone (the float upload layout).
#ifndef WAVES_PAPER_TYPES
#define WAVES_PAPER_TYPES
// The patch origin as the paper's model sees it (WaveField::cpuPatch).
struct WvPaper {
  WR4 horiz;   // xy: (cos, sin) of lambda0, z: rho0 = O's distance from the polar axis (m), w: O's z (m)
  WR4 angles;  // x: phi0 = atan(z0 / ((1 - e^2) rho0)) (rad), y: lambda0 in [-pi, pi) (rad),
               // z: lambda0 -/+ 2 pi (the other side of the seam), w: the seam's longitude
               // difference (pi - lambda0 if lambda0 >= 0, else -pi - lambda0)
  WR4 trig;    // x, y: sin, cos of phi0; z, w: 0
};
#endif

#if !defined(WV_PAPER_TYPES_ONLY) && !defined(WAVES_PAPER_GLSL)
#define WAVES_PAPER_GLSL
#define WV_WGS84_A 6378137.0
#define WV_WGS84_E2 0.0066943799901413165
#define WV_MEAN_RADIUS 6371008.8

// The GPU's own atan, sin and cos are not accurate enough for offsets that
// the seam's shear multiplies by up to pi (llvmpipe's atan errs by 2e-5
// relative: 16 mm of height 5 km from the origin), so the kernel uses
// these, accurate to ~1e-13 in double and to float rounding on the GPU.
// sin and cos of x for |x| <= pi / 2: Taylor series to x^17 / 17!.
WR2 wv_paperSinCos(WR x) {
  if (x == WR(0)) return WR2(0, 1);  // the query's own point: no series
  WR x2 = x * x, s = WR(1), c = WR(1);
  for (int k = 8; k >= 1; --k) {
    s = WR(1) - x2 / WR((2 * k) * (2 * k + 1)) * s;
    c = WR(1) - x2 / WR((2 * k - 1) * (2 * k)) * c;
  }
  return WR2(x * s, c);
}
// atan(t) for |t| <= 1: two half-angle steps (|t| <= tan(pi / 16)), then the
// series to t^17.
WR wv_paperAtan(WR t) {
  t = t / (WR(1) + sqrt(WR(1) + t * t));
  t = t / (WR(1) + sqrt(WR(1) + t * t));
  WR t2 = t * t, s = WR(0);
  for (int k = 8; k >= 0; --k) s = WR(1) / WR(2 * k + 1) - t2 * s;
  return WR(4) * t * s;
}
// atan2(y, x) in (-pi, pi]; 0 for (0, 0).
WR wv_paperAtan2(WR y, WR x) {
  WR ax = abs(x), ay = abs(y);
  if (ay == WR(0)) return x < WR(0) ? WR(WV_PI) : WR(0);  // also (0, 0), and the query's own point
  WR a = ay <= ax ? wv_paperAtan(ay / ax) : WR(0.5 * WV_PI) - wv_paperAtan(ax / ay);
  a = x < WR(0) ? WR(WV_PI) - a : a;
  return y < WR(0) ? -a : a;
}

// `count` octaves from wvOctaves[first] laid out for this model
// (WaveField.cpp paperOctaveAt): row0.x f R (lattice units per radian),
// row0.w amplitude (m), row1.w seed, fracO.xy / cellO.xy the lattice
// coordinate at O, fracO.zw / cellO.zw at O across the seam, vel.xy the
// lattice's drift (units per second). footprintM > 0 (a pixel's, ocean.frag)
// keeps each octave at weight smoothstep(2, 4, wavelength / footprintM):
// none under 2 footprints, so no sub-pixel sparkle; 0 keeps all (the query).
WvResult wv_paperNoiseFiltered(int first, int count, WR3 d, WvPaper pp, WR footprintM) {
  WR rho0 = pp.horiz.z, z0 = pp.horiz.w;
  // Longitude difference: the angle between the horizontal parts of O and
  // P from their cross and dot products (rho0 u x d, rho0^2 + rho0 u . d):
  // no large terms cancel.
  WR along = pp.horiz.x * d.x + pp.horiz.y * d.y;
  WR crs = pp.horiz.x * d.y - pp.horiz.y * d.x;
  WR dlam = wv_paperAtan2(crs, rho0 + along);
  // Latitude difference by the tangent subtraction formula on
  // t = z / ((1 - e^2) rho): the numerator dz rho0 - z0 drho has no
  // cancelling terms, drho = (rho^2 - rho0^2) / (rho + rho0).
  WR dxy2 = d.x * d.x + d.y * d.y;
  // (rho >= 0 and the axis itself guarded: at the pole rounding can make
  // the square negative, and both radii 0.)
  WR rho = sqrt(max(rho0 * rho0 + WR(2) * rho0 * along + dxy2, WR(0)));
  WR drho = rho0 + rho > WR(0) ? (WR(2) * rho0 * along + dxy2) / (rho0 + rho) : WR(0);
  WR e1 = WR(1) - WR(WV_WGS84_E2);
  WR dphi = wv_paperAtan2(e1 * (d.z * rho0 - z0 * drho), e1 * e1 * (rho0 + drho) * rho0 + (z0 + d.z) * z0);
  // The seam: past lambda = +-pi the point takes the other side's lattice
  // origin (lambda0 -/+ 2 pi), as the query wraps lambda into [-pi, pi).
  bool across = pp.angles.y >= WR(0) ? dlam >= pp.angles.w : dlam < pp.angles.w;
  WR lam0 = across ? pp.angles.z : pp.angles.y;
  WR lam = lam0 + dlam;
  // sin and cos of phi and lambda by the sum formulas from O's and the
  // half differences' (so exactly O's at d = 0).
  WR2 hp = wv_paperSinCos(WR(0.5) * dphi), hl = wv_paperSinCos(WR(0.5) * dlam);
  WR s0 = pp.trig.x, c0 = pp.trig.y;
  WR sd = WR(2) * hp.x * hp.y, cd = WR(1) - WR(2) * hp.x * hp.x;
  WR sp = s0 * cd + c0 * sd, cp = c0 * cd - s0 * sd;
  WR sdl = WR(2) * hl.x * hl.y, cdl = WR(1) - WR(2) * hl.x * hl.x;
  WR cl = pp.horiz.x * cdl - pp.horiz.y * sdl, sl = pp.horiz.y * cdl + pp.horiz.x * sdl;
  // lambda cos(phi) - lambda0 cos(phi0), cos(phi) - cos(phi0) as a product.
  WR dcos = WR(-2) * hp.x * (s0 * hp.y + c0 * hp.x);
  WR2 dq = WR2(dlam * cp + lam0 * dcos, dphi);
  WR h = WR(0), dhdt = WR(0);
  WR2 g = WR2(0);  // dh / d(lambda cos(phi), phi)
  for (int i = 0; i < count; ++i) {
    WvOctave o = wvOctaves[first + i];
    WR fR = o.row0.x;
    WR2 q = (across ? WR2(o.fracO.z, o.fracO.w) : WR2(o.fracO.x, o.fracO.y)) + fR * dq;
    WR2 fl = floor(q);
    ivec2 cell = (across ? ivec2(o.cellO.z, o.cellO.w) : ivec2(o.cellO.x, o.cellO.y)) + ivec2(fl);
    WR3 n = wv_perlin2(cell, q - fl, uint(o.row1.w));
    WR a = o.row0.w;
    if (footprintM > WR(0)) a *= smoothstep(WR(2), WR(4), WR(WV_MEAN_RADIUS) / (fR * footprintM));
    h += a * n.x;
    g += a * fR * WR2(n.y, n.z);
    dhdt += a * (n.y * o.vel.x + n.z * o.vel.y);
  }
  // Metric slopes: east, d/(N cos(phi) dlambda); north, d/(M dphi), where
  // d(lambda cos(phi))/dphi = -lambda sin(phi) (the shear away from lambda = 0).
  WR w = sqrt(WR(1) - WR(WV_WGS84_E2) * sp * sp);
  WR nRad = WR(WV_WGS84_A) / w, mRad = WR(WV_WGS84_A) * e1 / (w * w * w);
  WR dhde = g.x / nRad;
  WR dhdn = (g.y - g.x * lam * sp) / mRad;
  WR3 east = WR3(-sl, cl, WR(0)), north = WR3(-sp * cl, -sp * sl, cp), up = WR3(cp * cl, cp * sl, sp);
  return WvResult(WR4(up * h, h), WR4(normalize(up - dhde * east - dhdn * north), dhdt), WR4(0), WR4(1, 0, 1, 1));
}

WvResult wv_paperNoise(int first, int count, WR3 d, WvPaper pp) {
  return wv_paperNoiseFiltered(first, count, d, pp, WR(0));
}
#endif
