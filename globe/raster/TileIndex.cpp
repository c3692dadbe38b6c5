#include "globe/raster/TileIndex.h"

#include "globe/raster/Raster.h"

#include <cstring>

namespace geocean::raster {

namespace {
constexpr char kMagic[8] = {'G', 'E', 'O', 'T', 'I', 'L', 'E', 'S'};
// 2: level 0's tiles are stored too (valueMap applied), version 1 had levels 1 and up.
constexpr std::uint32_t kVersion = 2;
constexpr std::uint32_t kMaxString = 4096;

struct Writer {
  std::string out;
  template <class T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));
  }
  void str(const std::string& s) {
    put<std::uint32_t>(std::uint32_t(s.size()));
    out += s;
  }
};

struct Reader {
  const unsigned char* p;
  std::size_t n, at = 0;
  const std::string& name;
  [[noreturn]] void fail(const std::string& what) const {
    throw RasterError(name + ": tile cache index is corrupt: " + what + " (at byte " + std::to_string(at) + ")");
  }
  template <class T>
  T get(const char* field) {
    if (n - at < sizeof(T)) fail(std::string("truncated in field '") + field + "'");
    T v;
    std::memcpy(&v, p + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  std::string str(const char* field) {
    const auto len = get<std::uint32_t>(field);
    if (len > kMaxString) fail(std::string("field '") + field + "' length " + std::to_string(len) + " > " +
                               std::to_string(kMaxString));
    if (n - at < len) fail(std::string("truncated in field '") + field + "'");
    std::string s(reinterpret_cast<const char*>(p + at), len);
    at += len;
    return s;
  }
};
}  // namespace

std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::uint32_t levelTexels(std::uint32_t n, int level) {
  const std::uint64_t s = std::uint64_t(1) << level;
  return std::uint32_t((std::uint64_t(n) + s - 1) / s);
}

std::uint32_t levelTiles(std::uint32_t n, int level, std::uint32_t tileSize) {
  return (levelTexels(n, level) + tileSize - 1) / tileSize;
}

std::string serializeTileIndex(const TileIndex& index) {
  Writer w;
  w.out.append(kMagic, sizeof kMagic);
  w.put(kVersion);
  const TileCacheKey& k = index.key;
  w.str(k.sourcePath);
  w.put(k.sourceBytes);
  w.put(k.sourceMtimeNs);
  w.put(k.headerHash);
  w.str(k.valueMap);
  w.put(k.tileSize);
  w.put(k.channels);
  w.put(k.width);
  w.put(k.height);
  w.put(k.levels);
  w.put(index.dataBytes);
  w.put<std::uint64_t>(index.records.size());
  for (const TileRecord& r : index.records) {
    w.put(r.level);
    w.put(std::uint8_t(r.kind));
    w.put(r.x);
    w.put(r.y);
    w.put(r.offset);
    w.put(r.bytes);
  }
  w.put(fnv1a(w.out.data(), w.out.size()));
  return w.out;
}

TileIndex parseTileIndex(const void* data, std::size_t size, const std::string& name) {
  Reader r{static_cast<const unsigned char*>(data), size, 0, name};
  if (size < sizeof kMagic + 8 || std::memcmp(data, kMagic, sizeof kMagic) != 0) r.fail("no GEOTILES magic");
  {
    std::uint64_t stored;
    std::memcpy(&stored, r.p + size - 8, 8);
    if (stored != fnv1a(data, size - 8)) r.fail("checksum mismatch");
    r.n = size - 8;
  }
  r.at = sizeof kMagic;
  if (const auto v = r.get<std::uint32_t>("version"); v != kVersion)
    throw RasterError(name + ": tile cache index has format version " + std::to_string(v) + ", this build reads " +
                      std::to_string(kVersion));
  TileIndex idx;
  TileCacheKey& k = idx.key;
  k.sourcePath = r.str("sourcePath");
  k.sourceBytes = r.get<std::uint64_t>("sourceBytes");
  k.sourceMtimeNs = r.get<std::int64_t>("sourceMtimeNs");
  k.headerHash = r.get<std::uint64_t>("headerHash");
  k.valueMap = r.str("valueMap");
  k.tileSize = r.get<std::uint32_t>("tileSize");
  k.channels = r.get<std::uint32_t>("channels");
  k.width = r.get<std::uint32_t>("width");
  k.height = r.get<std::uint32_t>("height");
  k.levels = r.get<std::uint32_t>("levels");
  if (k.tileSize < 8 || k.tileSize > 4096) r.fail("tileSize " + std::to_string(k.tileSize));
  if (k.channels < 1 || k.channels > 4) r.fail("channels " + std::to_string(k.channels));
  if (k.width < 1 || k.height < 1 || k.width > (1u << 24) || k.height > (1u << 24))
    r.fail("size " + std::to_string(k.width) + " x " + std::to_string(k.height));
  if (k.levels < 1 || k.levels > 26) r.fail("levels " + std::to_string(k.levels));
  // The top level is the first that fits in one tile.
  if (levelTiles(k.width, int(k.levels) - 1, k.tileSize) != 1 || levelTiles(k.height, int(k.levels) - 1, k.tileSize) != 1 ||
      (k.levels > 1 && levelTiles(k.width, int(k.levels) - 2, k.tileSize) == 1 &&
       levelTiles(k.height, int(k.levels) - 2, k.tileSize) == 1))
    r.fail("levels " + std::to_string(k.levels) + " do not fit size " + std::to_string(k.width) + " x " +
           std::to_string(k.height));
  idx.dataBytes = r.get<std::uint64_t>("dataBytes");
  std::uint64_t expected = 0;
  for (std::uint32_t l = 0; l < k.levels; ++l)
    expected += std::uint64_t(levelTiles(k.width, int(l), k.tileSize)) * levelTiles(k.height, int(l), k.tileSize);
  const auto count = r.get<std::uint64_t>("recordCount");
  if (count != expected)
    r.fail("recordCount " + std::to_string(count) + ", the levels need " + std::to_string(expected));
  constexpr std::size_t kRecordBytes = 1 + 1 + 4 + 4 + 8 + 4;
  if ((r.n - r.at) / kRecordBytes < count) r.fail("truncated records");
  idx.records.resize(count);
  std::size_t i = 0;
  const std::uint64_t tileBytes = std::uint64_t(k.tileSize) * k.tileSize * k.channels * 4;
  for (std::uint32_t l = 0; l < k.levels; ++l) {
    const std::uint32_t tx = levelTiles(k.width, int(l), k.tileSize), ty = levelTiles(k.height, int(l), k.tileSize);
    for (std::uint32_t y = 0; y < ty; ++y)
      for (std::uint32_t x = 0; x < tx; ++x, ++i) {
        TileRecord& rec = idx.records[i];
        rec.level = r.get<std::uint8_t>("level");
        const auto kind = r.get<std::uint8_t>("kind");
        rec.x = r.get<std::uint32_t>("x");
        rec.y = r.get<std::uint32_t>("y");
        rec.offset = r.get<std::uint64_t>("offset");
        rec.bytes = r.get<std::uint32_t>("bytes");
        const std::string at = "record " + std::to_string(i) + " ";
        if (rec.level != l || rec.x != x || rec.y != y)
          r.fail(at + "is tile " + std::to_string(rec.level) + "/" + std::to_string(rec.x) + "/" +
                 std::to_string(rec.y) + ", expected " + std::to_string(l) + "/" + std::to_string(x) + "/" +
                 std::to_string(y));
        if (kind > 3) r.fail(at + "kind " + std::to_string(kind));
        rec.kind = TileKind(kind);
        if (rec.kind == TileKind::Empty && rec.bytes != 0) r.fail(at + "empty with bytes " + std::to_string(rec.bytes));
        if (rec.kind == TileKind::Constant && rec.bytes != 4 * k.channels)
          r.fail(at + "constant with bytes " + std::to_string(rec.bytes));
        if ((rec.kind == TileKind::Data || rec.kind == TileKind::DataBytes) &&
            (rec.bytes == 0 || rec.bytes > tileBytes + tileBytes / 8 + 1024))
          r.fail(at + "data with bytes " + std::to_string(rec.bytes));
        if (rec.offset > idx.dataBytes || idx.dataBytes - rec.offset < rec.bytes)
          r.fail(at + "offset " + std::to_string(rec.offset) + " + " + std::to_string(rec.bytes) +
                 " past the data's " + std::to_string(idx.dataBytes) + " bytes");
      }
  }
  if (r.at != r.n) r.fail(std::to_string(r.n - r.at) + " trailing bytes");
  return idx;
}

}  // namespace geocean::raster
