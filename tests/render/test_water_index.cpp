// WaterIndex against a brute-force scan of the same layer: random land on
// a small global grid, random rectangles (wrapping the antimeridian, past
// the poles, wider than the globe), and bad bounds.
#include "globe/world/WaterIndex.h"
#include "globe/world/TileWaterIndex.h"
#include "plugin/render/OceanRenderer.h"
#include "globe/render/WorldTextures.h"
#include "globe/world/WaterPyramid.h"
#include "globe/world/WorldGrids.h"
#include "globe/raster/GeoTiffWriter.h"
#include "globe/world/LayerStack.h"
#include "plugin/landsea/LayeredLandSea.h"
#include "plugin/render/OceanWorld.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

namespace geocean::world {
namespace {
namespace fs = std::filesystem;

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

// A lon/lat rectangle with a margin of m texels is widened by m on every
// side (latitude steps are negative: widening in texel rows by hand,
// texelY(lat0) - m and texelY(lat1) + m, narrowed it and saw no land along a
// rectangle's north and south edges). The ocean's coversOpaquely (which the
// host's terrain asks before leaving a tile out) must see such land: its
// margin holds the B-spline's reach.
TEST(WaterIndex, AMarginAroundALonLatRectangleWidensItOnEverySide) {
  // 1-degree texels; rectangle lat 5.5..9.5, lon 0.25..0.75 (texel rows
  // 80..84, column 180); a margin of 1 reaches rows 79..85, columns 179..181.
  for (const auto& [landLat, landLon, m, expect] :
       {std::tuple{10.5, 0.5, 1.0, false}, std::tuple{4.5, 0.5, 1.0, false}, std::tuple{7.5, 1.5, 1.0, false},
        std::tuple{7.5, -0.5, 1.0, false}, std::tuple{11.5, 0.5, 1.0, true}, std::tuple{3.5, 0.5, 1.0, true},
        std::tuple{12.5, 0.5, 3.0, false}, std::tuple{2.5, 0.5, 3.0, false}, std::tuple{13.5, 0.5, 3.0, true},
        std::tuple{7.5, 0.5, 0.0, false}}) {
    WorldLayer l = layer(360, 180, 0.0, 1);
    const int x = int(std::floor(landLon + 180.0)), y = int(std::floor(90.0 - landLat));
    l.values[std::size_t(y) * l.width + std::size_t(x)] = 0.0f;
    const WaterIndex wi(l);
    EXPECT_EQ(wi.allWaterAround(5.5, 9.5, 0.25, 0.75, m), expect) << landLat << " " << landLon << " margin " << m;
    EXPECT_EQ(wi.allWaterAround(9.5, 5.5, 0.75, 0.25, m), expect) << "corners in the other order";
  }
  // Land in the texel row just north of a tile's edge, within the
  // B-spline's two texels: the ocean does not cover that tile opaquely.
  for (const double landLat : {10.5, 4.5, 20.5}) {
    WorldLayer water = layer(360, 180, 0.0, 1);
    water.values[std::size_t(90.0 - landLat) * water.width + 180] = 0.0f;
    const WorldGrids grids(globalGridFor(nullptr), water);
    const bool covered = ocean_render::coversOpaquely(grids, 8.0, 5.0, 10.0, 0.0, 1.0, 1.0, false);
    EXPECT_EQ(covered, landLat > 15.0) << "land at " << landLat;
  }
}

// A regional mask's index (world::regionalWaterCover, the host terrain's
// all-water rule over a regional layer): a texel of the level is water
// only where every mask cell under it that has data is water, and where
// none has data it is water (the grid below answers there). Brute force
// over every texel, at level 0 and at the coarser level a small texel
// budget forces.
TEST(WaterIndex, ARegionalMasksCoverIsWaterWhereEveryCellWithDataIs) {
  constexpr int W = 600, H = 300;  // 0.01-degree cells over 10..16 E, 40..37 N
  std::vector<float> cls(std::size_t(W) * H, 0.0f);
  const auto at = [&](int x, int y) -> float& { return cls[std::size_t(y) * W + x]; };
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> ux(0, W - 1), uy(0, H - 1);
  for (int i = 0; i < 300; ++i) at(ux(rng), uy(rng)) = 1.0f;  // one-cell islands
  for (int y = 100; y < 180; ++y)
    for (int x = 250; x < 400; ++x) at(x, y) = 255.0f;  // nodata, with islands in it left out
  raster::GeoTransform t;
  t.originLonDeg = 10.0, t.originLatDeg = 40.0, t.lonStepDeg = 0.01, t.latStepDeg = -0.01;
  const auto mask = raster::Raster::fromPixels(cls, W, H, 1, t, 255.0);
  test::TempDir dir("geocean-regional-cover");
  raster::PyramidOptions po;
  po.cacheDir = dir.path.string();
  po.progress = raster::BuildProgress::Off;
  const auto pyr = waterPyramid(mask, {}, po);
  for (const std::size_t budget : {std::size_t(1) << 22, std::size_t(W * H / 16)}) {
    const WorldLayer l = regionalWaterCover(*pyr, budget);
    const int s = W / l.width;
    ASSERT_EQ(l.width * s, W);
    ASSERT_LE(std::size_t(l.width) * l.height, budget);
    EXPECT_DOUBLE_EQ(l.originLonDeg, 10.0);
    EXPECT_DOUBLE_EQ(l.lonStepDeg, 0.01 * s);
    int land = 0, nodata = 0;
    for (int y = 0; y < l.height; ++y)
      for (int x = 0; x < l.width; ++x) {
        bool anyLand = false, allNodata = true;
        for (int yy = y * s; yy < std::min((y + 1) * s, H); ++yy)
          for (int xx = x * s; xx < std::min((x + 1) * s, W); ++xx) {
            anyLand = anyLand || at(xx, yy) == 1.0f;
            allNodata = allNodata && at(xx, yy) == 255.0f;
          }
        const float v = l.values[std::size_t(y) * l.width + x];
        ASSERT_EQ(v >= 1.0f, !anyLand) << x << " " << y << " level texel " << s;
        land += anyLand, nodata += allNodata;
        if (allNodata) {
          ASSERT_EQ(v, 1.0f);
        }
      }
    EXPECT_GT(land, 100);
    EXPECT_GT(nodata, 100);
  }
}

// A regional layer too coarse to stream (10', the grid's 5' step draws
// it) across the antimeridian: 176 E .. 176 W, land on 178 E .. 178 W, over
// an all-ocean global layer. The stack's class and the drawing grid
// (waterLayerOf, resampled through the stack) have the land on both sides
// of 180; before, west of 180 the layer below answered (ocean).
TEST(WaterIndex, ARegionalLayerAcrossTheAntimeridianIsInTheGridOnBothSides) {
  constexpr int W = 48, H = 24;
  constexpr double kStep = 10.0 / 60.0;
  std::vector<float> cls(std::size_t(W) * H, 0.0f);
  for (int y = 0; y < H; ++y)
    for (int x = 12; x < 36; ++x) cls[std::size_t(y) * W + x] = 1.0f;  // 0 ocean, 1 land
  const auto regional = raster::Raster::fromPixels(cls, W, H, 1, {176.0, -10.0, kStep, -kStep, false});
  const auto ocean = raster::Raster::fromPixels(std::vector<float>(360 * 180, 0.0f), 360, 180, 1,
                                                {-180.0, 90.0, 1.0, -1.0, true});
  const LayerStack stack({RasterLayer{LayerKind::Mask, regional, {}, 0},
                          RasterLayer{LayerKind::Mask, ocean, {}, kDefaultWorldPriority}});
  const WorldLayer g = waterLayerOf(stack);
  ASSERT_GT(g.width, 0);
  const std::vector<std::pair<double, bool>> truth = {{179.0, false}, {-179.0, false}, {179.9, false},
                                                      {-179.9, false}, {177.0, true},  {-177.0, true}};
  for (const auto& [lon, water] : truth) {
    const int x = int(std::floor((lon - g.originLonDeg) / g.lonStepDeg)), y = int(std::floor((-12.0 - g.originLatDeg) / g.latStepDeg));
    ASSERT_TRUE(x >= 0 && x < g.width && y >= 0 && y < g.height) << lon;
    EXPECT_EQ(g.values[(std::size_t(y) * g.width + x) * g.channels], water ? 1.0f : 0.0f) << "grid at " << lon;
    const double lat = -12.0;
    Surface s;
    stack.classifyBatch(&lat, &lon, 1, &s);
    EXPECT_EQ(s, water ? Surface::Ocean : Surface::Land) << "class at " << lon;
  }
}

// Several streamed masks (world::streamedWaterLayers): in answer order,
// at most kMaxStreamedLayers, the rest past the limit named; the chain
// ends at a relief (it answers by sign where it has data), at a mask no
// finer than the grid, and after a global mask. Regional 1' masks (finer
// than the 5' grid) of decreasing priority, a global 1' mask, the
// default-like 1 degree global mask.
TEST(WaterIndex, SeveralStreamedMasksChainInAnswerOrderUpToTheLimit) {
  constexpr double kStep = 1.0 / 60.0, kGrid = 5.0 / 60.0;
  const auto regional = [&](double lon0) {
    return raster::Raster::fromPixels(std::vector<float>(60 * 60, 0.0f), 60, 60, 1, {lon0, 10.0, kStep, -kStep, false});
  };
  const auto global1m = raster::Raster::fromPixels(std::vector<float>(21600 * 2, 0.0f), 21600, 2, 1,
                                                   {-180.0, 90.0, kStep, -90.0, true});
  const auto coarse = raster::Raster::fromPixels(std::vector<float>(360 * 180, 0.0f), 360, 180, 1,
                                                 {-180.0, 90.0, 1.0, -1.0, true});
  std::vector<RasterLayer> layers;
  for (int i = 0; i < 6; ++i) layers.push_back({LayerKind::Mask, regional(i), {}, 10 - i});
  layers.push_back({LayerKind::Mask, coarse, {}, kDefaultWorldPriority});
  {
    const LayerStack stack(layers);
    const RasterLayer* beyond = nullptr;
    const auto chain = streamedWaterLayers(stack, kGrid, &beyond);
    ASSERT_EQ(int(chain.size()), kMaxStreamedLayers);
    for (int i = 0; i < kMaxStreamedLayers; ++i) EXPECT_EQ(chain[std::size_t(i)]->priority, 10 - i);
    ASSERT_NE(beyond, nullptr);
    EXPECT_EQ(beyond->priority, 10 - kMaxStreamedLayers);
    EXPECT_EQ(chain[0], streamedWaterLayer(stack, kGrid));
  }
  {  // two regional masks over the 1 degree world: both, the world in the grid below
    const LayerStack stack({layers[0], layers[1], layers[6]});
    const RasterLayer* beyond = nullptr;
    EXPECT_EQ(streamedWaterLayers(stack, kGrid, &beyond).size(), 2u);
    EXPECT_EQ(beyond, nullptr);
    const WorldLayer below = waterGridBelow(stack, streamedWaterLayers(stack, kGrid), kGrid);
    const WorldLayer world = waterLayerBelow(LayerStack({layers[6], layers[0]}), *layers[0].raster);
    EXPECT_EQ(below.values, world.values) << "the grid under the chain is the world's alone";
  }
  {  // a regional mask over a global streamed one: both; nothing after the global one
    const LayerStack stack({layers[0], RasterLayer{LayerKind::Mask, global1m, {}, 6}, layers[5], layers[6]});
    const auto chain = streamedWaterLayers(stack, kGrid);
    ASSERT_EQ(chain.size(), 2u);
    EXPECT_EQ(chain[1]->raster, global1m);
  }
  {  // a relief between two masks streams too (its 0 m line), a global relief with nodata ends the chain
    const auto relief = raster::Raster::fromPixels(std::vector<float>(60 * 60, -5.0f), 60, 60, 1,
                                                   {50.0, 10.0, 2.0 * kStep, -2.0 * kStep, false});
    const LayerStack stack({layers[0], RasterLayer{LayerKind::Elevation, relief, {}, 10}, layers[1], layers[6]});
    ASSERT_EQ(stack.layers()[1].kind, LayerKind::Elevation);
    const auto chain = streamedWaterLayers(stack, kGrid);
    ASSERT_EQ(chain.size(), 3u);
    EXPECT_EQ(chain[1]->raster, relief);
    EXPECT_EQ(chain[2]->raster, layers[1].raster);
    const auto holed = raster::Raster::fromPixels(std::vector<float>(21600 * 2, -5.0f), 21600, 2, 1,
                                                  {-180.0, 90.0, kStep, -90.0, true}, -9999.0);
    const LayerStack withHoles({layers[0], RasterLayer{LayerKind::Elevation, holed, {}, 10}, layers[1], layers[6]});
    EXPECT_EQ(streamedWaterLayers(withHoles, kGrid).size(), 1u) << "its nodata would be drawn as land";
  }
}

// Several streamed reliefs (world::streamedElevationLayers): elevation
// layers in answer order (masks between them have no elevation), at most
// kMaxStreamedLayers, the one past the limit named; the chain ends at a
// relief no finer than the grid and after a global one.
TEST(WaterIndex, SeveralStreamedReliefsChainInAnswerOrderUpToTheLimit) {
  constexpr double kStep = 1.0 / 60.0, kGrid = 5.0 / 60.0;
  const auto regional = [&](double lon0) {
    return raster::Raster::fromPixels(std::vector<float>(60 * 60, 10.0f), 60, 60, 1, {lon0, 10.0, kStep, -kStep, false});
  };
  const auto mask = raster::Raster::fromPixels(std::vector<float>(60 * 60, 0.0f), 60, 60, 1,
                                               {0.0, 10.0, kStep / 2.0, -kStep / 2.0, false});
  const auto coarse = raster::Raster::fromPixels(std::vector<float>(360 * 180, 0.0f), 360, 180, 1,
                                                 {-180.0, 90.0, 1.0, -1.0, true});
  std::vector<RasterLayer> layers;
  for (int i = 0; i < 6; ++i) layers.push_back({LayerKind::Elevation, regional(i), {}, 10 - i});
  layers.push_back({LayerKind::Elevation, coarse, {}, kDefaultWorldPriority});
  {
    std::vector<RasterLayer> all = layers;
    all.push_back({LayerKind::Mask, mask, {}, 9});  // between the reliefs in answer order
    const LayerStack stack(all);
    const RasterLayer* beyond = nullptr;
    const auto chain = streamedElevationLayers(stack, kGrid, &beyond);
    ASSERT_EQ(int(chain.size()), kMaxStreamedLayers);
    for (int i = 0; i < kMaxStreamedLayers; ++i) EXPECT_EQ(chain[std::size_t(i)]->priority, 10 - i);
    ASSERT_NE(beyond, nullptr);
    EXPECT_EQ(beyond->priority, 10 - kMaxStreamedLayers);
    EXPECT_EQ(chain[0], streamedElevationLayer(stack, kGrid));
  }
  {  // a relief no finer than the grid ends it
    const LayerStack stack({layers[0], RasterLayer{LayerKind::Elevation, coarse, {}, 10}, layers[1]});
    EXPECT_EQ(streamedElevationLayers(stack, kGrid).size(), 1u);
  }
}

// A streamed global mask's open water and the screen grid's near-water
// classes come from the pyramid level that is the ocean's water grid
// (ocean_render::waterIndexFollowsTiles, nearWaterClassifier): checked
// against the mask's own cells, brute force. The mask: 0 ocean, 1 land
// (the default encoding), a continent, land cells alone in the sea (islands
// one mask cell wide, in every position within a level-3 texel) and water
// cells alone inside the land; 8 x 8 mask cells per grid texel.
TEST(WaterIndex, AStreamedMasksLevelKeepsEveryOneCellIslandAndLake) {
  constexpr int W = 4096, H = 2048, kStep = 8;  // levels 0-4 of 256^2 tiles
  std::vector<float> cls(std::size_t(W) * H, 0.0f);
  const auto at = [&](int x, int y) -> float& { return cls[std::size_t(y) * W + x]; };
  const auto inLand = [](int x, int y, int in) { return x >= 800 + in && x < 2000 - in && y >= 400 + in && y < 1200 - in; };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (inLand(x, y, 0)) at(x, y) = 1.0f;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> ux(0, W - 1), uy(0, H - 1);
  int islands = 0, lakes = 0;
  for (int i = 0; i < 4000; ++i) {
    const int x = ux(rng), y = uy(rng);
    if (inLand(x, y, 10)) at(x, y) = 0.0f, ++lakes;
    else if (!inLand(x, y, 0)) at(x, y) = 1.0f, ++islands;
  }
  for (const int x : {0, W - 1}) at(x, 7) = 1.0f;  // islands on the antimeridian
  raster::GeoTransform t;
  t.lonStepDeg = 360.0 / W, t.latStepDeg = -180.0 / H, t.global = true;
  const auto mask = raster::Raster::fromPixels(cls, W, H, 1, t);
  test::TempDir dir("geocean-water-index");
  raster::PyramidOptions po;
  po.cacheDir = dir.path.string();
  po.progress = raster::BuildProgress::Off;
  const auto pyr = waterPyramid(mask, {}, po);
  WorldLayer water = waterLayerOf(*pyr, kStep * t.lonStepDeg);
  ASSERT_EQ(water.width, W / kStep) << "level 3 is the water grid";
  WorldLayer elevation = globalGridFor(nullptr);
  const WorldGrids grids(elevation, water);
  ASSERT_TRUE(ocean_render::waterIndexFollowsTiles(grids, *pyr));
  WorldLayer other = water;
  other.originLonDeg += 0.5 * other.lonStepDeg;  // not a level of this pyramid
  EXPECT_FALSE(ocean_render::waterIndexFollowsTiles(WorldGrids(elevation, other), *pyr));

  // Every rectangle of grid texels is water throughout exactly when every
  // mask cell under it is.
  const WaterIndex& wi = grids.waterIndex();
  const auto landUnder = [&](int gx0, int gx1, int gy0, int gy1) {
    for (int y = gy0 * kStep; y < (gy1 + 1) * kStep; ++y)
      for (int x = gx0 * kStep; x < (gx1 + 1) * kStep; ++x)
        if (at(((x % W) + W) % W, y) != 0.0f) return true;
    return false;
  };
  std::uniform_int_distribution<int> gx(-10, W / kStep + 10), gy(0, H / kStep - 1), size(0, 6);
  int open = 0;
  for (int i = 0; i < 20000; ++i) {
    const int x0 = gx(rng), y0 = gy(rng), x1 = x0 + size(rng), y1 = std::min(y0 + size(rng), H / kStep - 1);
    const bool expect = !landUnder(x0, x1, y0, y1);
    open += expect;
    ASSERT_EQ(wi.allWater(x0 + 0.5, x1 + 0.5, y0 + 0.5, y1 + 0.5), expect) << x0 << " " << x1 << " " << y0 << " " << y1;
  }
  EXPECT_GT(open, 1000);
  EXPECT_GT(20000 - open, 1000);

  // The grid's classes: every point within two mask cells of a water cell
  // (LandSea::classifyNearWaterBatch's reach) is Ocean; and points deep in
  // the continent away from its lakes are Land (the shortcut does something).
  const auto classify = ocean_render::nearWaterClassifier(water);
  std::uniform_real_distribution<double> lon(-180.0, 180.0), lat(-90.0, 90.0);
  int land = 0, nearWater = 0;
  for (int i = 0; i < 200000; ++i) {
    const double la = lat(rng), lo = lon(rng);
    world::Surface s;
    classify(&la, &lo, 1, &s);
    const int x = std::clamp(int((lo + 180.0) / t.lonStepDeg), 0, W - 1), y = std::clamp(int((90.0 - la) / -t.latStepDeg), 0, H - 1);
    bool wet = false;
    for (int dy = -2; dy <= 2 && !wet; ++dy)
      for (int dx = -2; dx <= 2 && !wet; ++dx) wet = at(((x + dx) % W + W) % W, std::clamp(y + dy, 0, H - 1)) == 0.0f;
    nearWater += wet;
    if (wet) {
      ASSERT_EQ(s, world::Surface::Ocean) << la << " " << lo;
    }
    land += s == world::Surface::Land;
  }
  EXPECT_GT(nearWater, 1000);
  EXPECT_GT(land, 1000);
  std::printf("%d islands, %d lakes; %d of 200000 points classed land\n", islands, lakes, land);
}

// A streamed global mask whose levels miss the water grid's step (a 1'
// mask's 4' level for the 5' grid) is resampled onto the step's own grid
// (waterLayerOf): the grid has the step's size whatever the raster's (the
// 1' mask's grid was 1.56x the 1.25' one's texels, +75 MB peak RSS on the
// two sides), and keeps what the shortcuts rely on, checked against the
// mask's own cells, brute force: a texel is 1 only where no mask cell it
// overlaps is land (the open-water index), and above 0 wherever one is
// water (the near-water classes). Masks of 0.09 and 0.18 degree cells (4000
// and 2000 wide: partial tiles), a 0.9 degree grid step: their 0.72 degree
// levels are finer than the step by 1.25x, as 4' against 5'.
TEST(WaterIndex, AStreamedMasksGridHasTheStepsSizeAndKeepsEveryIslandAndLake) {
  constexpr double kStepDeg = 0.9;
  for (const int W : {4000, 2000}) {
    const int H = W / 2;
    std::vector<float> cls(std::size_t(W) * H, 0.0f);
    const auto at = [&](int x, int y) -> float& { return cls[std::size_t(y) * W + x]; };
    const auto inLand = [&](int x, int y, int in) {
      return x >= W / 5 + in && x < W / 2 - in && y >= H / 5 + in && y < 3 * H / 5 - in;
    };
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        if (inLand(x, y, 0)) at(x, y) = 1.0f;
    std::mt19937 rng(9);
    std::uniform_int_distribution<int> ux(0, W - 1), uy(0, H - 1);
    for (int i = 0; i < 3000; ++i) {
      const int x = ux(rng), y = uy(rng);
      if (inLand(x, y, 10)) at(x, y) = 0.0f;   // a lake one cell wide
      else if (!inLand(x, y, 0)) at(x, y) = 1.0f;  // an island one cell wide
    }
    raster::GeoTransform t;
    t.lonStepDeg = 360.0 / W, t.latStepDeg = -180.0 / H, t.global = true;
    const auto mask = raster::Raster::fromPixels(cls, W, H, 1, t);
    test::TempDir dir("geocean-water-grid");
    raster::PyramidOptions po;
    po.cacheDir = dir.path.string();
    po.progress = raster::BuildProgress::Off;
    const auto pyr = waterPyramid(mask, {}, po);
    const WorldLayer water = waterLayerOf(*pyr, kStepDeg);
    ASSERT_EQ(water.width, 400) << W;
    ASSERT_EQ(water.height, 200) << W;
    const WorldGrids grids(globalGridFor(nullptr), water);
    EXPECT_TRUE(ocean_render::waterIndexFollowsTiles(grids, *pyr)) << W << ": the shortcuts stay on";
    int open = 0, wet = 0;
    for (int gy = 0; gy < water.height; ++gy)
      for (int gx = 0; gx < water.width; ++gx) {
        // Mask cells the texel overlaps (not just touches).
        const double x0 = gx * kStepDeg / t.lonStepDeg, x1 = (gx + 1) * kStepDeg / t.lonStepDeg;
        const double y0 = gy * kStepDeg / -t.latStepDeg, y1 = (gy + 1) * kStepDeg / -t.latStepDeg;
        bool anyLand = false, anyWater = false;
        for (int y = int(std::floor(y0 + 1e-9)); y < int(std::ceil(y1 - 1e-9)); ++y)
          for (int x = int(std::floor(x0 + 1e-9)); x < int(std::ceil(x1 - 1e-9)); ++x)
            (at(x, y) != 0.0f ? anyLand : anyWater) = true;
        const float v = water.values[std::size_t(gy) * water.width + gx];
        if (v == 1.0f) {
          ASSERT_FALSE(anyLand) << W << ": texel " << gx << "," << gy << " is 1 over land";
          ++open;
        }
        if (anyWater) {
          ASSERT_GT(v, 0.0f) << W << ": texel " << gx << "," << gy << " is 0 over water";
          ++wet;
        }
      }
    EXPECT_GT(open, 20000) << W;  // the open sea is still open (80000 texels)
    EXPECT_GT(wet, open) << W;
    // The grid's classes keep every water cell's reach (two mask cells).
    const auto classify = ocean_render::nearWaterClassifier(water);
    std::uniform_real_distribution<double> lon(-180.0, 180.0), lat(-90.0, 90.0);
    for (int i = 0; i < 100000; ++i) {
      const double la = lat(rng), lo = lon(rng);
      world::Surface s;
      classify(&la, &lo, 1, &s);
      const int x = std::clamp(int((lo + 180.0) / t.lonStepDeg), 0, W - 1);
      const int y = std::clamp(int((90.0 - la) / -t.latStepDeg), 0, H - 1);
      bool near = false;
      for (int dy = -2; dy <= 2 && !near; ++dy)
        for (int dx = -2; dx <= 2 && !near; ++dx) near = at(((x + dx) % W + W) % W, std::clamp(y + dy, 0, H - 1)) == 0.0f;
      if (near) {
        ASSERT_EQ(s, world::Surface::Ocean) << W << ": " << la << " " << lo;
      }
    }
    if (W != 2000) continue;
    // The grid kept in the pyramid's cache (TilePyramid::derived): a mask
    // file's first run stores it, the next reads it back, bit for bit the
    // grid computed above from the same cells (an in-memory raster has no
    // cache: computed there); a corrupt one is computed again; a rebuilt
    // cache (the source touched) drops it.
    const std::string file = (dir.path / "mask.tif").string();
    std::vector<std::uint8_t> bytes(cls.begin(), cls.end());
    raster::GeoTiffWriteOptions wo;
    wo.transform = t;
    wo.deflateLevel = 1;
    raster::writeGeoTiff(file, bytes.data(), W, H, 1, raster::SampleType::U8, wo);
    const auto sameBits = [&](const WorldLayer& l) {
      return l.width == water.width && l.height == water.height && l.originLonDeg == water.originLonDeg &&
             l.originLatDeg == water.originLatDeg && l.lonStepDeg == water.lonStepDeg &&
             l.latStepDeg == water.latStepDeg && l.values.size() == water.values.size() &&
             std::memcmp(l.values.data(), water.values.data(), 4 * l.values.size()) == 0;
    };
    const auto filePyr = [&] { return waterPyramid(raster::Raster::open(file), {}, po); };
    const auto cold = filePyr();
    const fs::path stored = fs::path(cold->stats().cachePath) / ("derived-water-grid-" + [&] {
      std::uint64_t b;
      std::memcpy(&b, &kStepDeg, 8);
      char h[17];
      std::snprintf(h, sizeof h, "%016llx", static_cast<unsigned long long>(b));
      return std::string(h);
    }());
    EXPECT_TRUE(sameBits(waterLayerOf(*cold, kStepDeg)));
    ASSERT_TRUE(fs::exists(stored)) << stored;
    EXPECT_TRUE(sameBits(waterLayerOf(*filePyr(), kStepDeg))) << "read back";
    {
      std::fstream f(stored, std::ios::in | std::ios::out | std::ios::binary);
      f.seekg(100);
      const char was = char(f.get());
      f.seekp(100);
      f.put(char(~was));
    }
    ASSERT_FALSE(cold->derived(stored.filename().string().substr(8)).has_value()) << "corrupt, not read";
    EXPECT_TRUE(sameBits(waterLayerOf(*filePyr(), kStepDeg))) << "computed again";
    EXPECT_TRUE(cold->derived(stored.filename().string().substr(8)).has_value()) << "and stored again";
    fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(5));
    const auto rebuilt = filePyr();
    EXPECT_TRUE(rebuilt->stats().builtNow);
    EXPECT_FALSE(fs::exists(stored)) << "a rebuilt cache drops what was derived from the old tiles";
  }
}

// A global relief finer than the 5' grid, without nodata and with no mask
// (--no-default-world --elevation): it decides the coast, and its 0 m line
// is streamed as a water pyramid (world::reliefWaterPyramid) on both sides.
// The host's grid (loadLayeredWorld) and the ocean's (oceanWaterTiles,
// oceanWorld) are the same 5' level of it, 1 exactly where every relief
// cell under a texel is below 0 m and above 0 where any is (checked
// against the relief's own cells); the ocean's shortcuts accept it; the
// query classes by the same cells. 2.5' cells: a continent (0.05..90.05 E, 45.05 S
// ..45.05 N, +100 m: edges inside grid texels), an island of 0.05 degrees radius at (10 N, 150 W),
// +50 m, sea at -1000 m.
TEST(WaterIndex, AGlobalReliefDecidingTheCoastIsStreamedAsItsZeroMetreLine) {
  constexpr int W = 8640, H = 4320;
  const auto elevation = [](int x, int y) {
    const double lon = -180.0 + (x + 0.5) * 360.0 / W, lat = 90.0 - (y + 0.5) * 180.0 / H;
    if (lon >= 0.05 && lon < 90.05 && std::abs(lat) < 45.05) return 100.0f;
    if (std::hypot(lat - 10.0, (lon + 150.0) * std::cos(10.0 * M_PI / 180.0)) < 0.05) return 50.0f;
    return -1000.0f;
  };
  test::TempDir dir("geocean-relief-water");
  ::setenv("GEOCEAN_TILE_CACHE", (dir.path / "cache").c_str(), 1);
  const std::string tif = (dir.path / "relief.tif").string();
  raster::GeoTiffWriteOptions wo;
  wo.transform = {-180.0, 90.0, 360.0 / W, -180.0 / H, true};
  raster::writeGeoTiffTiles(tif, W, H, 1, raster::SampleType::F32, wo, [&](int x0, int y0, void* tile) {
    float* v = static_cast<float*>(tile);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) v[y * 256 + x] = elevation(std::min(x0 + x, W - 1), std::min(y0 + y, H - 1));
  });
  const WorldData d = loadLayeredWorld({{LayerKind::Elevation, tif, "", 0}}, false);
  ASSERT_TRUE(d.waterSource);
  EXPECT_TRUE(d.waterFromRelief);
  ASSERT_EQ(d.water.width, 4320);
  ASSERT_EQ(d.water.height, 2160);
  int all = 0, some = 0;
  for (int gy = 0; gy < d.water.height; ++gy)
    for (int gx = 0; gx < d.water.width; ++gx) {
      bool anyLand = false, anyWater = false;
      for (int y = 2 * gy; y < 2 * gy + 2; ++y)
        for (int x = 2 * gx; x < 2 * gx + 2; ++x) (elevation(x, y) < 0.0f ? anyWater : anyLand) = true;
      const float v = d.water.values[std::size_t(gy) * d.water.width + gx];
      ASSERT_EQ(v == 1.0f, !anyLand) << gx << "," << gy;
      ASSERT_EQ(v > 0.0f, anyWater) << gx << "," << gy;
      all += !anyLand, some += anyLand && anyWater;
    }
  EXPECT_GT(all, 1000000);
  EXPECT_GT(some, 1000);
  const ocean::LayeredLandSea ls({{LayerKind::Elevation, raster::Raster::open(tif), {}, 0}});
  const auto tiles = ocean_render::oceanWaterTiles(&ls, nullptr);
  ASSERT_TRUE(tiles);
  const auto grids = ocean_render::oceanWorld(nullptr, ls.stack().drawingElevation(), &ls, {}, tiles.get());
  EXPECT_TRUE(grids->water().values == d.water.values) << "the ocean's grid is the host's";
  EXPECT_TRUE(ocean_render::waterIndexFollowsTiles(*grids, *tiles));
  EXPECT_EQ(ls.classify(10.0, -150.0), Surface::Land);
  EXPECT_EQ(ls.classify(10.0, -149.9), Surface::Ocean);
  EXPECT_EQ(ls.classify(0.0, 45.0), Surface::Land);
  ::unsetenv("GEOCEAN_TILE_CACHE");
}


// A streamed global mask with a continent (a block), one-cell islands and
// lakes; W x H cells of 360 / W degrees, 256^2 tiles (partial at the edge).
struct BlockMask {
  int W, H;
  std::vector<float> cls;  // the mask's classes: 0 ocean, 1 land
  raster::GeoTransform t;
  test::TempDir dir{"geocean-tile-water"};
  std::shared_ptr<const raster::TilePyramid> pyr;
  BlockMask(int w, int h, int specks) : W(w), H(h), cls(std::size_t(w) * h, 0.0f) {
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        if (inLand(x, y, 0)) at(x, y) = 1.0f;
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> ux(0, W - 1), uy(0, H - 1);
    for (int i = 0; i < specks; ++i) {
      const int x = ux(rng), y = uy(rng);
      at(x, y) = inLand(x, y, 0) ? 0.0f : 1.0f;
    }
    t.lonStepDeg = 360.0 / W, t.latStepDeg = -180.0 / H, t.global = true;
    raster::PyramidOptions po;
    po.cacheDir = dir.path.string();
    po.progress = raster::BuildProgress::Off;
    pyr = waterPyramid(raster::Raster::fromPixels(cls, W, H, 1, t), {}, po);
  }
  bool inLand(int x, int y, int in) const { return x >= W / 5 + in && x < W / 2 - in && y >= H / 5 + in && y < 3 * H / 5 - in; }
  float& at(int x, int y) { return cls[std::size_t(y) * W + x]; }
};

// TileWaterIndex against the mask's own cells, brute force: all water or
// all land only where every cell the rectangle touches is (any size,
// across the antimeridian), and exactly so for rectangles of up to 8 cells
// (read at level 0). Few tiles kept, so they are dropped and read again.
TEST(TileWaterIndex, AnswersAsTheMasksOwnCells) {
  BlockMask m(4000, 2000, 3000);
  TileWaterIndex ti(m.pyr, 6);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ux(-50.0, m.W + 50.0), uy(0.0, m.H - 1.0), unit(0.0, 1.0);
  int counts[3] = {0, 0, 0}, exact = 0;
  for (int i = 0; i < 4000; ++i) {
    const double size = i % 3 == 0 ? 8.0 * unit(rng) : i % 3 == 1 ? 60.0 * unit(rng) : 400.0 * unit(rng);
    const double x0 = ux(rng), y0 = uy(rng), x1 = x0 + size * unit(rng), y1 = std::min(y0 + size * unit(rng), m.H - 0.5);
    bool water = false, land = false;
    for (int y = int(std::floor(y0)); y <= int(std::floor(y1)); ++y)
      for (int x = int(std::floor(x0)); x <= int(std::floor(x1)); ++x)
        (m.at(((x % m.W) + m.W) % m.W, y) == 0.0f ? water : land) = true;
    const TileWaterIndex::Cover c = ti.cover(x1, x0, y1, y0);  // corners in any order
    ++counts[int(c)];
    if (c == TileWaterIndex::Cover::Water) {
      ASSERT_FALSE(land) << x0 << " " << x1 << " " << y0 << " " << y1;
    }
    if (c == TileWaterIndex::Cover::Land) {
      ASSERT_FALSE(water) << x0 << " " << x1 << " " << y0 << " " << y1;
    }
    if (std::max(x1 - x0, y1 - y0) <= 8.0) {
      ++exact;
      ASSERT_EQ(c, water && land ? TileWaterIndex::Cover::Mixed
                   : water       ? TileWaterIndex::Cover::Water
                                 : TileWaterIndex::Cover::Land)
          << x0 << " " << x1 << " " << y0 << " " << y1;
    }
  }
  EXPECT_GT(counts[0], 300) << "all land";
  EXPECT_GT(counts[1], 300) << "all water";
  EXPECT_GT(counts[2], 300) << "both";
  EXPECT_GT(exact, 1300);
  EXPECT_LE(ti.tilesKept(), 6u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ti.cover(nan, 1.0, 0.0, 1.0), TileWaterIndex::Cover::Mixed);
  EXPECT_EQ(ti.cover(0.0, 0.6 * m.W, 0.0, 1.0), TileWaterIndex::Cover::Mixed) << "over half the Earth";
}

// The ocean's cell groups over a streamed global mask (issue 12 item 6):
// the drawn grid's texel is 8 mask cells, so a cell 6 cells off the coast
// has land within the grid index's reach (3 grid texels) and took the
// per-pixel coverage; asked at the mask's cells it is open water, a cell
// deep in the continent is dropped (every fragment would discard), a cell
// on the coast keeps the coverage, and open sea stays open.
TEST(TileWaterIndex, CellsOffAStreamedCoastAreOpenAndInlandCellsDropped) {
  BlockMask m(4000, 2000, 0);
  constexpr int kStep = 8;
  const WorldGrids grids(globalGridFor(nullptr), waterLayerOf(*m.pyr, kStep * m.t.lonStepDeg));
  ASSERT_EQ(grids.water().width, m.W / kStep);
  grid::GridFrame f;
  std::vector<std::uint32_t> all;
  // Cells of 0.1 mask cell at these mask-cell x (the coast at x = W / 5),
  // mid-continent in y.
  const double xs[] = {m.W / 5 - 6.2, m.W / 5 - 0.05, m.W / 5 + 20.0, m.W / 5 - 60.0};  // off, on, inland, open sea
  for (const double x : xs) {
    const auto v0 = std::uint32_t(f.vertices.size());
    for (int k = 0; k < 4; ++k) {
      grid::GridVertex v{};
      v.lonDeg = m.t.originLonDeg + (x + 0.1 * (k & 1)) * m.t.lonStepDeg;
      v.latDeg = m.t.originLatDeg + (m.H / 2 + 0.1 * (k >> 1)) * m.t.latStepDeg;
      f.vertices.push_back(v);
    }
    for (const std::uint32_t k : {0u, 1u, 2u, 2u, 1u, 3u}) all.push_back(v0 + k);
  }
  f.cols = 2, f.rows = int(f.vertices.size()) / 2;
  const ocean_render::ScreenCull cull;  // no far group, no culling
  const auto cellsOf = [&](const std::vector<std::uint32_t>& idx, std::size_t from, std::size_t n) {
    std::vector<int> cells;
    for (std::size_t i = from; i < from + n; i += 6) cells.push_back(int(idx[i] / 4));
    std::sort(cells.begin(), cells.end());
    return cells;
  };
  std::vector<std::uint32_t> idx = all;
  auto g = ocean_render::partitionCells(f, grids.waterIndex(), 8.0, cull, false, true, idx, kStep);
  EXPECT_EQ(cellsOf(idx, 0, g.sharp), (std::vector<int>{0, 1, 2})) << "the grid's index alone";
  EXPECT_EQ(cellsOf(idx, g.sharp + g.smooth, g.open), (std::vector<int>{3}));
  TileWaterIndex ti(m.pyr);
  idx = all;
  g = ocean_render::partitionCells(f, grids.waterIndex(), 8.0, cull, false, true, idx, kStep, &ti);
  EXPECT_EQ(cellsOf(idx, 0, g.sharp), (std::vector<int>{1})) << "the coast";
  EXPECT_EQ(g.smooth, 0u);
  EXPECT_EQ(cellsOf(idx, g.sharp, g.open), (std::vector<int>{0, 3})) << "open water";
  EXPECT_EQ(idx.size(), g.sharp + g.open) << "the inland cell dropped";
}

}  // namespace
}  // namespace geocean::world
