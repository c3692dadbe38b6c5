#include "plugin/waves/FftOcean.h"

#include "plugin/waves/WaveField.h"

#include <kissfft.hh>

#include <algorithm>
#include <cmath>
#include <complex>

namespace geocean::waves {

namespace {
constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
// Cascade periods in peak wavelengths: 7.3 is far from any small-integer
// ratio, so the two tiles' repeats never line up.
constexpr double kLength0InPeaks = 5.3;
constexpr double kCascadeRatio = 7.3;
constexpr double kSplitInPeakK = 4.0;  // cascade 0: |k| < 4 k_p, cascade 1: |k| >= 4 k_p
constexpr int kMaxCachedTimes = 16;

using Cpx = std::complex<double>;

struct Rng {  // SplitMix64, as in WaveField.cpp: the same on every platform
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
};

// Variance density per unit area of wave-number space (m^2 per (rad/m)^2)
// before calibration; theta from the wind, |theta| < pi/2.
double density(const SeaState& sea, double k, double theta) {
  const double spread = (2.0 / kPi) * std::cos(theta) * std::cos(theta);
  if (sea.fetchM <= 0.0) {
    const double l = sea.windSpeedMps * sea.windSpeedMps / kG;  // Phillips' largest wave, L = U^2/g
    return std::exp(-1.0 / (k * l * k * l)) / (k * k * k * k) * spread;
  }
  const double omega = std::sqrt(kG * k);
  return jonswap(omega, sea.windSpeedMps, sea.fetchM) * (kG / (2.0 * omega)) / k * spread;
}

void inverseFft2d(std::vector<Cpx>& a, int n) {
  const kissfft<double> fft(std::size_t(n), /*inverse=*/true);
  std::vector<Cpx> tmp(static_cast<std::size_t>(n));
  for (int y = 0; y < n; ++y) {
    fft.transform(&a[std::size_t(y) * n], tmp.data());
    std::copy(tmp.begin(), tmp.end(), a.begin() + std::ptrdiff_t(y) * n);
  }
  for (int x = 0; x < n; ++x) {
    fft.transform(&a[std::size_t(x)], tmp.data(), 0, 1, std::size_t(n));
    for (int y = 0; y < n; ++y) a[std::size_t(y) * n + x] = tmp[std::size_t(y)];
  }
}
}  // namespace

FftOcean::FftOcean(const SeaState& sea, double hsM, double peakWavelengthM, const glm::dvec3& travelEcef) {
  Rng rng{sea.seed * 0xD1B54A32D192ED03ULL + 11};
  const double kp = kTwoPi / peakWavelengthM;
  const double split = kSplitInPeakK * kp;
  double variance = 0.0;
  for (int c = 0; c < kCascades; ++c) {
    Cascade& cas = cascades_[c];
    cas.lengthM = kLength0InPeaks * peakWavelengthM / std::pow(kCascadeRatio, c);
    const double dk = kTwoPi / cas.lengthM;
    // Nyquist rows/columns (|m| = N/2) are left empty: their -k is themselves.
    for (int my = -kN / 2 + 1; my < kN / 2; ++my)
      for (int mx = 1; mx < kN / 2; ++mx) {  // downwind half plane (cos theta > 0): mx > 0
        const double kx = mx * dk, ky = my * dk, k = std::hypot(kx, ky);
        if ((c == 0) != (k < split)) continue;
        Mode m;
        m.ix = mx;
        m.iy = (my + kN) % kN;
        m.kx = kx;
        m.ky = ky;
        const double f = density(sea, k, std::atan2(ky, kx));
        m.amp = std::sqrt(2.0 * f * dk * dk);
        m.omega = std::sqrt(kG * k * std::tanh(std::min(k * sea.referenceDepthM, 20.0)));
        m.phase0 = rng.uniform() * kTwoPi;
        // Bilinear interpolation of the tables keeps, on average over
        // positions, the fraction g(kx h) g(ky h) of a mode's variance,
        // g(x) = (2 + cos x) / 3 (h = texel): calibrate what is evaluated.
        const double h = cas.lengthM / kN;
        const double gain = (2.0 + std::cos(kx * h)) / 3.0 * (2.0 + std::cos(ky * h)) / 3.0;
        variance += 0.5 * m.amp * m.amp * gain;
        cas.modes.push_back(m);
      }
  }
  // Calibrate to the sea state's Hs = 4 sqrt(variance); then choose the
  // choppiness so that the horizontal map folds only beyond 4 standard
  // deviations of its Jacobian (the inversion needs it one-to-one).
  const double scale = variance > 0.0 ? hsM / (4.0 * std::sqrt(variance)) : 0.0;
  double varJ = 0.0;
  for (auto& cas : cascades_)
    for (auto& m : cas.modes) {
      m.amp *= scale;
      sumAmp_ += m.amp;
      const double k = std::hypot(m.kx, m.ky), j = m.amp * std::max(m.kx * m.kx, m.ky * m.ky) / k;
      varJ += 0.5 * j * j;
    }
  lambda_ = std::min(1.0, 0.25 / std::max(std::sqrt(varJ), 1e-30));

  for (int p = 0; p < kPlanes; ++p) {
    const glm::dvec3 e = planeAxis(p);
    glm::dvec3 u = travelEcef - glm::dot(travelEcef, e) * e;
    if (glm::length(u) < 0.2) u = planeAxis((p + 1) % kPlanes);  // travel nearly along e: any in-plane axis
    u_[p] = glm::normalize(u);
    v_[p] = glm::cross(e, u_[p]);
    offset_[p][0] = rng.uniform() * kN;
    offset_[p][1] = rng.uniform() * kN;
  }
}

glm::dvec3 FftOcean::planeAxis(int p) const {
  return {p == 0 ? 1.0 : 0.0, p == 1 ? 1.0 : 0.0, p == 2 ? 1.0 : 0.0};
}

std::vector<glm::dvec4> FftOcean::build(double tS) const {
  const std::size_t nn = std::size_t(kN) * kN;
  std::vector<glm::dvec4> out(kCascades * nn * kTexelParts, glm::dvec4(0.0));
  const Cpx i1(0.0, 1.0);
  std::vector<Cpx> z[4];
  for (int c = 0; c < kCascades; ++c) {
    for (auto& a : z) a.assign(nn, Cpx(0.0));
    for (const Mode& m : cascades_[c].modes) {
      // Reduced in double: t may be ~1e9 s. Beyond |w t| ~ 1.8e308 (t ~ 1e307 s)
      // the product overflows and the phase has no precision left (t's
      // spacing there is ~1e291 s): w t counts as 0 mod 2 pi, as the noise
      // lattice takes cell 0 (found while tracing fuzz finding 5; the
      // boundaries now refuse such times, plugin/waves/TimeRange.h).
      const double wt = m.omega * tS;
      double psi = std::fmod(m.phase0 - (std::isfinite(wt) ? wt : 0.0), kTwoPi);
      const Cpx h = 0.5 * m.amp * Cpx(std::cos(psi), std::sin(psi));
      const double k = std::hypot(m.kx, m.ky), ux = m.kx / k, uy = m.ky / k, lam = lambda_;
      // Spectral factors of each field (see FftOcean.h and waves_types.glsl):
      // h = a cos(psi), D = -lambda k^ a sin(psi), psi = k.x - w t + phase0.
      const Cpx pairs[4][2] = {
          {h, -i1 * m.omega * h},                               // h, dh/dt
          {i1 * lam * ux * h, i1 * lam * uy * h},               // Dx, Dy
          {i1 * m.kx * h, i1 * m.ky * h},                       // dh/du, dh/dv
          {lam * m.omega * ux * h, lam * m.omega * uy * h},     // dDx/dt, dDy/dt
      };
      const std::size_t at = std::size_t(m.iy) * kN + m.ix;
      const std::size_t neg = std::size_t((kN - m.iy) % kN) * kN + std::size_t((kN - m.ix) % kN);
      for (int f = 0; f < 4; ++f) {
        z[f][at] += pairs[f][0] + i1 * pairs[f][1];
        z[f][neg] += std::conj(pairs[f][0]) + i1 * std::conj(pairs[f][1]);
      }
    }
    for (auto& a : z) inverseFft2d(a, kN);
    glm::dvec4* t = out.data() + c * nn * kTexelParts;
    for (std::size_t i = 0; i < nn; ++i) {
      t[i * 2 + 0] = {z[0][i].real(), z[1][i].real(), z[1][i].imag(), z[0][i].imag()};
      t[i * 2 + 1] = {z[2][i].real(), z[2][i].imag(), z[3][i].real(), z[3][i].imag()};
    }
  }
  return out;
}

std::shared_ptr<const std::vector<glm::dvec4>> FftOcean::tablesAt(double tS) const {
  {
    std::lock_guard<std::mutex> lock(cache_->mutex);
    for (const auto& e : cache_->entries)
      if (e.first == tS) return e.second;
  }
  auto tables = std::make_shared<const std::vector<glm::dvec4>>(build(tS));
  std::lock_guard<std::mutex> lock(cache_->mutex);
  auto& es = cache_->entries;
  if (es.size() >= std::size_t(kMaxCachedTimes)) es.erase(es.begin());
  es.emplace_back(tS, tables);
  return tables;
}

}  // namespace geocean::waves
