#include "globe/raster/Raster.h"

#include "globe/raster/GeoTiff.h"
#include "globe/raster/PixelSource.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>

namespace geocean::raster {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void nanWhereNodata(std::vector<float>& v, std::optional<double> nodata) {
  if (!nodata) return;
  const float nd = static_cast<float>(*nodata);
  for (float& x : v)
    if (x == nd) x = kNaN;
}
}  // namespace

double GeoTransform::nearLon(double lonDeg) const {
  return !global && lonSpanDeg > 0.0 ? lonNear(lonDeg, originLonDeg + 0.5 * lonSpanDeg) : lonDeg;
}

double GeoTransform::pixelX(double lonDeg) const {
  lonDeg = nearLon(lonDeg);
  double x = (lonDeg - originLonDeg) / lonStepDeg;
  if (global) {
    const double w = 360.0 / lonStepDeg;
    x -= std::floor(x / w) * w;
    if (x >= w) x = 0.0;  // rounding of values just below a multiple of w
  }
  return x;
}

double GeoTransform::pixelY(double latDeg) const { return (latDeg - originLatDeg) / latStepDeg; }

// Pixels read on demand: libtiff block reads, or OpenImageIO's ImageCache.
struct Raster::CacheImpl {
  std::unique_ptr<detail::TileSource> src;
  int tileW = 256, tileH = 256;
  bool read(int x0, int x1, int y0, int y1, int channel, float* out) const {
    return src->read(x0, x1, y0, y1, channel, out);
  }
};

Raster::~Raster() = default;

std::shared_ptr<const Raster> Raster::open(const std::string& path, const OpenOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw RasterError(path + ": no such file");
  if (fs::is_directory(path, ec)) throw RasterError(path + ": is a directory, not a raster");

  // TIFF through libtiff in process; anything else through OpenImageIO.
  const bool tiff = detail::isTiff(path);
  const detail::ImageInfo info = tiff ? detail::tiffInfo(path) : detail::oiioInfo(path);
  const std::int64_t samples = std::int64_t(info.width) * info.height * std::max(info.channels, 1);
  const std::string dims =
      std::to_string(info.width) + " x " + std::to_string(info.height) + " x " + std::to_string(info.channels);
  if (info.width <= 0 || info.height <= 0 || info.channels <= 0)
    throw RasterError(path + ": dimensions " + dims + " are not a valid raster");
  if (samples > options.maxPixels)
    throw RasterError(path + ": dimensions " + dims + " exceed the limit of " + std::to_string(options.maxPixels) +
                      " samples");
  // A tile is read whole on every path: its declared size counts against
  // the same limit, and never beyond 8192 x 8192 samples (a header may
  // claim 65536 x 65536 tiles over a 32 x 32 image).
  const std::int64_t tileSamples = std::int64_t(std::max(info.tileW, 0)) * std::max(info.tileH, 0) *
                                   std::max(info.channels, 1);
  if (tileSamples > std::min(options.maxPixels, kMaxTileSamples))
    throw RasterError(path + ": tile size " + std::to_string(info.tileW) + " x " + std::to_string(info.tileH) +
                      " x " + std::to_string(info.channels) + " exceeds the limit of " +
                      std::to_string(std::min(options.maxPixels, kMaxTileSamples)) + " samples");
  // Every block is decoded whole, so the tiles covering the image count
  // against the limit too (a 19789 x 8 image of 16 x 55824 tiles would
  // decode 3.3 G samples: fuzz_geotiff's timeout).
  if (tileSamples > 0) {
    const std::int64_t blocks = (std::int64_t(info.width) + info.tileW - 1) / info.tileW *
                                ((std::int64_t(info.height) + info.tileH - 1) / info.tileH);
    if (blocks > options.maxPixels / tileSamples)
      throw RasterError(path + ": " + std::to_string(blocks) + " tiles of " + std::to_string(info.tileW) + " x " +
                        std::to_string(info.tileH) + " over a " + dims + " image exceed the limit of " +
                        std::to_string(options.maxPixels) + " samples");
  }
  if (info.depth > 1) throw RasterError(path + ": volume images (depth " + std::to_string(info.depth) + ") are not rasters");

  std::shared_ptr<Raster> r(new Raster);
  r->path_ = path;
  r->width_ = info.width;
  r->height_ = info.height;
  r->channels_ = info.channels;

  std::optional<GeoTransform> t;
  if (tiff) {
    auto g = detail::readTiffGeoref(path, info.width, info.height);
    t = g.transform;
    r->nodata_ = g.nodata;
  }
  if (!t) t = detail::readWorldFile(path);
  if (options.georef == Georef::GlobalEquirect) {
    GeoTransform g;
    g.lonStepDeg = 360.0 / info.width;
    g.latStepDeg = -180.0 / info.height;
    t = g;
  } else if (!t) {
    throw RasterError(path + ": no georeferencing (no GeoTIFF ModelTiepoint/ModelPixelScale or ModelTransformation, "
                             "no world file); if it is a whole-Earth equirectangular image, say so (--global)");
  }
  t->global = std::abs(info.width * t->lonStepDeg - 360.0) < 1e-6 * 360.0;
  t->lonSpanDeg = info.width * t->lonStepDeg;
  r->transform_ = *t;
  if (options.nodata) r->nodata_ = options.nodata;

  const bool libtiffOk = tiff && detail::tiffSupported(path);
  const std::size_t bytes = std::size_t(samples) * sizeof(float);
  // Pixels read on demand from `src`, within cacheBytes.
  const auto streamFrom = [&r](std::unique_ptr<detail::TileSource> src, std::size_t cacheBytes) {
    auto c = std::make_unique<CacheImpl>();
    c->tileW = src->tileW;
    c->tileH = src->tileH;
    c->src = std::move(src);
    r->cache_ = std::move(c);
    r->cacheBytes_ = cacheBytes;
  };
  if (options.fewLookups && libtiffOk && info.tileW > 0) {
    streamFrom(detail::tiffTiles(path, info, std::size_t(4) << 20), std::size_t(4) << 20);
  } else if (bytes <= options.inMemoryLimitBytes &&
             (t->global || !options.regionalInMemoryLimitBytes || bytes <= options.regionalInMemoryLimitBytes)) {
    if (libtiffOk && detail::sampleBytes(info.kind) <= 2) {
      r->narrow_ = detail::tiffReadAllNative(path, info);
      r->narrowKind_ = int(info.kind);
      return r;
    }
    r->pixels_ = libtiffOk ? detail::tiffReadAll(path, info) : detail::oiioReadAll(path, info);
    nanWhereNodata(r->pixels_, r->nodata_);
    return r;
  } else {
    // A TIFF libtiff reads, in blocks (tiles, or strips) of at most a
    // quarter of the cache: its own LRU of decoded blocks, no OpenImageIO
    // (whose Debian build maps ~110 MB of libraries and holds ~29 MB of its
    // own beside the cache; issue 12 item 6). Anything else streams through
    // OpenImageIO's ImageCache; for a TIFF of a few huge strips, loaded on
    // the first pixel read (a warm tile cache never reads one).
    const bool tiled = info.tileW > 0;
    const std::size_t blockBytes = std::size_t(tiled ? info.tileW : info.width) *
                                   std::size_t(tiled ? info.tileH : info.stripRows) *
                                   std::size_t(info.channels) * detail::sampleBytes(info.kind);
    const bool ownBlocks = libtiffOk && blockBytes <= options.cacheBytes / 4;
    streamFrom(ownBlocks   ? detail::tiffTiles(path, info, options.cacheBytes)
               : libtiffOk ? detail::oiioCacheOnFirstRead(path, info, options.cacheBytes)
                           : detail::oiioCache(path, info, options.cacheBytes),
               options.cacheBytes);
    if (libtiffOk && !ownBlocks) {  // the probe below through libtiff, not OpenImageIO
      float probe = 0;
      const auto tiles = detail::tiffTiles(path, info, 0);
      if (!tiles->read(0, 1, 0, 1, 0, &probe)) throw RasterError(tiles->error());
      return r;
    }
  }
  // Probe one pixel so a corrupt file fails now, not in the middle of a batch.
  float probe = 0;
  if (!r->cache_->read(0, 1, 0, 1, 0, &probe)) throw RasterError(r->cache_->src->error());
  return r;
}

std::shared_ptr<const Raster> Raster::fromPixels(std::vector<float> pixels, int width, int height, int channels,
                                                 const GeoTransform& transform, std::optional<double> nodata,
                                                 std::string name) {
  if (width <= 0 || height <= 0 || channels <= 0 ||
      pixels.size() != std::size_t(width) * std::size_t(height) * std::size_t(channels))
    throw RasterError(name + ": pixel count " + std::to_string(pixels.size()) + " does not match " +
                      std::to_string(width) + " x " + std::to_string(height) + " x " + std::to_string(channels));
  std::shared_ptr<Raster> r(new Raster);
  r->path_ = std::move(name);
  r->width_ = width;
  r->height_ = height;
  r->channels_ = channels;
  r->transform_ = transform;
  r->transform_.global = std::abs(width * transform.lonStepDeg - 360.0) < 1e-6 * 360.0;
  r->transform_.lonSpanDeg = width * transform.lonStepDeg;
  r->nodata_ = nodata;
  r->pixels_ = std::move(pixels);
  nanWhereNodata(r->pixels_, nodata);
  return r;
}

std::size_t Raster::memoryBytes() const {
  return !narrow_.empty() ? narrow_.size() : inMemory() ? pixels_.size() * sizeof(float) : cacheBytes_;
}

float Raster::narrowAt(std::size_t i) const {
  const auto kind = detail::SampleKind(narrowKind_);
  float v = kNaN;
  detail::toFloat(kind, narrow_.data() + i * detail::sampleBytes(kind), 1, &v);
  return nodata_ && v == static_cast<float>(*nodata_) ? kNaN : v;
}

std::vector<float> Raster::pixels() const {
  if (narrow_.empty()) return pixels_;
  const auto kind = detail::SampleKind(narrowKind_);
  std::vector<float> out(narrow_.size() / detail::sampleBytes(kind));
  detail::toFloat(kind, narrow_.data(), out.size(), out.data());
  nanWhereNodata(out, nodata_);
  return out;
}

float Raster::pixel(int x, int y, int channel) const {
  x = std::clamp(x, 0, width_ - 1);
  y = std::clamp(y, 0, height_ - 1);
  channel = std::clamp(channel, 0, channels_ - 1);
  const std::size_t i = (std::size_t(y) * width_ + x) * channels_ + channel;
  if (!narrow_.empty()) return narrowAt(i);
  if (!pixels_.empty()) return pixels_[i];
  float v = kNaN;
  if (!cache_->read(x, x + 1, y, y + 1, channel, &v)) return kNaN;
  if (nodata_ && v == static_cast<float>(*nodata_)) return kNaN;
  return v;
}

namespace {
// Pixel-space location of a sample: integer cell(s) and weights.
struct Footprint {
  bool valid = false;
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // bilinear corners (x1/y1 = neighbours)
  float wx = 0, wy = 0;
};

Footprint nearestCell(const GeoTransform& t, int w, int h, double lat, double lon) {
  Footprint f;
  if (!std::isfinite(lat) || !std::isfinite(lon)) return f;
  const double x = t.pixelX(lon), y = t.pixelY(lat);
  if (!std::isfinite(x) || !std::isfinite(y)) return f;
  if (!t.global && (x < 0 || x >= w)) return f;
  // Latitudes beyond the raster: clamp only for rasters reaching the poles.
  const bool polar = std::abs(t.originLatDeg) >= 90.0 - 1e-9 || std::abs(t.latOf(h)) >= 90.0 - 1e-9;
  if ((y < 0 || y >= h) && !(t.global && polar)) return f;
  f.valid = true;
  // Clamped in double: a latitude far beyond a polar raster (fuzz_worldfile:
  // y = -2e298) must not overflow the int conversion.
  f.x0 = static_cast<int>(std::clamp(std::floor(x), 0.0, double(w - 1)));
  f.y0 = static_cast<int>(std::clamp(std::floor(y), 0.0, double(h - 1)));
  return f;
}

Footprint bilinearCell(const GeoTransform& t, int w, int h, double lat, double lon) {
  Footprint f = nearestCell(t, w, h, lat, lon);
  if (!f.valid) return f;
  const double x = t.pixelX(lon) - 0.5, y = std::clamp(t.pixelY(lat) - 0.5, 0.0, double(h - 1));
  const double fx = std::clamp(std::floor(x), -1.0, double(w)), fy = std::floor(y);
  f.wx = static_cast<float>(x - fx);
  f.wy = static_cast<float>(y - fy);
  int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  int x1 = x0 + 1, y1 = std::min(y0 + 1, h - 1);
  if (t.global) {
    x0 = (x0 % w + w) % w;
    x1 = x1 % w;
  } else {
    x0 = std::clamp(x0, 0, w - 1);
    x1 = std::clamp(x1, 0, w - 1);
  }
  f.x0 = x0;
  f.x1 = x1;
  f.y0 = y0;
  f.y1 = y1;
  return f;
}

// Poles are single points (issue 12 item 5). For a global raster whose
// first or last row ends at a pole: that row (0 or h - 1) when the latitude
// lies between the row's centre and the pole, with the weight of the pole's
// own value, 1 at the pole and 0 at the row centre; else -1.
int polarRow(const GeoTransform& t, int h, double lat, double& poleWeight) {
  if (!t.global || !std::isfinite(lat)) return -1;
  const double y = t.pixelY(lat);
  for (const int row : {0, h - 1}) {
    const double edge = row == 0 ? 0.0 : double(h);  // the row's outer edge in pixel space
    if (std::abs(std::abs(t.latOf(edge)) - 90.0) > 1e-9) continue;
    const double fromPole = std::abs(y - edge);  // in rows
    if (fromPole < 0.5 && (row == 0 ? y <= 0.5 : y >= h - 0.5)) {
      poleWeight = 1.0 - 2.0 * fromPole;
      return row;
    }
  }
  return -1;
}

float blend(float v00, float v10, float v01, float v11, float wx, float wy) {
  const float w[4] = {(1 - wx) * (1 - wy), wx * (1 - wy), (1 - wx) * wy, wx * wy};
  const float v[4] = {v00, v10, v01, v11};
  float sum = 0, wsum = 0;
  for (int i = 0; i < 4; ++i)
    if (!std::isnan(v[i])) {
      sum += w[i] * v[i];
      wsum += w[i];
    }
  return wsum > 0 ? sum / wsum : kNaN;
}
}  // namespace

float Raster::poleValue(int row, int channel) const {
  // Read per call (w pixels): only points within half a row of a pole get here.
  std::vector<float> v;
  v.reserve(std::size_t(width_));
  for (int x = 0; x < width_; ++x)
    if (const float p = pixel(x, row, channel); !std::isnan(p)) v.push_back(p);
  if (v.empty()) return kNaN;
  // The upper median: robust against a few odd cells, and for a mask ring of
  // two classes the majority one.
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

float Raster::sampleNearest(double latDeg, double lonDeg, int channel) const {
  const Footprint f = nearestCell(transform_, width_, height_, latDeg, lonDeg);
  if (!f.valid) return kNaN;
  // At a pole itself every longitude is the same point: the polar row's one value.
  double w = 0;
  if (std::abs(latDeg) >= 90.0)
    if (const int row = polarRow(transform_, height_, latDeg, w); row >= 0) return poleValue(row, channel);
  return pixel(f.x0, f.y0, channel);
}

float Raster::sampleBilinear(double latDeg, double lonDeg, int channel) const {
  const Footprint f = bilinearCell(transform_, width_, height_, latDeg, lonDeg);
  if (!f.valid) return kNaN;
  const float v = blend(pixel(f.x0, f.y0, channel), pixel(f.x1, f.y0, channel), pixel(f.x0, f.y1, channel),
                        pixel(f.x1, f.y1, channel), f.wx, f.wy);
  // Towards a pole the row's values blend into the pole's one (the row's
  // median), so the value there does not depend on longitude and is
  // continuous across it.
  double w = 0;
  const int row = polarRow(transform_, height_, latDeg, w);
  if (row < 0) return v;
  const float pole = poleValue(row, channel);
  if (std::isnan(v)) return pole;
  if (std::isnan(pole)) return v;
  return float((1.0 - w) * v + w * pole);
}

namespace {
// Cached batches: visit points grouped by tile so each tile is fetched once
// per batch (random single-pixel ImageCache lookups cost ~165 us each).
template <class PerPoint>
void forEachByTile(std::size_t n, int tileW, int tileH, int w, const Footprint* fp, PerPoint&& fn) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  const int tilesX = (w + tileW - 1) / tileW;
  auto key = [&](std::uint32_t i) -> std::int64_t {
    if (!fp[i].valid) return -1;
    return std::int64_t(fp[i].y0 / tileH) * tilesX + fp[i].x0 / tileW;
  };
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return key(a) < key(b); });
  std::size_t s = 0;
  while (s < n) {
    std::size_t e = s + 1;
    const auto k = key(order[s]);
    while (e < n && key(order[e]) == k) ++e;
    fn(k, order.data() + s, e - s);
    s = e;
  }
}
}  // namespace

void Raster::sampleNearestBatch(const double* lat, const double* lon, std::size_t n, float* out, int channel) const {
  if (inMemory() || n < 4) {
    for (std::size_t i = 0; i < n; ++i) out[i] = sampleNearest(lat[i], lon[i], channel);
    return;
  }
  std::vector<Footprint> fp(n);
  for (std::size_t i = 0; i < n; ++i) fp[i] = nearestCell(transform_, width_, height_, lat[i], lon[i]);
  const int tw = cache_->tileW, th = cache_->tileH;
  std::vector<float> tile(std::size_t(tw) * th);
  const float nd = nodata_ ? static_cast<float>(*nodata_) : kNaN;
  forEachByTile(n, tw, th, width_, fp.data(), [&](std::int64_t key, const std::uint32_t* idx, std::size_t m) {
    if (key < 0) {
      for (std::size_t j = 0; j < m; ++j) out[idx[j]] = kNaN;
      return;
    }
    const int tx0 = (fp[idx[0]].x0 / tw) * tw, ty0 = (fp[idx[0]].y0 / th) * th;
    const int tx1 = std::min(tx0 + tw, width_), ty1 = std::min(ty0 + th, height_);
    const bool ok = cache_->read(tx0, tx1, ty0, ty1, std::clamp(channel, 0, channels_ - 1), tile.data());
    for (std::size_t j = 0; j < m; ++j) {
      const Footprint& f = fp[idx[j]];
      float v = ok ? tile[std::size_t(f.y0 - ty0) * (tx1 - tx0) + (f.x0 - tx0)] : kNaN;
      out[idx[j]] = (v == nd) ? kNaN : v;
    }
  });
  for (std::size_t i = 0; i < n; ++i)
    if (std::abs(lat[i]) >= 90.0) out[i] = sampleNearest(lat[i], lon[i], channel);  // the pole's one value
}

void Raster::sampleBilinearBatch(const double* lat, const double* lon, std::size_t n, float* out, int channel) const {
  if (inMemory() || n < 4) {
    for (std::size_t i = 0; i < n; ++i) out[i] = sampleBilinear(lat[i], lon[i], channel);
    return;
  }
  std::vector<Footprint> fp(n);
  for (std::size_t i = 0; i < n; ++i) fp[i] = bilinearCell(transform_, width_, height_, lat[i], lon[i]);
  const int tw = cache_->tileW, th = cache_->tileH;
  // Tile plus a one-pixel apron so neighbours inside the image are local.
  std::vector<float> tile(std::size_t(tw + 1) * (th + 1));
  const float nd = nodata_ ? static_cast<float>(*nodata_) : kNaN;
  const int ch = std::clamp(channel, 0, channels_ - 1);
  forEachByTile(n, tw, th, width_, fp.data(), [&](std::int64_t key, const std::uint32_t* idx, std::size_t m) {
    if (key < 0) {
      for (std::size_t j = 0; j < m; ++j) out[idx[j]] = kNaN;
      return;
    }
    const int tx0 = (fp[idx[0]].x0 / tw) * tw, ty0 = (fp[idx[0]].y0 / th) * th;
    const int tx1 = std::min(tx0 + tw + 1, width_), ty1 = std::min(ty0 + th + 1, height_);
    const int stride = tx1 - tx0;
    const bool ok = cache_->read(tx0, tx1, ty0, ty1, ch, tile.data());
    auto at = [&](int x, int y) -> float {
      float v;
      if (ok && x >= tx0 && x < tx1 && y >= ty0 && y < ty1)
        v = tile[std::size_t(y - ty0) * stride + (x - tx0)];
      else
        return pixel(x, y, ch);  // the wrap column of a global raster
      return v == nd ? kNaN : v;
    };
    for (std::size_t j = 0; j < m; ++j) {
      const Footprint& f = fp[idx[j]];
      out[idx[j]] = blend(at(f.x0, f.y0), at(f.x1, f.y0), at(f.x0, f.y1), at(f.x1, f.y1), f.wx, f.wy);
    }
  });
  double w = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (polarRow(transform_, height_, lat[i], w) >= 0) out[i] = sampleBilinear(lat[i], lon[i], channel);
}

}  // namespace geocean::raster
