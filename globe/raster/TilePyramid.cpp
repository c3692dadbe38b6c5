#include "globe/raster/TilePyramid.h"

#include "globe/raster/PixelSource.h"

#include <fcntl.h>
#include <libdeflate.h>
#include <sys/stat.h>
#include <tiffio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <list>
#include <mutex>
#include <thread>
#include <unordered_map>

namespace geocean::raster {

namespace fs = std::filesystem;

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::string errnoText(int e) { return std::strerror(e); }

// ---------------------------------------------------------------- source reads

// Rectangles of the source as float, channels interleaved, nodata as NaN.
class SourceReader {
 public:
  virtual ~SourceReader() = default;
  // [x0, x1) x [y0, y1) inside the raster; out has (x1-x0)*(y1-y0)*channels floats.
  virtual void read(int x0, int x1, int y0, int y1, float* out) = 0;
  virtual std::size_t boundBytes() const = 0;
};

// Any raster: through Raster::pixel (in memory, or its own bounded cache).
class RasterReader final : public SourceReader {
 public:
  explicit RasterReader(const Raster& r) : r_(r) {}
  void read(int x0, int x1, int y0, int y1, float* out) override {
    const int c = r_.channels();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int k = 0; k < c; ++k) *out++ = r_.pixel(x, y, k);
  }
  std::size_t boundBytes() const override { return 0; }  // counted in the raster's own memoryBytes

 private:
  const Raster& r_;
};

// A TIFF through libtiff, block (tile or strip) by block, with an LRU of
// decoded blocks in their native samples. Blocks of byte count 0 (sparse
// files, GDAL's SPARSE_OK) are nodata without decoding.
class TiffReader final : public SourceReader {
 public:
  TiffReader(const Raster& r, std::size_t budget) : r_(r) {
    TIFFSetWarningHandler(nullptr);
    TIFFSetErrorHandler(nullptr);
    t_ = TIFFOpen(r.path().c_str(), "rm");  // not memory-mapped: a file truncated under us is an error, not SIGBUS
    if (!t_) throw RasterError(r.path() + ": not a readable TIFF file (libtiff could not parse the header)");
    info_ = detail::tiffInfo(r.path());
    uint16_t spp = 1;
    TIFFGetFieldDefaulted(t_, TIFFTAG_SAMPLESPERPIXEL, &spp);
    spp_ = spp;
    tiled_ = TIFFIsTiled(t_);
    if (tiled_) {
      bw_ = info_.tileW;
      bh_ = info_.tileH;
    } else {
      uint32_t rps = 0;
      TIFFGetFieldDefaulted(t_, TIFFTAG_ROWSPERSTRIP, &rps);
      bw_ = r.width();
      bh_ = int(std::min<uint32_t>(rps, uint32_t(r.height())));
    }
    uint16_t compression = 0, photometric = 0;
    TIFFGetFieldDefaulted(t_, TIFFTAG_COMPRESSION, &compression);
    TIFFGetFieldDefaulted(t_, TIFFTAG_PHOTOMETRIC, &photometric);
    if (compression == COMPRESSION_JPEG && photometric == PHOTOMETRIC_YCBCR)
      TIFFSetField(t_, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB);
    blockBytes_ = std::size_t(bw_) * bh_ * spp_ * detail::sampleBytes(info_.kind);
    // Two block rows of a strip source are needed to read each strip once.
    const std::size_t need = tiled_ ? 8 * blockBytes_ : (std::size_t(2 * 256) / std::max(bh_, 1) + 2) * blockBytes_;
    capacity_ = std::max<std::size_t>(std::max(budget, need) / std::max<std::size_t>(blockBytes_, 1), 2);
    if (r.nodata()) nodata_ = float(*r.nodata());
  }
  ~TiffReader() override {
    if (t_) TIFFClose(t_);
  }
  std::size_t boundBytes() const override { return capacity_ * blockBytes_; }

  void read(int x0, int x1, int y0, int y1, float* out) override {
    std::lock_guard lock(mutex_);
    const int w = x1 - x0, c = r_.channels();
    const std::size_t sb = detail::sampleBytes(info_.kind);
    for (int by = (y0 / bh_) * bh_; by < y1; by += bh_)
      for (int bx = (x0 / bw_) * bw_; bx < x1; bx += bw_) {
        const Block& b = block(bx, by);
        const int ya = std::max(y0, by), yb = std::min(y1, by + bh_);
        const int xa = std::max(x0, bx), xb = std::min(x1, bx + bw_);
        for (int y = ya; y < yb; ++y) {
          float* o = out + (std::size_t(y - y0) * w + (xa - x0)) * c;
          if (b.empty) {
            std::fill(o, o + std::size_t(xb - xa) * c, kNaN);
            continue;
          }
          const unsigned char* s = b.bytes.data() + (std::size_t(y - by) * bw_ + (xa - bx)) * spp_ * sb;
          if (spp_ == c) {
            detail::toFloat(info_.kind, s, std::size_t(xb - xa) * c, o);
          } else {
            for (int x = xa; x < xb; ++x, s += spp_ * sb, o += c) detail::toFloat(info_.kind, s, std::size_t(c), o);
          }
          if (nodata_)
            for (std::size_t i = 0, n = std::size_t(xb - xa) * c; i < n; ++i)
              if (o[i] == *nodata_) o[i] = kNaN;
        }
      }
  }

 private:
  struct Block {
    std::vector<unsigned char> bytes;
    bool empty = false;
    std::list<long>::iterator lru;
  };
  const Block& block(int bx, int by) {
    const long key = long(by / bh_) * 1000003L + bx / bw_;
    if (auto it = blocks_.find(key); it != blocks_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second.lru);
      return it->second;
    }
    while (blocks_.size() >= capacity_) {
      blocks_.erase(lru_.back());
      lru_.pop_back();
    }
    Block b;
    const uint32_t strile = tiled_ ? TIFFComputeTile(t_, uint32_t(bx), uint32_t(by), 0, 0)
                                   : TIFFComputeStrip(t_, uint32_t(by), 0);
    if (TIFFGetStrileByteCount(t_, strile) == 0) {
      b.empty = true;
    } else {
      b.bytes.resize(blockBytes_);
      const tmsize_t got = tiled_ ? TIFFReadEncodedTile(t_, strile, b.bytes.data(), tmsize_t(blockBytes_))
                                  : TIFFReadEncodedStrip(t_, strile, b.bytes.data(), tmsize_t(blockBytes_));
      if (got < 0)
        throw RasterError(r_.path() + ": pixel data is unreadable at row " + std::to_string(by) + ", column " +
                          std::to_string(bx) + " (truncated or corrupt)");
    }
    lru_.push_front(key);
    b.lru = lru_.begin();
    return blocks_.emplace(key, std::move(b)).first->second;
  }

  const Raster& r_;
  TIFF* t_ = nullptr;
  detail::ImageInfo info_;
  int spp_ = 1, bw_ = 0, bh_ = 0;
  bool tiled_ = false;
  std::size_t blockBytes_ = 0, capacity_ = 2;
  std::optional<float> nodata_;
  std::unordered_map<long, Block> blocks_;
  std::list<long> lru_;
  std::mutex mutex_;
};

bool isRegularFile(const std::string& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::unique_ptr<SourceReader> readerFor(const Raster& r, std::size_t budget) {
  if (!r.inMemory() && isRegularFile(r.path()) && detail::isTiff(r.path()) && detail::tiffSupported(r.path()))
    return std::make_unique<TiffReader>(r, budget);
  return std::make_unique<RasterReader>(r);
}

// FNV-1a of the first and last 64 KiB (libtiff writes the IFD at the end).
std::uint64_t headerHash(const std::string& path, std::uint64_t size) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return 0;
  std::vector<char> buf(65536);
  std::uint64_t h = fnv1a(nullptr, 0);
  std::size_t n = std::fread(buf.data(), 1, buf.size(), f);
  h = fnv1a(buf.data(), n, h);
  if (size > buf.size()) {
    std::fseek(f, -long(std::min<std::uint64_t>(size - buf.size(), buf.size())), SEEK_END);
    n = std::fread(buf.data(), 1, buf.size(), f);
    h = fnv1a(buf.data(), n, h);
  }
  std::fclose(f);
  return h;
}

std::string hex(std::uint64_t v) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

// ---------------------------------------------------------------- storage

// The compressed coarse tiles: a file (pread/pwrite) or, as the fallback,
// memory.
class Store {
 public:
  ~Store() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool inMemory() const { return fd_ < 0; }
  std::uint64_t size() const { return size_; }

  void openFile(int fd, std::uint64_t size) {
    fd_ = fd;
    size_ = size;
  }
  // Appends; on a write error (disk full, ...) moves what it has to memory
  // and returns the error text once.
  std::string append(const void* data, std::size_t n, std::uint64_t& offset) {
    std::lock_guard lock(mutex_);
    offset = size_;
    std::string err;
    if (fd_ >= 0) {
      // A short write is retried so that the error (ENOSPC, EFBIG, ...) is the one reported.
      std::size_t done = 0;
      ssize_t w = 0;
      while (done < n && (w = ::pwrite(fd_, static_cast<const char*>(data) + done, n - done, off_t(size_ + done))) > 0)
        done += std::size_t(w);
      if (done == n) {
        size_ += n;
        return {};
      }
      err = w < 0 ? errnoText(errno) : "no space left";
      memory_.resize(size_);
      if (size_ > 0 && ::pread(fd_, memory_.data(), size_, 0) != ssize_t(size_)) err += "; and could not read back";
      ::close(fd_);
      fd_ = -1;
    }
    memory_.insert(memory_.end(), static_cast<const char*>(data), static_cast<const char*>(data) + n);
    size_ += n;
    return err;
  }
  bool read(std::uint64_t offset, std::size_t n, void* out) const {
    if (fd_ >= 0) return ::pread(fd_, out, n, off_t(offset)) == ssize_t(n);
    std::lock_guard lock(mutex_);
    if (offset + n > memory_.size()) return false;
    std::memcpy(out, memory_.data() + offset, n);
    return true;
  }
  std::size_t memoryBytes() const { return memory_.capacity(); }

 private:
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::vector<char> memory_;
  mutable std::mutex mutex_;
};

void warn(const std::string& text) { std::fprintf(stderr, "geocean: warning: %s\n", text.c_str()); }
}  // namespace

std::string defaultTileCacheDir() {
  if (const char* e = std::getenv("GEOCEAN_TILE_CACHE"); e && *e) return e;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "geocean" / "tiles").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "geocean" / "tiles").string();
  return (fs::temp_directory_path() / "geocean-tiles").string();
}

struct TilePyramid::Impl {
  const TilePyramid* self = nullptr;
  PyramidOptions options;
  std::unique_ptr<SourceReader> reader;  // null when level 0 comes from the cache (level0Stored)
  TileIndex index;
  std::vector<std::size_t> levelStart;  // first record of each level
  // Level 0's tiles are in the store (a cache on disk): the source is never read.
  bool level0Stored = false;
  Store store;
  std::mutex cacheMutex;
  std::unordered_map<std::uint64_t, std::pair<std::shared_ptr<const std::vector<float>>, std::list<std::uint64_t>::iterator>>
      decoded;
  std::list<std::uint64_t> lru;
  std::shared_ptr<const std::vector<float>> nanTile;

  std::size_t tileFloats() const { return std::size_t(self->tileSize_) * self->tileSize_ * self->channels_; }
  static std::uint64_t keyOf(TileId id) {
    return (std::uint64_t(id.level) << 56) | (std::uint64_t(std::uint32_t(id.y)) << 28) | std::uint32_t(id.x);
  }
  const TileRecord& record(TileId id) const {
    return index.records[levelStart[id.level] + std::size_t(id.y) * self->tilesX(id.level) + id.x];
  }

  std::shared_ptr<const std::vector<float>> cached(std::uint64_t key) {
    std::lock_guard lock(cacheMutex);
    auto it = decoded.find(key);
    if (it == decoded.end()) return nullptr;
    lru.splice(lru.begin(), lru, it->second.second);
    return it->second.first;
  }
  void remember(std::uint64_t key, std::shared_ptr<const std::vector<float>> t) {
    std::lock_guard lock(cacheMutex);
    if (decoded.count(key)) return;
    while (int(decoded.size()) >= std::max(options.decodedTiles, 1)) {
      decoded.erase(lru.back());
      lru.pop_back();
    }
    lru.push_front(key);
    decoded.emplace(key, std::make_pair(std::move(t), lru.begin()));
  }

  std::shared_ptr<const std::vector<float>> level0(TileId id) {
    const int T = self->tileSize_, c = self->channels_;
    auto t = std::make_shared<std::vector<float>>(tileFloats(), kNaN);
    const int x0 = id.x * T, y0 = id.y * T;
    const int x1 = std::min(x0 + T, self->source_->width()), y1 = std::min(y0 + T, self->source_->height());
    if (x1 <= x0 || y1 <= y0) return t;
    std::vector<float> rect(std::size_t(x1 - x0) * (y1 - y0) * c);
    reader->read(x0, x1, y0, y1, rect.data());
    if (std::all_of(rect.begin(), rect.end(), [](float v) { return std::isnan(v); })) return nanTile;
    if (options.valueMap) options.valueMap(rect.data(), rect.size() / c, c);
    for (int y = y0; y < y1; ++y)
      std::copy_n(rect.data() + std::size_t(y - y0) * (x1 - x0) * c, std::size_t(x1 - x0) * c,
                  t->data() + std::size_t(y - y0) * T * c);
    return t;
  }

  std::shared_ptr<const std::vector<float>> stored(TileId id) {
    const TileRecord& r = record(id);
    if (r.kind == TileKind::Empty) return nanTile;
    const int c = self->channels_;
    auto t = std::make_shared<std::vector<float>>(tileFloats());
    if (r.kind == TileKind::Constant) {
      float v[4];
      if (!store.read(r.offset, r.bytes, v)) throw RasterError(self->source_->path() + ": tile cache unreadable");
      for (std::size_t i = 0; i < t->size(); i += std::size_t(c))  // no division per texel
        std::copy_n(v, c, t->data() + i);
      return t;
    }
    std::vector<unsigned char> z(r.bytes);
    if (!store.read(r.offset, r.bytes, z.data()))
      throw RasterError(self->source_->path() + ": tile cache unreadable at offset " + std::to_string(r.offset));
    const bool bytes = r.kind == TileKind::DataBytes;
    const std::size_t rawBytes = bytes ? 2 + t->size() : t->size() * sizeof(float);
    thread_local std::vector<unsigned char> b;
    if (bytes) b.resize(rawBytes);
    // libdeflate: the same zlib stream (checksum verified) 2.7x faster
    // than zlib's uncompress on these tiles; one decompressor per thread.
    struct Inflater {
      libdeflate_decompressor* d = libdeflate_alloc_decompressor();
      ~Inflater() { libdeflate_free_decompressor(d); }
    };
    thread_local Inflater inflater;
    std::size_t n = 0;
    if (!inflater.d ||
        libdeflate_zlib_decompress(inflater.d, z.data(), z.size(), bytes ? static_cast<void*>(b.data()) : t->data(),
                                   rawBytes, &n) != LIBDEFLATE_SUCCESS ||
        n != rawBytes)
      throw RasterError(self->source_->path() + ": tile cache corrupt at level " + std::to_string(id.level) +
                        " tile " + std::to_string(id.x) + "," + std::to_string(id.y));
    if (bytes) {
      float lut[256];
      for (int i = 0; i < 256; ++i) lut[i] = float(i);
      if (b[0]) lut[b[1]] = kNaN;
      const unsigned char* in = b.data() + 2;
      float* o = t->data();
      for (std::size_t i = 0; i < t->size(); ++i) o[i] = lut[in[i]];
    }
    return t;
  }

  std::shared_ptr<const std::vector<float>> interior(TileId id) {
    const std::uint64_t key = keyOf(id);
    if (auto t = cached(key)) return t;
    auto t = id.level == 0 && !level0Stored ? level0(id) : stored(id);
    remember(key, t);
    return t;
  }

  // Stores a tile's texels as `rec` (level, x, y set): Empty when all NaN,
  // Constant when one value per channel, else zlib-deflated.
  std::string storeTile(const std::vector<float>& out, TileRecord& rec) {
    const int c = self->channels_;
    rec.kind = TileKind::Empty;
    rec.bytes = 0;
    rec.offset = 0;
    // Scans that stop at the first texel deciding them (no division per texel).
    if (std::all_of(out.begin(), out.end(), [](float v) { return std::isnan(v); })) return {};
    bool constant = true;
    for (std::size_t i = 0; i < out.size() && constant; i += std::size_t(c))
      for (int k = 0; k < c; ++k) constant &= out[i + k] == out[std::size_t(k)];  // NaN is never constant
    if (constant) {
      rec.kind = TileKind::Constant;
      rec.bytes = std::uint32_t(4 * c);
      return store.append(out.data(), rec.bytes, rec.offset);
    }
    // Integers 0..255 and NaN (a mask's classes, an 8-bit source): a byte a
    // texel with a byte value no texel uses for NaN.
    thread_local std::vector<unsigned char> small, z;  // reused: no allocation per tile
    small.resize(2 + out.size());
    {
      // A texel fits when its bits are those of float(byte) (so not -0),
      // or of kNaN (read back as kNaN: the same bits); NaN is marked 255
      // until a free code is known.
      std::uint32_t nanBits;
      std::memcpy(&nanBits, &kNaN, 4);
      bool fits = true, nan = false;
      for (std::size_t i = 0; i < out.size() && fits; ++i) {
        const float v = out[i];
        if (v != v) {
          std::uint32_t bits;
          std::memcpy(&bits, &v, 4);
          fits = bits == nanBits;
          nan = true;
          small[2 + i] = 255;
          continue;
        }
        const int b = v >= 0.0f && v <= 255.0f ? int(v) : -1;
        fits = b >= 0 && float(b) == v && !(b == 0 && std::signbit(v));
        small[2 + i] = static_cast<unsigned char>(b);
      }
      int code = 256;
      if (fits && nan) {
        bool used[256] = {};
        for (std::size_t i = 0; i < out.size(); ++i) used[small[2 + i]] |= !std::isnan(out[i]);
        code = 0;
        while (code < 256 && used[code]) ++code;
        if (code < 256 && code != 255)
          for (std::size_t i = 0; i < out.size(); ++i)
            if (std::isnan(out[i])) small[2 + i] = static_cast<unsigned char>(code);
      }
      if (!fits || (nan && code == 256)) {
        small.clear();
      } else {
        small[0] = nan, small[1] = static_cast<unsigned char>(nan ? code : 0);
      }
    }
    rec.kind = small.empty() ? TileKind::Data : TileKind::DataBytes;
    // libdeflate at level 1: the same zlib format, faster than zlib's
    // compress2 at level 1 (level 0 adds ~4x level 1's tiles to the build).
    struct Deflater {
      libdeflate_compressor* d = libdeflate_alloc_compressor(1);
      ~Deflater() { libdeflate_free_compressor(d); }
    };
    thread_local Deflater deflater;
    if (!deflater.d) throw RasterError(self->source_->path() + ": out of memory compressing a tile");
    const std::size_t raw = small.empty() ? out.size() * sizeof(float) : small.size();
    const void* in = small.empty() ? static_cast<const void*>(out.data()) : small.data();
    z.resize(libdeflate_zlib_compress_bound(deflater.d, raw));
    const std::size_t n = libdeflate_zlib_compress(deflater.d, in, raw, z.data(), z.size());
    if (n == 0) throw RasterError(self->source_->path() + ": a tile did not compress");
    rec.bytes = std::uint32_t(n);
    return store.append(z.data(), n, rec.offset);
  }

  // Level l from level l-1: the mean of the valid texels of each 2 x 2.
  std::string buildTile(TileId id, TileRecord& rec) {
    const int T = self->tileSize_, c = self->channels_;
    rec.level = std::uint8_t(id.level);
    rec.x = std::uint32_t(id.x);
    rec.y = std::uint32_t(id.y);
    std::shared_ptr<const std::vector<float>> kids[4];
    bool anyData = false;
    std::string err;
    for (int k = 0; k < 4; ++k) {
      const TileId ch{id.level - 1, 2 * id.x + (k & 1), 2 * id.y + (k >> 1)};
      if (ch.x >= self->tilesX(ch.level) || ch.y >= self->tilesY(ch.level)) continue;
      if (ch.level > 0 && record(ch).kind == TileKind::Empty) continue;
      if (ch.level == 0) {
        // Each level-0 tile is read here once: stored as it is read (not
        // in the memory fallback, whose memory would grow with the raster).
        kids[k] = level0(ch);
        TileRecord& r0 = index.records[levelStart[0] + std::size_t(ch.y) * self->tilesX(0) + ch.x];
        r0.level = 0, r0.x = std::uint32_t(ch.x), r0.y = std::uint32_t(ch.y);
        if (!store.inMemory() && kids[k] != nanTile)
          if (std::string e = storeTile(*kids[k], r0); err.empty()) err = e;
      } else {
        kids[k] = interior(ch);
      }
      if (kids[k] == nanTile) kids[k].reset();
      else anyData = true;
    }
    rec.kind = TileKind::Empty;
    rec.bytes = 0;
    rec.offset = 0;
    if (!anyData) return err;
    std::vector<float> out(tileFloats(), kNaN);
    const int h = T / 2;
    for (int k = 0; k < 4; ++k) {
      if (!kids[k]) continue;
      const float* s = kids[k]->data();
      const int ox = (k & 1) * h, oy = (k >> 1) * h;
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < h; ++i)
          for (int ch = 0; ch < c; ++ch) {
            float sum = 0.0f;
            int n = 0;
            for (int d = 0; d < 4; ++d) {
              const float v = s[(std::size_t(2 * j + (d >> 1)) * T + 2 * i + (d & 1)) * c + ch];
              if (!std::isnan(v)) {
                sum += v;
                ++n;
              }
            }
            if (n) out[(std::size_t(oy + j) * T + ox + i) * c + ch] = sum / float(n);
          }
    }
    if (std::string e = storeTile(out, rec); err.empty()) err = e;
    return err;
  }
};

TileKind TilePyramid::kind(TileId id) const {
  const TileKind k = kindStored(id);
  return k == TileKind::DataBytes ? TileKind::Data : k;
}

int TilePyramid::levelWidth(int level) const { return int(levelTexels(std::uint32_t(source_->width()), level)); }
int TilePyramid::levelHeight(int level) const { return int(levelTexels(std::uint32_t(source_->height()), level)); }
int TilePyramid::tilesX(int level) const {
  return int(levelTiles(std::uint32_t(source_->width()), level, std::uint32_t(tileSize_)));
}
int TilePyramid::tilesY(int level) const {
  return int(levelTiles(std::uint32_t(source_->height()), level, std::uint32_t(tileSize_)));
}

GeoTransform TilePyramid::levelTransform(int level) const {
  GeoTransform t = source_->transform();
  t.lonStepDeg *= double(1 << level);
  t.latStepDeg *= double(1 << level);
  return t;
}

TilePyramid::~TilePyramid() = default;

TileKind TilePyramid::kindStored(TileId id) const {
  if (id.level == 0) {
    if (levels_ == 1) return TileKind::Data;
    return impl_->record({1, id.x / 2, id.y / 2}).kind == TileKind::Empty ? TileKind::Empty : TileKind::Data;
  }
  return impl_->record(id).kind;
}

std::shared_ptr<const std::vector<float>> TilePyramid::interior(TileId id) const {
  if (id.level < 0 || id.level >= levels_ || id.x < 0 || id.y < 0 || id.x >= tilesX(id.level) ||
      id.y >= tilesY(id.level))
    throw RasterError(source_->path() + ": no tile " + std::to_string(id.level) + "/" + std::to_string(id.x) + "/" +
                      std::to_string(id.y) + " in the pyramid");
  if (id.level > 0 && impl_->record(id).kind == TileKind::Empty) return impl_->nanTile;
  return impl_->interior(id);
}

void TilePyramid::readTile(TileId id, float* out) const {
  const int T = tileSize_, c = channels_, B = T + 2;
  const int W = levelWidth(id.level), H = levelHeight(id.level);
  const bool wrap = source_->transform().global;
  // Each bordered column's source tile and column in it, once (the
  // divisions per texel were most of a tile's copy), then each row in runs
  // of consecutive columns of one tile.
  std::vector<int> tileX(std::size_t(B), 0), inX(std::size_t(B), 0);
  for (int i = 0; i < B; ++i) {
    int gx = id.x * T + i - 1;
    gx = wrap ? ((gx % W) + W) % W : std::clamp(gx, 0, W - 1);
    tileX[std::size_t(i)] = gx / T, inX[std::size_t(i)] = gx % T;
  }
  TileId last = id;
  std::shared_ptr<const std::vector<float>> t = interior(id);
  for (int j = 0; j < B; ++j) {
    const int gy = std::clamp(id.y * T + j - 1, 0, H - 1);
    for (int i = 0; i < B;) {
      const TileId want{id.level, tileX[std::size_t(i)], gy / T};
      int n = 1;
      while (i + n < B && tileX[std::size_t(i + n)] == want.x && inX[std::size_t(i + n)] == inX[std::size_t(i)] + n) ++n;
      if (!(want == last)) {
        t = interior(want);
        last = want;
      }
      const float* src = t->data() + (std::size_t(gy % T) * T + inX[std::size_t(i)]) * c;
      std::copy_n(src, std::size_t(n) * c, out + (std::size_t(j) * B + i) * c);
      i += n;
    }
  }
}

namespace {
constexpr char kDerivedMagic[8] = {'G', 'E', 'O', 'D', 'E', 'R', 'I', 'V'};
constexpr std::uint32_t kDerivedVersion = 1;
// A derived file: magic, version, cache identity, raw bytes (kDerivedPrefix),
// the deflated data, a checksum of all before it (8).
constexpr std::size_t kDerivedPrefix = 8 + 4 + 8 + 8;
constexpr std::size_t kDerivedHeader = kDerivedPrefix + 8;  // with the checksum

bool derivedNameOk(const std::string& n) {
  return !n.empty() && n.size() <= 100 && std::all_of(n.begin(), n.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '-';
  });
}

// What names a cache's source and build (its index's key and data size).
std::uint64_t cacheIdentity(const TileIndex& index) {
  TileIndex k;
  k.key = index.key;
  k.dataBytes = index.dataBytes;
  const std::string bytes = serializeTileIndex(k);
  return fnv1a(bytes.data(), bytes.size());
}
}  // namespace

std::optional<std::vector<unsigned char>> TilePyramid::derived(const std::string& name) const {
  if (stats_.cachePath.empty() || !derivedNameOk(name)) return std::nullopt;
  std::FILE* f = std::fopen((stats_.cachePath + "/derived-" + name).c_str(), "rb");
  if (!f) return std::nullopt;
  std::vector<unsigned char> file;
  unsigned char buf[65536];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) file.insert(file.end(), buf, buf + n);
  std::fclose(f);
  if (file.size() < kDerivedHeader || std::memcmp(file.data(), kDerivedMagic, 8) != 0) return std::nullopt;
  std::uint32_t version;
  std::uint64_t identity, raw, sum;
  std::memcpy(&version, file.data() + 8, 4);
  std::memcpy(&identity, file.data() + 12, 8);
  std::memcpy(&raw, file.data() + 20, 8);
  std::memcpy(&sum, file.data() + file.size() - 8, 8);
  if (version != kDerivedVersion || identity != cacheIdentity(impl_->index) || raw > (std::uint64_t(1) << 34) ||
      sum != fnv1a(file.data(), file.size() - 8))
    return std::nullopt;
  std::vector<unsigned char> out(raw);
  libdeflate_decompressor* d = libdeflate_alloc_decompressor();
  std::size_t n = 0;
  const bool ok = d &&
                  libdeflate_zlib_decompress(d, file.data() + kDerivedPrefix, file.size() - kDerivedHeader, out.data(),
                                             raw, &n) == LIBDEFLATE_SUCCESS &&
                  n == raw;
  libdeflate_free_decompressor(d);
  if (!ok) return std::nullopt;
  return out;
}

void TilePyramid::storeDerived(const std::string& name, const void* data, std::size_t bytes) const {
  if (stats_.cachePath.empty() || !derivedNameOk(name)) return;
  libdeflate_compressor* c = libdeflate_alloc_compressor(1);
  if (!c) return;
  std::vector<unsigned char> file(kDerivedHeader + libdeflate_zlib_compress_bound(c, bytes));
  const std::size_t z =
      libdeflate_zlib_compress(c, data, bytes, file.data() + kDerivedPrefix, file.size() - kDerivedHeader);
  libdeflate_free_compressor(c);
  if (z == 0) return;
  file.resize(kDerivedHeader + z);
  const std::uint64_t identity = cacheIdentity(impl_->index), raw = bytes;
  std::memcpy(file.data(), kDerivedMagic, 8);
  std::memcpy(file.data() + 8, &kDerivedVersion, 4);
  std::memcpy(file.data() + 12, &identity, 8);
  std::memcpy(file.data() + 20, &raw, 8);
  const std::uint64_t sum = fnv1a(file.data(), file.size() - 8);
  std::memcpy(file.data() + file.size() - 8, &sum, 8);
  const std::string path = stats_.cachePath + "/derived-" + name;
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." +
                          std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  bool ok = f && std::fwrite(file.data(), 1, file.size(), f) == file.size();
  if (f && std::fclose(f) != 0) ok = false;
  std::error_code ec;
  if (ok) fs::rename(tmp, path, ec);
  if (!ok || ec) fs::remove(tmp, ec);
}

std::size_t TilePyramid::residentBoundBytes() const {
  return (impl_->reader ? impl_->reader->boundBytes() : 0) +
         std::size_t(std::max(impl_->options.decodedTiles, 1) + 1) * impl_->tileFloats() * 4 +
         impl_->index.records.capacity() * sizeof(TileRecord) + impl_->store.memoryBytes();
}

std::shared_ptr<const TilePyramid> TilePyramid::open(std::shared_ptr<const Raster> source, PyramidOptions options) {
  if (!source) throw RasterError("tile pyramid: no source raster");
  if (options.tileSize < 8 || options.tileSize > 4096 || (options.tileSize & (options.tileSize - 1)))
    throw RasterError(source->path() + ": tile size " + std::to_string(options.tileSize) +
                      " is not a power of two in [8, 4096]");
  if (source->channels() > 4)
    throw RasterError(source->path() + ": " + std::to_string(source->channels()) + " channels, tiles hold at most 4");
  std::shared_ptr<TilePyramid> p(new TilePyramid());
  p->source_ = source;
  p->tileSize_ = options.tileSize;
  p->channels_ = source->channels();
  p->levels_ = 1;
  while (p->tilesX(p->levels_ - 1) > 1 || p->tilesY(p->levels_ - 1) > 1) ++p->levels_;
  p->impl_ = std::make_unique<Impl>();
  Impl& m = *p->impl_;
  m.self = p.get();
  m.options = options;
  m.nanTile = std::make_shared<const std::vector<float>>(m.tileFloats(), kNaN);
  m.levelStart.assign(std::size_t(p->levels_) + 1, 0);
  for (int l = 0; l < p->levels_; ++l)
    m.levelStart[l + 1] = m.levelStart[l] + std::size_t(p->tilesX(l)) * p->tilesY(l);
  // One tile: nothing to build or cache, level 0 is read from the source.
  const std::size_t total = p->levels_ > 1 ? m.levelStart[p->levels_] : 0;
  // The stats count levels 1 and up (level 0 is the source's own tiling).
  const auto countKinds = [&] {
    for (std::size_t i = m.levelStart[1]; i < m.index.records.size(); ++i) {
      const TileRecord& r = m.index.records[i];
      ++(r.kind == TileKind::Empty ? p->stats_.tilesEmpty
                                   : r.kind == TileKind::Constant ? p->stats_.tilesConstant : p->stats_.tilesData);
    }
  };

  TileCacheKey key;
  key.valueMap = options.valueMapId;
  key.tileSize = std::uint32_t(options.tileSize);
  key.channels = std::uint32_t(p->channels_);
  key.width = std::uint32_t(source->width());
  key.height = std::uint32_t(source->height());
  key.levels = std::uint32_t(p->levels_);
  std::string dir;
  if (isRegularFile(source->path())) {
    std::error_code ec;
    key.sourcePath = fs::absolute(source->path(), ec).lexically_normal().string();
    struct stat st {};
    if (::stat(source->path().c_str(), &st) == 0) {
      key.sourceBytes = std::uint64_t(st.st_size);
      key.sourceMtimeNs = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    }
    key.headerHash = headerHash(source->path(), key.sourceBytes);
    const std::string id = key.sourcePath + '\n' + key.valueMap + '\n' + std::to_string(key.tileSize);
    const fs::path root = options.cacheDir.empty() ? fs::path(defaultTileCacheDir()) : fs::path(options.cacheDir);
    dir = (root / (fs::path(source->path()).filename().string() + "-" + hex(fnv1a(id.data(), id.size())))).string();
  }

  // Reuse the cache when its index names this very source and build.
  if (!dir.empty() && total > 0) {
    const std::string indexPath = dir + "/index", dataPath = dir + "/tiles";
    std::FILE* f = std::fopen(indexPath.c_str(), "rb");
    if (f) {
      std::string bytes;
      char buf[65536];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) bytes.append(buf, n);
      std::fclose(f);
      try {
        TileIndex idx = parseTileIndex(bytes.data(), bytes.size(), indexPath);
        struct stat st {};
        const int fd = ::open(dataPath.c_str(), O_RDONLY | O_CLOEXEC);
        if (idx.key == key && fd >= 0 && ::fstat(fd, &st) == 0 && std::uint64_t(st.st_size) == idx.dataBytes) {
          m.index = std::move(idx);
          m.store.openFile(fd, m.index.dataBytes);
          m.level0Stored = true;  // every index on disk has level 0 (format 2)
          p->stats_.level0Stored = true;
          p->stats_.cachePath = dir;
          countKinds();
          p->stats_.storedBytes = m.index.dataBytes;
          return p;
        }
        if (fd >= 0) ::close(fd);
      } catch (const RasterError& e) {
        warn(std::string(e.what()) + ": rebuilding it");
      }
    }
  }

  // Build (or a source too small for coarse levels, or with no file).
  m.reader = readerFor(*source, options.sourceCacheBytes);
  p->stats_.builtNow = total > 0;
  std::string tmpData;
  if (!dir.empty() && total > 0) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    // What was derived from the old tiles (never read again: it names the old cache).
    std::error_code ignored;
    for (fs::directory_iterator it(ec ? fs::path() : fs::path(dir), ignored), end; !ignored && it != end;
         it.increment(ignored))
      if (it->path().filename().string().rfind("derived-", 0) == 0) fs::remove(it->path(), ignored);
    tmpData = dir + "/tiles.tmp." + std::to_string(::getpid());
    const int fd = ec ? -1 : ::open(tmpData.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
      warn("tile cache folder " + dir + " cannot be written (" + (ec ? ec.message() : errnoText(errno)) +
           "): keeping the coarse tiles of " + source->path() + " in memory this run");
      tmpData.clear();
    } else {
      m.store.openFile(fd, 0);
    }
  }
  m.index.key = key;
  m.index.records.resize(total);
  const std::size_t coarse = total > 0 ? total - m.levelStart[1] : 0;  // built tiles (level 0 is stored as read)
  const bool show = options.progress == BuildProgress::Auto && coarse > 1024;
  const bool tty = ::isatty(2);
  int shown = -1;
  std::size_t done = 0;
  std::string writeError;
  for (int l = 1; l < p->levels_ && total > 0; ++l)
    for (int y = 0; y < p->tilesY(l); ++y)
      for (int x = 0; x < p->tilesX(l); ++x) {
        TileRecord& rec = m.index.records[m.levelStart[l] + std::size_t(y) * p->tilesX(l) + x];
        std::string err = m.buildTile({l, x, y}, rec);
        if (!err.empty() && writeError.empty()) {
          writeError = err;
          warn("tile cache folder " + dir + " cannot be written (" + err + "): keeping the coarse tiles of " +
               source->path() + " in memory this run");
        }
        ++done;
        if (show) {
          const int pct = int(100 * done / coarse);
          if (tty ? pct != shown : pct / 10 != shown / 10) {
            std::fprintf(stderr, "%sgeocean: building the tile cache of %s: %3d%% (level %d of %d)%s",
                         tty ? "\r" : "", source->path().c_str(), pct, l, p->levels_ - 1, tty ? "" : "\n");
            std::fflush(stderr);
            shown = pct;
          }
        }
      }
  if (show && tty) std::fprintf(stderr, "\n");
  if (total > 0) countKinds();
  m.index.dataBytes = m.store.size();
  p->stats_.storedBytes = m.index.dataBytes;
  p->stats_.inMemory = m.store.inMemory();
  if (!m.store.inMemory()) {
    // Data first, then the index: an index always names complete data.
    const std::string bytes = serializeTileIndex(m.index);
    const std::string tmpIndex = dir + "/index.tmp." + std::to_string(::getpid());
    std::FILE* f = std::fopen(tmpIndex.c_str(), "wb");
    bool ok = f && std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    int e = errno;
    if (f && std::fclose(f) != 0) ok = false, e = errno;
    std::error_code ec;
    if (ok) fs::rename(tmpData, dir + "/tiles", ec);
    if (ok && !ec) fs::rename(tmpIndex, dir + "/index", ec);
    if (!ok || ec) {
      warn("tile cache folder " + dir + ": the index cannot be written (" + (ec ? ec.message() : errnoText(e)) +
           "): the tiles of " + source->path() + " are used this run and rebuilt next time");
      fs::remove(tmpIndex, ec);
      fs::remove(tmpData, ec);
      fs::remove(dir + "/tiles", ec);
    } else {
      p->stats_.cachePath = dir;
      // From now on level 0 is read back from the cache, as a warm open would.
      m.level0Stored = p->stats_.level0Stored = true;
    }
  } else if (!tmpData.empty()) {
    std::error_code ec;
    fs::remove(tmpData, ec);
  }
  return p;
}

}  // namespace geocean::raster
