#include "CoastScene.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

namespace geocean::render::test {

CoastRasters straightBeach(int width, int height, const raster::GeoTransform& place, double shoreLonDeg,
                           double slope) {
  std::vector<float> elev(std::size_t(width) * height), land(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double eastOfShoreM = (place.lonOf(x + 0.5) - shoreLonDeg) * 111320.0;
      elev[std::size_t(y) * width + x] = float(std::max(-200.0, slope * eastOfShoreM));
      land[std::size_t(y) * width + x] = eastOfShoreM > 0.0 ? 1.0f : 0.0f;
    }
  return {raster::Raster::fromPixels(elev, width, height, 1, place, std::nullopt, "beach"),
          raster::Raster::fromPixels(land, width, height, 1, place, std::nullopt, "beach_mask")};
}

ocean_render::OceanOptions CoastScene::options(bool withField) const {
  ocean_render::OceanOptions oo;
  oo.model = waves::Model::Gerstner;
  oo.sea = snap->seaState;
  if (withField) oo.coast = snap->waves->coastFieldShared();
  return oo;
}

std::unique_ptr<CoastScene> makeCoastScene(CoastRasters rasters, const waves::CoastField::Region& region) {
  auto c = std::make_unique<CoastScene>();
  c->rasters = std::move(rasters);
  const raster::Raster &elevation = *c->rasters.elevation, &mask = *c->rasters.mask;
  c->ocean.setRasters(c->rasters.mask, c->rasters.elevation);
  waves::SeaState sea;
  sea.windSpeedMps = 10.0;
  sea.windFromDeg = 270.0;  // waves travel east, onto a beach's shore
  sea.anchorLatDeg = region.latDeg;
  c->ocean.setSeaState(waves::Model::Gerstner, sea);
  c->ocean.setCoastRegion(region);
  c->snap = c->ocean.current();
  c->grids = std::make_shared<const world::WorldGrids>(world::layerOf(elevation, 0), world::waterLayerOf(mask));
  const int w = elevation.width(), h = elevation.height();
  std::vector<float> sand(std::size_t(w) * h * 3);
  for (std::size_t i = 0; i < sand.size(); i += 3) sand[i] = 194.0f, sand[i + 1] = 178.0f, sand[i + 2] = 128.0f;
  world::WorldData wd = world::loadDefaultWorld();
  wd.imagery = world::layerOf(*raster::Raster::fromPixels(sand, w, h, 3, elevation.transform(), std::nullopt, "sand"));
  wd.elevation = world::layerOf(elevation, 0);
  wd.water = world::waterLayerOf(mask);
  c->world = std::make_shared<const WorldTextures>(wd);
  return c;
}

std::unique_ptr<CoastScene> spillingBeach() {
  waves::CoastField::Region r;
  r.latDeg = 0.3, r.lonDeg = 0.0, r.cellM = 8.0, r.nodes = 501;
  r.islandRadiusM = 50.0;  // a straight shore casts no shadow
  return makeCoastScene(straightBeach(400, 800, {-0.02, 0.34, 0.0001, -0.0001, false}, kSpillingShoreLon, kSpillingSlope),
                        r);
}

bool seaPoint(const camera::Camera& cam, int x, int y, geo::Geodetic& out) {
  const glm::dvec3 eye = cam.eyeEcef(), ray = cam.pixelRay(x + 0.5, y + 0.5);
  double lo = 0.0, hi = 5000.0;
  if (geo::fromEcef(eye + hi * ray).heightM > 0.0) return false;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (geo::fromEcef(eye + mid * ray).heightM > 0.0 ? lo : hi) = mid;
  }
  out = geo::fromEcef(eye + hi * ray);
  return true;
}

}  // namespace geocean::render::test
