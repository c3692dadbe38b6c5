// The on-disk index of a tile pyramid's cache (globe/raster/TilePyramid.h):
// which source it was built from (path, size, mtime, a hash of the file's
// header and trailer), how it was built (value map, tile size) and where each
// stored tile's bytes lie in the data file. One small parser with a clean
// entry point, so a fuzzer can drive it (parseTileIndex).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace geocean::raster {

enum class TileKind : std::uint8_t {
  Empty = 0,     // every texel nodata: nothing stored, nothing to draw
  Constant = 1,  // one value per channel, stored raw (channels floats)
  Data = 2,      // tileSize^2 x channels float32, zlib-compressed
  // Stored form only (TilePyramid::kind says Data): a tile whose texels are
  // all integers 0..255 or NaN, zlib-compressed as [hasNaN, nanCode] and a
  // byte per texel (nanCode, unused by the texels, is NaN): a mask's
  // classes, 4x fewer bytes to deflate and inflate than float32.
  DataBytes = 3,
};

struct TileRecord {
  std::uint8_t level = 0;
  TileKind kind = TileKind::Empty;
  std::uint32_t x = 0, y = 0;
  std::uint64_t offset = 0;  // into the data file
  std::uint32_t bytes = 0;
};

// What identifies a source and a build. Two keys are equal when the cache
// can be reused.
struct TileCacheKey {
  std::string sourcePath;      // absolute
  std::uint64_t sourceBytes = 0;
  std::int64_t sourceMtimeNs = 0;
  std::uint64_t headerHash = 0;  // FNV-1a of the first and last 64 KiB
  std::string valueMap;          // what was applied to the texels before averaging
  std::uint32_t tileSize = 0, channels = 0, width = 0, height = 0, levels = 0;
  bool operator==(const TileCacheKey&) const = default;
};

struct TileIndex {
  TileCacheKey key;
  std::uint64_t dataBytes = 0;       // size of the data file the records point into
  std::vector<TileRecord> records;   // every tile of levels 0 .. levels-1, level-major, row-major
};

// Serialised form: magic, version, key, records, FNV-1a checksum of all before.
std::string serializeTileIndex(const TileIndex& index);
// Throws RasterError naming `name` and the field for anything malformed:
// bad magic/checksum, another format version ("format version N"), sizes out of range, record counts that do not
// match the levels, offsets past dataBytes, unknown kinds. Never reads past
// `size` bytes.
TileIndex parseTileIndex(const void* data, std::size_t size, const std::string& name);

// Tiles of a level: ceil(width / 2^level / tileSize) x the same for height.
std::uint32_t levelTexels(std::uint32_t n, int level);
std::uint32_t levelTiles(std::uint32_t n, int level, std::uint32_t tileSize);

// 64-bit FNV-1a.
std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = 1469598103934665603ull);

}  // namespace geocean::raster
