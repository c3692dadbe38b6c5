#include "globe/world/WaterPyramid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

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
  // MaskEncoding::isWater as a table (the build maps every texel of the
  // mask: a call and lround each were a third of a 30" mask's build):
  // x in [0, 255] rounds half away from zero as lround, exactly in double.
  std::array<float, 256> water{};
  for (std::size_t k = 0; k < water.size(); ++k) water[k] = encoding.classOf[k] != Surface::Land ? 1.0f : 0.0f;
  options.valueMap = [water, keepNodata](float* v, std::size_t n, int channels) {
    for (std::size_t i = 0; i < n; ++i) {
      const float x = v[i * channels];
      const float w = x >= 0.0f && x <= 255.0f ? water[std::size_t(double(x) + 0.5)]
                      : keepNodata && std::isnan(x) ? NAN
                                                    : 0.0f;  // NaN, negative, > 255: land (MaskEncoding::classify)
      for (int c = 0; c < channels; ++c) v[i * channels + c] = w;
    }
  };
  return raster::TilePyramid::open(std::move(mask), std::move(options));
}

std::shared_ptr<const raster::TilePyramid> reliefWaterPyramid(std::shared_ptr<const raster::Raster> relief,
                                                              raster::PyramidOptions options) {
  const bool keepNodata = !relief->transform().global;
  options.valueMapId = keepNodata ? "water-from-relief-regional" : "water-from-relief";
  options.valueMap = [keepNodata](float* v, std::size_t n, int channels) {
    for (std::size_t i = 0; i < n; ++i) {
      const float x = v[i * channels];
      // NaN < 0 is false: a global relief's nodata would be land (not streamed: streamedWaterLayer).
      const float w = keepNodata && std::isnan(x) ? NAN : x < 0.0f ? 1.0f : 0.0f;
      for (int c = 0; c < channels; ++c) v[i * channels + c] = w;
    }
  };
  return raster::TilePyramid::open(std::move(relief), std::move(options));
}

std::shared_ptr<const raster::TilePyramid> waterPyramid(const RasterLayer& layer, raster::PyramidOptions options) {
  return layer.kind == LayerKind::Elevation ? reliefWaterPyramid(layer.raster, std::move(options))
                                            : waterPyramid(layer.raster, layer.encoding, std::move(options));
}

namespace {
// The first layer of `kind` when it is north up and finer than the drawn
// grid; else none. Global: pole to pole and wrapping; regional: any other
// extent (across the antimeridian too: raster::lonNear), drawn over the grid, which answers
// outside it and where it has no data (isStreamedRegional).
bool streams(const RasterLayer& l, double gridLonStepDeg) {
  const raster::GeoTransform& t = l.raster->transform();
  const bool global = l.raster->wholeGlobeNorthUp();
  const bool regional = !t.global && t.latStepDeg < 0 && t.lonStepDeg > 0;
  return (global || regional) && t.lonStepDeg < 0.999 * gridLonStepDeg;
}

const RasterLayer* firstIfStreamed(const LayerStack& stack, LayerKind kind, double gridLonStepDeg) {
  for (const RasterLayer& l : stack.layers()) {
    if (l.kind != kind) continue;
    return streams(l, gridLonStepDeg) ? &l : nullptr;
  }
  return nullptr;
}
}  // namespace

bool isStreamedRegional(const raster::Raster& r) { return !r.transform().global; }

namespace {
// The stack without `streamed` (null when nothing is left).
std::unique_ptr<LayerStack> without(const LayerStack& stack, const std::vector<const raster::Raster*>& streamed) {
  std::vector<RasterLayer> rest;
  for (const RasterLayer& l : stack.layers())
    if (std::find(streamed.begin(), streamed.end(), l.raster.get()) == streamed.end()) rest.push_back(l);
  return rest.empty() ? nullptr : std::make_unique<LayerStack>(std::move(rest));
}
}  // namespace

WorldLayer waterLayerBelow(const LayerStack& stack, const raster::Raster& streamed) {
  return waterLayerBelow(stack, std::vector<const raster::Raster*>{&streamed});
}

WorldLayer waterLayerBelow(const LayerStack& stack, const std::vector<const raster::Raster*>& streamed) {
  const auto rest = without(stack, streamed);
  if (rest && (rest->has(LayerKind::Mask) || rest->has(LayerKind::Elevation))) return waterLayerOf(*rest);
  WorldLayer l = globalGridFor(nullptr);
  std::fill(l.values.begin(), l.values.end(), 0.0f);  // no layer answers: land, as classifyBatch
  return l;
}

const RasterLayer* streamedMaskLayer(const LayerStack& stack, double gridLonStepDeg) {
  return stack.drawingMask() ? firstIfStreamed(stack, LayerKind::Mask, gridLonStepDeg) : nullptr;
}

const RasterLayer* streamedWaterLayer(const LayerStack& stack, double gridLonStepDeg) {
  if (stack.drawingMask()) return streamedMaskLayer(stack, gridLonStepDeg);
  const RasterLayer* l = firstIfStreamed(stack, LayerKind::Elevation, gridLonStepDeg);
  if (!l || (l->raster->transform().global && l->raster->nodata())) return nullptr;
  for (const RasterLayer& o : stack.layers())  // it must answer first where it has data
    if (o.kind != LayerKind::Imagery) return &o == l ? l : nullptr;
  return nullptr;
}

namespace {
// The layers answering after `first` in the stack's order that stream too,
// up to kMaxStreamedLayers: a layer of a kind `takes` does not answer for
// is passed over; the chain ends at the first layer that cannot stream
// (`streamsHere`), or after a layer covering the Earth (nothing answers
// below it where it has data).
template <class Takes, class StreamsHere>
std::vector<const RasterLayer*> chainFrom(const LayerStack& stack, const RasterLayer* first,
                                          const RasterLayer** beyondLimit, Takes takes, StreamsHere streamsHere) {
  if (beyondLimit) *beyondLimit = nullptr;
  std::vector<const RasterLayer*> chain;
  if (!first) return chain;
  chain.push_back(first);
  bool after = false;
  for (const RasterLayer& l : stack.layers()) {
    if (&l == first) {
      after = true;
      continue;
    }
    if (!after || !takes(l)) continue;
    if (!isStreamedRegional(*chain.back()->raster) || !streamsHere(l)) break;
    if (int(chain.size()) == kMaxStreamedLayers) {
      if (beyondLimit) *beyondLimit = &l;
      break;
    }
    chain.push_back(&l);
  }
  return chain;
}
}  // namespace

std::vector<const RasterLayer*> streamedWaterLayers(const LayerStack& stack, double gridLonStepDeg,
                                                    const RasterLayer** beyondLimit) {
  return chainFrom(
      stack, streamedWaterLayer(stack, gridLonStepDeg), beyondLimit,
      [](const RasterLayer& l) { return l.kind != LayerKind::Imagery; },
      [&](const RasterLayer& l) {
        // A relief answers by sign where it has data (reliefWaterPyramid), a
        // mask by its encoding: either streams. A global relief with nodata
        // does not (its pyramid makes nodata land: streamedWaterLayer's rule).
        return streams(l, gridLonStepDeg) &&
               !(l.kind == LayerKind::Elevation && !isStreamedRegional(*l.raster) && l.raster->nodata());
      });
}

WorldLayer waterGridBelow(const LayerStack& stack, const std::vector<const RasterLayer*>& chain, double gridLonStepDeg) {
  if (chain.empty()) return waterLayerOf(stack);
  if (!isStreamedRegional(*chain.back()->raster)) return waterLayerOf(*waterPyramid(*chain.back()), gridLonStepDeg);
  std::vector<const raster::Raster*> streamed;
  for (const RasterLayer* l : chain) streamed.push_back(l->raster.get());
  return waterLayerBelow(stack, streamed);
}

const RasterLayer* streamedElevationLayer(const LayerStack& stack, double gridLonStepDeg) {
  return firstIfStreamed(stack, LayerKind::Elevation, gridLonStepDeg);
}

std::vector<const RasterLayer*> streamedElevationLayers(const LayerStack& stack, double gridLonStepDeg,
                                                        const RasterLayer** beyondLimit) {
  return chainFrom(
      stack, streamedElevationLayer(stack, gridLonStepDeg), beyondLimit,
      [](const RasterLayer& l) { return l.kind == LayerKind::Elevation; },  // masks and imagery have no elevation
      [&](const RasterLayer& l) { return streams(l, gridLonStepDeg); });
}

namespace {
int levelFor(const raster::TilePyramid& p, double stepDeg) {
  const raster::GeoTransform& t = p.source().transform();
  int level = 0;
  while (level + 1 < p.levels() && std::abs(t.lonStepDeg) * double(2 << level) <= stepDeg * (1.0 + 1e-9)) ++level;
  while (level + 1 < p.levels() && p.levelWidth(level) > 16384) ++level;
  return level;
}

// One level's rows, a band of tile rows at a time (the last two kept: the
// rows are asked for in order), NaN as 0.
class LevelRows {
 public:
  LevelRows(const raster::TilePyramid& p, int level) : p_(p), level_(level), w_(p.levelWidth(level)) {}
  const float* row(int y) {
    const int T = p_.tileSize(), ty = y / T;
    for (Band& b : bands_)
      if (b.ty == ty) return &b.v[std::size_t(y - ty * T) * w_];
    Band& b = bands_[next_];
    next_ ^= 1;
    b.ty = ty;
    b.v.assign(std::size_t(T) * w_, 0.0f);
    const int c = p_.channels();
    for (int tx = 0; tx < p_.tilesX(level_); ++tx) {
      const auto tile = p_.interior({level_, tx, ty});
      for (int yy = 0; yy < T; ++yy)
        for (int x = 0; x < T && tx * T + x < w_; ++x) {
          const float v = (*tile)[(std::size_t(yy) * T + x) * c];
          b.v[std::size_t(yy) * w_ + tx * T + x] = std::isnan(v) ? 0.0f : v;
        }
    }
    return &b.v[std::size_t(y - ty * T) * w_];
  }

 private:
  struct Band {
    int ty = -1;
    std::vector<float> v;
  };
  const raster::TilePyramid& p_;
  int level_, w_;
  Band bands_[2];
  int next_ = 0;
};
}  // namespace

namespace {
// The grid kept in the pyramid's cache (TilePyramid::derived): the app's
// world and the ocean plugin's each built it from the level's tiles at
// start (~0.1 s of loop and the tiles' decoding each, a 30" mask's 5'
// grid). Stored as a header, a byte a texel (0: 0.0f, 1: 1.0f, 2: the next
// of the other values, kept as their bits) and those values: the grid's
// bits exactly, 9.3 M texels in ~1 MB deflated.
constexpr std::uint32_t kGridFormat = 1;
struct GridHeader {
  std::uint32_t format, width, height, channels;
  double originLonDeg, originLatDeg, lonStepDeg, latStepDeg;
  std::uint64_t others;
};

std::string gridName(double stepDeg) {
  std::uint64_t bits;
  std::memcpy(&bits, &stepDeg, 8);
  char b[64];
  std::snprintf(b, sizeof b, "water-grid-%016llx", static_cast<unsigned long long>(bits));
  return b;
}

std::optional<WorldLayer> storedGrid(const raster::TilePyramid& water, double stepDeg) {
  const auto bytes = water.derived(gridName(stepDeg));
  if (!bytes || bytes->size() < sizeof(GridHeader)) return std::nullopt;
  GridHeader h;
  std::memcpy(&h, bytes->data(), sizeof h);
  const std::uint64_t n = std::uint64_t(h.width) * h.height * h.channels;
  if (h.format != kGridFormat || h.channels != 1 || n == 0 || n > (std::uint64_t(1) << 32) || h.others > n ||
      bytes->size() != sizeof h + n + h.others * 4)
    return std::nullopt;
  WorldLayer l;
  l.width = int(h.width), l.height = int(h.height), l.channels = int(h.channels);
  l.originLonDeg = h.originLonDeg, l.originLatDeg = h.originLatDeg;
  l.lonStepDeg = h.lonStepDeg, l.latStepDeg = h.latStepDeg;
  l.values.resize(n);
  const unsigned char* cls = bytes->data() + sizeof h;
  const unsigned char* other = cls + n;
  std::uint64_t used = 0;
  for (std::uint64_t i = 0; i < n; ++i) {
    if (cls[i] < 2) {
      l.values[i] = float(cls[i]);
    } else {
      if (cls[i] != 2 || used == h.others) return std::nullopt;
      std::memcpy(&l.values[i], other + 4 * used++, 4);
    }
  }
  if (used != h.others) return std::nullopt;
  return l;
}

void storeGrid(const raster::TilePyramid& water, double stepDeg, const WorldLayer& l) {
  if (water.stats().cachePath.empty() || l.channels != 1) return;
  const std::size_t n = l.values.size();
  std::vector<unsigned char> bytes(sizeof(GridHeader) + n);
  const float zero = 0.0f, one = 1.0f;
  std::uint32_t zeroBits, oneBits;
  std::memcpy(&zeroBits, &zero, 4), std::memcpy(&oneBits, &one, 4);
  std::uint64_t others = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t b;
    std::memcpy(&b, &l.values[i], 4);
    unsigned char c = b == zeroBits ? 0 : b == oneBits ? 1 : 2;
    bytes[sizeof(GridHeader) + i] = c;
    if (c == 2) {
      bytes.resize(bytes.size() + 4);
      std::memcpy(bytes.data() + bytes.size() - 4, &b, 4);
      ++others;
    }
  }
  const GridHeader h{kGridFormat, std::uint32_t(l.width), std::uint32_t(l.height), std::uint32_t(l.channels),
                     l.originLonDeg, l.originLatDeg, l.lonStepDeg, l.latStepDeg, others};
  std::memcpy(bytes.data(), &h, sizeof h);
  water.storeDerived(gridName(stepDeg), bytes.data(), bytes.size());
}

// The grid resampled from the level's tiles (what storeGrid keeps).
WorldLayer computeWaterLayerOf(const raster::TilePyramid& water, double stepDeg) {
  const int level = levelFor(water, stepDeg);
  const raster::GeoTransform lt = water.levelTransform(level);
  const bool fullGlobe = water.source().wholeGlobeNorthUp();
  const int W = int(std::lround(360.0 / stepDeg)), H = int(std::lround(180.0 / stepDeg));
  // The level is the grid (its texel is the step) or not global: the level itself.
  if (!fullGlobe || std::abs(lt.lonStepDeg) * (1.0 + 1e-9) >= 360.0 / W || W < 1 || H < 1) {
    WorldLayer l = levelLayerOf(water, stepDeg);
    for (float& v : l.values)
      if (std::isnan(v)) v = 0.0f;
    return l;
  }
  // A level finer than the step (by less than 2x): resampled onto the
  // step's own grid, so the grid's size is the step's whatever the
  // raster's (peak memory independent of the raster's size). A texel is 1
  // exactly when every level texel it overlaps is (so every mask cell under
  // it is water: the open-water index stays exact, waterIndexFollowsTiles),
  // above 0 when any is above 0 (nearWaterClassifier's "any water"), else
  // the overlap-weighted mean.
  WorldLayer l;
  l.width = W, l.height = H;
  l.originLonDeg = lt.originLonDeg, l.originLatDeg = lt.originLatDeg;
  l.lonStepDeg = 360.0 / W, l.latStepDeg = -180.0 / H;
  l.values.assign(std::size_t(W) * H, 0.0f);
  const int LW = water.levelWidth(level), LH = water.levelHeight(level);
  const double rx = l.lonStepDeg / std::abs(lt.lonStepDeg), ry = -l.latStepDeg / std::abs(lt.latStepDeg);
  if (rx >= 2.0 || ry >= 2.0) {  // the pyramid's top is finer than half the step: that level
    WorldLayer top = levelLayerOf(water, stepDeg);
    for (float& v : top.values)
      if (std::isnan(v)) v = 0.0f;
    return top;
  }
  // Level texels [first, last] under [a, b) with their overlaps (none below 1e-9 of a texel).
  struct Span {
    int first, last;
    double w[4];
  };
  const auto span = [](double a, double b) {
    Span s;
    s.first = int(std::floor(a + 1e-9));
    s.last = std::max(s.first, int(std::ceil(b - 1e-9)) - 1);
    for (int i = s.first; i <= s.last && i - s.first < 4; ++i)
      s.w[i - s.first] = std::min(b, double(i + 1)) - std::max(a, double(i));
    return s;
  };
  std::vector<Span> cols(W);
  for (int x = 0; x < W; ++x) cols[std::size_t(x)] = span(x * rx, (x + 1) * rx);
  LevelRows rows(water, level);
  std::vector<double> sum(W), wsum(W);
  std::vector<std::uint8_t> all(W);
  for (int y = 0; y < H; ++y) {
    const Span r = span(y * ry, (y + 1) * ry);
    std::fill(sum.begin(), sum.end(), 0.0), std::fill(wsum.begin(), wsum.end(), 0.0);
    std::fill(all.begin(), all.end(), std::uint8_t(1));
    for (int j = r.first; j <= r.last; ++j) {
      const float* row = rows.row(std::min(j, LH - 1));
      const double wy = r.w[j - r.first];
      for (int x = 0; x < W; ++x) {
        const Span& c = cols[std::size_t(x)];
        for (int i = c.first; i <= c.last; ++i) {
          const float v = row[std::min(i, LW - 1)];
          const double w = wy * c.w[i - c.first];
          sum[std::size_t(x)] += w * v, wsum[std::size_t(x)] += w;
          all[std::size_t(x)] &= v == 1.0f;
        }
      }
    }
    float* out = &l.values[std::size_t(y) * W];
    for (int x = 0; x < W; ++x)
      out[x] = all[std::size_t(x)] ? 1.0f
                                   : std::min(float(sum[std::size_t(x)] / wsum[std::size_t(x)]), std::nextafter(1.0f, 0.0f));
  }
  return l;
}
}  // namespace

WorldLayer waterLayerOf(const raster::TilePyramid& water, double stepDeg) {
  if (auto l = storedGrid(water, stepDeg)) return std::move(*l);
  WorldLayer l = computeWaterLayerOf(water, stepDeg);
  storeGrid(water, stepDeg, l);
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
  const int level = levelFor(water, stepDeg);
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
