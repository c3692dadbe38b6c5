// Shared by the C ABI fuzzers: values a host might pass (including the
// ones a careful host never would), and the ABI's error contract.
#pragma once

#include "geocean/geocean_ocean.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace geocean::fuzz {

// A double: often one of the values that break arithmetic, else any finite
// double, else one in [lo, hi] (where the interesting behaviour is).
inline double pickDouble(FuzzedDataProvider& p, double lo, double hi) {
  static const double kSpecial[] = {std::numeric_limits<double>::quiet_NaN(),
                                    std::numeric_limits<double>::infinity(),
                                    -std::numeric_limits<double>::infinity(),
                                    0.0, -0.0, 4.9e-324, -4.9e-324, 1e-300, 1e300, -1e300,
                                    std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                                    90.0, -90.0, 180.0, -180.0, 360.0, 1.0, -1.0};
  switch (p.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: return kSpecial[p.ConsumeIntegralInRange<std::size_t>(0, sizeof kSpecial / sizeof kSpecial[0] - 1)];
    case 1: return p.ConsumeFloatingPoint<double>();
    default: return p.ConsumeFloatingPointInRange<double>(lo, hi);
  }
}

// The ABI's contract for every call: a documented status; on error a
// message that names the function; INTERNAL (an exception we did not
// expect) and OUT_OF_MEMORY (inputs here are small) are bugs.
inline geocean_status checked(geocean_status s, const char* function) {
  if (s == GEOCEAN_OK) return s;
  const char* m = geocean_last_error();
  const bool documented = s == GEOCEAN_ERROR_NULL_ARGUMENT || s == GEOCEAN_ERROR_INVALID_ARGUMENT ||
                          s == GEOCEAN_ERROR_RASTER || s == GEOCEAN_ERROR_NOT_READY;
  if (!documented || !m || std::strncmp(m, function, std::strlen(function)) != 0) {
    std::fprintf(stderr, "%s: status %s, message '%s'\n", function, geocean_status_string(s), m ? m : "(null)");
    std::abort();
  }
  return s;
}

[[noreturn]] inline void broken(const char* what, double a = 0, double b = 0) {
  std::fprintf(stderr, "contract broken: %s (%.17g, %.17g)\n", what, a, b);
  std::abort();
}

}  // namespace geocean::fuzz
