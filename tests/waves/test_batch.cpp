// The SIMD batch (WaveField::surfaceBatch, plugin/waves/WaveBatch.cpp) is a
// second implementation of the shared kernel's algebra (noise, Gerstner, FFT): it must compute the
// same function as the scalar surfaceAt (which the GPU parity test pins to
// the GLSL) at random points, across the antimeridian, at and near the
// poles, between points 1 m apart, in shallow water and at large times.
#include "globe/geo/Ellipsoid.h"
#include "tests/waves/MakeField.h"
#include "plugin/waves/TimeRange.h"
#include "plugin/waves/WaveBatch.h"
#include "plugin/waves/WaveField.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace geocean::waves;

namespace {

using geocean::waves::test::make;

struct Case {
  std::vector<double> lat, lon, t, depth;
  void add(double la, double lo, double ts, double de) {
    lat.push_back(la), lon.push_back(lo), t.push_back(ts), depth.push_back(de);
  }
};

// 1 m of latitude / longitude in degrees (mean radius; exactness not needed).
constexpr double kDegPerM = 180.0 / (M_PI * 6371008.8);

Case points(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), lon(-180, 180), t(0, 3600), big(1e5, 1e6);
  const double depths[] = {kDeepWaterM, kDeepWaterM, 4000.0, 200.0, 40.0, 10.0, 3.0, 1.0, 0.3};
  auto depth = [&] { return depths[rng() % (sizeof(depths) / sizeof(depths[0]))]; };
  Case c;
  for (int i = 0; i < 3000; ++i) c.add(std::asin(u(rng)) * 180 / M_PI, lon(rng), t(rng), depth());
  for (int i = 0; i < 300; ++i) {
    const double la = std::asin(u(rng)) * 180 / M_PI, ts = t(rng), de = depth();
    c.add(la, 179.9999999 + 1e-7 * u(rng), ts, de);  // both sides of the antimeridian
    c.add(la, -179.9999999 + 1e-7 * u(rng), ts, de);
    c.add(la, 180.0, ts, de);
    c.add(la, -180.0, ts, de);
  }
  for (int i = 0; i < 300; ++i) {
    const double ts = t(rng), lo = lon(rng);
    c.add(90.0, lo, ts, depth());  // the poles themselves and within ~1 km
    c.add(-90.0, lo, ts, depth());
    c.add(89.99 + 0.01 * std::abs(u(rng)), lo, ts, depth());
    c.add(-89.99 - 0.01 * std::abs(u(rng)), lo, ts, depth());
    c.add(89.9, lo, ts, depth());
  }
  for (int i = 0; i < 500; ++i) {  // pairs 1 m apart (east and north)
    const double la = std::asin(0.99 * u(rng)) * 180 / M_PI, lo = lon(rng), ts = t(rng), de = depth();
    c.add(la, lo, ts, de);
    c.add(la, lo + kDegPerM / std::cos(la * M_PI / 180), ts, de);
    c.add(la + kDegPerM, lo, ts, de);
  }
  for (int i = 0; i < 200; ++i) c.add(std::asin(u(rng)) * 180 / M_PI, lon(rng), big(rng), depth());  // large t
  c.add(0.0, 0.0, 0.0, kDeepWaterM);  // the Gerstner anchor (a component source can be near)
  return c;
}

// Tolerances. Both paths compute the ECEF point from their own sin/cos (each
// within an ulp or two): the points differ by a few ulp of 6.4e6 m, i.e.
// ~1e-9 m, so heights differ by |slope| x 1e-9 m and normals by curvature x
// 1e-9 (the finest noise octave bends by ~10 rad/m): measured 2e-10 m and
// 2e-9. Noise bounds: 1e-8 m, 1e-7, 1e-7 m/s (1e5 below the query's 1 mm).
// Gerstner: both paths stop the horizontal inversion when the rest point is
// within 1e-5 m (kInversionToleranceM); rounding can make one path take one
// more Newton step than the other, so two results may sit at different rest
// points each within 1e-5 m of the exact one: the height then differs by at
// most |slope| * 2e-5 m, < 2e-5 m (the kernel's breaking limit keeps slopes
// below 1), the normal by curvature * 2e-5 (< 1e-5 for k A < 0.5 rad/m).
// Still 50x inside the 1 mm query tolerance. (The batch takes
// Chebyshev steps, the scalar path Newton steps: they stop at different
// points inside that tolerance; measured: 3e-6 m.)
struct Tol {
  double heightM, normal, velocityMps;
};

void compare(const WaveField& f, const Case& c, Tol tol, bool sameSteps) {
  const std::size_t n = c.lat.size();
  std::vector<SurfacePoint> out(n);
  f.surfaceBatch(c.lat.data(), c.lon.data(), c.t.data(), true, c.depth.data(), n, out.data());
  double maxH = 0, maxN = 0, maxW = 0;
  std::size_t beyondRounding = 0;
  double itBatch = 0, itScalar = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const SurfacePoint s = f.surfaceAt(c.lat[i], c.lon[i], c.t[i], c.depth[i]);
    ASSERT_TRUE(std::isfinite(out[i].heightM)) << i << " lat " << c.lat[i] << " lon " << c.lon[i];
    const double dh = std::abs(out[i].heightM - s.heightM);
    const double dn = glm::length(out[i].normalEnu - s.normalEnu);
    const double dw = std::abs(out[i].verticalVelocityMps - s.verticalVelocityMps);
    beyondRounding += dh > 1e-8;
    maxH = std::max(maxH, dh), maxN = std::max(maxN, dn), maxW = std::max(maxW, dw);
    EXPECT_LE(dh, tol.heightM) << i << " lat " << c.lat[i] << " lon " << c.lon[i] << " t " << c.t[i] << " depth "
                               << c.depth[i];
    EXPECT_LE(dn, tol.normal) << i;
    EXPECT_LE(dw, tol.velocityMps) << i;
    itBatch += out[i].iterations, itScalar += s.iterations;
  }
  if (sameSteps) {
    // Same algorithm: agreement to rounding (at least 99% within 1e-8 m).
    EXPECT_LE(beyondRounding, n / 100);
    EXPECT_EQ(itBatch, itScalar);
  } else {
    EXPECT_LE(itBatch, itScalar);  // the higher-order step never needs more on average
  }
  std::printf("%s (%s, %zu lanes): max |dh| %.3g m, |dn| %.3g, |dw| %.3g m/s over %zu points, %zu beyond 1e-8 m\n",
              toString(f.model()), batch::targetName(), batch::lanes(), maxH, maxN, maxW, n, beyondRounding);
  std::printf("  mean inversion steps: batch %.3f, scalar %.3f\n", itBatch / double(n), itScalar / double(n));
}

}  // namespace

TEST(SimdBatch, NoiseEqualsScalar) {
  for (double wind : {5.0, 10.0, 20.0})
    compare(make(Model::Noise, wind, 7), points(11), {1e-8, 1e-7, 1e-7}, true);
}

TEST(SimdBatch, GerstnerEqualsScalar) {
  for (double wind : {5.0, 10.0, 20.0})
    compare(make(Model::Gerstner, wind, 3), points(12), {2e-5, 1e-5, 1e-4}, false);
}

// Independent of the scalar path: the particle whose rest point the batch
// found sits, once displaced (scalar sample, GeographicLib frames), above the
// queried point to within the inversion tolerance, at the returned height.
TEST(SimdBatch, GerstnerInversionPutsTheParticleAboveThePoint) {
  namespace geo = geocean::geo;
  const WaveField f = make(Model::Gerstner, 15.0, 2);
  double sumAk = 0.0;
  for (const auto& comp : f.components()) sumAk += comp.amplitudeM * comp.kRef;
  const Case c = points(15);
  const std::size_t n = 2000;
  std::vector<SurfacePoint> out(n);
  f.surfaceBatch(c.lat.data(), c.lon.data(), c.t.data(), true, c.depth.data(), n, out.data());
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const geo::EnuFrame fp = geo::enuFrame({c.lat[i], c.lon[i], 0.0});
    const geo::Geodetic rest = geo::fromEcef(fp.originEcef + fp.toEcef(out[i].restOffsetEnuM));
    const WaveSample ws = f.sample(rest.latDeg, rest.lonDeg, c.t[i], c.depth[i]);
    const geo::EnuFrame fr = geo::enuFrame({rest.latDeg, rest.lonDeg, 0.0});
    const glm::dvec3 local = fp.toLocal(geo::toEcef({rest.latDeg, rest.lonDeg, 0.0}) + fr.toEcef(ws.displacementEnuM) -
                                        fp.originEcef);
    const double miss = std::hypot(local.x, local.y);
    worst = std::max(worst, miss);
    // 1e-5 m: the inversion's stopping tolerance, plus 1e-6 m for the
    // round trip through geodetic coordinates.
    EXPECT_LT(miss, 1.1e-5) << i;
    // The height is the batch's last evaluation, the rest offset one step
    // (< the 1e-5 m tolerance) later: the particle's height moves by at most
    // sum a k (its map's Lipschitz bound) times that, plus the round trip.
    EXPECT_NEAR(local.z, out[i].heightM, 1e-6 + sumAk * 1.1e-5) << i;
  }
  std::printf("batch inversion: worst horizontal miss %.3g m\n", worst);
}

// FFT: the batch takes the scalar path's Newton steps, so the two agree to
// rounding like the noise model. Times: each new time costs a table
// synthesis, so runs of points share a few times (the batch splits at every
// change of time).
TEST(SimdBatch, FftEqualsScalar) {
  for (double t : {0.0, 37.25, -1.0}) {
    Case c = points(16);
    for (std::size_t i = 0; i < c.t.size(); ++i) c.t[i] = t >= 0 ? t : 10.0 * double((i / 100) % 3);
    compare(make(Model::Fft, 10.0, 4), c, {1e-8, 1e-7, 1e-7}, true);
  }
}

TEST(SimdBatch, OtherModelsAndEdgeSizes) {
  // The paper's noise loops over surfaceAt: identical.
  const Case c = points(13);
  for (Model m : {Model::NoisePaper}) {
    const WaveField f = make(m, 10.0, 1);
    std::vector<SurfacePoint> out(50);
    f.surfaceBatch(c.lat.data(), c.lon.data(), c.t.data(), false, nullptr, 50, out.data());
    for (std::size_t i = 0; i < 50; ++i) EXPECT_EQ(out[i].heightM, f.surfaceAt(c.lat[i], c.lon[i], c.t[0]).heightM);
  }
  // Every tail length (1..17 points: partial vectors) and one time for all.
  for (Model m : {Model::Gerstner, Model::Fft}) {
  const WaveField f = make(m, 10.0, 1);
  for (std::size_t n = 0; n <= 17; ++n) {
    std::vector<SurfacePoint> out(n + 1);
    out[n].heightM = 12345.0;  // must stay untouched
    f.surfaceBatch(c.lat.data(), c.lon.data(), c.t.data(), false, nullptr, n, out.data());
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_NEAR(out[i].heightM, f.surfaceAt(c.lat[i], c.lon[i], c.t[0]).heightM, 2e-5) << n << " " << i;
    EXPECT_EQ(out[n].heightM, 12345.0);
  }
  }
}

// Every instruction set the library was compiled for that this CPU runs
// (SSE4, AVX2, AVX-512 here): users' machines may pick any of them.
TEST(SimdBatch, EveryDispatchTargetEqualsScalar) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  EXPECT_GE(targets.size(), 2u);
  const Case c = points(14);
  for (std::int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    EXPECT_STREQ(batch::targetName(), hwy::TargetName(t));
    compare(make(Model::Noise, 10.0, 5), c, {1e-8, 1e-7, 1e-7}, true);
    compare(make(Model::Gerstner, 10.0, 5), c, {2e-5, 1e-5, 1e-4}, false);
    Case one = c;
    for (double& ti : one.t) ti = 5.0;
    compare(make(Model::Fft, 10.0, 5), one, {1e-8, 1e-7, 1e-7}, true);
  }
  hwy::SetSupportedTargetsForTest(0);
}

// Non-finite input gives a non-finite height in the lane it is in and leaves
// the other lanes of its vector alone (no crash: texel and lattice indices
// stay in range whatever the coordinates).
TEST(SimdBatch, NonFiniteInputStaysInItsLane) {
  const double nan = std::nan(""), inf = HUGE_VAL;
  const std::vector<double> lat = {10.0, nan, 20.0, 30.0, inf, -40.0, 50.0, 60.0, 0.5};
  const std::vector<double> lon = {10.0, 11.0, -inf, 13.0, 14.0, nan, 16.0, 17.0, 0.5};
  const double t = 3.0;
  for (Model m : {Model::Noise, Model::Gerstner, Model::Fft}) {
    const WaveField f = make(m, 10.0, 1);
    std::vector<SurfacePoint> out(lat.size());
    f.surfaceBatch(lat.data(), lon.data(), &t, false, nullptr, lat.size(), out.data());
    for (std::size_t i = 0; i < lat.size(); ++i) {
      if (std::isfinite(lat[i]) && std::isfinite(lon[i]))
        EXPECT_NEAR(out[i].heightM, f.surfaceAt(lat[i], lon[i], t).heightM, 2e-5) << toString(m) << " " << i;
      else
        EXPECT_FALSE(std::isfinite(out[i].heightM)) << toString(m) << " " << i;
    }
  }
}

// Unix-epoch times (1.7e9 s): the noise lattice's drift v t carries the
// finest octaves' cells past int32, where the conversion overflowed (the
// cells saturated: a frozen, wrong sea). Cells are now taken modulo 2^32,
// whose hash is the same. Truth that is not the lattice code: the height
// must change at the rate the kernel's own vertical velocity says (central
// difference over +-1 ms: error ~ dt^2 h''' / 6 < 1e-5 m/s for these seas),
// the SIMD batch must equal the scalar path, and the sea must keep its
// height statistics (rms within 20 % of the same points at t = 1000 s).
TEST(SimdBatch, NoiseAtUnixEpochTimes) {
  for (Model m : {Model::Noise, Model::NoisePaper}) {
    const WaveField f = test::make(m, 12.0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> lat(-60.0, 60.0), lon(-180.0, 180.0);
    double sumNow = 0.0, sumThen = 0.0;
    const int n = 400;
    std::vector<double> la(n), lo(n);
    for (int i = 0; i < n; ++i) la[i] = lat(rng), lo[i] = lon(rng);
    const double t0 = 1709294400.0, dt = 1e-3;
    std::vector<SurfacePoint> batch(n);
    f.surfaceBatch(la.data(), lo.data(), &t0, false, nullptr, n, batch.data());
    for (int i = 0; i < n; ++i) {
      const SurfacePoint p = f.surfaceAt(la[i], lo[i], t0);
      const double rate = (f.surfaceAt(la[i], lo[i], t0 + dt).heightM - f.surfaceAt(la[i], lo[i], t0 - dt).heightM) /
                          (2.0 * dt);
      ASSERT_NEAR(rate, p.verticalVelocityMps, 1e-3 + 1e-3 * std::abs(p.verticalVelocityMps)) << toString(m) << " " << i;
      if (m == Model::Noise) {
        // q ~ 2e9 cells carries ~2.4e-7 cell of rounding, differently fused in
        // the SIMD path: 1e-6 m (test_batch's 1e-8 holds at small t).
        EXPECT_NEAR(batch[i].heightM, p.heightM, 1e-6) << i;
      }
      sumNow += p.heightM * p.heightM;
      const double h1000 = f.surfaceAt(la[i], lo[i], 1000.0).heightM;
      sumThen += h1000 * h1000;
    }
    const double ratio = std::sqrt(sumNow / sumThen);
    EXPECT_GT(ratio, 0.8) << toString(m);
    EXPECT_LT(ratio, 1.25) << toString(m);
  }
}

// Times so large that v t overflows the lattice coordinate to infinity
// (fuzz_capi_sea_state: 1e307 s through geocean_query_surface): the noise
// is that of cell 0 (finiteFrac, wrapCell32), finite, scalar = batch; before
// the fix the scalar path converted a NaN fraction's floor to int (UB) and
// the batch returned NaN heights.
TEST(SimdBatch, NoiseAtTimesBeyondTheLatticeIsFinite) {
  const double big = std::numeric_limits<double>::max();
  for (Model m : {Model::Noise, Model::NoisePaper}) {
    const WaveField f = test::make(m, 12.0);
    for (double t : {1e307, -1e307, big, -big}) {
      const double la[] = {0.0, 36.0, -60.0, 89.9}, lo[] = {0.0, -5.6, 170.0, -179.9};
      SurfacePoint batch[4];
      f.surfaceBatch(la, lo, &t, false, nullptr, 4, batch);
      for (int i = 0; i < 4; ++i) {
        const SurfacePoint p = f.surfaceAt(la[i], lo[i], t);
        ASSERT_TRUE(std::isfinite(p.heightM) && std::isfinite(p.verticalVelocityMps)) << toString(m) << " t " << t;
        const WaveSample s = f.sample(la[i], lo[i], t, kDeepWaterM);
        ASSERT_TRUE(std::isfinite(s.displacementEnuM.z) && std::isfinite(s.verticalVelocityMps) &&
                    std::isfinite(s.normalEnu.z)) << toString(m) << " t " << t;
        ASSERT_TRUE(std::isfinite(batch[i].heightM)) << toString(m) << " t " << t << " " << i;
        if (m == Model::Noise) {
          EXPECT_NEAR(batch[i].heightM, p.heightM, 1e-6) << i;  // as NoiseAtUnixEpochTimes
        }
      }
    }
  }
}

// The time bound (plugin/waves/TimeRange.h, fuzz finding 5): at |t| =
// kMaxTimeS the SIMD Gerstner batch still computes the scalar path's sea.
// Both round w t at its magnitude (the scalar reduces it by an exact fmod,
// the batch by ph - 2 pi floor(ph / 2 pi), a fused multiply-add): their
// phases differ by a few ulp of w t, |dphi| <= 4 w |t| 2^-52 per component,
// which moves the surface by at most the sum of a (1 + slope) |dphi| <=
// 2 sum(a |dphi|) (the kernel's breaking limit keeps slopes below 1), plus
// the inversion tolerance of GerstnerEqualsScalar. Beyond the bound (1e33 s,
// the finding) the batch answered 3e7 m: that time is refused at every
// boundary now, so only the bound itself is pinned here.
TEST(SimdBatch, GerstnerAtTheTimeBoundEqualsScalar) {
  for (double wind : {0.2, 10.0, 60.0}) {
    const WaveField f = make(Model::Gerstner, wind, 3);
    for (double t : {kMaxTimeS, -kMaxTimeS}) {
      double tol = 2e-5;
      for (const auto& c : f.components()) tol += 2.0 * c.amplitudeM * 4.0 * c.omega * std::abs(t) * 0x1p-52;
      Case c;
      std::mt19937_64 rng(17);
      std::uniform_real_distribution<double> u(-1, 1), lon(-180, 180);
      for (int i = 0; i < 500; ++i) c.add(std::asin(u(rng)) * 180 / M_PI, lon(rng), t, kDeepWaterM);
      std::vector<SurfacePoint> out(c.lat.size());
      f.surfaceBatch(c.lat.data(), c.lon.data(), c.t.data(), true, c.depth.data(), c.lat.size(), out.data());
      double maxH = 0.0;
      for (std::size_t i = 0; i < c.lat.size(); ++i) {
        const SurfacePoint s = f.surfaceAt(c.lat[i], c.lon[i], t, kDeepWaterM);
        maxH = std::max(maxH, std::abs(out[i].heightM - s.heightM));
        ASSERT_NEAR(out[i].heightM, s.heightM, tol) << "wind " << wind << " t " << t << " point " << i;
      }
      std::printf("wind %g m/s, t %g s: max |dh| %.3g m (bound %.3g m)\n", wind, t, maxH, tol);
    }
  }
}
