#include "globe/world/LayerStack.h"

#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/world/WaterPyramid.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace geocean::world {

namespace {

bool globalInMemory(const raster::Raster& r) {
  const auto& t = r.transform();
  return r.inMemory() && t.global && t.latStepDeg < 0 && std::abs(t.latStepDeg * r.height() + 180.0) < 1e-6;
}


}  // namespace

const char* toString(LayerKind k) { return k == LayerKind::Mask ? "mask" : "elevation"; }

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
    std::vector<double> lat, lon;
    cellCentres(l, lat, lon);
    stack.elevationBatch(lat.data(), lon.data(), lat.size(), l.values.data());
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
  std::vector<double> lat, lon;
  cellCentres(l, lat, lon);
  std::vector<Surface> cls(lat.size());
  stack.classifyBatch(lat.data(), lon.data(), lat.size(), cls.data());
  for (std::size_t i = 0; i < cls.size(); ++i) l.values[i] = cls[i] == Surface::Land ? 0.0f : 1.0f;
  return l;
}

LayerStack openLayerStack(const std::vector<LayerSource>& layers, bool defaultWorld, const raster::OpenOptions& options) {
  std::vector<RasterLayer> all;
  for (const LayerSource& l : layers)
    all.push_back({l.kind, raster::Raster::open(l.path, options),
                   l.encoding.empty() ? MaskEncoding{} : MaskEncoding::parse(l.encoding), l.priority});
  if (defaultWorld) {
    const raster::WorldFiles files = raster::defaultWorld();
    all.push_back({LayerKind::Mask, raster::Raster::open(files.mask, options), {}, kDefaultWorldPriority});
    all.push_back({LayerKind::Elevation, raster::Raster::open(files.elevation, options), {}, kDefaultWorldPriority});
  }
  return LayerStack(std::move(all));
}

WorldData loadLayeredWorld(const std::vector<LayerSource>& layers, bool defaultWorld,
                           const raster::OpenOptions& options) {
  if (layers.empty() && defaultWorld) return loadDefaultWorld();
  const LayerStack stack = openLayerStack(layers, defaultWorld, options);
  WorldData d;
  d.imagery = layerOf(*raster::Raster::open(raster::defaultWorld().imagery));
  d.elevation = elevationLayerOf(stack);
  d.water = waterLayerOf(stack);
  // The first mask to answer, when it covers the Earth and is finer than the
  // drawn grid (at most 5'), is drawn from its tiles (issue 12 item 2); a
  // finer elevation layer (drawingMask null) decides the coast instead.
  if (const RasterLayer* l = streamedMaskLayer(stack, d.water.lonStepDeg)) {
    d.waterSource = l->raster;
    d.waterEncoding = l->encoding;
  }
  return d;
}

}  // namespace geocean::world
