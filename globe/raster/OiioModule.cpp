// geocean_oiio: the only code that links OpenImageIO, built as a module and
// loaded on demand by geocean_raster (see PixelSource.h for why).
#include "globe/raster/OiioModuleApi.h"
#include "globe/raster/PixelSource.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <mutex>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {
using geocean::raster::detail::SampleKind;

void setErr(char* err, std::size_t len, const std::string& msg) {
  if (err && len) std::snprintf(err, len, "%s", msg.c_str());
}

int kindOf(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8: return int(SampleKind::U8);
    case OIIO::TypeDesc::INT8: return int(SampleKind::I8);
    case OIIO::TypeDesc::UINT16: return int(SampleKind::U16);
    case OIIO::TypeDesc::INT16: return int(SampleKind::I16);
    case OIIO::TypeDesc::UINT32: return int(SampleKind::U32);
    case OIIO::TypeDesc::INT32: return int(SampleKind::I32);
    case OIIO::TypeDesc::FLOAT: return int(SampleKind::F32);
    case OIIO::TypeDesc::DOUBLE: return int(SampleKind::F64);
    default: return 0;
  }
}

// Native type to request so integers are not normalised; halfs read as float.
OIIO::TypeDesc readType(OIIO::TypeDesc t) { return kindOf(t) ? t : OIIO::TypeDesc(OIIO::TypeDesc::FLOAT); }

void liftSizeGuard() {
  // Geocean checks dimensions itself (naming them) before any allocation.
  static const bool once = OIIO::attribute("limits:imagesize_MB", 1 << 30);
  (void)once;
}

bool info(const char* path, GeoceanOiioInfo* out, char* err, std::size_t errLen) {
  liftSizeGuard();
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    const std::string why = OIIO::geterror();
    setErr(err, errLen, why.empty() ? "unknown format" : why);
    return false;
  }
  const OIIO::ImageSpec& s = in->spec();
  *out = {};
  out->width = s.width;
  out->height = s.height;
  out->channels = s.nchannels;
  out->depth = s.depth;
  out->tileW = s.tile_width;
  out->tileH = s.tile_height;
  out->kind = kindOf(s.format);
  std::snprintf(out->format, sizeof out->format, "%s", in->format_name());
  return true;
}

bool readAll(const char* path, float* out, char* err, std::size_t errLen) {
  liftSizeGuard();
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    setErr(err, errLen, OIIO::geterror());
    return false;
  }
  const OIIO::ImageSpec& s = in->spec();
  const OIIO::TypeDesc t = readType(s.format);
  const std::size_t n = std::size_t(s.width) * s.height * s.nchannels;
  std::vector<unsigned char> raw(n * t.size());
  if (!in->read_image(0, 0, 0, s.nchannels, t, raw.data())) {
    const std::string why = in->geterror();
    setErr(err, errLen, why.empty() ? "truncated or corrupt" : why);
    return false;
  }
  geocean::raster::detail::toFloat(SampleKind(kindOf(t)), raw.data(), n, out);
  return true;
}

// OpenImageIO 2.4's ImageCache answers a tile past the end of a file
// truncated under it with unwritten memory, get_pixels true and no error.
// So at every tile it reads from disk the file it opened is checked: our own descriptor of the same inode (a
// rename replacing the path leaves both on the old file, which stays right),
// its size and mtime against those at open. Once changed, every read fails
// (no data), cached tiles too: one tile read after the change may be
// garbage and is in the cache by then. A read racing that first miss in
// another thread is the only window left.
struct Cache {
  OIIO::ImageCache* cache = nullptr;
  OIIO::ustring file;
  OIIO::TypeDesc type;
  int fd = -1;
  struct stat atOpen {};
  std::atomic<int> tilesSeen{0};
  std::atomic<bool> changed{false};
  std::mutex whyMutex;
  std::string why;  // written once, under whyMutex, before `changed` is set
};

bool sameFile(const struct stat& a, const struct stat& b) {
  return a.st_size == b.st_size && a.st_mtim.tv_sec == b.st_mtim.tv_sec && a.st_mtim.tv_nsec == b.st_mtim.tv_nsec;
}

void* cacheCreate(const char* path, double maxMB, char* err, std::size_t errLen) {
  liftSizeGuard();
  auto* c = new Cache;
  c->cache = OIIO::ImageCache::create(/*shared=*/false);
  c->file = OIIO::ustring(path);
  c->fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (c->fd < 0 || ::fstat(c->fd, &c->atOpen) != 0) {
    setErr(err, errLen, std::string("cannot open: ") + std::strerror(errno));
    if (c->fd >= 0) ::close(c->fd);
    OIIO::ImageCache::destroy(c->cache);
    delete c;
    return nullptr;
  }
  c->cache->attribute("max_memory_MB", float(maxMB));
  c->cache->attribute("autotile", 256);  // scanline files are cached in tiles too
  c->cache->attribute("max_open_files", 4);
  const OIIO::ImageSpec* spec = c->cache->imagespec(c->file);
  if (!spec) {
    setErr(err, errLen, c->cache->geterror());
    ::close(c->fd);
    OIIO::ImageCache::destroy(c->cache);
    delete c;
    return nullptr;
  }
  c->type = readType(spec->format);
  return c;
}

// After a read: did a tile come from disk, and is the file still the one opened?
void checkFile(Cache* c) {
  // Tiles created, not the file's "stat:tilesread": a tile that failed to
  // read is created but not counted as read. One file per cache, so the
  // cache's count is the file's. 130 ns against 410 ns for a cached one-pixel
  // get_pixels on this machine; an fstat per read would cost 1,400 ns.
  int tiles = 0;
  if (!c->cache->getattribute("stat:tiles_created", tiles)) return;
  if (tiles == c->tilesSeen.load()) return;
  struct stat now {};
  const bool ok = ::fstat(c->fd, &now) == 0;
  if (!ok || !sameFile(now, c->atOpen)) {
    std::lock_guard lock(c->whyMutex);
    if (!c->changed.load()) {
      c->why = !ok ? std::string("cannot be checked (") + std::strerror(errno) + ")"
                   : "changed on disk while open (" + std::to_string((long long)c->atOpen.st_size) + " -> " +
                         std::to_string((long long)now.st_size) + " bytes, mtime " +
                         (now.st_mtim.tv_sec == c->atOpen.st_mtim.tv_sec &&
                                  now.st_mtim.tv_nsec == c->atOpen.st_mtim.tv_nsec
                              ? "same"
                              : "changed") +
                         "); no data until it is opened again";
      std::fprintf(stderr, "geocean: warning: %s: %s\n", c->file.c_str(), c->why.c_str());
      c->changed.store(true);
    }
  }
  c->tilesSeen.store(tiles);  // after `changed`: a reader that sees it also sees the flag
}

bool cacheRead(void* h, int x0, int x1, int y0, int y1, int ch, float* out, char* err, std::size_t errLen) {
  auto* c = static_cast<Cache*>(h);
  const std::size_t n = std::size_t(x1 - x0) * std::size_t(y1 - y0);
  thread_local std::vector<unsigned char> tmp;
  tmp.resize(n * c->type.size());
  const bool ok = c->cache->get_pixels(c->file, 0, 0, x0, x1, y0, y1, 0, 1, ch, ch + 1, c->type, tmp.data());
  // A tile that fails to decode can leave get_pixels true with the buffer
  // unwritten: the error says so when there is one; checkFile when not.
  const std::string e = c->cache->geterror();
  if (!ok || !e.empty()) {
    setErr(err, errLen, e.empty() ? std::string("read failed") : e);
    return false;
  }
  checkFile(c);
  if (c->changed.load()) {
    setErr(err, errLen, c->why.empty() ? std::string("changed on disk while open") : c->why);
    return false;
  }
  geocean::raster::detail::toFloat(SampleKind(kindOf(c->type)), tmp.data(), n, out);
  return true;
}

void cacheDestroy(void* h) {
  auto* c = static_cast<Cache*>(h);
  ::close(c->fd);
  OIIO::ImageCache::destroy(c->cache);
  delete c;
}

bool write8(const char* path, const unsigned char* data, int w, int h, int ch, char* err, std::size_t errLen) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    setErr(err, errLen, OIIO::geterror());
    return false;
  }
  OIIO::ImageSpec spec(w, h, ch, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, data) || !out->close()) {
    setErr(err, errLen, out->geterror());
    return false;
  }
  return true;
}

const GeoceanOiioApi kApi = {GEOCEAN_OIIO_MODULE_ABI, info, readAll, cacheCreate, cacheRead, cacheDestroy, write8};
}  // namespace

extern "C" __attribute__((visibility("default"))) const GeoceanOiioApi* geocean_oiio_api(void) { return &kApi; }
