// The simulation times the sea is defined at: |t| <= kMaxTimeS seconds.
// Every boundary (C ABI, façade, CLI, Python) refuses other times, naming
// the field and the value.
//
// Why 1e12 s (31,700 years; Unix-epoch times, ~1.8e9 s, are well inside):
// a wave's phase is w t rounded to a double, an error of up to
// w |t| 2^-53 rad before any reduction mod 2 pi. At 1e12 s that is 7e-4 rad
// for a 1 s wave (w = 2 pi) and 0.05 rad for the FFT's finest mode at the
// lowest wind, 0.2 m/s (w ~ 470 rad/s, a 0.3 mm ripple). At 1e15 s a 1 s
// wave's phase is off by 0.7 rad: nothing of it is left. Far beyond, the
// SIMD Gerstner batch's reduction ph - 2 pi floor(ph / 2 pi) leaves
// [0, 2 pi) by more than its sine's range: heights of 3e7 m at 1e33 s and
// NaN from 1e44 s (fuzz finding 5, a Gerstner sea).
#pragma once

namespace geocean::waves {

inline constexpr double kMaxTimeS = 1e12;
inline constexpr const char* kTimeRangeText = "-1e12 .. 1e12 s";

// False for NaN and infinities too.
inline constexpr bool timeInRange(double tS) { return tS >= -kMaxTimeS && tS <= kMaxTimeS; }

}  // namespace geocean::waves
