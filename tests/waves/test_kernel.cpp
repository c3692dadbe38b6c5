// The shared wave kernel (shaders/waves.glsl through GLM): noise statistics
// the models are calibrated with, analytic derivatives, and the explicit
// dispersion relation against an exact solve.
#include "plugin/waves/WaveField.h"
#include "plugin/waves/WaveKernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace geocean::waves;

TEST(WaveKernel, PerlinStandardDeviationsMatchTheCalibrationConstants) {
  // WaveField.cpp scales the noise models with these measured values; a
  // change to the noise must re-measure them. 400k samples give ~0.2% error.
  kd::Kernel k;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1e5, 1e5);
  double s3 = 0, s2 = 0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 q(u(rng), u(rng), u(rng));
    const glm::dvec3 f = glm::floor(q);
    s3 += std::pow(k.wv_perlin3(glm::ivec3(f), q - f, 77u + i % 13).x, 2);
    const glm::dvec2 q2(q.x, q.y), f2 = glm::floor(q2);
    s2 += std::pow(k.wv_perlin2(glm::ivec2(f2), q2 - f2, 5u + i % 7).x, 2);
  }
  EXPECT_NEAR(std::sqrt(s3 / n), 0.27008, 0.27008 * 0.01);
  EXPECT_NEAR(std::sqrt(s2 / n), 0.21046, 0.21046 * 0.01);
}

TEST(WaveKernel, NoiseGradientsMatchFiniteDifferences) {
  kd::Kernel k;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-50, 50);
  const double h = 1e-6;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 q(u(rng), u(rng), u(rng));
    auto at = [&](glm::dvec3 p) {
      const glm::dvec3 f = glm::floor(p);
      return k.wv_perlin3(glm::ivec3(f), p - f, 9u).x;
    };
    const glm::dvec3 f = glm::floor(q);
    const glm::dvec4 v = k.wv_perlin3(glm::ivec3(f), q - f, 9u);
    // Central differences with h = 1e-6 are good to ~1e-9 here; 1e-6 leaves room
    // for crossing a cell face (the noise is C2 there).
    EXPECT_NEAR(v.y, (at(q + glm::dvec3(h, 0, 0)) - at(q - glm::dvec3(h, 0, 0))) / (2 * h), 1e-6);
    EXPECT_NEAR(v.z, (at(q + glm::dvec3(0, h, 0)) - at(q - glm::dvec3(0, h, 0))) / (2 * h), 1e-6);
    EXPECT_NEAR(v.w, (at(q + glm::dvec3(0, 0, h)) - at(q - glm::dvec3(0, 0, h))) / (2 * h), 1e-6);
    const glm::dvec2 q2(q.x, q.y), f2 = glm::floor(q2);
    const glm::dvec3 w = k.wv_perlin2(glm::ivec2(f2), q2 - f2, 4u);
    auto at2 = [&](glm::dvec2 p) {
      const glm::dvec2 g = glm::floor(p);
      return k.wv_perlin2(glm::ivec2(g), p - g, 4u).x;
    };
    EXPECT_NEAR(w.y, (at2(q2 + glm::dvec2(h, 0)) - at2(q2 - glm::dvec2(h, 0))) / (2 * h), 1e-6);
    EXPECT_NEAR(w.z, (at2(q2 + glm::dvec2(0, h)) - at2(q2 - glm::dvec2(0, h))) / (2 * h), 1e-6);
  }
}

TEST(WaveKernel, NoiseIsContinuousAcrossCellFaces) {
  kd::Kernel k;
  // Same point expressed from two neighbouring cells (f = 1 vs f = 0).
  for (int i = -5; i < 5; ++i) {
    const glm::dvec3 f(0.3, 0.7, 1.0);
    const double a = k.wv_perlin3(glm::ivec3(i, 2, 3), f, 1u).x;
    const double b = k.wv_perlin3(glm::ivec3(i, 2, 4), glm::dvec3(0.3, 0.7, 0.0), 1u).x;
    EXPECT_NEAR(a, b, 1e-15);
  }
}

TEST(WaveKernel, ExplicitDispersionMatchesExactSolve) {
  // The kernel's explicit form (Guo 2002 + one Newton step) against a
  // bisection solve of w^2 = g k tanh(kh) to machine precision; the issue
  // asks for 2%, the Newton steps give 1e-8 in double.
  kd::Kernel k;
  for (double kh = 0.01; kh < 20.0; kh *= 1.3) {
    const double depth = 25.0;
    const double kTrue = kh / depth;
    const double omega = std::sqrt(9.80665 * kTrue * std::tanh(kh));
    EXPECT_NEAR(waveNumberExact(omega, depth), kTrue, kTrue * 1e-12) << "kh " << kh;
    EXPECT_NEAR(k.wv_waveNumber(omega, depth), kTrue, kTrue * 1e-8) << "kh " << kh;
  }
}

TEST(WaveKernel, SpectraHaveTheirTextbookMoments) {
  // Pierson-Moskowitz: Hs = 0.21 U^2/g (the reference) follows from
  // alpha = 0.0081 and w_p = 0.877 g/U; integrate numerically.
  for (double u : {5.0, 10.0, 20.0}) {
    double m0 = 0.0;
    const double dw = 1e-4;
    for (double w = dw; w < 20.0; w += dw) m0 += piersonMoskowitz(w, u) * dw;
    EXPECT_NEAR(4.0 * std::sqrt(m0), 0.2094 * u * u / 9.80665, 0.2094 * u * u / 9.80665 * 0.005);
  }
  // JONSWAP with a long fetch peaks at 22 (g^2/(U F))^(1/3).
  const double u = 12.0, fetch = 100e3;
  double best = 0.0, wBest = 0.0;
  for (double w = 0.2; w < 3.0; w += 1e-4)
    if (jonswap(w, u, fetch) > best) best = jonswap(w, u, fetch), wBest = w;
  EXPECT_NEAR(wBest, 22.0 * std::cbrt(9.80665 * 9.80665 / (u * fetch)), 1e-3);
}
