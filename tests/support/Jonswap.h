// The textbook JONSWAP spectrum's significant wave height, as a reference
// independent of plugin/waves (tests of the query CLI and the sea state).
#pragma once

#include <cmath>

namespace geocean::test {

// Hs = 4 sqrt(m0) of the JONSWAP spectrum (Hasselmann et al. 1973): alpha =
// 0.076 (U^2 / (F g))^0.22, w_p = 22 (g^2 / (U F))^(1/3), gamma 3.3, sigma
// 0.07 / 0.09; Simpson over 0.3 .. 30 w_p (20,000 panels).
inline double textbookJonswapHs(double u, double fetchM) {
  constexpr double kG = 9.80665;
  const double alpha = 0.076 * std::pow(u * u / (fetchM * kG), 0.22), wp = 22.0 * std::cbrt(kG * kG / (u * fetchM));
  auto s = [&](double w) {
    const double sigma = w <= wp ? 0.07 : 0.09;
    return alpha * kG * kG / std::pow(w, 5) * std::exp(-1.25 * std::pow(wp / w, 4)) *
           std::pow(3.3, std::exp(-(w - wp) * (w - wp) / (2 * sigma * sigma * wp * wp)));
  };
  const int n = 20000;
  const double a = 0.3 * wp, h = (30.0 * wp - a) / n;
  double sum = s(a) + s(a + n * h);
  for (int i = 1; i < n; ++i) sum += s(a + i * h) * (i % 2 ? 4 : 2);
  return 4.0 * std::sqrt(sum * h / 3.0);
}

}  // namespace geocean::test
