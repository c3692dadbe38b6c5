// SIMD batch of the sea-height query (see WaveBatch.h). Compiled once per
// x86 target by Highway's foreach_target; HWY_DYNAMIC_DISPATCH picks one at
// run time. Each function mirrors the algebra of shaders/waves.glsl and
// WaveField.cpp (locate, makeFrame, octaveAt/waveAt/fftPlanesAt,
// wv_solidNoise, wv_gerstner, wv_fft, the Newton inversion of surfaceAt)
// lane by lane; where it differs it says why. Noise and FFT differ from the
// scalar path only by rounding (FMA, polynomial sin/cos/atan, a different
// but exact-in-real-arithmetic order of the trilinear interpolation);
// Gerstner also by its Chebyshev inversion steps, within the inversion
// tolerance: tests/waves/test_batch.cpp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "plugin/waves/WaveBatch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
// foreach_target first, then highway.h (Highway's required order).
#include <hwy/aligned_allocator.h>
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "plugin/waves/FftOcean.h"
#include "plugin/waves/WaveBatch.h"

#include <algorithm>
#include <cmath>
#include <cstring>

HWY_BEFORE_NAMESPACE();
namespace geocean::waves::batch {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using DU64 = hn::RebindToUnsigned<D>;
using DI32 = hn::Rebind<int32_t, D>;
using DU32 = hn::Rebind<uint32_t, D>;
using VI32 = hn::Vec<DI32>;
using VU32 = hn::Vec<DU32>;

// Room for the widest vector of any target (AVX-512: 8 doubles).
constexpr std::size_t kL = HWY_MAX_BYTES / sizeof(double);

// The same constants as WaveField.cpp / waves_types.glsl.
constexpr double kPi = 3.14159265358979323846;
constexpr double kA = 6378137.0;
constexpr double kF = 1.0 / 298.257223563;
constexpr double kB = kA * (1.0 - kF);
constexpr double kE2 = kF * (2.0 - kF);
constexpr double kG = 9.80665;
constexpr double kTaperRad = 0.0078480615;
constexpr double kInversionToleranceM = 1e-5;

HWY_INLINE V S(double x) { return hn::Set(D(), x); }

// sin and cos of x from one range reduction (|x| < 1e5 here): x = n pi/2 + r
// (fdlibm's two-part pi/2, r exact to ~1e-16), fdlibm's minimax polynomials
// for sin and cos on [-pi/4, pi/4] (< 1 ulp), quadrant by swap and sign.
HWY_INLINE void SinCos(V x, V& s, V& c) {
  const D d;
  const DU64 du;
  const V magic = S(0x1.8p52);  // adding it rounds to an integer in the low mantissa bits
  const V t = hn::MulAdd(x, S(0.63661977236758134308), magic);
  const V n = hn::Sub(t, magic);
  V r = hn::NegMulAdd(n, S(1.57079632673412561417e+00), x);
  r = hn::NegMulAdd(n, S(6.07710050650619224932e-11), r);
  const V z = hn::Mul(r, r);
  V ps = hn::MulAdd(z, S(1.58969099521155010221e-10), S(-2.50507602534068634195e-08));
  ps = hn::MulAdd(z, ps, S(2.75573137070700676789e-06));
  ps = hn::MulAdd(z, ps, S(-1.98412698298579493134e-04));
  ps = hn::MulAdd(z, ps, S(8.33333333332248946124e-03));
  ps = hn::MulAdd(z, ps, S(-1.66666666666666324348e-01));
  const V sr = hn::MulAdd(hn::Mul(r, z), ps, r);
  V pc = hn::MulAdd(z, S(-1.13596475577881948265e-11), S(2.08757232129817482790e-09));
  pc = hn::MulAdd(z, pc, S(-2.75573143513906633035e-07));
  pc = hn::MulAdd(z, pc, S(2.48015872894767294178e-05));
  pc = hn::MulAdd(z, pc, S(-1.38888888888741095749e-03));
  pc = hn::MulAdd(z, pc, S(4.16666666666666019037e-02));
  const V hz = hn::Mul(z, S(0.5));
  const V w = hn::Sub(S(1.0), hz);
  // 1 - z/2 with its rounding error added back (fdlibm's __kernel_cos).
  const V cr = hn::Add(w, hn::MulAdd(hn::Mul(z, z), pc, hn::Sub(hn::Sub(S(1.0), w), hz)));
  const auto q = hn::BitCast(du, t);
  const auto swap = hn::RebindMask(d, hn::TestBit(q, hn::Set(du, 1)));
  const V sign = hn::BitCast(d, hn::Set(du, 0x8000000000000000ull));
  const V sSign = hn::And(hn::BitCast(d, hn::ShiftLeft<62>(q)), sign);
  const V cSign = hn::And(hn::BitCast(d, hn::ShiftLeft<62>(hn::Add(q, hn::Set(du, 1)))), sign);
  s = hn::Xor(hn::IfThenElse(swap, cr, sr), sSign);
  c = hn::Xor(hn::IfThenElse(swap, sr, cr), cSign);
}

// atan2(y, x) from Highway's Atan on [0, 1] (3 ulp) and octant symmetry.
HWY_INLINE V Atan2(V y, V x) {
  const D d;
  const V ay = hn::Abs(y), ax = hn::Abs(x);
  const auto swap = hn::Gt(ay, ax);
  V a = hn::Atan(d, hn::Div(hn::Min(ay, ax), hn::Max(ay, ax)));
  a = hn::IfThenElse(swap, hn::Sub(S(0.5 * kPi), a), a);
  a = hn::IfThenElse(hn::Lt(x, hn::Zero(d)), hn::Sub(S(kPi), a), a);
  return hn::CopySign(a, y);
}

HWY_INLINE V Dot(V ax, V ay, V az, V bx, V by, V bz) { return hn::MulAdd(ax, bx, hn::MulAdd(ay, by, hn::Mul(az, bz))); }

// locate() of WaveField.cpp: the point on the ellipsoid and its ENU frame.
struct Loc {
  V p[3], e[3], n[3], u[3];
};
HWY_INLINE Loc Locate(V latDeg, V lonDeg) {
  V sp, cp, sl, cl;
  SinCos(hn::Mul(latDeg, S(kPi / 180.0)), sp, cp);
  SinCos(hn::Mul(lonDeg, S(kPi / 180.0)), sl, cl);
  const V nr = hn::Div(S(kA), hn::Sqrt(hn::NegMulAdd(S(kE2), hn::Mul(sp, sp), S(1.0))));
  Loc l;
  const V ncp = hn::Mul(nr, cp);
  l.p[0] = hn::Mul(ncp, cl);
  l.p[1] = hn::Mul(ncp, sl);
  l.p[2] = hn::Mul(hn::Mul(nr, S(1.0 - kE2)), sp);
  l.e[0] = hn::Neg(sl);
  l.e[1] = cl;
  l.e[2] = hn::Zero(D());
  l.n[0] = hn::Neg(hn::Mul(sp, cl));
  l.n[1] = hn::Neg(hn::Mul(sp, sl));
  l.n[2] = cp;
  l.u[0] = hn::Mul(cp, cl);
  l.u[1] = hn::Mul(cp, sl);
  l.u[2] = sp;
  return l;
}

// The lanes of one block: inputs padded with the last point.
struct Block {
  V lat, lon, t, depth;
  std::size_t i, m;  // first point, points in use
};
template <class F>
HWY_INLINE void ForBlocks(const Points& p, F&& f) {
  const D d;
  const std::size_t nl = hn::Lanes(d);
  HWY_ALIGN double la[kL], lo[kL], ts[kL], de[kL];
  for (std::size_t i = 0; i < p.n; i += nl) {
    const std::size_t m = std::min(nl, p.n - i);
    for (std::size_t k = 0; k < nl; ++k) {
      const std::size_t j = i + std::min(k, m - 1);
      la[k] = p.latDeg[j];
      lo[k] = p.lonDeg[j];
      ts[k] = p.timesPerPoint ? p.tS[j] : p.tS[0];
      de[k] = p.depthM ? p.depthM[j] : 1e30;
    }
    f(Block{hn::Load(d, la), hn::Load(d, lo), hn::Load(d, ts), hn::Load(d, de), i, m});
  }
}

// ---- solid noise -----------------------------------------------------------

HWY_INLINE VU32 Hash(VU32 x) {
  const DU32 du;
  x = hn::Xor(x, hn::ShiftRight<16>(x));
  x = hn::Mul(x, hn::Set(du, 0x7feb352du));
  x = hn::Xor(x, hn::ShiftRight<15>(x));
  x = hn::Mul(x, hn::Set(du, 0x846ca68bu));
  return hn::Xor(x, hn::ShiftRight<16>(x));
}

// One corner of wv_perlin3: the gradient wv_grad3(h) (value and its dot
// product with the corner offset (ox, oy, oz)), decoded branch-free:
// g = h % 12 has g & 3 = h & 3 (the two signs, moved into the sign bit) and
// axis g >> 2 = (h >> 2) % 3 (exact in double: (a + 1/2) / 3 is >= 1/6 from
// an integer and a < 2^30).
struct Corner {
  V v, gx, gy, gz;
};
HWY_INLINE Corner Grad(VU32 h, V ox, V oy, V oz) {
  const D d;
  const DU64 du;
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
  // AVX-512: g = h % 12 in 64-bit lanes (floor(h / 12) = h * 0xAAAAAAAB >> 35,
  // exact for 32-bit h), then the 12 gradients from two-register permutes.
  const auto hb = hn::PromoteTo(du, h);
  const hn::Repartition<uint32_t, DU64> du32x2;
  const auto q = hn::ShiftRight<35>(hn::MulEven(hn::BitCast(du32x2, hb), hn::Set(du32x2, 0xAAAAAAABu)));
  const auto g = hn::Sub(hb, hn::Add(hn::ShiftLeft<3>(q), hn::ShiftLeft<2>(q)));
  // wv_grad3 for g = 0..11: axis g >> 2 = 0: (s1, s2, 0), 1: (s1, 0, s2), 2: (0, s1, s2).
  const __m512d x0 = _mm512_setr_pd(1, -1, 1, -1, 1, -1, 1, -1), x1 = _mm512_setr_pd(0, 0, 0, 0, 0, 0, 0, 0);
  const __m512d y0 = _mm512_setr_pd(1, 1, -1, -1, 0, 0, 0, 0), y1 = _mm512_setr_pd(1, -1, 1, -1, 0, 0, 0, 0);
  const __m512d z0 = _mm512_setr_pd(0, 0, 0, 0, 1, 1, -1, -1), z1 = _mm512_setr_pd(1, 1, -1, -1, 0, 0, 0, 0);
  Corner c;
  c.gx = V{_mm512_permutex2var_pd(x0, g.raw, x1)};
  c.gy = V{_mm512_permutex2var_pd(y0, g.raw, y1)};
  c.gz = V{_mm512_permutex2var_pd(z0, g.raw, z1)};
  c.v = hn::MulAdd(c.gz, oz, hn::MulAdd(c.gy, oy, hn::Mul(c.gx, ox)));
  return c;
#else
  const DI32 di;
  const auto hb = hn::PromoteTo(du, h);
  const V s1 = hn::BitCast(d, hn::ShiftLeft<63>(hb));
  const V s2 = hn::BitCast(d, hn::ShiftLeft<63>(hn::ShiftRight<1>(hb)));
  const V a = hn::PromoteTo(d, hn::BitCast(di, hn::ShiftRight<2>(h)));
  const V axis = hn::NegMulAdd(hn::Floor(hn::MulAdd(a, S(1.0 / 3.0), S(1.0 / 6.0))), S(3.0), a);
  const auto is0 = hn::Eq(axis, hn::Zero(d)), is2 = hn::Eq(axis, S(2.0));
  // axis 0: (s1, s2, 0); 1: (s1, 0, s2); 2: (0, s1, s2).
  Corner c;
  c.v = hn::Add(hn::Xor(hn::IfThenElse(is2, oy, ox), s1), hn::Xor(hn::IfThenElse(is0, oy, oz), s2));
  const V one1 = hn::Xor(S(1.0), s1), one2 = hn::Xor(S(1.0), s2);
  c.gx = hn::IfThenZeroElse(is2, one1);
  c.gy = hn::IfThenElse(is0, one2, hn::IfThenElseZero(is2, one1));
  c.gz = hn::IfThenZeroElse(is0, one2);
  return c;
#endif
}

HWY_INLINE V Lerp(V a, V b, V t) { return hn::MulAdd(t, hn::Sub(b, a), a); }
// Trilinear interpolation of 8 corner values (a..h in wv_perlin3's order).
HWY_INLINE V Tri(V a, V b, V c, V dd, V e, V f, V g, V h, V ux, V uy, V uz) {
  return Lerp(Lerp(Lerp(a, b, ux), Lerp(c, dd, ux), uy), Lerp(Lerp(e, f, ux), Lerp(g, h, ux), uy), uz);
}

// wv_perlin3: (value, d/dx, d/dy, d/dz). The interpolation is written as a
// lerp tree (the same polynomial as the kernel's expanded form).
HWY_INLINE void Perlin3(V fx, V fy, V fz, VI32 cx, VI32 cy, VI32 cz, uint32_t seed, V& val, V& nx, V& ny, V& nz) {
  const DU32 du;
  const VU32 ka = hn::Set(du, 0x8da6b343u), kb = hn::Set(du, 0xd8163841u), kc = hn::Set(du, 0xcb1ab31fu);
  const VU32 x0 = hn::Mul(hn::BitCast(du, cx), ka), x1 = hn::Add(x0, ka);
  const VU32 y0 = hn::Mul(hn::BitCast(du, cy), kb), y1 = hn::Add(y0, kb);
  const VU32 z0 = hn::Mul(hn::BitCast(du, cz), kc), z1 = hn::Add(z0, kc);
  const VU32 sd = hn::Set(du, seed);
  const VU32 s0 = hn::Xor(sd, x0), s1 = hn::Xor(sd, x1);
  const VU32 k00 = hn::Xor(s0, y0), k10 = hn::Xor(s1, y0), k01 = hn::Xor(s0, y1), k11 = hn::Xor(s1, y1);
  const V one = S(1.0);
  const V gx = hn::Sub(fx, one), gy = hn::Sub(fy, one), gz = hn::Sub(fz, one);
  const Corner a = Grad(Hash(hn::Xor(k00, z0)), fx, fy, fz);
  const Corner b = Grad(Hash(hn::Xor(k10, z0)), gx, fy, fz);
  const Corner c = Grad(Hash(hn::Xor(k01, z0)), fx, gy, fz);
  const Corner dd = Grad(Hash(hn::Xor(k11, z0)), gx, gy, fz);
  const Corner e = Grad(Hash(hn::Xor(k00, z1)), fx, fy, gz);
  const Corner f = Grad(Hash(hn::Xor(k10, z1)), gx, fy, gz);
  const Corner g = Grad(Hash(hn::Xor(k01, z1)), fx, gy, gz);
  const Corner h = Grad(Hash(hn::Xor(k11, z1)), gx, gy, gz);
  // Quintic fade u and its derivative du.
  auto fade = [](V t) { return hn::Mul(hn::Mul(hn::Mul(t, t), t), hn::MulAdd(t, hn::MulAdd(t, S(6.0), S(-15.0)), S(10.0))); };
  auto dfade = [](V t) { return hn::Mul(hn::Mul(S(30.0), hn::Mul(t, t)), hn::MulAdd(t, hn::Sub(t, S(2.0)), S(1.0))); };
  const V ux = fade(fx), uy = fade(fy), uz = fade(fz);
  const V vab = Lerp(a.v, b.v, ux), vcd = Lerp(c.v, dd.v, ux), vef = Lerp(e.v, f.v, ux), vgh = Lerp(g.v, h.v, ux);
  const V v0 = Lerp(vab, vcd, uy), v1 = Lerp(vef, vgh, uy);
  val = Lerp(v0, v1, uz);
  const V dvx = Lerp(Lerp(hn::Sub(b.v, a.v), hn::Sub(dd.v, c.v), uy), Lerp(hn::Sub(f.v, e.v), hn::Sub(h.v, g.v), uy), uz);
  const V dvy = Lerp(hn::Sub(vcd, vab), hn::Sub(vgh, vef), uz);
  const V dvz = hn::Sub(v1, v0);
  nx = hn::MulAdd(dfade(fx), dvx, Tri(a.gx, b.gx, c.gx, dd.gx, e.gx, f.gx, g.gx, h.gx, ux, uy, uz));
  ny = hn::MulAdd(dfade(fy), dvy, Tri(a.gy, b.gy, c.gy, dd.gy, e.gy, f.gy, g.gy, h.gy, ux, uy, uz));
  nz = hn::MulAdd(dfade(fz), dvz, Tri(a.gz, b.gz, c.gz, dd.gz, e.gz, f.gz, g.gz, h.gz, ux, uy, uz));
}

struct Out {
  HWY_ALIGN double h[kL], ne[kL], nn[kL], nu[kL], w[kL], it[kL], re[kL], rn[kL], ru[kL];
  void write(const Block& b, SurfacePoint* out) const {
    for (std::size_t k = 0; k < b.m; ++k) {
      SurfacePoint& s = out[b.i + k];
      s.heightM = h[k];
      s.normalEnu = {ne[k], nn[k], nu[k]};
      s.verticalVelocityMps = w[k];
      s.iterations = int(it[k]);
      s.restOffsetEnuM = {re[k], rn[k], ru[k]};
    }
  }
};

// The cell modulo 2^32 as an int32 value, as WaveField's wrapCell32 (the
// scalar path) takes it: the hash is the same, DemoteTo then never saturates.
V WrapCell32(V fl) {
  const D d;
  const V m = hn::NegMulAdd(S(4294967296.0), hn::Floor(hn::Mul(fl, S(1.0 / 4294967296.0))), fl);
  const V w = hn::IfThenElse(hn::Ge(m, S(2147483648.0)), hn::Sub(m, S(4294967296.0)), m);
  return hn::IfThenElse(hn::IsFinite(fl), w, hn::Zero(d));
}

// surfaceAt for model Noise: octaveAt + wv_solidNoise at d = 0 + toEnu.
void Noise(const NoiseOctave* oc, int count, const Points& pts, SurfacePoint* out) {
  const D d;
  const DI32 di;
  ForBlocks(pts, [&](const Block& b) {
    const Loc l = Locate(b.lat, b.lon);
    V h = hn::Zero(d), w = h, g0 = h, g1 = h, g2 = h;
    for (int i = 0; i < count; ++i) {
      const NoiseOctave& o = oc[i];
      V q[3], fr[3];
      VI32 cell[3];
      for (int k = 0; k < 3; ++k) {
        q[k] = hn::MulAdd(S(o.vel[k]), b.t, Dot(S(o.row[k][0]), S(o.row[k][1]), S(o.row[k][2]), l.p[0], l.p[1], l.p[2]));
        const V fl = hn::Floor(q[k]);
        fr[k] = hn::IfThenZeroElse(hn::IsInf(q[k]), hn::Sub(q[k], fl));  // as WaveField's finiteFrac
        cell[k] = hn::DemoteTo(di, WrapCell32(fl));
      }
      V nv, nx, ny, nz;
      Perlin3(fr[0], fr[1], fr[2], cell[0], cell[1], cell[2], o.seed, nv, nx, ny, nz);
      const V a = S(o.amplitudeM);
      h = hn::MulAdd(a, nv, h);
      const V ax = hn::Mul(a, nx), ay = hn::Mul(a, ny), az = hn::Mul(a, nz);
      g0 = hn::MulAdd(S(o.row[0][0]), ax, hn::MulAdd(S(o.row[1][0]), ay, hn::MulAdd(S(o.row[2][0]), az, g0)));
      g1 = hn::MulAdd(S(o.row[0][1]), ax, hn::MulAdd(S(o.row[1][1]), ay, hn::MulAdd(S(o.row[2][1]), az, g1)));
      g2 = hn::MulAdd(S(o.row[0][2]), ax, hn::MulAdd(S(o.row[1][2]), ay, hn::MulAdd(S(o.row[2][2]), az, g2)));
      w = hn::MulAdd(ax, S(o.vel[0]), hn::MulAdd(ay, S(o.vel[1]), hn::MulAdd(az, S(o.vel[2]), w)));
    }
    // Normal of up * h with the tangential gradient: (-ge, -gn, 1) normalised.
    const V ge = Dot(g0, g1, g2, l.e[0], l.e[1], l.e[2]), gn = Dot(g0, g1, g2, l.n[0], l.n[1], l.n[2]);
    const V inv = hn::Div(S(1.0), hn::Sqrt(hn::MulAdd(ge, ge, hn::MulAdd(gn, gn, S(1.0)))));
    Out o;
    const V zero = hn::Zero(d);
    hn::Store(h, d, o.h);
    hn::Store(hn::Neg(hn::Mul(ge, inv)), d, o.ne);
    hn::Store(hn::Neg(hn::Mul(gn, inv)), d, o.nn);
    hn::Store(inv, d, o.nu);
    hn::Store(w, d, o.w);
    hn::Store(zero, d, o.it);
    hn::Store(zero, d, o.re);
    hn::Store(zero, d, o.rn);
    hn::Store(zero, d, o.ru);
    o.write(b, out);
  });
}

// ---- Gerstner ----------------------------------------------------------------

// Per component and query point: waveAt() plus the depth terms of
// wv_gerstner, which depend on the point's depth but not on the Newton
// offset d (the scalar kernel recomputes them at every evaluation).
struct CompLanes {
  HWY_ALIGN double g[3][kL];  // dirO.xyz
  HWY_ALIGN double sO[kL];
  HWY_ALIGN double bn[3][kL];  // binO.xyz
  HWY_ALIGN double cO[kL];
  HWY_ALIGN double phase[kL];
  HWY_ALIGN double c[3][kL];  // source direction n0 cO - g0 sO
  HWY_ALIGN double az0[kL];   // amplitude * shoaling
  HWY_ALIGN double axf[kL];   // choppiness / tanh(kh)
};

struct Frame {
  V n0[3], invR, up0[3], upScale[3];
};

struct Eval {
  V hor[3], z, dzdt, nrm[3], hvel[3], a11, a12, a22, det, up[3], t1[3], t2[3];
  V t111, t112, t122, t222;  // second derivatives of the horizontal map in (t1, t2)
};

// The inversion's miss: rest offset d plus the horizontal displacement H(d),
// without its component along the query point's up u; returns its length.
HWY_INLINE V TangentMiss(V dx, V dy, V dz, const V hor[3], const V u[3], V& m0, V& m1, V& m2) {
  m0 = hn::Add(dx, hor[0]), m1 = hn::Add(dy, hor[1]), m2 = hn::Add(dz, hor[2]);
  const V mu = Dot(m0, m1, m2, u[0], u[1], u[2]);
  m0 = hn::NegMulAdd(mu, u[0], m0);
  m1 = hn::NegMulAdd(mu, u[1], m1);
  m2 = hn::NegMulAdd(mu, u[2], m2);
  return hn::Sqrt(Dot(m0, m1, m2, m0, m1, m2));
}

HWY_INLINE void Normalize(V& x, V& y, V& z) {
  const V inv = hn::Div(S(1.0), hn::Sqrt(Dot(x, y, z, x, y, z)));
  x = hn::Mul(x, inv);
  y = hn::Mul(y, inv);
  z = hn::Mul(z, inv);
}

// wv_gerstner at offset (dx, dy, dz) from the query point. kOrigin: the
// offset is 0 (the first evaluation), where the arc offset and its atan
// vanish exactly (p = sO, s = sqrt(sO^2) = sO, e = y = 0, dTheta = 0).
template <bool kOrigin>
HWY_INLINE void EvalGerstner(const GerstnerComponent* cs, const CompLanes* cl, int count, const Frame& fr, V dx, V dy,
                             V dz, V depth, Eval& r) {
  const D d;
  const V vx = hn::MulAdd(dx, fr.invR, fr.n0[0]), vy = hn::MulAdd(dy, fr.invR, fr.n0[1]),
          vz = hn::MulAdd(dz, fr.invR, fr.n0[2]);
  const V lenV = hn::Sqrt(Dot(vx, vy, vz, vx, vy, vz));
  const V il = hn::Div(S(1.0), lenV);
  const V ph0 = hn::Mul(vx, il), ph1 = hn::Mul(vy, il), ph2 = hn::Mul(vz, il);
  V u0 = hn::MulAdd(fr.upScale[0], dx, fr.up0[0]), u1 = hn::MulAdd(fr.upScale[1], dy, fr.up0[1]),
    u2 = hn::MulAdd(fr.upScale[2], dz, fr.up0[2]);
  Normalize(u0, u1, u2);
  // wv_tangent1(dirO of component 0, up), t2 = up x t1.
  const V d0 = hn::Load(d, cl[0].g[0]), d1 = hn::Load(d, cl[0].g[1]), d2 = hn::Load(d, cl[0].g[2]);
  const V dd = Dot(d0, d1, d2, u0, u1, u2);
  V t10 = hn::NegMulAdd(dd, u0, d0), t11 = hn::NegMulAdd(dd, u1, d1), t12 = hn::NegMulAdd(dd, u2, d2);
  Normalize(t10, t11, t12);
  const V t20 = hn::MulSub(u1, t12, hn::Mul(u2, t11)), t21 = hn::MulSub(u2, t10, hn::Mul(u0, t12)),
          t22 = hn::MulSub(u0, t11, hn::Mul(u1, t10));
  const V en = hn::Mul(Dot(dx, dy, dz, fr.n0[0], fr.n0[1], fr.n0[2]), fr.invR);
  const V onePlusEn = hn::Add(S(1.0), en);

  const V zero = hn::Zero(d);
  V z = zero, dzdt = zero, sumAz = zero, sumKAx = zero;
  V hor0 = zero, hor1 = zero, hor2 = zero, hv0 = zero, hv1 = zero, hv2 = zero, gz0 = zero, gz1 = zero, gz2 = zero;
  V jxx = zero, jxy = zero, jyy = zero, t111 = zero, t112 = zero, t122 = zero, t222 = zero;
  for (int i = 0; i < count; ++i) {
    const CompLanes& c = cl[i];
    const V sO = hn::Load(d, c.sO);
    V s, psi;
    if constexpr (kOrigin) {
      s = sO;
      psi = hn::Load(d, c.phase);
    } else {
      const V g0 = hn::Load(d, c.g[0]), g1 = hn::Load(d, c.g[1]), g2 = hn::Load(d, c.g[2]);
      const V b0 = hn::Load(d, c.bn[0]), b1 = hn::Load(d, c.bn[1]), b2 = hn::Load(d, c.bn[2]);
      const V cO = hn::Load(d, c.cO);
      const V eg = hn::Mul(Dot(dx, dy, dz, g0, g1, g2), fr.invR), eb = hn::Mul(Dot(dx, dy, dz, b0, b1, b2), fr.invR);
      const V p = hn::MulAdd(cO, eg, hn::Mul(sO, onePlusEn));
      const V eb2 = hn::Mul(eb, eb);
      s = hn::Sqrt(hn::MulAdd(p, p, eb2));
      const V e = hn::Div(eb2, hn::Max(hn::Add(s, p), S(1e-30)));
      const V y = hn::MulAdd(cO, e, eg), x = hn::MulAdd(sO, e, onePlusEn);
      // wv_atan2Small: Taylor series for |y/x| <= 0.05 (always within the
      // query's offsets of metres), atan2 otherwise.
      const V t = hn::Div(y, x);
      const auto small = hn::Le(hn::Abs(t), S(0.05));
      const V t2 = hn::Mul(t, t);
      V at = hn::MulAdd(t2, S(-1.0 / 11.0), S(1.0 / 9.0));
      at = hn::MulAdd(t2, at, S(-1.0 / 7.0));
      at = hn::MulAdd(t2, at, S(0.2));
      at = hn::MulAdd(t2, at, S(-1.0 / 3.0));
      at = hn::Mul(t, hn::MulAdd(t2, at, S(1.0)));
      if (!hn::AllTrue(d, small)) at = hn::IfThenElse(small, at, Atan2(y, x));
      psi = hn::MulAdd(S(cs[i].kR), at, hn::Load(d, c.phase));
    }
    // (The kernel reduces psi to [-pi, pi] for the GPU's sin/cos; SinCos
    // reduces exactly itself, and |psi| < 2 pi + k |d| stays small.)
    // Direction of travel at P: away from the source, tangent at up.
    const V c0 = hn::Load(d, c.c[0]), c1 = hn::Load(d, c.c[1]), c2 = hn::Load(d, c.c[2]);
    const V cp = Dot(c0, c1, c2, ph0, ph1, ph2);
    V r0 = hn::MulSub(ph0, cp, c0), r1 = hn::MulSub(ph1, cp, c1), r2 = hn::MulSub(ph2, cp, c2);
    const V ru = Dot(r0, r1, r2, u0, u1, u2);
    r0 = hn::NegMulAdd(ru, u0, r0);
    r1 = hn::NegMulAdd(ru, u1, r1);
    r2 = hn::NegMulAdd(ru, u2, r2);
    Normalize(r0, r1, r2);
    // smoothstep(T, 2T, s / lenV)
    const V tp = hn::Min(hn::Max(hn::Mul(hn::Sub(hn::Mul(s, il), S(kTaperRad)), S(1.0 / kTaperRad)), zero), S(1.0));
    const V taper = hn::Mul(hn::Mul(tp, tp), hn::NegMulAdd(S(2.0), tp, S(3.0)));
    const V az = hn::Mul(hn::Load(d, c.az0), taper);
    const V ax = hn::Mul(hn::Load(d, c.axf), az);
    const V kP = S(cs[i].kRef), om = S(cs[i].omega);
    V sn, cn;
    SinCos(psi, sn, cn);
    sumAz = hn::Add(sumAz, az);
    sumKAx = hn::MulAdd(ax, kP, sumKAx);
    z = hn::MulAdd(az, cn, z);
    dzdt = hn::MulAdd(hn::Mul(az, om), sn, dzdt);
    const V gzs = hn::Mul(hn::Mul(az, kP), sn), hs = hn::Mul(ax, sn), hvs = hn::Mul(hn::Mul(ax, om), cn);
    gz0 = hn::NegMulAdd(gzs, r0, gz0);
    gz1 = hn::NegMulAdd(gzs, r1, gz1);
    gz2 = hn::NegMulAdd(gzs, r2, gz2);
    hor0 = hn::NegMulAdd(hs, r0, hor0);
    hor1 = hn::NegMulAdd(hs, r1, hor1);
    hor2 = hn::NegMulAdd(hs, r2, hor2);
    hv0 = hn::MulAdd(hvs, r0, hv0);
    hv1 = hn::MulAdd(hvs, r1, hv1);
    hv2 = hn::MulAdd(hvs, r2, hv2);
    const V gx = Dot(r0, r1, r2, t10, t11, t12), gy = Dot(r0, r1, r2, t20, t21, t22);
    const V cj = hn::Mul(hn::Mul(ax, kP), cn);
    const V cjx = hn::Mul(cj, gx);
    jxx = hn::MulAdd(cjx, gx, jxx);
    jxy = hn::MulAdd(cjx, gy, jxy);
    jyy = hn::MulAdd(hn::Mul(cj, gy), gy, jyy);
    // d2H_i / dx_j dx_k = ax kP^2 sin(psi) g_i g_j g_k (before the limit lam).
    const V q = hn::Mul(hs, S(cs[i].kRef * cs[i].kRef));
    const V qxx = hn::Mul(hn::Mul(q, gx), gx), qyy = hn::Mul(hn::Mul(q, gy), gy);
    t111 = hn::MulAdd(qxx, gx, t111);
    t112 = hn::MulAdd(qxx, gy, t112);
    t122 = hn::MulAdd(qyy, gx, t122);
    t222 = hn::MulAdd(qyy, gy, t222);
  }
  // Breaking limit, one-to-one horizontal map, normal: as in the kernel.
  const V one = S(1.0);
  const V sB = hn::Min(one, hn::Div(hn::Mul(S(0.39), depth), hn::Max(sumAz, S(1e-30))));
  const V lam = hn::Mul(sB, hn::Min(one, hn::Div(S(0.9), hn::Max(hn::Mul(sB, sumKAx), S(1e-30)))));
  r.z = hn::Mul(z, sB);
  r.dzdt = hn::Mul(dzdt, sB);
  gz0 = hn::Mul(gz0, sB);
  gz1 = hn::Mul(gz1, sB);
  gz2 = hn::Mul(gz2, sB);
  r.hor[0] = hn::Mul(hor0, lam);
  r.hor[1] = hn::Mul(hor1, lam);
  r.hor[2] = hn::Mul(hor2, lam);
  r.hvel[0] = hn::Mul(hv0, lam);
  r.hvel[1] = hn::Mul(hv1, lam);
  r.hvel[2] = hn::Mul(hv2, lam);
  r.t111 = hn::Mul(t111, lam);
  r.t112 = hn::Mul(t112, lam);
  r.t122 = hn::Mul(t122, lam);
  r.t222 = hn::Mul(t222, lam);
  r.a11 = hn::NegMulAdd(lam, jxx, one);
  r.a12 = hn::Neg(hn::Mul(lam, jxy));
  r.a22 = hn::NegMulAdd(lam, jyy, one);
  r.det = hn::NegMulAdd(r.a12, r.a12, hn::Mul(r.a11, r.a22));
  const V gzx = Dot(gz0, gz1, gz2, t10, t11, t12), gzy = Dot(gz0, gz1, gz2, t20, t21, t22);
  const V idet = hn::Div(one, r.det);
  const V sx = hn::Mul(hn::NegMulAdd(r.a12, gzy, hn::Mul(r.a22, gzx)), idet);
  const V sy = hn::Mul(hn::NegMulAdd(r.a12, gzx, hn::Mul(r.a11, gzy)), idet);
  r.nrm[0] = hn::NegMulAdd(t20, sy, hn::NegMulAdd(t10, sx, u0));
  r.nrm[1] = hn::NegMulAdd(t21, sy, hn::NegMulAdd(t11, sx, u1));
  r.nrm[2] = hn::NegMulAdd(t22, sy, hn::NegMulAdd(t12, sx, u2));
  Normalize(r.nrm[0], r.nrm[1], r.nrm[2]);
  r.up[0] = u0, r.up[1] = u1, r.up[2] = u2;
  r.t1[0] = t10, r.t1[1] = t11, r.t1[2] = t12;
  r.t2[0] = t20, r.t2[1] = t21, r.t2[2] = t22;
}

// Shoaling terms of wv_gerstner for one component at one depth (scalar: only
// for points in shallow water, through the shared kernel's wv_waveNumber).
// One step of an inversion (Gerstner, FFT) on its active lanes: the step
// (st1, st2) in the tangent basis where it is converging (`newton`), else
// the plain miss (m0, m1, m2); counts the step.
template <class E, class M>
HWY_INLINE void TakeStep(const E& r, M newton, M active, V st1, V st2, V m0, V m1, V m2, V missM, V& dx, V& dy, V& dz,
                         V& lastMiss, V& iters) {
  const V s0 = hn::IfThenElse(newton, hn::MulAdd(r.t1[0], st1, hn::Mul(r.t2[0], st2)), m0);
  const V s1 = hn::IfThenElse(newton, hn::MulAdd(r.t1[1], st1, hn::Mul(r.t2[1], st2)), m1);
  const V s2 = hn::IfThenElse(newton, hn::MulAdd(r.t1[2], st1, hn::Mul(r.t2[2], st2)), m2);
  dx = hn::IfThenElse(active, hn::Sub(dx, s0), dx);
  dy = hn::IfThenElse(active, hn::Sub(dy, s1), dy);
  dz = hn::IfThenElse(active, hn::Sub(dz, s2), dz);
  lastMiss = hn::IfThenElse(active, missM, lastMiss);
  iters = hn::Add(iters, hn::IfThenElseZero(active, S(1.0)));
}

// The end of an inverted query (Gerstner, FFT): the surface's normal and
// vertical velocity at the fixed point in the point's ENU frame, and the
// rest offset found. E: the model's evaluation (Eval, FftEval).
template <class E>
HWY_INLINE void WriteSurface(const E& r, const Loc& l, V dx, V dy, V dz, V iters, const Block& b, SurfacePoint* out) {
  const D d;
  const V ne = Dot(r.nrm[0], r.nrm[1], r.nrm[2], l.e[0], l.e[1], l.e[2]);
  const V nn = Dot(r.nrm[0], r.nrm[1], r.nrm[2], l.n[0], l.n[1], l.n[2]);
  const V nu = Dot(r.nrm[0], r.nrm[1], r.nrm[2], l.u[0], l.u[1], l.u[2]);
  const V ve = Dot(r.hvel[0], r.hvel[1], r.hvel[2], l.e[0], l.e[1], l.e[2]);
  const V vn = Dot(r.hvel[0], r.hvel[1], r.hvel[2], l.n[0], l.n[1], l.n[2]);
  // w - grad(eta) . v_h with grad(eta) = -n_h / n_u.
  const V w = hn::Add(r.dzdt, hn::Div(hn::MulAdd(ne, ve, hn::Mul(nn, vn)), nu));
  Out o;
  hn::Store(r.z, d, o.h);
  hn::Store(ne, d, o.ne);
  hn::Store(nn, d, o.nn);
  hn::Store(nu, d, o.nu);
  hn::Store(w, d, o.w);
  hn::Store(iters, d, o.it);
  hn::Store(Dot(dx, dy, dz, l.e[0], l.e[1], l.e[2]), d, o.re);
  hn::Store(Dot(dx, dy, dz, l.n[0], l.n[1], l.n[2]), d, o.rn);
  hn::Store(Dot(dx, dy, dz, l.u[0], l.u[1], l.u[2]), d, o.ru);
  o.write(b, out);
}

void Shoal(double omega, double depth, double& th, double& ks) {
  th = 1.0, ks = 1.0;
  if (omega * omega / kG * depth < 12.0) {
    kd::Kernel k;
    const double kLoc = k.wv_waveNumber(omega, depth);
    th = std::tanh(kLoc * depth);
    const double n = 0.5 * (1.0 + kLoc * depth * (1.0 - th * th) / th);
    ks = std::sqrt(kG * kLoc / (2.0 * omega * omega * n));
  }
}

// surfaceAt for model Gerstner: waveAt per component, then the Newton
// inversion of the horizontal displacement lane by lane (a lane that has
// converged keeps its offset; its re-evaluation gives the same result).
void Gerstner(const GerstnerComponent* cs, int count, const Points& pts, SurfacePoint* out) {
  const D d;
  const std::size_t nl = hn::Lanes(d);
  auto lanesBuf = hwy::AllocateAligned<CompLanes>(std::size_t(count));
  CompLanes* cl = lanesBuf.get();
  double minKDeep = 1e300;
  for (int i = 0; i < count; ++i) minKDeep = std::min(minKDeep, cs[i].omega * cs[i].omega / kG);
  ForBlocks(pts, [&](const Block& b) {
    const Loc l = Locate(b.lat, b.lon);
    // makeFrame
    Frame fr;
    const V rr = hn::Sqrt(Dot(l.p[0], l.p[1], l.p[2], l.p[0], l.p[1], l.p[2]));
    fr.invR = hn::Div(S(1.0), rr);
    for (int k = 0; k < 3; ++k) fr.n0[k] = hn::Div(l.p[k], rr);
    const V o0 = hn::Div(l.p[0], S(kA * kA)), o1 = hn::Div(l.p[1], S(kA * kA)), o2 = hn::Div(l.p[2], S(kB * kB));
    const V ld = hn::Sqrt(Dot(o0, o1, o2, o0, o1, o2));
    fr.up0[0] = hn::Div(o0, ld), fr.up0[1] = hn::Div(o1, ld), fr.up0[2] = hn::Div(o2, ld);
    fr.upScale[0] = hn::Div(S(1.0), hn::Mul(S(kA * kA), ld));
    fr.upScale[1] = fr.upScale[0];
    fr.upScale[2] = hn::Div(S(1.0), hn::Mul(S(kB * kB), ld));
    const V depth = hn::Max(b.depth, S(0.05));
    HWY_ALIGN double depthL[kL];
    hn::Store(depth, d, depthL);
    bool shallow = false;
    for (std::size_t k = 0; k < nl; ++k) shallow |= minKDeep * depthL[k] < 12.0;
    // waveAt
    for (int i = 0; i < count; ++i) {
      const GerstnerComponent& c = cs[i];
      CompLanes& q = cl[i];
      const V sx = S(c.source[0]), sy = S(c.source[1]), sz = S(c.source[2]);
      const V cosT = Dot(sx, sy, sz, fr.n0[0], fr.n0[1], fr.n0[2]);
      V g0 = hn::MulSub(fr.n0[0], cosT, sx), g1 = hn::MulSub(fr.n0[1], cosT, sy), g2 = hn::MulSub(fr.n0[2], cosT, sz);
      V sinT = hn::Sqrt(Dot(g0, g1, g2, g0, g1, g2));
      const auto degenerate = hn::Lt(sinT, S(1e-15));
      const V inv = hn::Div(S(1.0), sinT);
      g0 = hn::Mul(g0, inv), g1 = hn::Mul(g1, inv), g2 = hn::Mul(g2, inv);
      if (!hn::AllFalse(d, degenerate)) {
        // At the source or its antipode: any tangent (the taper is 0 there).
        const auto useZ = hn::Lt(hn::Abs(fr.n0[2]), S(0.9));
        const V rx = hn::IfThenZeroElse(useZ, S(1.0)), rz = hn::IfThenElseZero(useZ, S(1.0));
        V a0 = hn::Mul(fr.n0[1], rz), a1 = hn::MulSub(fr.n0[2], rx, hn::Mul(fr.n0[0], rz)),
          a2 = hn::Neg(hn::Mul(fr.n0[1], rx));
        Normalize(a0, a1, a2);
        g0 = hn::IfThenElse(degenerate, a0, g0);
        g1 = hn::IfThenElse(degenerate, a1, g1);
        g2 = hn::IfThenElse(degenerate, a2, g2);
        sinT = hn::IfThenZeroElse(degenerate, sinT);
      }
      const V theta = Atan2(sinT, cosT);
      V ph = hn::Add(hn::NegMulAdd(S(c.omega), b.t, hn::Mul(S(c.kR), theta)), S(c.phase0));
      ph = hn::NegMulAdd(S(2.0 * kPi), hn::Floor(hn::Mul(ph, S(0.5 / kPi))), ph);
      hn::Store(g0, d, q.g[0]);
      hn::Store(g1, d, q.g[1]);
      hn::Store(g2, d, q.g[2]);
      hn::Store(sinT, d, q.sO);
      hn::Store(hn::MulSub(fr.n0[1], g2, hn::Mul(fr.n0[2], g1)), d, q.bn[0]);
      hn::Store(hn::MulSub(fr.n0[2], g0, hn::Mul(fr.n0[0], g2)), d, q.bn[1]);
      hn::Store(hn::MulSub(fr.n0[0], g1, hn::Mul(fr.n0[1], g0)), d, q.bn[2]);
      hn::Store(cosT, d, q.cO);
      hn::Store(ph, d, q.phase);
      hn::Store(hn::MulSub(fr.n0[0], cosT, hn::Mul(g0, sinT)), d, q.c[0]);
      hn::Store(hn::MulSub(fr.n0[1], cosT, hn::Mul(g1, sinT)), d, q.c[1]);
      hn::Store(hn::MulSub(fr.n0[2], cosT, hn::Mul(g2, sinT)), d, q.c[2]);
      if (!shallow) {
        hn::Store(S(c.amplitudeM), d, q.az0);
        hn::Store(S(c.choppiness), d, q.axf);
      } else {
        for (std::size_t k = 0; k < nl; ++k) {
          double th, ks;
          Shoal(c.omega, depthL[k], th, ks);
          q.az0[k] = c.amplitudeM * ks;
          q.axf[k] = c.choppiness / th;
        }
      }
    }
    // Newton inversion (WaveField::surfaceAt).
    const V zero = hn::Zero(d);
    V dx = zero, dy = zero, dz = zero, lastMiss = S(1e300), iters = zero;
    auto active = hn::Eq(zero, zero);
    Eval r;
    EvalGerstner<true>(cs, cl, count, fr, dx, dy, dz, depth, r);
    for (int it = 0; it < 100; ++it) {
      V m0, m1, m2;
      const V missM = TangentMiss(dx, dy, dz, r.hor, l.u, m0, m1, m2);
      active = hn::AndNot(hn::Lt(missM, S(kInversionToleranceM)), active);
      if (hn::AllFalse(d, active)) break;
      const auto newton = hn::Lt(missM, hn::Mul(S(0.5), lastMiss));
      const V mx = Dot(m0, m1, m2, r.t1[0], r.t1[1], r.t1[2]), my = Dot(m0, m1, m2, r.t2[0], r.t2[1], r.t2[2]);
      // Chebyshev step (Newton plus the second-order term): the Newton step
      // st = J^-1 miss, then st + J^-1 (T(st, st) / 2). Cubic convergence puts
      // every point within tolerance after two steps (Newton alone needs a
      // third at ~9% of points, i.e. in half of the 8-lane vectors).
      const V idet = hn::Div(S(1.0), r.det);
      const V n1 = hn::Mul(hn::NegMulAdd(r.a12, my, hn::Mul(r.a22, mx)), idet);
      const V n2 = hn::Mul(hn::NegMulAdd(r.a12, mx, hn::Mul(r.a11, my)), idet);
      const V n11 = hn::Mul(n1, n1), n12 = hn::Add(hn::Mul(n1, n2), hn::Mul(n1, n2)), n22 = hn::Mul(n2, n2);
      const V wx = hn::Mul(S(0.5), hn::MulAdd(r.t111, n11, hn::MulAdd(r.t112, n12, hn::Mul(r.t122, n22))));
      const V wy = hn::Mul(S(0.5), hn::MulAdd(r.t112, n11, hn::MulAdd(r.t122, n12, hn::Mul(r.t222, n22))));
      const V st1 = hn::MulAdd(hn::NegMulAdd(r.a12, wy, hn::Mul(r.a22, wx)), idet, n1);
      const V st2 = hn::MulAdd(hn::NegMulAdd(r.a12, wx, hn::Mul(r.a11, wy)), idet, n2);
      TakeStep(r, newton, active, st1, st2, m0, m1, m2, missM, dx, dy, dz, lastMiss, iters);
      EvalGerstner<false>(cs, cl, count, fr, dx, dy, dz, depth, r);
    }
    WriteSurface(r, l, dx, dy, dz, iters, b, out);
  });
}

// ---- FFT ocean -----------------------------------------------------------------

constexpr int kFftN = FftOcean::kN;
constexpr int kFftPlanes = FftOcean::kPlanes;
constexpr int kFftCascades = FftOcean::kCascades;

// Per query point and (plane, cascade): fractions and cells of the tile
// coordinates (fftPlanesAt), the part of wv_fft that depends on the point only.
struct FftLanes {
  HWY_ALIGN double fracU[kFftPlanes * kFftCascades][kL];
  HWY_ALIGN double fracV[kFftPlanes * kFftCascades][kL];
  HWY_ALIGN double cellU[kFftPlanes * kFftCascades][kL];
  HWY_ALIGN double cellV[kFftPlanes * kFftCascades][kL];
};

// wv_fftTangent1: the ECEF axis most nearly horizontal at up, made tangent.
HWY_INLINE void FftTangent1(V u0, V u1, V u2, V& e0, V& e1, V& e2) {
  const V a0 = hn::Abs(u0), a1 = hn::Abs(u1), a2 = hn::Abs(u2);
  const auto useX = hn::And(hn::Le(a0, a1), hn::Le(a0, a2));
  const auto useY = hn::AndNot(useX, hn::Le(a1, a2));
  const auto useZ = hn::Not(hn::Or(useX, useY));
  const V one = S(1.0);
  const V r0 = hn::IfThenElseZero(useX, one), r1 = hn::IfThenElseZero(useY, one), r2 = hn::IfThenElseZero(useZ, one);
  const V dd = Dot(r0, r1, r2, u0, u1, u2);
  e0 = hn::NegMulAdd(dd, u0, r0);
  e1 = hn::NegMulAdd(dd, u1, r1);
  e2 = hn::NegMulAdd(dd, u2, r2);
  Normalize(e0, e1, e2);
}

struct FftEval {
  V hor[3], z, dzdt, nrm[3], hvel[3], a11, a12, a22, det, up[3], t1[3], t2[3];
};

// Bilinear fetch of texel part `part`, component `comp` at the 4 corners.
struct Quad {
  V a, b, c, e;
};
HWY_INLINE Quad Fetch(const double* texels, hn::Vec<hn::RebindToSigned<D>> ia, hn::Vec<hn::RebindToSigned<D>> ib,
                      hn::Vec<hn::RebindToSigned<D>> ic, hn::Vec<hn::RebindToSigned<D>> ie, int offset) {
  const D d;
  const hn::RebindToSigned<D> di;
  const auto o = hn::Set(di, offset);
  return {hn::GatherIndex(d, texels, hn::Add(ia, o)), hn::GatherIndex(d, texels, hn::Add(ib, o)),
          hn::GatherIndex(d, texels, hn::Add(ic, o)), hn::GatherIndex(d, texels, hn::Add(ie, o))};
}

// wv_fft at offset (dx, dy, dz).
HWY_INLINE void EvalFft(const FftPlane* pl, const double* texels, const FftLanes& fl, const Frame& fr, V dx, V dy,
                        V dz, FftEval& r) {
  const D d;
  const hn::RebindToSigned<D> di;
  V u0 = hn::MulAdd(fr.upScale[0], dx, fr.up0[0]), u1 = hn::MulAdd(fr.upScale[1], dy, fr.up0[1]),
    u2 = hn::MulAdd(fr.upScale[2], dz, fr.up0[2]);
  Normalize(u0, u1, u2);
  auto weight = [](V c) {
    const V x = hn::Max(hn::Sub(hn::Abs(c), S(0.5)), hn::Zero(D()));
    return hn::Mul(x, x);
  };
  const V w0 = weight(u0), w1 = weight(u1), w2 = weight(u2);
  const V norm = hn::Div(S(1.0), hn::Sqrt(Dot(w0, w1, w2, w0, w1, w2)));
  V e10, e11, e12;
  FftTangent1(u0, u1, u2, e10, e11, e12);
  const V e20 = hn::MulSub(u1, e12, hn::Mul(u2, e11)), e21 = hn::MulSub(u2, e10, hn::Mul(u0, e12)),
          e22 = hn::MulSub(u0, e11, hn::Mul(u1, e10));
  const V zero = hn::Zero(d), one = S(1.0);
  V z = zero, dzdt = zero, g1 = zero, g2 = zero, j11 = zero, j12 = zero, j21 = zero, j22 = zero;
  V h0 = zero, h1 = zero, h2 = zero, v0 = zero, v1 = zero, v2 = zero;
  const V wp[3] = {hn::Mul(w0, norm), hn::Mul(w1, norm), hn::Mul(w2, norm)};
  const auto mask = hn::Set(di, kFftN - 1);
  for (int p = 0; p < kFftPlanes; ++p) {
    const V w = wp[p];
    if (hn::AllFalse(d, hn::Gt(w, zero))) continue;
    V val0 = zero, val1 = zero, val2 = zero, val3 = zero, du0 = zero, du1 = zero, du2 = zero, dv0 = zero,
      dv1 = zero, dv2 = zero, vel2 = zero, vel3 = zero;
    for (int c = 0; c < kFftCascades; ++c) {
      const int k = p * kFftCascades + c;
      const FftPlane& q = pl[k];
      const V tu = hn::Add(hn::Load(d, fl.fracU[k]), Dot(S(q.u[0]), S(q.u[1]), S(q.u[2]), dx, dy, dz));
      const V tv = hn::Add(hn::Load(d, fl.fracV[k]), Dot(S(q.v[0]), S(q.v[1]), S(q.v[2]), dx, dy, dz));
      const V fu = hn::Floor(tu), fv = hn::Floor(tv);
      const V fx = hn::Sub(tu, fu), fy = hn::Sub(tv, fv), perM = S(1.0 / q.metresPerTexel);
      const auto ix = hn::ConvertTo(di, hn::Add(hn::Load(d, fl.cellU[k]), fu));
      const auto iy = hn::ConvertTo(di, hn::Add(hn::Load(d, fl.cellV[k]), fv));
      const auto x0 = hn::And(ix, mask), x1 = hn::And(hn::Add(ix, hn::Set(di, 1)), mask);
      const auto y0 = hn::ShiftLeft<7>(hn::And(iy, mask)), y1 = hn::ShiftLeft<7>(hn::And(hn::Add(iy, hn::Set(di, 1)), mask));
      static_assert(kFftN == 128, "ShiftLeft<7> is the row stride");
      const auto base = hn::Set(di, q.firstTexel);
      // Index of double 0 of part 0 of each corner texel (2 dvec4 per texel).
      const auto ia = hn::ShiftLeft<3>(hn::Add(base, hn::Add(y0, x0)));
      const auto ib = hn::ShiftLeft<3>(hn::Add(base, hn::Add(y0, x1)));
      const auto ic = hn::ShiftLeft<3>(hn::Add(base, hn::Add(y1, x0)));
      const auto ie = hn::ShiftLeft<3>(hn::Add(base, hn::Add(y1, x1)));
      const V gx = hn::Sub(one, fx), gy = hn::Sub(one, fy);
      auto bil = [&](const Quad& t) {
        return hn::MulAdd(hn::MulAdd(t.c, gx, hn::Mul(t.e, fx)), fy, hn::Mul(hn::MulAdd(t.a, gx, hn::Mul(t.b, fx)), gy));
      };
      auto ddu = [&](const Quad& t) {
        return hn::Mul(hn::MulAdd(hn::Sub(t.b, t.a), gy, hn::Mul(hn::Sub(t.e, t.c), fy)), perM);
      };
      auto ddv = [&](const Quad& t) {
        return hn::Mul(hn::MulAdd(hn::Sub(t.c, t.a), gx, hn::Mul(hn::Sub(t.e, t.b), fx)), perM);
      };
      const Quad q0 = Fetch(texels, ia, ib, ic, ie, 0), q1 = Fetch(texels, ia, ib, ic, ie, 1);
      const Quad q2 = Fetch(texels, ia, ib, ic, ie, 2), q3 = Fetch(texels, ia, ib, ic, ie, 3);
      const Quad q6 = Fetch(texels, ia, ib, ic, ie, 6), q7 = Fetch(texels, ia, ib, ic, ie, 7);
      val0 = hn::Add(val0, bil(q0));
      val1 = hn::Add(val1, bil(q1));
      val2 = hn::Add(val2, bil(q2));
      val3 = hn::Add(val3, bil(q3));
      du0 = hn::Add(du0, ddu(q0));
      du1 = hn::Add(du1, ddu(q1));
      du2 = hn::Add(du2, ddu(q2));
      dv0 = hn::Add(dv0, ddv(q0));
      dv1 = hn::Add(dv1, ddv(q1));
      dv2 = hn::Add(dv2, ddv(q2));
      vel2 = hn::Add(vel2, bil(q6));
      vel3 = hn::Add(vel3, bil(q7));
    }
    // Unit tile axes of the plane (first cascade), gradients of (u, v) in (e1, e2).
    const FftPlane& q = pl[p * kFftCascades];
    const double mpt = q.metresPerTexel;
    const V ua0 = S(q.u[0] * mpt), ua1 = S(q.u[1] * mpt), ua2 = S(q.u[2] * mpt);
    const V va0 = S(q.v[0] * mpt), va1 = S(q.v[1] * mpt), va2 = S(q.v[2] * mpt);
    const V m11 = Dot(ua0, ua1, ua2, e10, e11, e12), m12 = Dot(va0, va1, va2, e10, e11, e12);
    const V m21 = Dot(ua0, ua1, ua2, e20, e21, e22), m22 = Dot(va0, va1, va2, e20, e21, e22);
    z = hn::MulAdd(w, val0, z);
    dzdt = hn::MulAdd(w, val3, dzdt);
    const V hu = hn::Mul(w, val1), hv = hn::Mul(w, val2);
    h0 = hn::MulAdd(hu, ua0, hn::MulAdd(hv, va0, h0));
    h1 = hn::MulAdd(hu, ua1, hn::MulAdd(hv, va1, h1));
    h2 = hn::MulAdd(hu, ua2, hn::MulAdd(hv, va2, h2));
    const V su = hn::Mul(w, vel2), sv = hn::Mul(w, vel3);
    v0 = hn::MulAdd(su, ua0, hn::MulAdd(sv, va0, v0));
    v1 = hn::MulAdd(su, ua1, hn::MulAdd(sv, va1, v1));
    v2 = hn::MulAdd(su, ua2, hn::MulAdd(sv, va2, v2));
    g1 = hn::MulAdd(w, hn::MulAdd(du0, m11, hn::Mul(dv0, m12)), g1);
    g2 = hn::MulAdd(w, hn::MulAdd(du0, m21, hn::Mul(dv0, m22)), g2);
    const V b11 = hn::MulAdd(du1, m11, hn::Mul(dv1, m12)), b12 = hn::MulAdd(du1, m21, hn::Mul(dv1, m22));
    const V b21 = hn::MulAdd(du2, m11, hn::Mul(dv2, m12)), b22 = hn::MulAdd(du2, m21, hn::Mul(dv2, m22));
    j11 = hn::MulAdd(w, hn::MulAdd(m11, b11, hn::Mul(m12, b21)), j11);
    j12 = hn::MulAdd(w, hn::MulAdd(m11, b12, hn::Mul(m12, b22)), j12);
    j21 = hn::MulAdd(w, hn::MulAdd(m21, b11, hn::Mul(m22, b21)), j21);
    j22 = hn::MulAdd(w, hn::MulAdd(m21, b12, hn::Mul(m22, b22)), j22);
  }
  const V hu = Dot(h0, h1, h2, u0, u1, u2), vu = Dot(v0, v1, v2, u0, u1, u2);
  r.hor[0] = hn::NegMulAdd(hu, u0, h0), r.hor[1] = hn::NegMulAdd(hu, u1, h1), r.hor[2] = hn::NegMulAdd(hu, u2, h2);
  r.hvel[0] = hn::NegMulAdd(vu, u0, v0), r.hvel[1] = hn::NegMulAdd(vu, u1, v1), r.hvel[2] = hn::NegMulAdd(vu, u2, v2);
  const V a11 = hn::Add(one, j11), a22 = hn::Add(one, j22);
  const V idet = hn::Div(one, hn::NegMulAdd(j12, j21, hn::Mul(a11, a22)));
  const V s1 = hn::Mul(hn::NegMulAdd(j21, g2, hn::Mul(a22, g1)), idet);
  const V s2 = hn::Mul(hn::NegMulAdd(j12, g1, hn::Mul(a11, g2)), idet);
  r.nrm[0] = hn::NegMulAdd(e20, s2, hn::NegMulAdd(e10, s1, u0));
  r.nrm[1] = hn::NegMulAdd(e21, s2, hn::NegMulAdd(e11, s1, u1));
  r.nrm[2] = hn::NegMulAdd(e22, s2, hn::NegMulAdd(e12, s1, u2));
  Normalize(r.nrm[0], r.nrm[1], r.nrm[2]);
  const V js = hn::Mul(S(0.5), hn::Add(j12, j21));
  r.z = z;
  r.dzdt = dzdt;
  r.a11 = a11, r.a12 = js, r.a22 = a22, r.det = hn::NegMulAdd(js, js, hn::Mul(a11, a22));
  r.up[0] = u0, r.up[1] = u1, r.up[2] = u2;
  r.t1[0] = e10, r.t1[1] = e11, r.t1[2] = e12;
  r.t2[0] = e20, r.t2[1] = e21, r.t2[2] = e22;
}

// surfaceAt for model Fft (one time: the tables given): fftPlanesAt, then
// the Newton inversion exactly as the scalar path takes it.
void Fft(const FftPlane* pl, const glm::dvec4* tex, const Points& pts, SurfacePoint* out) {
  const D d;
  const double* texels = &tex[0].x;
  FftLanes fl;
  ForBlocks(pts, [&](const Block& b) {
    const Loc l = Locate(b.lat, b.lon);
    Frame fr;
    const V o0 = hn::Div(l.p[0], S(kA * kA)), o1 = hn::Div(l.p[1], S(kA * kA)), o2 = hn::Div(l.p[2], S(kB * kB));
    const V ld = hn::Sqrt(Dot(o0, o1, o2, o0, o1, o2));
    fr.up0[0] = hn::Div(o0, ld), fr.up0[1] = hn::Div(o1, ld), fr.up0[2] = hn::Div(o2, ld);
    fr.upScale[0] = hn::Div(S(1.0), hn::Mul(S(kA * kA), ld));
    fr.upScale[1] = fr.upScale[0];
    fr.upScale[2] = hn::Div(S(1.0), hn::Mul(S(kB * kB), ld));
    for (int k = 0; k < kFftPlanes * kFftCascades; ++k) {
      const FftPlane& q = pl[k];
      const V tu = hn::Add(Dot(S(q.u[0]), S(q.u[1]), S(q.u[2]), l.p[0], l.p[1], l.p[2]), S(q.offU));
      const V tv = hn::Add(Dot(S(q.v[0]), S(q.v[1]), S(q.v[2]), l.p[0], l.p[1], l.p[2]), S(q.offV));
      const V fu = hn::Floor(tu), fv = hn::Floor(tv);
      hn::Store(hn::Sub(tu, fu), d, fl.fracU[k]);
      hn::Store(hn::Sub(tv, fv), d, fl.fracV[k]);
      // floor mod N (exact: integers below 2^53, N a power of 2)
      hn::Store(hn::NegMulAdd(hn::Floor(hn::Mul(fu, S(1.0 / kFftN))), S(kFftN), fu), d, fl.cellU[k]);
      hn::Store(hn::NegMulAdd(hn::Floor(hn::Mul(fv, S(1.0 / kFftN))), S(kFftN), fv), d, fl.cellV[k]);
    }
    const V zero = hn::Zero(d);
    V dx = zero, dy = zero, dz = zero, lastMiss = S(1e300), iters = zero;
    auto active = hn::Eq(zero, zero);
    FftEval r;
    EvalFft(pl, texels, fl, fr, dx, dy, dz, r);
    for (int it = 0; it < 100; ++it) {
      V m0, m1, m2;
      const V missM = TangentMiss(dx, dy, dz, r.hor, l.u, m0, m1, m2);
      active = hn::AndNot(hn::Lt(missM, S(kInversionToleranceM)), active);
      if (hn::AllFalse(d, active)) break;
      const auto newton = hn::Lt(missM, hn::Mul(S(0.5), lastMiss));
      const V mx = Dot(m0, m1, m2, r.t1[0], r.t1[1], r.t1[2]), my = Dot(m0, m1, m2, r.t2[0], r.t2[1], r.t2[2]);
      const V idet = hn::Div(S(1.0), r.det);
      const V st1 = hn::Mul(hn::NegMulAdd(r.a12, my, hn::Mul(r.a22, mx)), idet);
      const V st2 = hn::Mul(hn::NegMulAdd(r.a12, mx, hn::Mul(r.a11, my)), idet);
      TakeStep(r, newton, active, st1, st2, m0, m1, m2, missM, dx, dy, dz, lastMiss, iters);
      EvalFft(pl, texels, fl, fr, dx, dy, dz, r);
    }
    WriteSurface(r, l, dx, dy, dz, iters, b, out);
  });
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }
std::size_t LaneCount() { return hn::Lanes(D()); }

}  // namespace HWY_NAMESPACE
}  // namespace geocean::waves::batch
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace geocean::waves::batch {
HWY_EXPORT(Noise);
HWY_EXPORT(Gerstner);
HWY_EXPORT(Fft);
HWY_EXPORT(TargetName);
HWY_EXPORT(LaneCount);

void noise(const NoiseOctave* octaves, int count, const Points& p, SurfacePoint* out) {
  HWY_DYNAMIC_DISPATCH(Noise)(octaves, count, p, out);
}
void gerstner(const GerstnerComponent* comps, int count, const Points& p, SurfacePoint* out) {
  HWY_DYNAMIC_DISPATCH(Gerstner)(comps, count, p, out);
}
void fft(const FftPlane* planes, const glm::dvec4* texels, const Points& p, SurfacePoint* out) {
  HWY_DYNAMIC_DISPATCH(Fft)(planes, texels, p, out);
}
const char* targetName() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }
std::size_t lanes() { return HWY_DYNAMIC_DISPATCH(LaneCount)(); }
}  // namespace geocean::waves::batch
#endif
