// Tile pyramid (globe/raster/TilePyramid): building the coarse levels of a
// 10800 x 5400 uint8 GeoTIFF (a 2' world, 58 M pixels) against the reference
// of decoding every source tile once (libtiff through Raster, the least a
// build must do); opening with a warm cache; reading bordered tiles; and
// gl::TilePool's throughput (load on its workers, upload into the texture
// array) against reading the same tiles on one thread.
// Run by hand: build/tests/bench/bench_tiles; ratios go to docs/PERFORMANCE.md.
#include "globe/gl/HeadlessContext.h"
#include "globe/gl/TilePool.h"
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/Raster.h"
#include "globe/raster/TilePyramid.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace geocean::raster;
namespace fs = std::filesystem;

namespace {
constexpr int kW = 10800, kH = 5400;

const std::string& source() {
  static const std::string path = [] {
    const fs::path dir = fs::temp_directory_path() / "geocean-bench-tiles";
    fs::create_directories(dir);
    const std::string p = (dir / "world2m.tif").string();
    GeoTiffWriteOptions o;
    o.transform.lonStepDeg = 360.0 / kW;
    o.transform.latStepDeg = -180.0 / kH;
    o.deflateLevel = 1;
    writeGeoTiffTiles(p, kW, kH, 1, SampleType::U8, o, [](int x0, int y0, void* tile) {
      auto* v = static_cast<std::uint8_t*>(tile);
      for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) v[y * 256 + x] = std::uint8_t((((x0 + x) >> 3) ^ ((y0 + y) >> 3)) & 1);
    });
    return p;
  }();
  return path;
}

PyramidOptions options(const std::string& cache) {
  PyramidOptions o;
  o.cacheDir = cache;
  o.progress = BuildProgress::Off;
  return o;
}

const std::string kCache = (fs::temp_directory_path() / "geocean-bench-tiles" / "cache").string();

// Reference: every pixel decoded once, in tile order (what any build reads).
void BM_DecodeAllTiles(benchmark::State& state) {
  OpenOptions ro;
  ro.fewLookups = true;
  for (auto _ : state) {
    auto r = Raster::open(source(), ro);
    double sum = 0;
    for (int ty = 0; ty < kH; ty += 256)
      for (int tx = 0; tx < kW; tx += 256)
        for (int y = ty; y < std::min(ty + 256, kH); ++y)
          for (int x = tx; x < std::min(tx + 256, kW); ++x) sum += r->pixel(x, y);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(kW) * kH);
}
BENCHMARK(BM_DecodeAllTiles)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_PyramidBuildCold(benchmark::State& state) {
  auto r = Raster::open(source());
  for (auto _ : state) {
    fs::remove_all(kCache);
    auto p = TilePyramid::open(r, options(kCache));
    benchmark::DoNotOptimize(p->stats().storedBytes);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(kW) * kH);
}
BENCHMARK(BM_PyramidBuildCold)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_PyramidOpenWarm(benchmark::State& state) {
  auto r = Raster::open(source());
  TilePyramid::open(r, options(kCache));
  for (auto _ : state) {
    auto p = TilePyramid::open(r, options(kCache));
    if (p->stats().builtNow) state.SkipWithError("rebuilt");
  }
}
BENCHMARK(BM_PyramidOpenWarm)->Unit(benchmark::kMillisecond);

// Bordered 258^2 tiles: level 0 (from the source) and level 2 (cache).
void BM_ReadTile(benchmark::State& state) {
  auto r = Raster::open(source());
  auto p = TilePyramid::open(r, options(kCache));
  const int level = int(state.range(0));
  std::vector<float> t(258 * 258);
  int i = 0;
  for (auto _ : state) {
    // Distinct tiles round-robin (more than the 64 decoded ones kept).
    const int n = p->tilesX(level) * p->tilesY(level);
    const int k = (i++ * 7) % n;
    p->readTile({level, k % p->tilesX(level), k / p->tilesX(level)}, t.data());
    benchmark::DoNotOptimize(t.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ReadTile)->Arg(0)->Arg(2)->Unit(benchmark::kMicrosecond);

// gl::TilePool (llvmpipe, EGL surfaceless): 128 distinct level-0 tiles
// asked for at once, until all are resident (workers decode and border
// them, endFrame uploads 16 a frame as R8), in a fresh pool each time;
// the reference is BM_ReadTile(0)'s single-thread read of the same tiles.
void BM_TilePoolLoadAndUpload(benchmark::State& state) {
  static std::unique_ptr<geocean::gl::HeadlessContext> ctx = [] {
    std::string err;
    auto c = geocean::gl::HeadlessContext::create(err, false);
    if (!c) throw std::runtime_error("no headless OpenGL context: " + err);
    return c;
  }();
  auto p = TilePyramid::open(Raster::open(source()), options(kCache));
  constexpr int kTiles = 128;
  int first = 0;
  for (auto _ : state) {
    geocean::gl::TilePool pool(p);
    const int n = p->tilesX(0) * p->tilesY(0);
    std::vector<TileId> want;
    for (int i = 0; i < kTiles; ++i) {
      const int k = (first + i * 7) % n;
      want.push_back({0, k % p->tilesX(0), k / p->tilesX(0)});
    }
    first += kTiles * 7;
    // Asked for again every frame, as a drawer does (the pool forgets
    // requests older than two frames).
    for (int frame = 0;; ++frame) {
      int missing = 0;
      for (const TileId& id : want)
        if (pool.residentSlot(id) < 0) ++missing, pool.request(id);
      if (missing == 0) break;
      if (frame > 100000) {
        state.SkipWithError("tiles never arrived");
        break;
      }
      pool.waitIdle();
      pool.endFrame();
    }
    glFinish();
  }
  state.SetItemsProcessed(state.iterations() * kTiles);
}
BENCHMARK(BM_TilePoolLoadAndUpload)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
