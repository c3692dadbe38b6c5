// libFuzzer: any bytes as a tile pyramid's on-disk cache index
// (globe/raster/TileIndex.cpp parseTileIndex), then TilePyramid::open of a
// small source (TileIndexSource.h) over a cache folder holding that index
// and a data file of the size it names, and every coarse tile read back.
// Contract (TileIndex.h, TilePyramid.h): the parser returns an index that
// serialises back to the same bytes or throws RasterError; the pyramid
// either reuses the cache (any RasterError on a tile read is allowed: the
// data file is the real one cut or padded to the fuzzed size) or rebuilds
// it with a warning, and then every tile equals the pyramid built from the
// source; no other exception, no memory error, no undefined behaviour.
#include "globe/raster/Raster.h"
#include "globe/raster/TileIndex.h"
#include "globe/raster/TilePyramid.h"
#include "tests/fuzz/FuzzSupport.h"
#include "tests/fuzz/TileIndexSource.h"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

using namespace geocean::raster;
namespace fs = std::filesystem;

namespace {

std::string gRoot;  // removed at exit (a global: destroyed after the atexit handler ran)

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

// Every coarse tile with its border, NaN-aware: bit patterns.
std::vector<std::uint32_t> allTiles(const TilePyramid& p) {
  std::vector<std::uint32_t> out;
  std::vector<float> t(std::size_t(p.tileSize() + 2) * (p.tileSize() + 2) * p.channels());
  for (int l = 1; l < p.levels(); ++l)
    for (int y = 0; y < p.tilesY(l); ++y)
      for (int x = 0; x < p.tilesX(l); ++x) {
        out.push_back(std::uint32_t(p.kind({l, x, y})));
        p.readTile({l, x, y}, t.data());
        for (float v : t) {
          std::uint32_t b;
          std::memcpy(&b, &v, 4);
          out.push_back(v != v ? 0x7fc00000u : b);  // any NaN is "no data"
        }
      }
  return out;
}

struct Fixture {
  std::string root, source, cacheDir, index, tiles;
  TileCacheKey key;
  std::vector<std::uint32_t> reference;
  std::shared_ptr<const Raster> raster;

  Fixture() {
    const std::string base = geocean::fuzz::scratchPath("tile_index", "");
    root = base + ".d";
    fs::create_directories(root);
    gRoot = root;
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(gRoot, ec);
    });
    source = root + "/src.tif";
    geocean::fuzz::writeTileIndexSource(source);
    raster = Raster::open(source);
    auto p = TilePyramid::open(raster, geocean::fuzz::tileIndexPyramidOptions(root + "/cache"));
    cacheDir = p->stats().cachePath;
    if (cacheDir.empty() || !p->stats().builtNow) std::abort();
    index = readAll(cacheDir + "/index");
    key = parseTileIndex(index.data(), index.size(), "startup index").key;
    tiles = readAll(cacheDir + "/tiles");
    reference = allTiles(*p);
  }
  static Fixture& fixture();
};

Fixture& Fixture::fixture() {
  static Fixture f;
  return f;
}

// A parsed index must serialise to exactly the bytes it came from.
void checkRoundTrip(const TileIndex& idx, const std::string& bytes) {
  if (serializeTileIndex(idx) != bytes) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Fixture& fx = Fixture::fixture();
  std::string bytes(reinterpret_cast<const char*>(data), size);
  // 1. The bytes as they are (the checksum rejects almost every mutation).
  try {
    checkRoundTrip(parseTileIndex(bytes.data(), bytes.size(), "fuzz index"), bytes);
  } catch (const RasterError&) {
  }
  // 2. With the checksum made right, so mutations reach every field.
  if (size < 16) return 0;
  const std::uint64_t sum = fnv1a(bytes.data(), size - 8);
  std::memcpy(bytes.data() + size - 8, &sum, 8);
  TileIndex idx;
  try {
    idx = parseTileIndex(bytes.data(), bytes.size(), "fuzz index");
  } catch (const RasterError&) {
    return 0;
  }
  checkRoundTrip(idx, bytes);
  // 3. As the cache of the fixture's source: its identity, the fuzzed build
  // (value map, tile size, sizes, levels) and records.
  if (idx.dataBytes > (std::uint64_t(1) << 22)) return 0;  // the fuzzer's disk budget, not a limit of the code
  idx.key.sourcePath = fx.key.sourcePath;
  idx.key.sourceBytes = fx.key.sourceBytes;
  idx.key.sourceMtimeNs = fx.key.sourceMtimeNs;
  idx.key.headerHash = fx.key.headerHash;
  const std::string index = serializeTileIndex(idx);
  std::string tiles = fx.tiles;
  tiles.resize(std::size_t(idx.dataBytes), '\0');
  geocean::fuzz::writeFile(fx.cacheDir + "/index", reinterpret_cast<const std::uint8_t*>(index.data()), index.size());
  geocean::fuzz::writeFile(fx.cacheDir + "/tiles", reinterpret_cast<const std::uint8_t*>(tiles.data()), tiles.size());
  std::shared_ptr<const TilePyramid> p;
  try {
    p = TilePyramid::open(fx.raster, geocean::fuzz::tileIndexPyramidOptions(fx.root + "/cache"));
  } catch (const RasterError&) {
    std::abort();  // the source is readable: an index is reused or rebuilt, never an error
  }
  if (p->levels() != 4 || p->tileSize() != geocean::fuzz::kPyramidTile) std::abort();
  try {
    const auto got = allTiles(*p);
    // A rebuilt pyramid, or the real index reused, answers the source's values.
    if ((p->stats().builtNow || (index == fx.index && tiles == fx.tiles)) &&
        got != fx.reference)
      std::abort();
  } catch (const RasterError&) {
    if (p->stats().builtNow) std::abort();
  }
  return 0;
}
