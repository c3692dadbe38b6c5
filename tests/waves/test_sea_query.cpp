// The sea-height query on the default world: land says land, ocean gives the
// wave surface, shallow water changes the Gerstner sea, batch = single
// (to the SIMD path's tolerance).
#include "globe/raster/World.h"
#include "plugin/waves/SeaQuery.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace geocean;
using namespace geocean::waves;

namespace {
std::shared_ptr<const ocean::LandSea> world() {
  static auto ls = std::make_shared<const ocean::LandSea>(raster::Raster::open(raster::defaultWorld().mask),
                                                          raster::Raster::open(raster::defaultWorld().elevation));
  return ls;
}
SeaQuery makeQuery(Model m) {
  std::string err;
  auto f = WaveField::create(m, SeaState{}, err);
  EXPECT_TRUE(f) << err;
  return SeaQuery(*f, world());
}
}  // namespace

TEST(SeaQuery, LandSaysLandAndOceanGivesTheWaveSurface) {
  for (Model m : {Model::Noise, Model::Gerstner}) {
    const SeaQuery q = makeQuery(m);
    // Central Sahara and central Pacific (well away from any coast).
    const SeaQueryResult land = q.query(23.0, 13.0, 10.0), sea = q.query(0.0, -150.0, 10.0);
    EXPECT_EQ(land.surface, ocean::Surface::Land);
    EXPECT_TRUE(std::isnan(land.seaHeightM));
    EXPECT_EQ(sea.surface, ocean::Surface::Ocean);
    EXPECT_TRUE(std::isfinite(sea.seaHeightM));
    EXPECT_GT(sea.depthM, 3000.0 * (m == Model::Gerstner));  // ETOPO: > 4 km deep there
    EXPECT_EQ(sea.seaHeightM, q.field().surfaceAt(0.0, -150.0, 10.0, sea.depthM).heightM);
    EXPECT_LE(std::abs(sea.seaHeightM), q.field().maxVerticalM());
  }
}

TEST(SeaQuery, BatchEqualsSingleQueries) {
  const SeaQuery q = makeQuery(Model::Gerstner);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> lat(-80, 80), lon(-180, 180), t(0, 100);
  const std::size_t n = 5000;
  std::vector<double> la(n), lo(n), ts(n);
  for (std::size_t i = 0; i < n; ++i) la[i] = lat(rng), lo[i] = lon(rng), ts[i] = t(rng);
  std::vector<SeaQueryResult> out(n);
  q.queryBatch(la.data(), lo.data(), ts.data(), true, n, out.data());
  int land = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const SeaQueryResult s = q.query(la[i], lo[i], ts[i]);
    ASSERT_EQ(out[i].surface, s.surface) << i;
    land += s.surface != ocean::Surface::Ocean;
    if (std::isnan(s.seaHeightM))
      EXPECT_TRUE(std::isnan(out[i].seaHeightM));
    else  // the batch runs the SIMD path: same function to 2e-5 m (tests/waves/test_batch.cpp)
      EXPECT_NEAR(out[i].seaHeightM, s.seaHeightM, 2e-5);
  }
  // About 29% of the Earth is land (a sanity check that both classes occur).
  EXPECT_GT(land, int(n) / 6);
  EXPECT_LT(land, int(n) / 2);
}
