// Paper 002's spherical noise model evaluates 2D noise at (lon cos(lat), lat).
// Issue #3 asks to measure its defects and to show that the improved model
// (solid noise on the 3D surface point) has none. The numbers printed here
// are the ones in docs/PERFORMANCE.md ("Waves").
//
// Waves per km along a direction = up-crossings per km by Rice's formula,
// (1 / 2 pi) sqrt(E[h'^2] / E[h^2]), with h' the height slope along that
// direction (central differences over 1 cm, far below the shortest wave).
#include "plugin/waves/WaveField.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace geocean::waves;

namespace {
constexpr double kA = 6378137.0, kE2 = 0.0066943799901413165;

WaveField make(Model m) {
  std::string err;
  auto w = WaveField::create(m, SeaState{}, err);
  EXPECT_TRUE(w) << err;
  return *w;
}

struct Density {
  double eastPerKm, northPerKm;
  double ratio() const { return eastPerKm / northPerKm; }
};

// At latitude latDeg, longitudes uniform in [lonLo, lonHi).
Density density(const WaveField& w, double latDeg, double lonLo, double lonHi, int n) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> lon(lonLo, lonHi), time(0, 1000);
  const double phi = latDeg * M_PI / 180, s = std::sin(phi);
  const double nRad = kA / std::sqrt(1 - kE2 * s * s), mRad = kA * (1 - kE2) / std::pow(1 - kE2 * s * s, 1.5);
  const double step = 0.01;
  const double dLon = step / (nRad * std::cos(phi)) * 180 / M_PI, dLat = step / mRad * 180 / M_PI;
  double h2 = 0, e2 = 0, n2 = 0, hm = 0;
  for (int i = 0; i < n; ++i) {
    const double lo = lon(rng), t = time(rng);
    const double h = w.surfaceAt(latDeg, lo, t).heightM;
    const double he = (w.surfaceAt(latDeg, lo + dLon, t).heightM - w.surfaceAt(latDeg, lo - dLon, t).heightM) / (2 * step);
    const double hn = (w.surfaceAt(latDeg + dLat, lo, t).heightM - w.surfaceAt(latDeg - dLat, lo, t).heightM) / (2 * step);
    hm += h;
    h2 += h * h;
    e2 += he * he;
    n2 += hn * hn;
  }
  const double var = h2 / n - (hm / n) * (hm / n);
  return {1000 / (2 * M_PI) * std::sqrt(e2 / n / var), 1000 / (2 * M_PI) * std::sqrt(n2 / n / var)};
}

// Largest height jump between lon = 180 - eps and -180 + eps, eps = 1e-9 deg (0.1 mm).
double seamJumpM(const WaveField& w) {
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    // FFT: one table synthesis per time, so 4 times.
    const double lat = -89.0 + 178.0 * i / 1999.0, t = (w.model() == Model::Fft ? i % 4 : i) * 0.37;
    worst = std::max(worst, std::abs(w.surfaceAt(lat, 180.0 - 1e-9, t).heightM - w.surfaceAt(lat, -180.0 + 1e-9, t).heightM));
  }
  return worst;
}

// Within 1 km of the north pole: largest height difference between points
// 1 m apart (any direction, including across the pole and the seam) divided
// by the largest slope the model can have: > 1 means a jump.
double poleJumpM(const WaveField& w) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1000, 1000), ang(0, 2 * M_PI);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    // Polar stereographic-like local plane at the pole (x, y metres).
    const double x = u(rng), y = u(rng), a = ang(rng);
    auto at = [&](double px, double py) {
      const double r = std::hypot(px, py);
      const double lat = 90.0 - r / 6399593.6 * 180 / M_PI;  // polar radius of curvature
      return w.surfaceAt(lat, std::atan2(py, px) * 180 / M_PI, 3.0).heightM;
    };
    worst = std::max(worst, std::abs(at(x, y) - at(x + std::cos(a), y + std::sin(a))));
  }
  return worst;
}
}  // namespace

TEST(SphereDefects, PaperModelShearsAwayFromThePrimeMeridianAndSeamsAt180) {
  const WaveField paper = make(Model::NoisePaper);
  std::printf("paper model (noise-paper): waves per km E-W / N-S and ratio\n");
  for (double lat : {0.0, 30.0, 60.0, 80.0, 89.0}) {
    const Density nearPm = density(paper, lat, -1, 1, 4000), all = density(paper, lat, -180, 180, 4000);
    std::printf("  lat %4.0f  |lon|<1: %.2f / %.2f = %.3f   all lon: %.2f / %.2f = %.3f\n", lat, nearPm.eastPerKm,
                nearPm.northPerKm, nearPm.ratio(), all.eastPerKm, all.northPerKm, all.ratio());
    if (lat >= 30.0) {
      EXPECT_LT(all.ratio(), 0.9) << "the shear defect should show at lat " << lat;
    }
  }
  const double seam = seamJumpM(paper), pole = poleJumpM(paper);
  std::printf("  seam jump at lon 180: %.3f m; largest change over 1 m within 1 km of the pole: %.3f m\n", seam, pole);
  EXPECT_GT(seam, 0.1);  // the antimeridian discontinuity (x jumps by 2 pi R cos(lat))
}

TEST(SphereDefects, SolidNoiseHasConstantDensityNoSeamAndQuietPoles) {
  const WaveField solid = make(Model::Noise);
  std::printf("improved model (noise): waves per km E-W / N-S and ratio\n");
  for (double lat : {0.0, 30.0, 60.0, 80.0, 89.0}) {
    const Density d = density(solid, lat, -180, 180, 20000);
    std::printf("  lat %4.0f  %.2f / %.2f = %.3f\n", lat, d.eastPerKm, d.northPerKm, d.ratio());
    // Issue target 1 +- 0.02 up to 80 deg; the estimate's own sampling error
    // with 20k points is ~0.7%, so this can fail only on a real anisotropy.
    EXPECT_NEAR(d.ratio(), 1.0, 0.02) << lat;
  }
  const double seam = seamJumpM(solid), pole = poleJumpM(solid);
  std::printf("  seam jump at lon 180: %.2e m; largest change over 1 m within 1 km of the pole: %.3f m\n", seam, pole);
  EXPECT_LT(seam, 1e-4);  // issue: < 0.1 mm
  // Over 1 m the change is bounded by the steepest slope the noise has
  // (finest octave, < 1 m/m): no jump at the pole.
  EXPECT_LT(pole, 1.0);
}

TEST(SphereDefects, GerstnerHasNoSeam) {
  const WaveField g = make(Model::Gerstner);
  const double seam = seamJumpM(g), pole = poleJumpM(g);
  std::printf("gerstner: seam jump at lon 180: %.2e m; largest change over 1 m near the pole: %.3f m\n", seam, pole);
  EXPECT_LT(seam, 1e-4);
  EXPECT_LT(pole, 1.0);
}

TEST(SphereDefects, FftHasNoSeamAndQuietPoles) {
  // The FFT tiles are laid on the ellipsoid through ECEF (triplanar), which
  // knows no antimeridian and no pole.
  const WaveField f = make(Model::Fft);
  const double seam = seamJumpM(f), pole = poleJumpM(f);
  std::printf("fft: seam jump at lon 180: %.2e m; largest change over 1 m near the pole: %.3f m\n", seam, pole);
  EXPECT_LT(seam, 1e-4);
  EXPECT_LT(pole, 1.0);
}
