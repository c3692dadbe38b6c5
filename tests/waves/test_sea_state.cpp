// The query's sea-state outputs (issue 15 item 6): Hs, peak period, peak
// wavelength and the direction waves come from, against Pierson-Moskowitz's
// closed forms and against statistics of the surface the kernel draws.
#include "tests/waves/MakeField.h"
#include "plugin/waves/WaveField.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace geocean::waves;
using geocean::waves::test::make;

namespace {
constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;

// Pierson-Moskowitz, S = a g^2 w^-5 exp(-5/4 (wp/w)^4), integrates to
// m0 = a g^2 / (5 wp^4): Hs = 4 sqrt(a / 5) g / wp^2, wp = 0.877 g / U.
double pmHs(double u) {
  const double wp = 0.877 * kG / u;
  return 4.0 * std::sqrt(0.0081 / 5.0) * kG / (wp * wp);
}
double pmPeakPeriod(double u) { return 2.0 * kPi * u / (0.877 * kG); }

double angleDiffDeg(double a, double b) {
  double d = std::fmod(a - b + 540.0, 360.0) - 180.0;
  return std::abs(d);
}
}  // namespace

class SeaStateModels : public ::testing::TestWithParam<Model> {};

TEST_P(SeaStateModels, DeepWaterMatchesPiersonMoskowitz) {
  for (double u : {5.0, 10.0, 20.0}) {
    const WaveField w = make(GetParam(), u);
    // Near the anchor (0 N, 0 E): far from every Gerstner source's taper.
    for (const auto& p : {std::pair{0.0, 0.0}, std::pair{1.5, -2.0}, std::pair{-3.0, 4.0}}) {
      const LocalSeaState s = w.seaStateAt(p.first, p.second);
      // 0.2 %: the spectrum is integrated from 0.2 wp to 20 wp (Simpson); the
      // tail beyond holds 1e-6 of m0, the part below exp(-781) of it.
      EXPECT_NEAR(s.hsM, pmHs(u), 2e-3 * pmHs(u)) << toString(GetParam()) << " U=" << u;
      EXPECT_NEAR(s.peakPeriodS, pmPeakPeriod(u), 1e-9 * pmPeakPeriod(u));
      // Deep water: L = g T^2 / (2 pi).
      const double lDeep = kG * s.peakPeriodS * s.peakPeriodS / (2.0 * kPi);
      EXPECT_NEAR(s.peakWavelengthM, lDeep, 1e-9 * lDeep);
    }
  }
}

TEST_P(SeaStateModels, WavesComeFromUpwind) {
  // Nautical convention: the direction waves come FROM, clockwise from north.
  for (double from : {0.0, 90.0, 200.0, 315.0}) {
    SeaState sea;
    sea.windFromDeg = from;
    std::string err;
    const auto w = WaveField::create(GetParam(), sea, err);
    ASSERT_TRUE(w) << err;
    const double got = w->seaStateAt(0.0, 0.0).waveFromDeg;
    EXPECT_GE(got, 0.0);
    EXPECT_LT(got, 360.0);
    if (GetParam() == Model::Gerstner)
      // 16 components drawn from cos^2 spreading (std 32.5 deg each): their
      // energy-weighted mean lies within 25 deg of the wind for these seeds.
      EXPECT_LT(angleDiffDeg(got, from), 25.0) << from;
    else
      EXPECT_LT(angleDiffDeg(got, from), 1e-9) << from;
  }
}

INSTANTIATE_TEST_SUITE_P(Local, SeaStateModels, ::testing::Values(Model::Noise, Model::Gerstner, Model::Fft),
                         [](const ::testing::TestParamInfo<Model>& p) { return std::string(toString(p.param)); });

// Hs = 4 std(eta) of the surface the kernel draws, at a fixed rest point
// over a long time, in deep water and over a shoal (shoaling and the
// breaking cap): the output describes the drawn sea, not only the spectrum.
TEST(LocalSeaState, GerstnerHsIsFourStdOfTheDrawnSurface) {
  const WaveField w = make(Model::Gerstner, 12.0);
  for (double depth : {kDeepWaterM, 30.0, 6.0, 2.0}) {
    double sum = 0.0, sum2 = 0.0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
      const double t = 0.37 + i * 7.31;  // 3e5 s: beats of 16 incommensurate components average out
      const double h = w.sample(0.5, 0.5, t, depth).displacementEnuM.z;
      sum += h;
      sum2 += h * h;
    }
    const double hs = 4.0 * std::sqrt(sum2 / n - (sum / n) * (sum / n));
    // 2 %: sampling error of a variance over 4e4 samples of a sum of
    // sinusoids (sqrt(2 / N) per component, fewer effective samples).
    EXPECT_NEAR(w.seaStateAt(0.5, 0.5, depth).hsM, hs, 0.02 * hs) << "depth " << depth;
  }
  // The breaking cap holds: Hs <= 0.78 h (the crest sum is capped at 0.39 h).
  EXPECT_LE(w.seaStateAt(0.5, 0.5, 2.0).hsM, 0.78 * 2.0);
}

// The direction measured from the surface: for linear waves
// -<deta/dt grad(eta)> = sum a^2 omega k / 2 along each travel direction, so
// with one component it is the travel direction itself.
TEST(LocalSeaState, GerstnerDirectionIsTheDrawnSurfaceDirection) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    SeaState sea;
    sea.gerstnerComponents = 1;
    sea.seed = seed;
    sea.windFromDeg = 40.0;
    std::string err;
    const auto w = WaveField::create(Model::Gerstner, sea, err);
    ASSERT_TRUE(w) << err;
    double fe = 0.0, fn = 0.0;
    for (int i = 0; i < 400; ++i) {
      const WaveSample s = w->sample(1.0, 2.0, 0.1 + 0.173 * i);
      const double ge = -s.normalEnu.x / s.normalEnu.z, gn = -s.normalEnu.y / s.normalEnu.z;
      fe -= s.verticalVelocityMps * ge;
      fn -= s.verticalVelocityMps * gn;
    }
    const double travel = std::atan2(fe, fn) * 180.0 / kPi;
    EXPECT_LT(angleDiffDeg(w->seaStateAt(1.0, 2.0).waveFromDeg, travel + 180.0), 0.5) << "seed " << seed;
  }
}
