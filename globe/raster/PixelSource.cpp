#include "globe/raster/PixelSource.h"

#include "globe/raster/GeoTiff.h"
#include "globe/raster/OiioModuleApi.h"
#include "globe/raster/Raster.h"

#include <dlfcn.h>
#include <tiffio.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <fstream>
#include <list>
#include <mutex>
#include <unordered_map>

#ifndef GEOCEAN_OIIO_MODULE_BUILD
#define GEOCEAN_OIIO_MODULE_BUILD ""
#endif
#ifndef GEOCEAN_OIIO_MODULE_INSTALL
#define GEOCEAN_OIIO_MODULE_INSTALL ""
#endif

namespace geocean::raster::detail {

// ---------------------------------------------------------------- libtiff

namespace {
struct TiffFile {
  TIFF* t = nullptr;
  explicit TiffFile(const std::string& path) {
    static std::once_flag silence;  // process-wide handlers; handles open from many threads
    std::call_once(silence, [] {
      TIFFSetWarningHandler(nullptr);
      TIFFSetErrorHandler(nullptr);
    });
    registerGeoTiffTags();  // so GDAL_NODATA reads as text (sparse blocks are filled with it)
    // "m": no memory mapping. A file truncated while open (replaced in
    // place, a full disk) made reads of a mapped tile past the new end
    // SIGBUS (RasterFaults.FileReplacedOrTruncatedUnderCachedReads); read()
    // returns short instead, and the tile is "unreadable".
    t = TIFFOpen(path.c_str(), "rm");
  }
  ~TiffFile() {
    if (t) TIFFClose(t);
  }
};

struct TiffLayout {
  uint16_t spp = 1, bps = 8, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG, photometric = 1;
  uint16_t compression = COMPRESSION_NONE;
  uint32_t w = 0, h = 0, tw = 0, th = 0, rowsPerStrip = 0;
  bool tiled = false;
  double fill = 0.0;  // blocks of byte count 0 (sparse files): GDAL_NODATA, else 0, as GDAL reads them
};

TiffLayout layoutOf(TIFF* t) {
  TiffLayout l;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &l.w);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &l.h);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &l.spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &l.bps);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &l.format);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &l.planar);
  TIFFGetFieldDefaulted(t, TIFFTAG_PHOTOMETRIC, &l.photometric);
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &l.compression);
  l.tiled = TIFFIsTiled(t);
  char* nod = nullptr;
  if (TIFFGetField(t, 42113, &nod) && nod) l.fill = std::strtod(nod, nullptr);
  if (l.tiled) {
    TIFFGetField(t, TIFFTAG_TILEWIDTH, &l.tw);
    TIFFGetField(t, TIFFTAG_TILELENGTH, &l.th);
  } else {
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &l.rowsPerStrip);
    l.rowsPerStrip = std::min(l.rowsPerStrip, l.h);
  }
  // JPEG-in-TIFF stored as YCbCr: let libtiff convert to RGB.
  if (l.compression == COMPRESSION_JPEG && l.photometric == PHOTOMETRIC_YCBCR)
    TIFFSetField(t, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB);
  return l;
}

std::optional<SampleKind> kindOf(const TiffLayout& l) {
  if (l.format == SAMPLEFORMAT_IEEEFP) {
    if (l.bps == 32) return SampleKind::F32;
    if (l.bps == 64) return SampleKind::F64;
    return std::nullopt;
  }
  const bool s = l.format == SAMPLEFORMAT_INT;
  if (l.format != SAMPLEFORMAT_UINT && !s) return std::nullopt;
  switch (l.bps) {
    case 8: return s ? SampleKind::I8 : SampleKind::U8;
    case 16: return s ? SampleKind::I16 : SampleKind::U16;
    case 32: return s ? SampleKind::I32 : SampleKind::U32;
    default: return std::nullopt;
  }
}

bool supported(const TiffLayout& l) {
  return l.planar == PLANARCONFIG_CONTIG && kindOf(l).has_value() && l.photometric != PHOTOMETRIC_PALETTE &&
         l.compression != COMPRESSION_OJPEG && (l.tiled ? (l.tw > 0 && l.th > 0) : l.rowsPerStrip > 0);
}

template <class T>
void fillAs(double v, std::vector<unsigned char>& buf) {
  const T s = static_cast<T>(v);
  for (std::size_t i = 0; i + sizeof(T) <= buf.size(); i += sizeof(T)) std::memcpy(&buf[i], &s, sizeof(T));
}
void fillBlock(SampleKind k, double v, std::vector<unsigned char>& buf) {
  switch (k) {
    case SampleKind::U8: fillAs<std::uint8_t>(v, buf); break;
    case SampleKind::I8: fillAs<std::int8_t>(v, buf); break;
    case SampleKind::U16: fillAs<std::uint16_t>(v, buf); break;
    case SampleKind::I16: fillAs<std::int16_t>(v, buf); break;
    case SampleKind::U32: fillAs<std::uint32_t>(v, buf); break;
    case SampleKind::I32: fillAs<std::int32_t>(v, buf); break;
    case SampleKind::F32: fillAs<float>(v, buf); break;
    case SampleKind::F64: fillAs<double>(v, buf); break;
  }
}

// Decodes the block (tile or strip) holding pixel row y / column x into
// `buf` (native samples, blockW x blockH x spp). Returns false on error.
bool readBlock(TIFF* t, const TiffLayout& l, uint32_t x, uint32_t y, std::vector<unsigned char>& buf,
               uint32_t& bx0, uint32_t& by0, uint32_t& bw, uint32_t& bh) {
  const std::size_t px = std::size_t(l.spp) * (l.bps / 8);
  uint32_t strile;
  if (l.tiled) {
    bx0 = (x / l.tw) * l.tw;
    by0 = (y / l.th) * l.th;
    bw = l.tw;
    bh = l.th;
    buf.resize(std::size_t(l.tw) * l.th * px);
    strile = TIFFComputeTile(t, x, y, 0, 0);
  } else {
    bx0 = 0;
    by0 = (y / l.rowsPerStrip) * l.rowsPerStrip;
    bw = l.w;
    bh = std::min(l.rowsPerStrip, l.h - by0);
    buf.resize(std::size_t(l.w) * l.rowsPerStrip * px);
    strile = TIFFComputeStrip(t, y, 0);
  }
  if (TIFFGetStrileByteCount(t, strile) == 0) {  // sparse: never written
    fillBlock(*kindOf(l), l.fill, buf);
    return true;
  }
  return (l.tiled ? TIFFReadEncodedTile(t, strile, buf.data(), tmsize_t(buf.size()))
                  : TIFFReadEncodedStrip(t, strile, buf.data(), tmsize_t(buf.size()))) >= 0;
}
}  // namespace

bool isTiff(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char m[4] = {};
  f.read(reinterpret_cast<char*>(m), 4);
  return (m[0] == 'I' && m[1] == 'I' && (m[2] == 42 || m[2] == 43) && m[3] == 0) ||
         (m[0] == 'M' && m[1] == 'M' && m[2] == 0 && (m[3] == 42 || m[3] == 43));
}

ImageInfo tiffInfo(const std::string& path) {
  TiffFile f(path);
  if (!f.t) throw RasterError(path + ": not a readable TIFF file (libtiff could not parse the header)");
  const TiffLayout l = layoutOf(f.t);
  ImageInfo info;
  info.width = int(std::min<uint32_t>(l.w, 0x7fffffff));
  info.height = int(std::min<uint32_t>(l.h, 0x7fffffff));
  info.channels = l.spp;
  info.tileW = int(std::min<uint32_t>(l.tw, 0x7fffffff));
  info.tileH = int(std::min<uint32_t>(l.th, 0x7fffffff));
  info.stripRows = l.tiled ? 0 : int(std::min<uint32_t>(l.rowsPerStrip, 0x7fffffff));
  info.kind = kindOf(l).value_or(SampleKind::F32);
  info.format = "tiff";
  return info;
}

bool tiffSupported(const std::string& path) {
  TiffFile f(path);
  return f.t && supported(layoutOf(f.t));
}

namespace {
// Every block of the image in turn, each of its rows inside the image as
// rowOf(samples, sample count, the row's first sample index in the image).
template <class RowFn>
void forEachBlockRow(const std::string& path, TiffFile& f, const TiffLayout& l, RowFn&& rowOf) {
  const std::size_t spp = l.spp, sb = sampleBytes(*kindOf(l));
  std::vector<unsigned char> buf;
  const uint32_t stepX = l.tiled ? l.tw : l.w, stepY = l.tiled ? l.th : l.rowsPerStrip;
  for (uint32_t y = 0; y < l.h; y += stepY)
    for (uint32_t x = 0; x < l.w; x += stepX) {
      uint32_t bx0, by0, bw, bh;
      if (!readBlock(f.t, l, x, y, buf, bx0, by0, bw, bh))
        throw RasterError(path + ": pixel data is unreadable at row " + std::to_string(y) + ", column " +
                          std::to_string(x) + " (truncated or corrupt)");
      const uint32_t cw = std::min(bw, l.w - bx0), ch = std::min(bh, l.h - by0);
      for (uint32_t r = 0; r < ch; ++r)
        rowOf(buf.data() + std::size_t(r) * bw * spp * sb, std::size_t(cw) * spp,
              (std::size_t(by0 + r) * l.w + bx0) * spp);
    }
}
}  // namespace

std::vector<std::uint8_t> tiffReadAllNative(const std::string& path, const ImageInfo& info) {
  TiffFile f(path);
  if (!f.t) throw RasterError(path + ": not a readable TIFF file");
  const TiffLayout l = layoutOf(f.t);
  const std::size_t sb = sampleBytes(*kindOf(l));
  std::vector<std::uint8_t> out(std::size_t(info.width) * info.height * l.spp * sb);
  forEachBlockRow(path, f, l, [&](const unsigned char* src, std::size_t n, std::size_t at) {
    std::memcpy(out.data() + at * sb, src, n * sb);
  });
  return out;
}

std::vector<float> tiffReadAll(const std::string& path, const ImageInfo& info) {
  TiffFile f(path);
  if (!f.t) throw RasterError(path + ": not a readable TIFF file");
  const TiffLayout l = layoutOf(f.t);
  const SampleKind kind = *kindOf(l);
  std::vector<float> out(std::size_t(info.width) * info.height * l.spp);
  forEachBlockRow(path, f, l, [&](const unsigned char* src, std::size_t n, std::size_t at) {
    toFloat(kind, src, n, out.data() + at);
  });
  return out;
}

namespace {
template <class T>
void widenStrided(const unsigned char* src, std::size_t n, std::size_t stride, float* dst) {
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, src + i * stride * sizeof(T), sizeof(T));
    dst[i] = static_cast<float>(v);
  }
}
// n samples of one channel, `stride` samples apart, widened to float.
void toFloatStrided(SampleKind k, const unsigned char* src, std::size_t n, std::size_t stride, float* dst) {
  if (stride == 1) return toFloat(k, src, n, dst);
  switch (k) {
    case SampleKind::U8: widenStrided<std::uint8_t>(src, n, stride, dst); break;
    case SampleKind::I8: widenStrided<std::int8_t>(src, n, stride, dst); break;
    case SampleKind::U16: widenStrided<std::uint16_t>(src, n, stride, dst); break;
    case SampleKind::I16: widenStrided<std::int16_t>(src, n, stride, dst); break;
    case SampleKind::U32: widenStrided<std::uint32_t>(src, n, stride, dst); break;
    case SampleKind::I32: widenStrided<std::int32_t>(src, n, stride, dst); break;
    case SampleKind::F32: widenStrided<float>(src, n, stride, dst); break;
    case SampleKind::F64: widenStrided<double>(src, n, stride, dst); break;
  }
}

// Decoded blocks (tiles, or strips) of a TIFF kept in an LRU bounded by
// cacheBytes, in the file's own sample type (an int16 relief's tile is half
// its floats). Thread-safe: the lock covers only the LRU; blocks decode
// outside it, each thread on a libtiff handle of its own from a pool (a
// TIFF* is not thread-safe), and readers hold a block by shared_ptr, so an
// eviction never frees one being copied. Two threads missing the same
// block both decode it (the second insert finds the first's).
class TiffTiles final : public TileSource {
 public:
  TiffTiles(const std::string& path, std::size_t cacheBytes) : path_(path) {
    auto f = std::make_unique<TiffFile>(path);
    if (!f->t) throw RasterError(path + ": not a readable TIFF file");
    layout_ = layoutOf(f->t);
    kind_ = *kindOf(layout_);
    free_.push_back(std::move(f));
    tileW = int(layout_.tiled ? layout_.tw : layout_.w);
    tileH = int(layout_.tiled ? layout_.th : layout_.rowsPerStrip);
    tilesX_ = (std::int64_t(layout_.w) + tileW - 1) / tileW;
    const std::size_t blockBytes = std::size_t(tileW) * tileH * layout_.spp * sampleBytes(kind_);
    capacity_ = std::max<std::size_t>(2, cacheBytes / std::max<std::size_t>(blockBytes, 1));
  }
  bool read(int x0, int x1, int y0, int y1, int channel, float* out) override {
    const std::size_t spp = layout_.spp, sb = sampleBytes(kind_), outW = std::size_t(x1 - x0);
    for (int ty0 = (y0 / tileH) * tileH; ty0 < y1; ty0 += tileH)
      for (int tx0 = (x0 / tileW) * tileW; tx0 < x1; tx0 += tileW) {
        const std::shared_ptr<const Block> b = block(tx0, ty0);
        if (!b) return false;
        const int cx0 = std::max(x0, tx0), cx1 = std::min(x1, tx0 + tileW);
        const int cy0 = std::max(y0, ty0), cy1 = std::min(y1, ty0 + tileH);
        for (int y = cy0; y < cy1; ++y)
          toFloatStrided(kind_, b->data() + ((std::size_t(y - ty0) * tileW + (cx0 - tx0)) * spp + channel) * sb,
                         std::size_t(cx1 - cx0), spp, out + std::size_t(y - y0) * outW + (cx0 - x0));
      }
    return true;
  }
  std::string error() override {
    std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  using Block = std::vector<unsigned char>;
  using Entry = std::pair<std::int64_t, std::shared_ptr<const Block>>;

  std::shared_ptr<const Block> block(int tx0, int ty0) {
    const std::int64_t key = std::int64_t(ty0 / tileH) * tilesX_ + tx0 / tileW;
    std::unique_ptr<TiffFile> f;
    {
      std::lock_guard lock(mutex_);
      if (auto it = index_.find(key); it != index_.end()) {
        lru_.splice(lru_.begin(), lru_, it->second);
        return it->second->second;
      }
      if (!free_.empty()) {
        f = std::move(free_.back());
        free_.pop_back();
      }
    }
    if (!f) {  // another thread decodes on the first handle
      f = std::make_unique<TiffFile>(path_);
      if (f->t) layoutOf(f->t);  // its per-handle settings (JPEG as RGB)
    }
    auto b = std::make_shared<Block>();
    uint32_t bx0, by0, bw, bh;
    const bool ok = f->t && readBlock(f->t, layout_, uint32_t(tx0), uint32_t(ty0), *b, bx0, by0, bw, bh);
    std::lock_guard lock(mutex_);
    if (f->t) free_.push_back(std::move(f));
    if (!ok) {
      error_ = path_ + ": pixel data is unreadable near row " + std::to_string(ty0) + " (truncated or corrupt)";
      return nullptr;
    }
    if (auto it = index_.find(key); it != index_.end()) return it->second->second;
    if (lru_.size() >= capacity_) {
      index_.erase(lru_.back().first);
      lru_.pop_back();
    }
    lru_.emplace_front(key, std::move(b));
    index_[key] = lru_.begin();
    return lru_.front().second;
  }

  std::string path_, error_;
  TiffLayout layout_;
  SampleKind kind_ = SampleKind::U8;
  std::int64_t tilesX_ = 1;
  std::size_t capacity_ = 2;
  std::vector<std::unique_ptr<TiffFile>> free_;
  std::list<Entry> lru_;
  std::unordered_map<std::int64_t, std::list<Entry>::iterator> index_;
  std::mutex mutex_;
};
}  // namespace

std::unique_ptr<TileSource> tiffTiles(const std::string& path, const ImageInfo&, std::size_t cacheBytes) {
  return std::make_unique<TiffTiles>(path, cacheBytes);
}

// ---------------------------------------------------------- OpenImageIO

namespace {
const GeoceanOiioApi* loadModule() {
  namespace fs = std::filesystem;
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("GEOCEAN_OIIO_MODULE"); env && *env) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    candidates.push_back((exe.parent_path() / "geocean_oiio.so").string());
    candidates.push_back((exe.parent_path().parent_path() / "lib" / "geocean" / "geocean_oiio.so").string());
  }
  // Next to the object holding this code: libgeocean_ocean.so inside
  // another engine installs the module as <libdir>/geocean/geocean_oiio.so.
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&oiioInfo), &self) && self.dli_fname) {
    const fs::path dir = fs::path(self.dli_fname).parent_path();
    candidates.push_back((dir / "geocean" / "geocean_oiio.so").string());
    candidates.push_back((dir / "geocean_oiio.so").string());
  }
  candidates.emplace_back(GEOCEAN_OIIO_MODULE_BUILD);
  candidates.emplace_back(GEOCEAN_OIIO_MODULE_INSTALL);
  std::string tried;
  for (const auto& c : candidates) {
    if (c.empty() || !fs::exists(c, ec)) continue;
    void* h = dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) {
      tried += "\n  " + c + ": " + dlerror();
      continue;
    }
    auto fn = reinterpret_cast<const GeoceanOiioApi* (*)()>(dlsym(h, "geocean_oiio_api"));
    const GeoceanOiioApi* api = fn ? fn() : nullptr;
    if (api && api->abi == GEOCEAN_OIIO_MODULE_ABI) return api;
    tried += "\n  " + c + ": not a compatible geocean_oiio module";
  }
  throw RasterError("cannot load the OpenImageIO module geocean_oiio.so (set GEOCEAN_OIIO_MODULE)" +
                    (tried.empty() ? std::string(": not found next to the executable or in ") +
                                         GEOCEAN_OIIO_MODULE_INSTALL
                                   : tried));
}

const GeoceanOiioApi& oiio() {
  static const GeoceanOiioApi* api = loadModule();  // thread-safe; throws again next time if it failed
  return *api;
}

class OiioCache final : public TileSource {
 public:
  OiioCache(const std::string& path, const ImageInfo& info, std::size_t cacheBytes) : path_(path) {
    char err[512] = {};
    h_ = oiio().cacheCreate(path.c_str(), double(cacheBytes) / (1 << 20), err, sizeof err);
    if (!h_) throw RasterError(path + ": cannot open through the image cache (" + err + ")");
    if (info.tileW > 0) {
      tileW = info.tileW;
      tileH = info.tileH;
    }
  }
  ~OiioCache() override { oiio().cacheDestroy(h_); }
  bool read(int x0, int x1, int y0, int y1, int channel, float* out) override {
    char err[512] = {};
    if (oiio().cacheRead(h_, x0, x1, y0, y1, channel, out, err, sizeof err)) return true;
    std::lock_guard lock(mutex_);
    error_ = err;
    return false;
  }
  std::string error() override {
    std::lock_guard lock(mutex_);
    return path_ + ": " + error_;
  }

 private:
  void* h_ = nullptr;
  std::string path_, error_;
  std::mutex mutex_;
};
}  // namespace

ImageInfo oiioInfo(const std::string& path) {
  GeoceanOiioInfo i{};
  char err[512] = {};
  if (!oiio().info(path.c_str(), &i, err, sizeof err))
    throw RasterError(path + ": cannot read as an image (" + std::string(err[0] ? err : "unknown format") + ")");
  ImageInfo info;
  info.width = i.width;
  info.height = i.height;
  info.channels = i.channels;
  info.depth = i.depth;
  info.tileW = i.tileW;
  info.tileH = i.tileH;
  info.kind = i.kind ? SampleKind(i.kind) : SampleKind::F32;
  info.format = i.format;
  return info;
}

std::vector<float> oiioReadAll(const std::string& path, const ImageInfo& info) {
  std::vector<float> out(std::size_t(info.width) * info.height * info.channels);
  char err[512] = {};
  if (!oiio().readAll(path.c_str(), out.data(), err, sizeof err))
    throw RasterError(path + ": pixel data is unreadable (" + std::string(err[0] ? err : "truncated or corrupt") + ")");
  return out;
}

std::unique_ptr<TileSource> oiioCache(const std::string& path, const ImageInfo& info, std::size_t cacheBytes) {
  return std::make_unique<OiioCache>(path, info, cacheBytes);
}

namespace {
// OiioCache made on the first read: a big raster whose pixels all come
// from a warm tile cache (raster::TilePyramid) never loads OpenImageIO.
class LazyOiioCache final : public TileSource {
 public:
  LazyOiioCache(const std::string& path, const ImageInfo& info, std::size_t cacheBytes)
      : path_(path), info_(info), cacheBytes_(cacheBytes) {
    if (info.tileW > 0) tileW = info.tileW, tileH = info.tileH;
  }
  bool read(int x0, int x1, int y0, int y1, int channel, float* out) override {
    TileSource* s = source();
    return s && s->read(x0, x1, y0, y1, channel, out);
  }
  std::string error() override {
    TileSource* s = source();
    if (s) return s->error();
    std::lock_guard lock(mutex_);
    return openError_;
  }

 private:
  TileSource* source() {
    std::lock_guard lock(mutex_);
    if (!src_ && openError_.empty()) {
      try {
        src_ = std::make_unique<OiioCache>(path_, info_, cacheBytes_);
      } catch (const std::exception& e) {
        openError_ = e.what();
      }
    }
    return src_.get();
  }
  std::string path_;
  ImageInfo info_;
  std::size_t cacheBytes_;
  std::mutex mutex_;
  std::unique_ptr<TileSource> src_;
  std::string openError_;
};
}  // namespace

std::unique_ptr<TileSource> oiioCacheOnFirstRead(const std::string& path, const ImageInfo& info,
                                                 std::size_t cacheBytes) {
  return std::make_unique<LazyOiioCache>(path, info, cacheBytes);
}

void oiioWrite8(const std::string& path, const unsigned char* data, int width, int height, int channels) {
  char err[512] = {};
  if (!oiio().write8(path.c_str(), data, width, height, channels, err, sizeof err))
    throw RasterError(path + ": cannot write image (" + std::string(err) + ")");
}

}  // namespace geocean::raster::detail
