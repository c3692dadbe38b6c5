// A WaveField for tests: the default sea state with the given wind and seed;
// a sea state the field refuses fails the calling test.
#pragma once

#include "plugin/waves/WaveField.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace geocean::waves::test {

inline WaveField make(Model m, double windMps = 10.0, std::uint32_t seed = 1) {
  SeaState s;
  s.windSpeedMps = windMps;
  s.seed = seed;
  std::string err;
  auto w = WaveField::create(m, s, err);
  EXPECT_TRUE(w) << err;
  return *w;
}

}  // namespace geocean::waves::test
