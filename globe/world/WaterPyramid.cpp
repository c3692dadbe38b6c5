#include "globe/world/WaterPyramid.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

namespace geocean::world {

std::shared_ptr<const raster::TilePyramid> waterPyramid(std::shared_ptr<const raster::Raster> mask,
                                                        const MaskEncoding& encoding, raster::PyramidOptions options) {
  // The map's id names the encoding's classes: another encoding, another cache.
  std::string classes;
  for (const Surface s : encoding.classOf) classes += char('0' + int(s));
  // A regional mask keeps its nodata (NaN): there the layers below answer,
  // and the drawing falls through to the water grid (geo_uv.glsl).
  const bool keepNodata = !mask->transform().global;
  options.valueMapId = (keepNodata ? "water-coverage-regional:" : "water-coverage:") + classes;
  options.valueMap = [encoding, keepNodata](float* v, std::size_t n, int channels) {
    for (std::size_t i = 0; i < n; ++i) {
      const float x = v[i * channels];
      const float w = keepNodata && std::isnan(x) ? NAN : encoding.isWater(x) ? 1.0f : 0.0f;
      for (int c = 0; c < channels; ++c) v[i * channels + c] = w;
    }
  };
  return raster::TilePyramid::open(std::move(mask), std::move(options));
}

namespace {
// The first layer of `kind` when it is north up and finer than the drawn
// grid; else none. Global: pole to pole and wrapping; regional: any other
// extent (not across the antimeridian), drawn over the grid, which answers
// outside it and where it has no data (isStreamedRegional).
const RasterLayer* firstIfStreamed(const LayerStack& stack, LayerKind kind, double gridLonStepDeg) {
  for (const RasterLayer& l : stack.layers()) {
    if (l.kind != kind) continue;
    const raster::GeoTransform& t = l.raster->transform();
    const bool global = t.global && t.latStepDeg < 0 && std::abs(t.latStepDeg * l.raster->height() + 180.0) < 1e-6;
    const bool regional = !t.global && t.latStepDeg < 0 && t.lonStepDeg > 0;
    return (global || regional) && t.lonStepDeg < 0.999 * gridLonStepDeg ? &l : nullptr;
  }
  return nullptr;
}
}  // namespace

bool isStreamedRegional(const raster::Raster& r) { return !r.transform().global; }

namespace {
// The stack without `streamed` (null when nothing is left).
std::unique_ptr<LayerStack> without(const LayerStack& stack, const raster::Raster& streamed) {
  std::vector<RasterLayer> rest;
  for (const RasterLayer& l : stack.layers())
    if (l.raster.get() != &streamed) rest.push_back(l);
  return rest.empty() ? nullptr : std::make_unique<LayerStack>(std::move(rest));
}
}  // namespace

WorldLayer waterLayerBelow(const LayerStack& stack, const raster::Raster& streamed) {
  const auto rest = without(stack, streamed);
  if (rest && (rest->has(LayerKind::Mask) || rest->has(LayerKind::Elevation))) return waterLayerOf(*rest);
  WorldLayer l = globalGridFor(nullptr);
  std::fill(l.values.begin(), l.values.end(), 0.0f);  // no layer answers: land, as classifyBatch
  return l;
}

const RasterLayer* streamedMaskLayer(const LayerStack& stack, double gridLonStepDeg) {
  return stack.drawingMask() ? firstIfStreamed(stack, LayerKind::Mask, gridLonStepDeg) : nullptr;
}

const RasterLayer* streamedElevationLayer(const LayerStack& stack, double gridLonStepDeg) {
  return firstIfStreamed(stack, LayerKind::Elevation, gridLonStepDeg);
}

WorldLayer waterLayerOf(const raster::TilePyramid& water, double stepDeg) {
  WorldLayer l = levelLayerOf(water, stepDeg);
  for (float& v : l.values)
    if (std::isnan(v)) v = 0.0f;
  return l;
}

WorldLayer regionalWaterCover(const raster::TilePyramid& water, std::size_t maxTexels) {
  int level = 0;
  while (level + 1 < water.levels() &&
         std::size_t(water.levelWidth(level)) * std::size_t(water.levelHeight(level)) > maxTexels)
    ++level;
  const double step = std::abs(water.levelTransform(level).lonStepDeg);
  WorldLayer l = levelLayerOf(water, step);
  for (float& v : l.values)
    if (std::isnan(v)) v = 1.0f;
  return l;
}

WorldLayer levelLayerOf(const raster::TilePyramid& water, double stepDeg) {
  const raster::GeoTransform& t = water.source().transform();
  int level = 0;
  while (level + 1 < water.levels() && std::abs(t.lonStepDeg) * double(2 << level) <= stepDeg * (1.0 + 1e-9)) ++level;
  while (level + 1 < water.levels() && water.levelWidth(level) > 16384) ++level;
  const raster::GeoTransform lt = water.levelTransform(level);
  WorldLayer l;
  l.width = water.levelWidth(level), l.height = water.levelHeight(level);
  l.originLonDeg = lt.originLonDeg, l.originLatDeg = lt.originLatDeg;
  l.lonStepDeg = lt.lonStepDeg, l.latStepDeg = lt.latStepDeg;
  l.values.assign(std::size_t(l.width) * l.height, NAN);
  const int T = water.tileSize(), c = water.channels();
  for (int ty = 0; ty < water.tilesY(level); ++ty)
    for (int tx = 0; tx < water.tilesX(level); ++tx) {
      const auto tile = water.interior({level, tx, ty});
      for (int y = 0; y < T && ty * T + y < l.height; ++y)
        for (int x = 0; x < T && tx * T + x < l.width; ++x) {
          const float v = (*tile)[(std::size_t(y) * T + x) * c];
          l.values[std::size_t(ty * T + y) * l.width + tx * T + x] = v;
        }
    }
  return l;
}

}  // namespace geocean::world
