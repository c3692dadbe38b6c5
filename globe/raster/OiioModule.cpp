// geocean_oiio: the only code that links OpenImageIO, built as a module and
// loaded on demand by geocean_raster (see PixelSource.h for why).
#include "globe/raster/OiioModuleApi.h"
#include "globe/raster/PixelSource.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>

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

struct Cache {
  OIIO::ImageCache* cache;
  OIIO::ustring file;
  OIIO::TypeDesc type;
};

void* cacheCreate(const char* path, double maxMB, char* err, std::size_t errLen) {
  liftSizeGuard();
  auto* c = new Cache{OIIO::ImageCache::create(/*shared=*/false), OIIO::ustring(path), {}};
  c->cache->attribute("max_memory_MB", float(maxMB));
  c->cache->attribute("autotile", 256);  // scanline files are cached in tiles too
  c->cache->attribute("max_open_files", 4);
  const OIIO::ImageSpec* spec = c->cache->imagespec(c->file);
  if (!spec) {
    setErr(err, errLen, c->cache->geterror());
    OIIO::ImageCache::destroy(c->cache);
    delete c;
    return nullptr;
  }
  c->type = readType(spec->format);
  return c;
}

bool cacheRead(void* h, int x0, int x1, int y0, int y1, int ch, float* out, char* err, std::size_t errLen) {
  auto* c = static_cast<Cache*>(h);
  const std::size_t n = std::size_t(x1 - x0) * std::size_t(y1 - y0);
  thread_local std::vector<unsigned char> tmp;
  tmp.resize(n * c->type.size());
  const bool ok = c->cache->get_pixels(c->file, 0, 0, x0, x1, y0, y1, 0, 1, ch, ch + 1, c->type, tmp.data());
  // A tile that fails to decode (the file truncated under the cache) can
  // leave get_pixels true with the buffer unwritten: the error says so.
  const std::string e = c->cache->geterror();
  if (!ok || !e.empty()) {
    setErr(err, errLen, e.empty() ? std::string("read failed") : e);
    return false;
  }
  geocean::raster::detail::toFloat(SampleKind(kindOf(c->type)), tmp.data(), n, out);
  return true;
}

void cacheDestroy(void* h) {
  auto* c = static_cast<Cache*>(h);
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
