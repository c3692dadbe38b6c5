#include "globe/world/LayerStack.h"

#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/world/WaterPyramid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

namespace geocean::world {

namespace {

// A layer beyond kMaxStreamedLayers of its kind is drawn from the grid
// below the streamed ones (the query still answers at its cells): say so.
void warnBeyondStreamLimit(const RasterLayer* beyond, const char* kind, double gridStepDeg) {
  if (!beyond) return;
  std::fprintf(stderr,
               "geocean: warning: %s: more than %d %s layers to stream; it and the layers after it are drawn from the "
               "%.4g' %s grid (the query still answers at their cells)\n",
               beyond->raster->path().c_str(), kMaxStreamedLayers, kind, gridStepDeg * 60.0, kind);
}

}  // namespace

const char* toString(LayerKind k) {
  return k == LayerKind::Mask ? "mask" : k == LayerKind::Elevation ? "elevation" : "imagery";
}

double RasterLayer::cellDeg() const {
  const auto& t = raster->transform();
  return std::sqrt(std::abs(t.lonStepDeg * t.latStepDeg));
}

LayerStack::LayerStack(std::vector<RasterLayer> layers) : layers_(std::move(layers)) {
  if (layers_.empty()) throw std::invalid_argument("layer stack: no layers");
  for (std::size_t i = 0; i < layers_.size(); ++i)
    if (!layers_[i].raster)
      throw std::invalid_argument("layer stack: layer " + std::to_string(i) + " (" + toString(layers_[i].kind) +
                                  ") has no raster");
  std::stable_sort(layers_.begin(), layers_.end(), [](const RasterLayer& a, const RasterLayer& b) {
    if (a.priority != b.priority) return a.priority > b.priority;
    return a.cellDeg() < b.cellDeg();
  });
  auto drawing = [&](LayerKind k) -> std::shared_ptr<const raster::Raster> {
    const RasterLayer *only = nullptr, *finestRegional = nullptr, *first = nullptr;
    int count = 0;
    for (const RasterLayer& l : layers_) {
      if (l.kind != k) continue;
      ++count;
      if (!first) first = &l;
      only = &l;
      if (!globalInMemory(*l.raster) && (!finestRegional || l.cellDeg() < finestRegional->cellDeg()))
        finestRegional = &l;
    }
    if (count == 0) return nullptr;
    if (count == 1) return only->raster;
    return (finestRegional ? finestRegional : first)->raster;
  };
  drawingMask_ = drawing(LayerKind::Mask);
  drawingElevation_ = drawing(LayerKind::Elevation);
  double finestMask = INFINITY, finestElevation = INFINITY;
  for (const RasterLayer& l : layers_)
    if (l.kind != LayerKind::Imagery)
      (l.kind == LayerKind::Mask ? finestMask : finestElevation) =
        std::min(l.kind == LayerKind::Mask ? finestMask : finestElevation, l.cellDeg());
  if (drawingMask_ && finestElevation < finestMask) drawingMask_ = nullptr;
}

bool LayerStack::has(LayerKind k) const {
  return std::any_of(layers_.begin(), layers_.end(), [k](const RasterLayer& l) { return l.kind == k; });
}

void LayerStack::classifyBatch(const double* lat, const double* lon, std::size_t n, Surface* out,
                               std::int32_t* answeredBy) const {
  std::vector<std::size_t> pending;
  pending.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = Surface::Land;
    if (answeredBy) answeredBy[i] = -1;
    if (std::isfinite(lat[i]) && std::isfinite(lon[i])) pending.push_back(i);
  }
  std::vector<double> la, lo;
  std::vector<float> v;
  for (std::size_t li = 0; li < layers_.size() && !pending.empty(); ++li) {
    const RasterLayer& l = layers_[li];
    if (l.kind == LayerKind::Imagery) continue;
    la.resize(pending.size());
    lo.resize(pending.size());
    v.resize(pending.size());
    for (std::size_t j = 0; j < pending.size(); ++j) la[j] = lat[pending[j]], lo[j] = lon[pending[j]];
    if (l.kind == LayerKind::Mask)
      l.raster->sampleNearestBatch(la.data(), lo.data(), pending.size(), v.data());
    else
      l.raster->sampleBilinearBatch(la.data(), lo.data(), pending.size(), v.data());
    std::size_t keep = 0;
    for (std::size_t j = 0; j < pending.size(); ++j) {
      const std::size_t i = pending[j];
      if (std::isnan(v[j])) {
        pending[keep++] = i;
        continue;
      }
      out[i] = l.kind == LayerKind::Mask ? l.encoding.classify(v[j]) : (v[j] < 0.0f ? Surface::Ocean : Surface::Land);
      if (answeredBy) answeredBy[i] = std::int32_t(li);
    }
    pending.resize(keep);
  }
}

void LayerStack::elevationBatch(const double* lat, const double* lon, std::size_t n, float* out) const {
  std::vector<std::size_t> pending;
  pending.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = NAN;
    if (std::isfinite(lat[i]) && std::isfinite(lon[i])) pending.push_back(i);
  }
  std::vector<double> la, lo;
  std::vector<float> v;
  for (const RasterLayer& l : layers_) {
    if (pending.empty()) break;
    if (l.kind != LayerKind::Elevation) continue;
    la.resize(pending.size());
    lo.resize(pending.size());
    v.resize(pending.size());
    for (std::size_t j = 0; j < pending.size(); ++j) la[j] = lat[pending[j]], lo[j] = lon[pending[j]];
    l.raster->sampleBilinearBatch(la.data(), lo.data(), pending.size(), v.data());
    std::size_t keep = 0;
    for (std::size_t j = 0; j < pending.size(); ++j) {
      if (std::isnan(v[j])) pending[keep++] = pending[j];
      else out[pending[j]] = v[j];
    }
    pending.resize(keep);
  }
}

WorldLayer elevationLayerOf(const LayerStack& stack) {
  const auto e = stack.drawingElevation();
  WorldLayer l;
  if (e && globalInMemory(*e)) {
    l = layerOf(*e, 0);
  } else if (e) {
    l = globalGridFor(e.get());
    forCellChunks(l, [&](std::size_t first, const double* lat, const double* lon, std::size_t n) {
      stack.elevationBatch(lat, lon, n, l.values.data() + first);
    });
  } else {
    l.width = 360, l.height = 180;
    // No relief: deep water everywhere, as the queries assume.
    l.values.assign(std::size_t(l.width) * l.height, -10000.0f);
  }
  nodataToSeaLevel(l);
  return l;
}

WorldLayer waterLayerOf(const LayerStack& stack) {
  const auto m = stack.drawingMask();
  if (m && globalInMemory(*m)) {
    for (const RasterLayer& layer : stack.layers())
      if (layer.raster == m) return waterLayerOf(*m, layer.encoding);
  }
  const auto grid = m ? m : stack.drawingElevation();
  WorldLayer l = globalGridFor(grid.get());
  std::vector<Surface> cls;
  forCellChunks(l, [&](std::size_t first, const double* lat, const double* lon, std::size_t n) {
    cls.resize(n);
    stack.classifyBatch(lat, lon, n, cls.data());
    for (std::size_t i = 0; i < n; ++i) l.values[first + i] = cls[i] == Surface::Land ? 0.0f : 1.0f;
  });
  return l;
}

LayerStack openLayerStack(const std::vector<LayerSource>& layers, bool defaultWorld, const raster::OpenOptions& options) {
  std::vector<RasterLayer> all;
  // Imagery is read once, into a texture: no regional streaming rule.
  raster::OpenOptions imageryOptions = options;
  imageryOptions.regionalInMemoryLimitBytes = 0;
  for (const LayerSource& l : layers) {
    all.push_back({l.kind, raster::Raster::open(l.path, l.kind == LayerKind::Imagery ? imageryOptions : options),
                   l.encoding.empty() ? MaskEncoding{} : MaskEncoding::parse(l.encoding), l.priority});
    const int c = all.back().raster->channels();
    if (l.kind == LayerKind::Imagery && c != 3 && c != 4)
      throw raster::RasterError(l.path + ": imagery needs 3 (RGB) or 4 (RGBA) channels, the file has " +
                                std::to_string(c));
  }
  if (defaultWorld) {
    const raster::WorldFiles files = raster::defaultWorld();
    all.push_back({LayerKind::Mask, raster::Raster::open(files.mask, options), {}, kDefaultWorldPriority});
    all.push_back({LayerKind::Elevation, raster::Raster::open(files.elevation, options), {}, kDefaultWorldPriority});
  }
  return LayerStack(std::move(all));
}

ImageryLayer imageryLayerOf(std::shared_ptr<const raster::Raster> r, int maxSide) {
  const int c = r->channels();
  if (c != 3 && c != 4)
    throw raster::RasterError(r->path() + ": imagery needs 3 (RGB) or 4 (RGBA) channels, the file has " +
                              std::to_string(c));
  ImageryLayer l;
  l.name = r->path();
  const raster::GeoTransform* t = &r->transform();
  raster::GeoTransform lt;
  std::vector<float> px;
  if (r->inMemory() && std::max(r->width(), r->height()) <= maxSide) {
    l.width = r->width(), l.height = r->height();
    px = r->pixels();
  } else {
    // Too big for one texture or not in memory: a coarse level of its pyramid
    // (built once, then read from the tile cache).
    const auto pyr = raster::TilePyramid::open(r);
    int level = 0;
    while (level + 1 < pyr->levels() && std::max(pyr->levelWidth(level), pyr->levelHeight(level)) > maxSide) ++level;
    lt = pyr->levelTransform(level);
    t = &lt;
    l.width = pyr->levelWidth(level), l.height = pyr->levelHeight(level);
    px.assign(std::size_t(l.width) * l.height * c, NAN);
    const int T = pyr->tileSize();
    for (int ty = 0; ty < pyr->tilesY(level); ++ty)
      for (int tx = 0; tx < pyr->tilesX(level); ++tx) {
        if (pyr->kind({level, tx, ty}) == raster::TileKind::Empty) continue;
        const auto tile = pyr->interior({level, tx, ty});
        for (int y = 0; y < T && ty * T + y < l.height; ++y)
          for (int x = 0; x < T && tx * T + x < l.width; ++x)
            for (int k = 0; k < c; ++k)
              px[(std::size_t(ty * T + y) * l.width + tx * T + x) * c + k] = (*tile)[(std::size_t(y) * T + x) * c + k];
      }
  }
  l.originLonDeg = t->originLonDeg, l.originLatDeg = t->originLatDeg;
  l.lonStepDeg = t->lonStepDeg, l.latStepDeg = t->latStepDeg;
  l.global = r->transform().global;
  l.rgba.resize(std::size_t(l.width) * l.height * 4);
  for (std::size_t i = 0; i < std::size_t(l.width) * l.height; ++i) {
    const float* v = &px[i * c];
    bool valid = true;
    for (int k = 0; k < c; ++k) {
      if (std::isnan(v[k])) {
        valid = false;
        continue;
      }
      if (!(v[k] >= 0.0f && v[k] <= 255.0f))
        throw raster::RasterError(l.name + ": imagery values must be 8-bit (0..255); pixel (" +
                                  std::to_string(i % l.width) + ", " + std::to_string(i / l.width) + ") channel " +
                                  std::to_string(k) + " is " + std::to_string(v[k]));
    }
    // Alpha is the validity: nodata in any channel, or the file's alpha.
    const float a = !valid ? 0.0f : c == 4 ? v[3] / 255.0f : 1.0f;
    for (int k = 0; k < 3; ++k) l.rgba[i * 4 + k] = std::uint8_t(valid ? v[k] * a + 0.5f : 0.0f);
    l.rgba[i * 4 + 3] = std::uint8_t(a * 255.0f + 0.5f);
  }
  return l;
}

WorldData loadLayeredWorld(const std::vector<LayerSource>& layers, bool defaultWorld,
                           const raster::OpenOptions& options) {
  if (layers.empty() && defaultWorld) return loadDefaultWorld();
  const LayerStack stack = openLayerStack(layers, defaultWorld, options);
  std::vector<ImageryLayer> imagery;
  for (const RasterLayer& l : stack.layers())
    if (l.kind == LayerKind::Imagery) imagery.push_back(imageryLayerOf(l.raster));
  if (int(imagery.size()) > kMaxImageryLayers)
    throw std::invalid_argument("--imagery: at most " + std::to_string(kMaxImageryLayers) + " imagery layers are drawn, " +
                                std::to_string(imagery.size()) + " given");
  const bool shapeLayers = std::any_of(layers.begin(), layers.end(),
                                       [](const LayerSource& l) { return l.kind != LayerKind::Imagery; });
  if (!shapeLayers && defaultWorld) {  // only imagery: the default world's grids as without layers
    WorldData d = loadDefaultWorld();
    d.imageryLayers = std::move(imagery);
    return d;
  }
  WorldData d;
  d.imageryLayers = std::move(imagery);
  d.imagery = layerOf(*raster::Raster::open(raster::defaultWorld().imagery));
  const auto e = stack.drawingElevation();
  const double elevationStep = drawingGridStepDeg(e.get());
  const RasterLayer* beyondElevation = nullptr;
  const auto elevationChain = streamedElevationLayers(stack, elevationStep, &beyondElevation);
  warnBeyondStreamLimit(beyondElevation, "elevation", elevationStep);
  for (std::size_t i = 1; i < elevationChain.size(); ++i)
    d.elevationTilesBelow.push_back(raster::TilePyramid::open(elevationChain[i]->raster));
  const RasterLayer* streamedElevation = elevationChain.empty() ? nullptr : elevationChain.back();
  if (streamedElevation && isStreamedRegional(*streamedElevation->raster)) {
    // Regional layers' tiles are drawn over the stack's resampled grid
    // (geo_uv.glsl: outside the layers and at their nodata the grid answers;
    // relief is continuous, and the grid keeps the layers' relief at 5' for
    // the terrain's LOD bounds).
    d.elevationTiles = raster::TilePyramid::open(elevationChain.front()->raster);
    d.elevation = elevationLayerOf(stack);
  } else if (const RasterLayer* l = streamedElevation) {
    // A global last layer: its tiles are drawn; the CPU grid is its
    // pyramid's coarse level (means of its cells), cells without data from
    // the layers below the chain.
    const auto last = raster::TilePyramid::open(l->raster);
    d.elevationTiles = elevationChain.size() == 1 ? last : raster::TilePyramid::open(elevationChain.front()->raster);
    d.elevation = levelLayerOf(*last, elevationStep);
    std::vector<RasterLayer> below;
    for (const RasterLayer& o : stack.layers())
      if (o.kind == LayerKind::Elevation &&
          std::find(elevationChain.begin(), elevationChain.end(), &o) == elevationChain.end())
        below.push_back(o);
    std::vector<std::size_t> holes;
    for (std::size_t i = 0; i < d.elevation.values.size(); ++i)
      if (std::isnan(d.elevation.values[i])) holes.push_back(i);
    if (!below.empty() && !holes.empty()) {
      const LayerStack rest(std::move(below));
      // In chunks: a sparse raster leaves most of the grid to the layers below.
      constexpr std::size_t kChunk = std::size_t(1) << 20;
      std::vector<double> lat, lon;
      std::vector<float> v;
      for (std::size_t k0 = 0; k0 < holes.size(); k0 += kChunk) {
        const std::size_t n = std::min(kChunk, holes.size() - k0);
        lat.resize(n), lon.resize(n), v.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
          const std::size_t i = holes[k0 + k], w = std::size_t(d.elevation.width);
          lat[k] = d.elevation.originLatDeg + (double(i / w) + 0.5) * d.elevation.latStepDeg;
          lon[k] = d.elevation.originLonDeg + (double(i % w) + 0.5) * d.elevation.lonStepDeg;
        }
        rest.elevationBatch(lat.data(), lon.data(), n, v.data());
        for (std::size_t k = 0; k < n; ++k) d.elevation.values[holes[k0 + k]] = v[k];
      }
    }
    nodataToSeaLevel(d.elevation);
  } else {
    d.elevation = elevationLayerOf(stack);
  }
  // The first mask to answer, when it covers the Earth and is finer than the
  // drawn grid (at most 5'), is drawn from its tiles (issue 12 item 2); where
  // a finer elevation layer (drawingMask null) decides the coast, its 0 m
  // line is, the same way (streamedWaterLayer). Its
  // water grid is then the pyramid's coarse level, as the ocean's
  // (plugin/render/OceanWorld): one level's tiles from the disk cache instead
  // of classifying every grid cell through the stack.
  const auto m = stack.drawingMask();
  const double gridStep = m ? drawingGridStepDeg(m.get()) : globalGridFor(stack.drawingElevation().get()).lonStepDeg;
  const RasterLayer* beyond = nullptr;
  const auto chain = streamedWaterLayers(stack, gridStep, &beyond);
  warnBeyondStreamLimit(beyond, "water", gridStep);
  if (!chain.empty()) {
    const RasterLayer* l = chain.front();
    d.waterSource = l->raster;
    d.waterFromRelief = l->kind == LayerKind::Elevation;
    d.waterEncoding = l->encoding;
    for (std::size_t i = 1; i < chain.size(); ++i) {
      d.waterSourcesBelow.push_back(chain[i]->raster);
      d.waterEncodingsBelow.push_back(chain[i]->encoding);
      d.waterFromReliefBelow.push_back(chain[i]->kind == LayerKind::Elevation);
    }
    // A regional mask (or relief) is drawn over the grid of the layers below it.
    d.water = waterGridBelow(stack, chain, gridStep);
  } else {
    d.water = waterLayerOf(stack);
  }
  return d;
}

}  // namespace geocean::world
