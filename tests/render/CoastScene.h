// Synthetic coasts for the near-shore tests (issue 15): rasters made in
// the test, the façade over them with a coast region, the ocean's own grids
// and the host's world (relief, water, sand imagery: the default's there is
// the Gulf of Guinea's deep blue). One builder for the beaches of
// test_coast_bands, test_spray and test_coast_waves and its island.
#pragma once

#include "RenderFixture.h"

#include "globe/camera/Camera.h"
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/Raster.h"
#include "globe/world/WorldData.h"
#include "plugin/ocean/Ocean.h"

#include <memory>

namespace geocean::render::test {

struct CoastRasters {
  std::shared_ptr<const raster::Raster> elevation, mask;  // mask: 0 ocean, 1 land
};

// A straight north-south beach on width x height pixels at `place`: the
// elevation is slope x (metres east of shoreLonDeg, 111320 m a degree),
// down to -200 m; land east of the shore.
CoastRasters straightBeach(int width, int height, const raster::GeoTransform& place, double shoreLonDeg,
                           double slope);

struct CoastScene {
  CoastRasters rasters;
  ocean::Ocean ocean;  // the rasters, a U10 10 m/s Gerstner sea from the west, the coast region
  std::shared_ptr<const ocean::Snapshot> snap;
  std::shared_ptr<const world::WorldGrids> grids;  // the ocean's own
  std::shared_ptr<const WorldTextures> world;      // the host's
  // The renderer's options for the snapshot's sea: Gerstner, its sea state,
  // its coast field (none without withField); callers set the rest.
  ocean_render::OceanOptions options(bool withField = true) const;
};

// The sea is anchored at the region's latitude.
std::unique_ptr<CoastScene> makeCoastScene(CoastRasters rasters, const waves::CoastField::Region& region);

// The 1:50 spilling beach (U10 10 m/s onto the shore: Iribarren ~0.1) of
// test_coast_bands and test_spray: 0.0001-degree rasters (11 m), lon
// -0.02 .. 0.02, lat 0.26 .. 0.34, the shore at lon kSpillingShoreLon,
// down to 200 m; its coast region 4 km of 8 m cells (the whole view's surf
// zone), a straight shore casting no shadow.
constexpr double kSpillingShoreLon = 0.005, kSpillingSlope = 0.02;
std::unique_ptr<CoastScene> spillingBeach();

// Where the ray through pixel (x, y)'s centre meets the ellipsoid
// (bisection on the geodetic height); false if it does not within 5 km.
bool seaPoint(const camera::Camera& cam, int x, int y, geo::Geodetic& out);

}  // namespace geocean::render::test
