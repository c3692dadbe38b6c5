// A tile pyramid over any raster (issue 12 item 2): a quadtree of
// tileSize^2-texel tiles. Level 0 is the raster itself (value map applied);
// level l+1 averages 2 x 2 texels of level l (nodata, NaN, ignored; NaN
// where all four are). Levels 1 and up are computed once, row by row from
// the source (never the whole raster in memory), and kept with level 0's
// tiles (stored as the build reads them) in an on-disk cache reused across
// runs, so a warm open never reads the source:
//   $GEOCEAN_TILE_CACHE, else $XDG_CACHE_HOME/geocean/tiles, else
//   ~/.cache/geocean/tiles; one folder per (source path, value map, tile
//   size) holding `index` (TileIndex.h) and `tiles`. The index names the
//   source's size, mtime and a hash of its first and last 64 KiB: a touched
//   or rewritten source is rebuilt in place.
// A cache folder that cannot be written (read-only, full, not a folder) is
// reported on stderr and the coarse tiles are kept in memory (compressed);
// level 0 is then read on demand from the source through its tiles or
// strips (as for a raster of one tile, or with no file).
// The value map is not applied to source tiles that are all nodata.
// Tiles that are all nodata are Empty, tiles of one value Constant: a
// sparse raster costs little to build, store or draw.
//
// Resident memory (residentBoundBytes) is the source's block cache (none
// when level 0 comes from the cache), the decoded-tile cache and the index
// (40 bytes per tile), plus, in the memory fallback, the compressed coarse
// tiles. It does not grow with the
// raster except through the index, and for strip (untiled) sources through
// the block cache, which must then hold 2 x tileSize full rows.
//
// Thread safety: all const methods may be called from any number of threads.
#pragma once

#include "globe/raster/Raster.h"
#include "globe/raster/TileIndex.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace geocean::raster {

struct TileId {
  int level = 0, x = 0, y = 0;
  bool operator==(const TileId&) const = default;
};

enum class BuildProgress {
  Auto,  // on stderr for builds of more than 1024 tiles ('\r' on a terminal, lines every 10% otherwise)
  Off,
};

struct PyramidOptions {
  int tileSize = 256;
  // "" : defaultTileCacheDir(). The pyramid's own folder is made below it.
  std::string cacheDir;
  // Applied to the level-0 texels (nodata already NaN), in place, before
  // anything is averaged: e.g. mask classes to water coverage. `valueMapId`
  // names it in the cache key: a different map is a different cache.
  std::function<void(float* texels, std::size_t count, int channels)> valueMap;
  std::string valueMapId;
  std::size_t sourceCacheBytes = std::size_t(32) << 20;  // decoded source blocks (native samples)
  // Decoded pyramid tiles kept (float, 256 KB each at 256^2): a bordered
  // tile reads its 3 x 3 neighbours, which 16 hold; the pools keep the rest.
  int decodedTiles = 16;
  BuildProgress progress = BuildProgress::Auto;
};

struct PyramidStats {
  bool builtNow = false;      // this open built the coarse levels (false: reused the cache)
  bool inMemory = false;      // the memory fallback (or a source with no file)
  std::string cachePath;      // the pyramid's folder ("" in memory)
  std::uint64_t storedBytes = 0;  // compressed tiles (level 0's too when level0Stored)
  bool level0Stored = false;      // level 0 is read from the cache, never from the source
  std::uint64_t tilesEmpty = 0, tilesConstant = 0, tilesData = 0;  // levels >= 1
};

// $GEOCEAN_TILE_CACHE, $XDG_CACHE_HOME/geocean/tiles or ~/.cache/geocean/tiles.
std::string defaultTileCacheDir();

class TilePyramid {
 public:
  // Opens or builds the pyramid of `source` (which must stay alive: level 0
  // reads go through it or its file). Throws RasterError naming the file
  // when the source cannot be read.
  static std::shared_ptr<const TilePyramid> open(std::shared_ptr<const Raster> source, PyramidOptions options = {});
  ~TilePyramid();

  int tileSize() const { return tileSize_; }
  int channels() const { return channels_; }
  int levels() const { return levels_; }  // level levels()-1 is one tile
  int levelWidth(int level) const;        // texels
  int levelHeight(int level) const;
  int tilesX(int level) const;
  int tilesY(int level) const;
  // Level l's texel (i, j) covers source pixels [i 2^l, (i+1) 2^l) x [j 2^l, (j+1) 2^l).
  GeoTransform levelTransform(int level) const;
  const Raster& source() const { return *source_; }

  // Empty: all nodata (nothing to draw). Constant tiles give their value.
  TileKind kind(TileId id) const;
  // The tile with a one-texel border for filtering: (tileSize+2)^2 x
  // channels floats, row-major from the tile's row -1, channels
  // interleaved. Border texels are the neighbours' (longitude wraps for a
  // global source, otherwise edges repeat); texels past the raster's edge
  // repeat its last row/column (or wrap). NaN where nodata.
  void readTile(TileId id, float* out) const;
  // The tile's texels without border (tileSize^2 x channels), NaN past the edge.
  std::shared_ptr<const std::vector<float>> interior(TileId id) const;

  // Data derived from the tiles (e.g. a grid resampled from a level),
  // kept in the cache folder beside them as `derived-<name>`, named by
  // the cache's source and build so a rebuilt cache never answers with
  // another source's: the bytes storeDerived stored under `name` for this
  // very cache, else nullopt (none, stale, corrupt: the caller computes
  // and stores again, or no cache folder: always nullopt). `name`:
  // [A-Za-z0-9._-], at most 100 characters.
  std::optional<std::vector<unsigned char>> derived(const std::string& name) const;
  // Best effort (deflated, written to a temporary file then renamed): a
  // cache that cannot be written is not an error, the next run computes
  // again. Nothing without a cache folder.
  void storeDerived(const std::string& name, const void* data, std::size_t bytes) const;

  const PyramidStats& stats() const { return stats_; }
  std::size_t residentBoundBytes() const;

  struct Impl;

 private:
  TileKind kindStored(TileId id) const;
  TilePyramid() = default;
  std::shared_ptr<const Raster> source_;
  int tileSize_ = 256, channels_ = 1, levels_ = 1;
  PyramidStats stats_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace geocean::raster
