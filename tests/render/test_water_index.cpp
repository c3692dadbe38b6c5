// WaterIndex against a brute-force scan of the same layer: random land on
// a small global grid, random rectangles (wrapping the antimeridian, past
// the poles, wider than the globe), and bad bounds.
#include "globe/world/WaterIndex.h"
#include "globe/render/WorldTextures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace geocean::world {
namespace {

WorldLayer layer(int w, int h, double landShare, unsigned seed) {
  WorldLayer l;
  l.width = w, l.height = h;
  l.lonStepDeg = 360.0 / w, l.latStepDeg = -180.0 / h;
  l.values.assign(std::size_t(w) * h, 1.0f);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (float& v : l.values)
    if (u(rng) < landShare) v = u(rng) < 0.5 ? 0.0f : 0.5f;  // land, or part water: not water throughout
  return l;
}

bool bruteAllWater(const WorldLayer& l, double x0, double x1, double y0, double y1) {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  const int iy0 = std::clamp(int(std::floor(y0)), 0, l.height - 1), iy1 = std::clamp(int(std::floor(y1)), 0, l.height - 1);
  for (long x = long(std::floor(x0)); x <= long(std::floor(x1)); ++x)
    for (int y = iy0; y <= iy1; ++y) {
      const long xm = ((x % l.width) + l.width) % l.width;
      if (l.values[std::size_t(y) * l.width + xm] < 1.0f) return false;
    }
  return true;
}

TEST(WaterIndex, AgreesWithABruteForceScan) {
  // 90 x 45 is not a power of two: partial blocks at every level.
  for (const double landShare : {0.0005, 0.003, 0.02}) {
    const WorldLayer l = layer(90, 45, landShare, 7);
    const WaterIndex wi(l);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> pos(-200.0, 200.0), size(0.0, 30.0);
    int water = 0;
    for (int i = 0; i < 20000; ++i) {
      const double x0 = pos(rng), y0 = pos(rng) * 0.3, x1 = x0 + size(rng) * (i % 7 == 0 ? 4.0 : 1.0),
                   y1 = y0 + size(rng) * 0.5;
      const bool expect = bruteAllWater(l, x0, x1, y0, y1);
      water += expect;
      ASSERT_EQ(wi.allWater(x0, x1, y0, y1), expect) << x0 << " " << x1 << " " << y0 << " " << y1;
      ASSERT_EQ(wi.allWater(x1, x0, y1, y0), expect) << "corners in the other order";
    }
    EXPECT_GT(water, 100) << "the test must see open water too";
    EXPECT_LT(water, 19900) << "and land";
  }
}

TEST(WaterIndex, MapsLonLatToTexelsAndRejectsBadBounds) {
  const WorldLayer l = layer(360, 180, 0.0, 1);
  const WaterIndex wi(l);
  EXPECT_DOUBLE_EQ(wi.texelX(-180.0), 0.0);
  EXPECT_DOUBLE_EQ(wi.texelX(0.5), 180.5);
  EXPECT_DOUBLE_EQ(wi.texelY(90.0), 0.0);
  EXPECT_DOUBLE_EQ(wi.texelY(-89.5), 179.5);
  EXPECT_TRUE(wi.allWater(-1e12, 1e12, -5.0, 500.0));  // an all-water world, any rectangle
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(wi.allWater(nan, 1.0, 0.0, 1.0));
  EXPECT_FALSE(wi.allWater(0.0, 1.0, 0.0, nan));
  EXPECT_FALSE(WaterIndex().allWater(0.0, 1.0, 0.0, 1.0));
}

}  // namespace
}  // namespace geocean::world
