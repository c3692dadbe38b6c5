// The layer stack (issue 12 item 1): user masks and elevations over the
// bundled world, the finest with data answering; through the façade and
// through `geocean query`/`pick`/`demo`.
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/World.h"
#include "plugin/ocean/Ocean.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

using namespace geocean;
using geocean::test::run;

namespace {
const std::string kGeocean = GEOCEAN_EXE;

std::string tempDir() {
  static const std::string d = [] {
    auto p = std::filesystem::temp_directory_path() / ("geocean_layers_" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p.string();
  }();
  return d;
}

// A 290 m island peak at (0.25, 0.25) in a 200 m deep sea: 15" cells over
// -0.5 .. 1 degrees (finer than the 5' default mask, which says ocean there).
constexpr double kStep = 1.0 / 240.0;
constexpr int kSide = 360;
float islandM(double lat, double lon) {
  const double r2 = ((lat - 0.25) * (lat - 0.25) + (lon - 0.25) * (lon - 0.25)) / (0.15 * 0.15);
  return float(-200.0 + 490.0 * std::exp(-r2));
}
std::string islandTif() {
  static const std::string path = [] {
    std::vector<float> px(std::size_t(kSide) * kSide);
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) px[std::size_t(y) * kSide + x] = islandM(1.0 - (y + 0.5) * kStep, -0.5 + (x + 0.5) * kStep);
    raster::GeoTiffWriteOptions wo;
    wo.transform = {-0.5, 1.0, kStep, -kStep, false};
    const std::string p = tempDir() + "/island.tif";
    raster::writeGeoTiff(p, px.data(), kSide, kSide, 1, raster::SampleType::F32, wo);
    return p;
  }();
  return path;
}

// A regional mask around the Strait of Gibraltar (35..37 N, 7..4 W), all
// ocean (0), with a nodata (255) band along its north row and a land (1)
// block at 36.5..37 N, 6..5 W. Outside it the default world answers.
std::string regionalMaskTif() {
  static const std::string path = [] {
    constexpr double step = 1.0 / 60.0;
    const int w = 180, h = 120;
    std::vector<std::uint8_t> px(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double lat = 37.0 - (y + 0.5) * step, lon = -7.0 + (x + 0.5) * step;
        if (y < 6) px[std::size_t(y) * w + x] = 255;
        else if (lat > 36.5 && lon > -6.0 && lon < -5.0) px[std::size_t(y) * w + x] = 1;
      }
    raster::GeoTiffWriteOptions wo;
    wo.transform = {-7.0, 37.0, step, -step, false};
    wo.nodata = 255;
    const std::string p = tempDir() + "/gibraltar_mask.tif";
    raster::writeGeoTiff(p, px.data(), w, h, 1, raster::SampleType::U8, wo);
    return p;
  }();
  return path;
}

ocean::Surface classOf(const ocean::Snapshot& s, double lat, double lon) {
  ocean::Surface c;
  s.classify(&lat, &lon, 1, &c);
  return c;
}
float elevationOf(const ocean::Snapshot& s, double lat, double lon) {
  float e;
  s.elevationAt(&lat, &lon, 1, &e);
  return e;
}
}  // namespace

TEST(Layers, FinerElevationDecidesLandOverTheDefaultMask) {
  ocean::Ocean o;
  o.setDefaultWorld(ocean::Ocean::defaultWorldDir());
  // The 5' default mask says ocean at the peak: the premise of the test.
  ASSERT_EQ(classOf(*o.current(), 0.25, 0.25), ocean::Surface::Ocean);
  o.addElevationLayerFile(islandTif());
  const auto s = o.current();
  EXPECT_EQ(classOf(*s, 0.25, 0.25), ocean::Surface::Land);
  EXPECT_NEAR(elevationOf(*s, 0.25, 0.25), islandM(0.25, 0.25), 2.0);
  // Off the island inside the raster: its sea (below 0 m) is ocean.
  EXPECT_EQ(classOf(*s, 0.9, 0.9), ocean::Surface::Ocean);
  EXPECT_NEAR(elevationOf(*s, 0.9, 0.9), -200.0, 1.0);
  // Outside the raster the default world answers: the Caspian is a lake,
  // the Sahara land with ETOPO's relief.
  EXPECT_EQ(classOf(*s, 42.0, 50.5), ocean::Surface::Lake);
  EXPECT_EQ(classOf(*s, 23.0, 10.0), ocean::Surface::Land);
  const auto base = std::make_shared<ocean::Ocean>();
  base->setDefaultWorld(ocean::Ocean::defaultWorldDir());
  EXPECT_EQ(elevationOf(*s, 23.0, 10.0), elevationOf(*base->current(), 23.0, 10.0));
  // The draw half's grids come from the island (regional: resampled
  // through the stack), and the water grid at the elevation's step.
  EXPECT_EQ(s->elevation->path(), islandTif());
  EXPECT_EQ(s->mask, nullptr);
  // Removing the layer brings back the default world alone.
  EXPECT_EQ(o.removeLayer(islandTif()), 1u);
  EXPECT_EQ(o.removeLayer(islandTif()), 0u);
  EXPECT_EQ(classOf(*o.current(), 0.25, 0.25), ocean::Surface::Ocean);
  EXPECT_TRUE(o.current()->layers.empty());
}

TEST(Layers, RegionalMaskSitsOnTheDefaultWorldWithItsNodata) {
  ocean::Ocean o;
  o.setDefaultWorld(ocean::Ocean::defaultWorldDir());
  const double inLat = 36.7, inLon = -5.5;  // the regional mask's land block
  const auto before = o.current();
  o.addMaskLayerFile(regionalMaskTif());
  const auto s = o.current();
  EXPECT_EQ(classOf(*s, inLat, inLon), ocean::Surface::Land);
  EXPECT_EQ(classOf(*s, 35.5, -6.5), ocean::Surface::Ocean);  // the mask's ocean
  // Its nodata row (36.9 .. 37 N) falls through to the default world.
  for (double lon : {-6.9, -5.6, -4.1})
    EXPECT_EQ(classOf(*s, 36.95, lon), classOf(*before, 36.95, lon)) << lon;
  // Far outside: the default world, not "ocean" as when a mask replaced it.
  EXPECT_EQ(classOf(*s, 42.0, 50.5), ocean::Surface::Lake);
  EXPECT_EQ(classOf(*s, 47.7, -87.5), ocean::Surface::Lake);
  EXPECT_EQ(classOf(*s, 23.0, 10.0), ocean::Surface::Land);
  // Its own encoding: a second copy of the same file at a higher priority
  // calling 0 land is refused (same path), a remapped in-memory copy wins.
  EXPECT_THROW(o.addMaskLayerFile(regionalMaskTif(), 5), std::invalid_argument);
  auto r = raster::Raster::open(regionalMaskTif());
  auto copy = raster::Raster::fromPixels(r->pixels(), r->width(), r->height(), 1, r->transform(), std::nullopt,
                                         "<memory: all land>");
  o.addMaskLayer(copy, 5, ocean::MaskEncoding::parse("0=land,1=land"));
  EXPECT_EQ(classOf(*o.current(), 35.5, -6.5), ocean::Surface::Land);
  EXPECT_EQ(classOf(*o.current(), 42.0, 50.5), ocean::Surface::Lake);
  // The priority floor belongs to the default world.
  EXPECT_THROW(o.addMaskLayer(copy, world::kDefaultWorldPriority), std::invalid_argument);
}

TEST(Layers, WithoutTheDefaultWorldOnlyTheLayersAnswer) {
  ocean::Ocean o;
  o.addElevationLayerFile(islandTif());
  const auto s = o.current();
  EXPECT_EQ(classOf(*s, 0.25, 0.25), ocean::Surface::Land);
  EXPECT_EQ(classOf(*s, 0.9, 0.9), ocean::Surface::Ocean);
  EXPECT_EQ(classOf(*s, 42.0, 50.5), ocean::Surface::Land);  // no data: land, as a lone mask says outside itself
  EXPECT_TRUE(std::isnan(elevationOf(*s, 42.0, 50.5)));
  // The finer of two layers of one priority answers; a higher priority beats it.
  const auto coarse = raster::Raster::fromPixels(std::vector<float>(4, 1.0f), 2, 2, 1, {-1.0, 1.0, 1.0, -1.0, false},
                                                 std::nullopt, "<memory: coarse land>");
  o.addMaskLayer(coarse);
  EXPECT_EQ(classOf(*o.current(), 0.9, 0.9), ocean::Surface::Ocean);  // the 15" island is finer than 1 degree
  o.removeLayer("<memory: coarse land>");
  o.addMaskLayer(coarse, 1);
  EXPECT_EQ(classOf(*o.current(), 0.9, 0.9), ocean::Surface::Land);
}

TEST(LayersCli, QueryOverASyntheticIslandAnswersLand) {
  // The example: `geocean query 0.25 0.25 --elevation island.tif`.
  auto r = run(kGeocean + " query 0.25 0.25 --elevation " + islandTif());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("0.25,0.25,land,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(",null,null,null,null,null"), std::string::npos) << r.out;  // no sea height on land
  // The Caspian outside the user's mask stays a lake, without waves.
  r = run(kGeocean + " query 42 50.5 --mask " + regionalMaskTif());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("42,50.5,lake,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(",null,null,null,null,null"), std::string::npos) << r.out;
  // Repeated options: both layers, each answering in its region.
  r = run(kGeocean + " query --points - --mask " + regionalMaskTif() + " --elevation " + islandTif(),
          "0.25,0.25\n36.7,-5.5\n35.5,-6.5\n42,50.5\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("0.25,0.25,land,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("36.7,-5.5,land,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("35.5,-6.5,ocean,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("42,50.5,lake,"), std::string::npos) << r.out;
  // --no-default-world: nothing under the layers (no data is land).
  r = run(kGeocean + " query 42 50.5 --no-default-world --mask " + regionalMaskTif());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("42,50.5,land,"), std::string::npos) << r.out;
  r = run(kGeocean + " query 0 0 --no-default-world");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--no-default-world needs --mask or --elevation"), std::string::npos) << r.err;
  // A bad file among several is named.
  r = run(kGeocean + " query 0 0 --mask " + regionalMaskTif() + " --mask /nonexistent/second.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("/nonexistent/second.tif"), std::string::npos) << r.err;
}

TEST(LayersCli, DemoAndPickTakeTheLayers) {
  auto r = run(kGeocean + " demo --mask " + regionalMaskTif());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("Caspian Sea"), std::string::npos);
  EXPECT_NE(r.out.find("lake"), std::string::npos);
  // Straight down onto the peak from 10 km: the island's terrain, land.
  r = run(kGeocean + " pick --camera 0.25,0.25,10000,0,-90 --fov 1 --size 3x3 --pixel 1,1 --elevation " +
          islandTif());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find(",land"), std::string::npos) << r.out;
  // Without the layer the default world there is sea.
  r = run(kGeocean + " pick --camera 0.25,0.25,10000,0,-90 --fov 1 --size 3x3 --pixel 1,1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find(",ocean"), std::string::npos) << r.out;
}
