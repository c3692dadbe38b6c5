#include "plugin/render/OceanWorld.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/raster/Raster.h"
#include "globe/world/WaterPyramid.h"
#include "plugin/landsea/LayeredLandSea.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace geocean::ocean_render {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The water grid's step the streamed layers are chosen at (0: none): the
// drawing mask's, or without one (a relief finer than every mask decides
// the coast) the drawing elevation's.
double waterGridStep(const ocean::LayeredLandSea* layered, const std::shared_ptr<const raster::Raster>& mask) {
  const auto grid = layered && mask ? mask : layered ? layered->stack().drawingElevation() : nullptr;
  return grid ? world::globalGridFor(grid.get()).lonStepDeg : 0.0;
}

// A global raster in memory, north up, pole to pole: copied pixel for pixel.
bool directlyCopied(const std::shared_ptr<const raster::Raster>& r) { return r && world::globalInMemory(*r); }
}  // namespace

// The ocean's global equirectangular layers from its rasters: a global raster in memory is copied pixel for pixel (the
// viewer's own textures, so the picture matches it); anything else is
// resampled through the classifier onto a global grid at the raster's step.
std::shared_ptr<const world::WorldGrids> oceanWorld(const std::shared_ptr<const raster::Raster>& mask,
                                                    const std::shared_ptr<const raster::Raster>& elevation,
                                                    const ocean::LandSea* landSea, const world::MaskEncoding& encoding,
                                                    const raster::TilePyramid* waterTiles) {
  using world::WorldLayer;
  using raster::Raster;
  world::WorldData d;
  if (directlyCopied(elevation)) {
    d.elevation = world::layerOf(*elevation, 0);
  } else if (elevation) {
    d.elevation = world::globalGridFor(elevation.get());
    world::forCellChunks(d.elevation, [&](std::size_t first, const double* lat, const double* lon, std::size_t n) {
      landSea->elevationBatch(lat, lon, n, d.elevation.values.data() + first);
    });
  } else {
    d.elevation = world::globalGridFor(nullptr);
    // No relief: deep water everywhere, as the queries assume.
    std::fill(d.elevation.values.begin(), d.elevation.values.end(), -10000.0f);
  }
  world::nodataToSeaLevel(d.elevation);  // as the viewer does
  const auto* layered = dynamic_cast<const ocean::LayeredLandSea*>(landSea);
  if (waterTiles && world::isStreamedRegional(waterTiles->source()) && layered) {
    // A regional pyramid is drawn over the grid of the layers below it,
    // the host terrain's (world::loadLayeredWorld); several streamed layers
    // (oceanWaterTileLayers) over the grid below them all.
    const auto chain = world::streamedWaterLayers(layered->stack(), waterGridStep(layered, mask));
    if (chain.size() > 1 && chain[0]->raster.get() == &waterTiles->source())
      d.water = world::waterGridBelow(layered->stack(), chain, waterGridStep(layered, mask));
    else
      d.water = world::waterLayerBelow(layered->stack(), waterTiles->source());
  } else if (waterTiles && !world::isStreamedRegional(waterTiles->source())) {
    d.water = world::waterLayerOf(*waterTiles, world::globalGridFor((mask ? mask : elevation).get()).lonStepDeg);
  } else if (directlyCopied(mask)) {
    d.water = world::waterLayerOf(*mask, encoding);
  } else if (landSea) {
    d.water = world::globalGridFor((mask ? mask : elevation).get());
    std::vector<ocean::Surface> cls;
    world::forCellChunks(d.water, [&](std::size_t first, const double* lat, const double* lon, std::size_t n) {
      cls.resize(n);
      landSea->classifyBatch(lat, lon, n, cls.data());
      for (std::size_t i = 0; i < n; ++i) d.water.values[first + i] = cls[i] == ocean::Surface::Land ? 0.0f : 1.0f;
    });
  } else {
    d.water = world::globalGridFor(nullptr);
    std::fill(d.water.values.begin(), d.water.values.end(), 1.0f);
  }
  return std::make_shared<const world::WorldGrids>(std::move(d.elevation), std::move(d.water));
}

std::shared_ptr<const raster::TilePyramid> oceanWaterTiles(const ocean::LandSea* landSea,
                                                           const std::shared_ptr<const raster::Raster>& mask) {
  const auto* layered = dynamic_cast<const ocean::LayeredLandSea*>(landSea);
  const double step = waterGridStep(layered, mask);
  if (!(step > 0.0)) return nullptr;
  const world::RasterLayer* l = world::streamedWaterLayer(layered->stack(), step);
  return l ? world::waterPyramid(*l) : nullptr;
}

std::vector<std::shared_ptr<const raster::TilePyramid>> oceanWaterTileLayers(
    const ocean::LandSea* landSea, const std::shared_ptr<const raster::Raster>& mask) {
  std::vector<std::shared_ptr<const raster::TilePyramid>> out;
  const auto* layered = dynamic_cast<const ocean::LayeredLandSea*>(landSea);
  const double step = waterGridStep(layered, mask);
  if (!(step > 0.0)) return out;
  for (const world::RasterLayer* l : world::streamedWaterLayers(layered->stack(), step))
    out.push_back(world::waterPyramid(*l));
  return out;
}

std::vector<std::shared_ptr<const raster::TilePyramid>> oceanElevationTileLayers(
    const ocean::LandSea* landSea, const std::shared_ptr<const raster::Raster>& elevation) {
  std::vector<std::shared_ptr<const raster::TilePyramid>> out;
  const auto* layered = dynamic_cast<const ocean::LayeredLandSea*>(landSea);
  if (!layered || !elevation) return out;
  // oceanWorld's elevation grid step (and loadLayeredWorld's for the host).
  for (const world::RasterLayer* l : world::streamedElevationLayers(layered->stack(), world::drawingGridStepDeg(elevation.get())))
    out.push_back(raster::TilePyramid::open(l->raster));
  return out;
}

std::vector<float> reliefUnderMaskWater(const world::WorldGrids& world) {
  const world::WorldLayer& e = world.elevation();
  const world::WorldLayer& wl = world.water();
  const int w = e.width, h = e.height;
  const auto elev = [&](int x, int y) {
    return e.values[(std::size_t(std::clamp(y, 0, h - 1)) * w + std::size_t((x % w + w) % w)) * std::size_t(e.channels)];
  };
  // Cell (x, y) spans the texel centres x .. x + 1, y .. y + 1 (the
  // bilinear's pieces); sampled at the water grid's step (at least 2 x 2).
  const int n = std::clamp(int(std::ceil(std::abs(e.lonStepDeg / wl.lonStepDeg))) + 1, 2, 16);
  // Whether the water can be above 0.5 in cell (x, y): one of the water
  // texels its bilinear reads there is (four at or below 0.5 keep it so).
  const auto wetIn = [&](int x, int y) {
    const auto range = [](double a, double b, double origin, double step) {
      const double u = (a - origin) / step - 0.5, v = (b - origin) / step - 0.5;
      return std::pair<long, long>(long(std::floor(std::min(u, v))), long(std::floor(std::max(u, v))) + 1);
    };
    const auto [xa, xb] = range(e.originLonDeg + (x + 0.5) * e.lonStepDeg, e.originLonDeg + (x + 1.5) * e.lonStepDeg,
                                wl.originLonDeg, wl.lonStepDeg);
    const auto [ya, yb] = range(e.originLatDeg + (y + 0.5) * e.latStepDeg, e.originLatDeg + (y + 1.5) * e.latStepDeg,
                                wl.originLatDeg, wl.latStepDeg);
    const long W = wl.width, H = wl.height, x0 = (xa % W + W) % W, nx = std::min(xb - xa + 1, W);
    const std::size_t c = std::size_t(wl.channels);
    for (long yy = std::max(ya, 0L); yy <= std::min(yb, H - 1); ++yy) {
      const float* row = wl.values.data() + std::size_t(yy) * W * c;
      for (long k = 0, xx = x0; k < nx; ++k, xx = xx + 1 == W ? 0 : xx + 1)
        if (row[std::size_t(xx) * c] > 0.5f) return true;
    }
    return false;
  };
  std::vector<std::uint8_t> cell(std::size_t(w) * (h + 1), 0);
  for (int y = -1; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c00 = elev(x, y), c10 = elev(x + 1, y), c01 = elev(x, y + 1), c11 = elev(x + 1, y + 1);
      if (std::max({c00, c10, c01, c11}) < 0.0f) continue;  // the bilinear is below 0 m throughout
      if (!wetIn(x, y)) continue;
      // On land throughout (no corner below 0 m): a water texel above 0.5
      // within reach is the mask's water on the relief's land.
      bool hit = std::min({c00, c10, c01, c11}) >= 0.0f;
      for (int j = 0; j < n && !hit; ++j)
        for (int i = 0; i < n && !hit; ++i) {
          const double fx = (i + 0.5) / n, fy = (j + 0.5) / n;
          const double v = (c00 * (1 - fx) + c10 * fx) * (1 - fy) + (c01 * (1 - fx) + c11 * fx) * fy;
          if (v < 0.0) continue;
          const double lat = std::clamp(e.originLatDeg + (y + 0.5 + fy) * e.latStepDeg, -90.0, 90.0);
          hit = world.waterAt(lat, e.originLonDeg + (x + 0.5 + fx) * e.lonStepDeg) > 0.5f;
        }
      cell[std::size_t(y + 1) * w + x] = hit;
    }
  // A texel is 1 when one of the four cells its bilinear reaches is: at any
  // point such a cell holds all four of its texels are 1.
  std::vector<float> out(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int xl = (x + w - 1) % w;
      const std::size_t r0 = std::size_t(y) * w, r1 = std::size_t(y + 1) * w;  // cells y - 1 and y
      out[r0 + x] = float(cell[r0 + xl] | cell[r0 + x] | cell[r1 + xl] | cell[r1 + x]);
    }
  return out;
}

bool waterIndexFollowsTiles(const world::WorldGrids& world, const raster::TilePyramid& water) {
  // A level-k texel is the mean of 2 x 2 texels of level k - 1 (NaN past
  // the raster's edge left out: 4, 2 or 1 of them), so of 4^k mask cells
  // that are 0 or 1 (a global mask's nodata is land): every partial sum is
  // a multiple of 4^-(k-1) up to 4, exact in a float's 24 bits while
  // 2k <= 24, so the mean is 1 only when all of them are water.
  if (world::isStreamedRegional(water.source())) return false;
  const world::WorldLayer& w = world.water();
  for (int level = 0; level < water.levels() && level <= 12; ++level) {
    const raster::GeoTransform t = water.levelTransform(level);
    if (water.levelWidth(level) == w.width && water.levelHeight(level) == w.height &&
        std::abs(t.originLonDeg - w.originLonDeg) < 1e-9 && std::abs(t.originLatDeg - w.originLatDeg) < 1e-9 &&
        std::abs(t.lonStepDeg - w.lonStepDeg) < 1e-12 && std::abs(t.latStepDeg - w.latStepDeg) < 1e-12)
      return true;
  }
  // Or such a level (finer than the grid's step by under 2x) resampled
  // onto the step's grid by world::waterLayerOf: 1 only where every level
  // texel it overlaps is 1.
  const raster::GeoTransform& t0 = water.source().transform();
  const double s = w.lonStepDeg;
  if (!t0.global || s <= 0.0 || w.width != int(std::lround(360.0 / s)) || std::abs(w.width * s - 360.0) > 1e-9 ||
      w.height != int(std::lround(180.0 / s)) || std::abs(w.latStepDeg * w.height + 180.0) > 1e-9 ||
      std::abs(t0.originLonDeg - w.originLonDeg) > 1e-9 || std::abs(t0.originLatDeg - w.originLatDeg) > 1e-9)
    return false;
  for (int level = 0; level < water.levels() && level <= 12; ++level) {
    const double texel = std::abs(water.levelTransform(level).lonStepDeg);
    if (texel <= s * (1.0 + 1e-9) && 2.0 * texel > s) return true;
  }
  return false;
}

ocean::SurfaceClassifier nearWaterClassifier(const world::WorldLayer& water) {
  const int w = water.width, h = water.height;
  const auto wet = [&](int x, int y) {
    return water.values[(std::size_t(y) * w + std::size_t((x + w) % w)) * std::size_t(water.channels)] > 0.0f;
  };
  // Separable dilation by one texel (longitude wraps, latitude clamps).
  std::vector<std::uint8_t> rows(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) rows[std::size_t(y) * w + x] = wet(x - 1, y) || wet(x, y) || wet(x + 1, y);
  auto near = std::make_shared<std::vector<std::uint8_t>>(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      (*near)[std::size_t(y) * w + x] = rows[std::size_t(std::max(y - 1, 0)) * w + x] |
                                        rows[std::size_t(y) * w + x] | rows[std::size_t(std::min(y + 1, h - 1)) * w + x];
  for (const int y : {0, h - 1})  // a pole is one point
    if (std::any_of(near->begin() + std::ptrdiff_t(y) * w, near->begin() + std::ptrdiff_t(y + 1) * w,
                    [](std::uint8_t v) { return v != 0; }))
      std::fill(near->begin() + std::ptrdiff_t(y) * w, near->begin() + std::ptrdiff_t(y + 1) * w, std::uint8_t(1));
  const double ox = water.originLonDeg, oy = water.originLatDeg, sx = water.lonStepDeg, sy = water.latStepDeg;
  return [near, w, h, ox, oy, sx, sy](const double* lat, const double* lon, std::size_t n, ocean::Surface* out) {
    for (std::size_t i = 0; i < n; ++i) {
      const double fx = (lon[i] - ox) / sx, fy = (lat[i] - oy) / sy;
      if (!std::isfinite(fx) || !std::isfinite(fy)) {
        out[i] = ocean::Surface::Land;
        continue;
      }
      const double wx = fx - w * std::floor(fx / w);
      const int x = std::clamp(int(wx), 0, w - 1), y = std::clamp(int(std::floor(fy)), 0, h - 1);
      out[i] = (*near)[std::size_t(y) * w + x] ? ocean::Surface::Ocean : ocean::Surface::Land;
    }
  };
}

bool coversOpaquely(const world::WorldGrids& world, double cellPx, double lat0, double lat1, double lon0, double lon1,
                    double footprintM, bool paged) {
  // Every pixel over the rectangle is drawn opaque, and none of the grid
  // cells over it is skipped as land, if the water layer is water
  // throughout it and a margin around it: the B-spline's 2 texels, the
  // mipmap footprint (up to 3 texels per pixel of footprintM) and, for the
  // grid, two cells (whose corners must be water for a cell to be drawn).
  const world::WaterIndex& wi = world.waterIndex();
  if (wi.width() == 0) return false;
  const double maxAbsLat = std::max(std::abs(lat0), std::abs(lat1));
  const double texelM = std::min(wi.latStepDeg(), wi.lonStepDeg() * std::cos(std::min(maxAbsLat, 89.0) * kDeg)) * kDeg *
                        geo::kWgs84B;
  const double tpp = footprintM / texelM;
  const double margin = 3.0 + ((paged ? 6.0 : 3.0) + 2.0 * cellPx) * tpp;
  if (margin > 256.0) return false;
  return wi.allWaterAround(lat0, lat1, lon0, lon1, margin);
}

}  // namespace geocean::ocean_render
