#include "plugin/landsea/LandSea.h"

#include <cmath>
#include <immintrin.h>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geocean::ocean {

LandSea::LandSea(std::shared_ptr<const raster::Raster> mask, std::shared_ptr<const raster::Raster> elevation,
                 MaskEncoding encoding)
    : mask_(std::move(mask)), elevation_(std::move(elevation)), encoding_(encoding) {
  if (!mask_ && !elevation_) throw std::invalid_argument("land/sea needs a mask raster, an elevation raster, or both");
  if (mask_ && mask_->inMemory()) {
    const auto& px = mask_->pixels();
    const int c = mask_->channels();
    classes_.resize(std::size_t(mask_->width()) * mask_->height());
    for (std::size_t i = 0; i < classes_.size(); ++i) {
      const float v = px[i * c];
      // Integral mask values (the usual case) index the table directly.
      const bool integral = v >= 0.0f && v <= 255.0f && v == static_cast<float>(static_cast<int>(v));
      classes_[i] = static_cast<std::uint8_t>(integral ? encoding_.classOf[static_cast<std::size_t>(v)] : classOfValue(v));
    }
    const auto& t = mask_->transform();
    markCoast(t.global);
    // Three bytes past the last cell: the AVX-512 lookup gathers 4 bytes per cell.
    classes_.resize(classes_.size() + 3, std::uint8_t(Surface::Land));
    fast_.invLonStep = 1.0 / t.lonStepDeg;
    fast_.invLatStep = 1.0 / t.latStepDeg;
    fast_.originLon = t.originLonDeg;
    fast_.originLat = t.originLatDeg;
    fast_.centreLon = t.originLonDeg + 0.5 * mask_->width() * t.lonStepDeg;
    fast_.width = mask_->width();
    fast_.height = mask_->height();
    fast_.global = t.global;
  }
}

Surface LandSea::classOfValue(float v) const { return encoding_.classify(v); }

void LandSea::markCoast(bool global) {
  // kCoast on cells with another class within one cell (3 x 3). Elsewhere
  // the nearest cell's class is the coverage rule's: a point's B-spline
  // support reaches at most two cells from its cell, and the cells two away
  // weigh at most (1/2)^3/6 = 0.021 a side, 0.041 in all, so a uniform 3 x 3
  // keeps the coverage below 0.05 or above 0.95 and its class the heaviest.
  // Separable: rows, then columns; longitude wraps when global.
  const int w = mask_->width(), h = mask_->height();
  auto bit = [&](std::size_t i) -> std::uint8_t { return std::uint8_t(1u << (classes_[i] & 7u)); };
  std::vector<std::uint8_t> rows(classes_.size());
  for (int y = 0; y < h; ++y) {
    const std::size_t row = std::size_t(y) * w;
    for (int x = 0; x < w; ++x) {
      const int l = global ? (x == 0 ? w - 1 : x - 1) : std::max(x - 1, 0);
      const int r = global ? (x == w - 1 ? 0 : x + 1) : std::min(x + 1, w - 1);
      rows[row + x] = bit(row + l) | bit(row + x) | bit(row + r);
    }
  }
  for (int y = 0; y < h; ++y) {
    std::uint8_t* dst = classes_.data() + std::size_t(y) * w;
    const std::uint8_t* up = rows.data() + std::size_t(std::max(y - 1, 0)) * w;
    const std::uint8_t* mid = rows.data() + std::size_t(y) * w;
    const std::uint8_t* down = rows.data() + std::size_t(std::min(y + 1, h - 1)) * w;
    for (int x = 0; x < w; ++x) {
      const unsigned any = up[x] | mid[x] | down[x];
      if (any & (any - 1)) dst[x] |= kCoast;  // more than one class
    }
  }
}

namespace {
// The 4 x 4 cells whose B-spline covers a point of raster r, read in one
// batch (the reader sorts them by tile). Cells beyond a regional raster's
// edge repeat the edge (a texture's clamp to edge), or with
// `outsideIsNodata` have no data (NaN) at their own centres (as a regional
// layer's pages are drawn: past the edge the layers below answer); longitude
// wraps for a global one; latitude clamps.
struct Cells16 {
  double px, py;  // continuous pixel coordinates of the point
  world::BSplineTaps tx, ty;
  float v[16];
  double la[16], lo[16];  // the cells' centres
  float at(int cx, int cy) const { return v[(cy - ty.first) * 4 + (cx - tx.first)]; }
};
Cells16 gatherCells(const raster::Raster& r, double latDeg, double lonDeg, bool outsideIsNodata = false) {
  const auto& t = r.transform();
  const int w = r.width(), h = r.height();
  double px = t.pixelX(lonDeg);
  if (t.global) px -= std::floor(px / w) * w;
  const double py = t.pixelY(latDeg);
  Cells16 c{px, py, world::BSplineTaps(px), world::BSplineTaps(py), {}, {}, {}};
  double* la = c.la;
  double* lo = c.lo;
  bool outside[16] = {};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int k = j * 4 + i;
      int cx = c.tx.first + i, cy = c.ty.first + j;
      if (!t.global && outsideIsNodata && (cx < 0 || cx >= w || cy < 0 || cy >= h)) {
        outside[k] = true;
        la[k] = t.latOf(cy + 0.5), lo[k] = t.lonOf(cx + 0.5);
        continue;
      }
      cx = t.global ? ((cx % w) + w) % w : std::clamp(cx, 0, w - 1);
      cy = std::clamp(cy, 0, h - 1);
      la[k] = t.latOf(cy + 0.5), lo[k] = t.lonOf(cx + 0.5);
    }
  r.sampleNearestBatch(la, lo, 16, c.v);
  for (int k = 0; k < 16; ++k)
    if (outside[k]) c.v[k] = std::numeric_limits<float>::quiet_NaN();
  return c;
}
}  // namespace

world::CoverageClass LandSea::coverageClass(double latDeg, double lonDeg) const {
  const int w = mask_->width(), h = mask_->height();
  if (!classes_.empty()) {
    // The hot path (every point near a coast). Once x is wrapped into
    // [0, w] the taps' columns lie in [-2, w + 2], so one add or subtract
    // wraps them when w >= 3; a mask 1 or 2 cells wide needs the modulo (a
    // texture's GL_REPEAT, as the slow path below), taken only off [0, w).
    double px = fast_.pixelX(lonDeg);
    if (fast_.global) px -= std::floor(px / w) * w;
    const double py = (latDeg - fast_.originLat) * fast_.invLatStep;
    const std::uint8_t* cls = classes_.data();
    const bool global = fast_.global;
    const auto wrap = [w, global](int cx) {
      if (unsigned(cx) < unsigned(w)) return cx;
      return w >= 3 ? (cx < 0 ? cx + w : cx - w) : ((cx % w) + w) % w;
    };
    const auto classAt = [cls, w, h, global, &wrap](int cx, int cy) {
      cx = global ? wrap(cx) : std::clamp(cx, 0, w - 1);
      cy = std::clamp(cy, 0, h - 1);
      return static_cast<Surface>(cls[std::size_t(cy) * std::size_t(w) + std::size_t(cx)] & kClassBits);
    };
    if (below_ && (!global || !noData_.empty())) {
      // Taps past a regional mask's edge or on cells without data take the
      // layers below (a global mask's rows clamp at the poles).
      const auto hasData = [&](int cx, int cy) {
        if (!global && (cx < 0 || cx >= w || cy < 0 || cy >= h)) return false;
        if (noData_.empty()) return true;
        cx = global ? wrap(cx) : cx;
        cy = std::clamp(cy, 0, h - 1);
        return !noData_[std::size_t(cy) * std::size_t(w) + std::size_t(cx)];
      };
      const world::BSplineTaps tx(px), ty(py);
      bool all = true;
      for (int j = 0; j < 4 && all; ++j)
        for (int i = 0; i < 4 && all; ++i) all = hasData(tx.first + i, ty.first + j);
      if (!all) return blendBelow(mask_->transform(), px, py, classAt, hasData);
    }
    return world::coverageClassAt(px, py, classAt);
  }
  // A cached mask: its 16 cells in one batch (with layers below, NaN past a
  // regional edge).
  const Cells16 c = gatherCells(*mask_, latDeg, lonDeg, /*outsideIsNodata=*/bool(below_));
  const auto classAt = [&](int cx, int cy) { return classOfValue(c.at(cx, cy)); };
  if (below_ && std::any_of(std::begin(c.v), std::end(c.v), [](float x) { return std::isnan(x); }))
    return blendBelow(mask_->transform(), c.px, c.py, classAt, [&](int cx, int cy) { return !std::isnan(c.at(cx, cy)); });
  return world::coverageClassAt(c.px, c.py, classAt);
}

template <class CellClass, class HasData>
world::CoverageClass LandSea::blendBelow(const raster::GeoTransform& t, double px, double py, CellClass&& cellClass,
                                         HasData&& hasData) const {
  // world::coverageClassAt's sums (row by row, ocean and lake apart), a
  // cell without data adding the layers below's water at its centre to
  // their class's sum.
  const world::BSplineTaps tx(px), ty(py);
  float ocean = 0.0f, lake = 0.0f;
  bool allWet = true;
  for (int j = 0; j < 4; ++j) {
    float rowOcean = 0.0f, rowLake = 0.0f;
    for (int i = 0; i < 4; ++i) {
      const int cx = tx.first + i, cy = ty.first + j;
      if (hasData(cx, cy)) {
        const Surface s = cellClass(cx, cy);
        rowOcean += s == Surface::Ocean ? tx.w[i] : 0.0f;
        rowLake += s == Surface::Lake ? tx.w[i] : 0.0f;
        allWet &= s != Surface::Land;
        continue;
      }
      const world::CoverageClass b = below_(t.latOf(cy + 0.5), t.lonOf(cx + 0.5));
      const float water = std::clamp(b.coverage, 0.0f, 1.0f);
      (b.surface == Surface::Lake ? rowLake : rowOcean) += tx.w[i] * water;
      allWet &= water >= 1.0f;
    }
    ocean += ty.w[j] * rowOcean;
    lake += ty.w[j] * rowLake;
  }
  world::CoverageClass c;
  c.coverage = allWet ? 1.0f : std::min(1.0f, ocean + lake);
  if (world::coverageIsWater(c.coverage)) c.surface = lake > ocean ? Surface::Lake : Surface::Ocean;
  return c;
}

void LandSea::setCoverageBelow(CoverageBelow below) {
  below_ = std::move(below);
  noData_.clear();
  if (!below_ || classes_.empty()) return;
  // An in-memory mask's cells next to one without data or on a regional
  // mask's edge now take the coverage rule (kCoast): markCoast's argument,
  // with the layers below in place of another class.
  const int w = fast_.width, h = fast_.height;
  const auto& px = mask_->pixels();
  const int ch = mask_->channels();
  const std::size_t cells = std::size_t(w) * h;
  noData_.assign(cells, 0);
  bool any = false;
  for (std::size_t i = 0; i < cells; ++i) any |= (noData_[i] = std::isnan(px[i * ch]) ? 1 : 0) != 0;
  if (!any) noData_.clear();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      bool near = !fast_.global && (x == 0 || x == w - 1 || y == 0 || y == h - 1);
      for (int dy = -1; dy <= 1 && !near && any; ++dy)
        for (int dx = -1; dx <= 1 && !near; ++dx) {
          int xx = x + dx;
          const int yy = std::clamp(y + dy, 0, h - 1);
          if (fast_.global) xx = (xx + w) % w;
          else if (xx < 0 || xx >= w) continue;
          near = noData_[std::size_t(yy) * w + xx] != 0;
        }
      if (near) classes_[i] |= kCoast;
    }
}

world::CoverageClass LandSea::maskCoverageAt(double latDeg, double lonDeg) const {
  if (!mask_ || !std::isfinite(latDeg) || !std::isfinite(lonDeg)) return {};
  if (Surface p; poleClass(latDeg, p)) return {p == Surface::Land ? 0.0f : 1.0f, p};
  if (std::isnan(mask_->sampleNearest(latDeg, lonDeg))) return {};
  return coverageClass(latDeg, lonDeg);
}

bool LandSea::poleClass(double latDeg, Surface& out) const {
  if (!mask_ || !(std::abs(latDeg) >= 90.0)) return false;
  const auto& t = mask_->transform();
  if (!t.global) return false;
  // The row that ends at this pole (north is row 0 for a north-up raster).
  const double edge = (latDeg > 0.0) == (t.latStepDeg < 0.0) ? 0.0 : double(mask_->height());
  if (std::abs(std::abs(t.latOf(edge)) - 90.0) > 1e-9) return false;
  const float v = mask_->sampleNearest(latDeg, 0.0);  // the row's one pole value
  if (std::isnan(v)) return false;
  out = classOfValue(v);
  return true;
}

Surface LandSea::fromElevation(float elevationM) const {
  return (!std::isnan(elevationM) && elevationM < 0.0f) ? Surface::Ocean : Surface::Land;
}

world::CoverageClass LandSea::reliefCoverage(double latDeg, double lonDeg, float e) const {
  if (std::isnan(e)) return {};
  if (std::abs(latDeg) >= 90.0) {
    world::CoverageClass c;
    c.surface = fromElevation(e);
    c.coverage = c.surface == Surface::Land ? 0.0f : 1.0f;
    return c;
  }
  // With layers below, cells past a regional relief's edge are theirs too.
  const Cells16 c = gatherCells(*elevation_, latDeg, lonDeg, /*outsideIsNodata=*/bool(below_));
  const auto classAt = [&](int cx, int cy) {
    const float x = c.at(cx, cy);
    return !std::isnan(x) && x < 0.0f ? Surface::Ocean : Surface::Land;
  };
  // Cells without data take the layers below at their centres, as the
  // relief's pages are drawn, instead of counting as land.
  if (below_ && std::any_of(std::begin(c.v), std::end(c.v), [](float x) { return std::isnan(x); }))
    return blendBelow(elevation_->transform(), c.px, c.py, classAt, [&](int cx, int cy) { return !std::isnan(c.at(cx, cy)); });
  return world::coverageClassAt(c.px, c.py, classAt);
}

world::CoverageClass LandSea::reliefCoverageAt(double latDeg, double lonDeg) const {
  if (!elevation_ || !std::isfinite(latDeg) || !std::isfinite(lonDeg)) return {};
  return reliefCoverage(latDeg, lonDeg, elevation_->sampleBilinear(latDeg, lonDeg));
}

Surface LandSea::classify(double latDeg, double lonDeg) const {
  if (!std::isfinite(latDeg) || !std::isfinite(lonDeg)) return Surface::Land;
  if (Surface p; poleClass(latDeg, p)) return p;
  if (!classes_.empty()) {
    const int idx = fast_.index(latDeg, lonDeg);
    if (idx >= 0) {
      const std::uint8_t c = classes_[std::size_t(idx)];
      return (c & kCoast) ? coverageClass(latDeg, lonDeg).surface : static_cast<Surface>(c);
    }
  } else if (mask_) {
    // The nearest cell says whether the mask has data here; the coverage
    // rule says what it is.
    const float v = mask_->sampleNearest(latDeg, lonDeg);
    if (!std::isnan(v)) return coverageClass(latDeg, lonDeg).surface;
  }
  // No mask here: the elevation decides.
  return elevation_ ? reliefClass(latDeg, lonDeg, elevation_->sampleBilinear(latDeg, lonDeg)) : Surface::Land;
}

namespace {
// FastIndex::index over a batch, branch-free so the compiler vectorises the
// index arithmetic (the scalar loop was ~50 instructions per point, most of
// the grid's classifier cost); the byte lookups stay scalar. Same
// operations as FastIndex::index, so the same cells. GCC if-converts the
// range tests only without trapping math (this code uses no FP exceptions).
#ifdef __SANITIZE_THREAD__
// No clones under ThreadSanitizer: the ifunc resolver runs during relocation,
// before TSan's runtime is up, and its instrumentation crashes the process.
__attribute__((optimize("no-trapping-math")))
#else
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4"), optimize("no-trapping-math")))
#endif
void cellIndices(double originLon, double originLat, double invLonStep, double invLatStep, double centreLon,
                 int width, int height, bool global, const double* __restrict lat, const double* __restrict lon, std::size_t n,
                 std::int32_t* __restrict out) {
  const double w = width, hiY = height + 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    double x = ((global ? lon[i] : raster::lonNear(lon[i], centreLon)) - originLon) * invLonStep;
    const double y = (lat[i] - originLat) * invLatStep;
    x = global ? x - std::floor(x / w) * w : x;
    // Bitwise, not short-circuit: no branch in the loop. NaN gives false.
    const bool ok = (x >= 0.0) & (x < w) & (y > -1.0) & (y < hiY);
    const int ix = static_cast<int>(ok ? x : 0.0);
    const int iy = std::clamp(static_cast<int>(std::floor(ok ? y : 0.0)), 0, height - 1);
    out[i] = ok ? iy * width + ix : -1;
  }
}
}  // namespace

// out[i] = class byte at idx[i], Land where idx[i] < 0, 16 points per
// masked gather (the scalar byte loop was two thirds of the classifier's
// time in the grid build). cls must have 3 readable bytes past its last
// cell. Returns whether every idx was >= 0.
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // GCC 12: its own _mm512_undefined_* placeholders
__attribute__((target("avx512f,avx512vl,avx512bw"))) bool lookupAvx512(const std::uint8_t* cls,
                                                                      const std::int32_t* idx, std::size_t n,
                                                                      Surface* out) {
  const __m512i zero = _mm512_setzero_si512(), land = _mm512_set1_epi32(int(Surface::Land)),
                low = _mm512_set1_epi32(0xFF);
  bool all = true;
  std::size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    const __m512i v = _mm512_loadu_si512(idx + i);
    const __mmask16 inside = _mm512_cmpge_epi32_mask(v, zero);
    all &= inside == 0xFFFF;
    const __m512i g = _mm512_and_si512(_mm512_mask_i32gather_epi32(land, inside, v, cls, 1), low);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm512_cvtepi32_epi8(g));
  }
  for (; i < n; ++i) {
    const bool inside = idx[i] >= 0;
    all &= inside;
    out[i] = static_cast<Surface>(inside ? cls[idx[i]] : std::uint8_t(Surface::Land));
  }
  return all;
}
#pragma GCC diagnostic pop
}  // namespace

void LandSea::classifyBatch(const double* lat, const double* lon, std::size_t n, Surface* out) const {
  if (!classes_.empty()) {
    bool allInside = true;
    const std::uint8_t* cls = classes_.data();
#if defined(__clang__) && __clang_major__ < 16
    // Clang before 16 cannot test the x86-64 levels by name (the libFuzzer
    // build, tests/fuzz): x86-64-v4's AVX-512 features, as Clang 14 can test them.
    static const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                               __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx2") &&
                               __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
#else
    static const bool avx512 = __builtin_cpu_supports("x86-64-v4");
#endif
    constexpr std::size_t kBlock = 512;
    std::int32_t idx[kBlock];
    for (std::size_t b = 0; b < n; b += kBlock) {
      const std::size_t m = std::min(kBlock, n - b);
      cellIndices(fast_.originLon, fast_.originLat, fast_.invLonStep, fast_.invLatStep, fast_.centreLon, fast_.width,
                  fast_.height, fast_.global, lat + b, lon + b, m, idx);
      if (avx512) {
        allInside &= lookupAvx512(cls, idx, m, out + b);
        continue;
      }
      for (std::size_t i = 0; i < m; ++i) {
        const bool inside = idx[i] >= 0;
        allInside &= inside;
        out[b + i] = static_cast<Surface>(inside ? cls[inside ? idx[i] : 0] : std::uint8_t(Surface::Land));
      }
    }
    // Cells near a coast: the coverage rule (about one point in ten on the
    // default world's coasts; open sea and inland stay a lookup).
    for (std::size_t i = 0; i < n; ++i)
      if (std::uint8_t(out[i]) & kCoast) out[i] = coverageClass(lat[i], lon[i]).surface;
    fixPoles(lat, lon, n, out);
    if (allInside || !elevation_) return;
    for (std::size_t i = 0; i < n; ++i)
      if (fast_.index(lat[i], lon[i]) < 0 && std::isfinite(lat[i]) && std::isfinite(lon[i]))
        out[i] = reliefClass(lat[i], lon[i], elevation_->sampleBilinear(lat[i], lon[i]));
    return;
  }
  std::vector<float> v(n);
  if (mask_) {
    mask_->sampleNearestBatch(lat, lon, n, v.data());
    for (std::size_t i = 0; i < n; ++i)
      out[i] = std::isnan(v[i]) ? Surface::Land : coverageClass(lat[i], lon[i]).surface;
    fixPoles(lat, lon, n, out);
  } else {
    // Elevation only: points it cannot sample (non-finite) are land, as in
    // classify(); without this they kept whatever the caller's buffer held
    // (fuzz_capi_pixels: class 196 from geocean_query_class).
    std::fill(out, out + n, Surface::Land);
  }
  if (!elevation_) return;
  std::vector<double> la, lo;
  std::vector<std::size_t> where;
  for (std::size_t i = 0; i < n; ++i)
    if ((!mask_ || std::isnan(v[i])) && std::isfinite(lat[i]) && std::isfinite(lon[i])) {
      la.push_back(lat[i]);
      lo.push_back(lon[i]);
      where.push_back(i);
    }
  std::vector<float> e(where.size());
  elevation_->sampleBilinearBatch(la.data(), lo.data(), where.size(), e.data());
  for (std::size_t j = 0; j < where.size(); ++j) out[where[j]] = reliefClass(la[j], lo[j], e[j]);
}

void LandSea::classifyNearWaterBatch(const double* lat, const double* lon, std::size_t n, Surface* out) const {
  if (classes_.empty() && !mask_ && elevation_) {
    // A relief alone: water wherever any of the 4 x 4 cells the drawn
    // coast is filtered from is (coverage above 0), as a mask's two-cell reach.
    std::vector<float> e(n);
    elevation_->sampleBilinearBatch(lat, lon, n, e.data());
    for (std::size_t i = 0; i < n; ++i)
      out[i] = std::isfinite(lat[i]) && std::isfinite(lon[i]) && reliefCoverage(lat[i], lon[i], e[i]).coverage > 0.0f
                   ? Surface::Ocean
                   : Surface::Land;
    return;
  }
  if (classes_.empty()) {
    classifyBatch(lat, lon, n, out);
    return;
  }
  std::call_once(nearWaterOnce_, [this] {
    // Separable dilation of the water cells by two cells (longitude wraps
    // for a global mask, latitude clamps).
    const int w = fast_.width, h = fast_.height;
    constexpr int kR = 2;
    const std::size_t cells = std::size_t(fast_.width) * fast_.height;
    std::vector<std::uint8_t> rows(cells);
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* c = classes_.data() + std::size_t(y) * w;
      std::uint8_t* r = rows.data() + std::size_t(y) * w;
      for (int x = 0; x < w; ++x) {
        std::uint8_t any = 0;
        for (int d = -kR; d <= kR && !any; ++d) {
          int xx = x + d;
          if (fast_.global) xx = (xx % w + w) % w;
          else if (xx < 0 || xx >= w) continue;
          any = (c[xx] & kClassBits) != std::uint8_t(Surface::Land);
        }
        r[x] = any;
      }
    }
    nearWater_.assign(cells, 0);
    for (int y = 0; y < h; ++y)
      for (int d = -kR; d <= kR; ++d) {
        const int yy = std::clamp(y + d, 0, h - 1);
        const std::uint8_t* src = rows.data() + std::size_t(yy) * w;
        std::uint8_t* dst = nearWater_.data() + std::size_t(y) * w;
        for (int x = 0; x < w; ++x) dst[x] |= src[x];
      }
  });
  for (std::size_t i = 0; i < n; ++i) {
    const int idx = fast_.index(lat[i], lon[i]);
    out[i] = (idx >= 0 && nearWater_[std::size_t(idx)]) ? Surface::Ocean : Surface::Land;
    // A water pole is water at every longitude: never skipped there.
    if (Surface p; out[i] == Surface::Land && std::isfinite(lon[i]) && poleClass(lat[i], p) && p != Surface::Land)
      out[i] = Surface::Ocean;
  }
}

void LandSea::fixPoles(const double* lat, const double* lon, std::size_t n, Surface* out) const {
  for (std::size_t i = 0; i < n; ++i)
    if (std::abs(lat[i]) >= 90.0 && std::isfinite(lon[i])) poleClass(lat[i], out[i]);
}

float LandSea::waterCoverage(double latDeg, double lonDeg) const {
  if (!std::isfinite(latDeg) || !std::isfinite(lonDeg)) return 0.0f;
  if (!mask_) {
    if (!elevation_) return 0.0f;
    // Elevation only: coverage ramps over +-50 m around sea level.
    const float e = elevation_->sampleBilinear(latDeg, lonDeg);
    return std::isnan(e) ? 0.0f : std::clamp(0.5f - e / 100.0f, 0.0f, 1.0f);
  }
  // A pole is one point: its one class (poleClass).
  if (Surface p; poleClass(latDeg, p)) return p == Surface::Land ? 0.0f : 1.0f;
  // Outside a regional mask (no data there): the point's own class.
  if (!classes_.empty() ? fast_.index(latDeg, lonDeg) < 0 : std::isnan(mask_->sampleNearest(latDeg, lonDeg)))
    return classify(latDeg, lonDeg) == Surface::Land ? 0.0f : 1.0f;
  return coverageClass(latDeg, lonDeg).coverage;
}

float LandSea::elevationM(double latDeg, double lonDeg) const {
  return elevation_ ? elevation_->sampleBilinear(latDeg, lonDeg) : std::numeric_limits<float>::quiet_NaN();
}

void LandSea::elevationBatch(const double* lat, const double* lon, std::size_t n, float* out) const {
  if (!elevation_) {
    std::fill(out, out + n, std::numeric_limits<float>::quiet_NaN());
    return;
  }
  elevation_->sampleBilinearBatch(lat, lon, n, out);
}

}  // namespace geocean::ocean
