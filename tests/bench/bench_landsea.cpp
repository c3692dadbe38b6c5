// Land/sea classification throughput on the default 5' mask (in memory):
// the per-frame cost of classifying every vertex of a 512^2 grid.
#include "globe/raster/World.h"
#include "plugin/landsea/LandSea.h"

#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include <random>

using namespace geocean;

namespace {
const ocean::LandSea& landSea() {
  static const ocean::LandSea ls(raster::Raster::open(raster::defaultWorld().mask), nullptr);
  return ls;
}

// A 512 x 512 grid over a 20 x 20 degree view (coherent, like a frame) or
// uniformly random points (worst case for caches).
struct Points {
  std::vector<double> lat, lon;
  explicit Points(bool coherent) : lat(512 * 512), lon(512 * 512) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> ulat(-90, 90), ulon(-180, 180);
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x) {
        const std::size_t i = std::size_t(y) * 512 + x;
        lat[i] = coherent ? 30.0 + 20.0 * y / 512 : ulat(rng);
        lon[i] = coherent ? -20.0 + 20.0 * x / 512 : ulon(rng);
      }
  }
};

void classify(benchmark::State& state, bool coherent) {
  const auto& ls = landSea();
  const Points p(coherent);
  std::vector<ocean::Surface> out(p.lat.size());
  for (auto _ : state) {
    ls.classifyBatch(p.lat.data(), p.lon.data(), p.lat.size(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(p.lat.size()));
}

void classifyParallel(benchmark::State& state) {
  const auto& ls = landSea();
  const Points p(true);
  std::vector<ocean::Surface> out(p.lat.size());
  for (auto _ : state) {
    tbb::parallel_for(std::size_t(0), std::size_t(64), [&](std::size_t b) {
      const std::size_t s = b * 4096;
      ls.classifyBatch(p.lat.data() + s, p.lon.data() + s, 4096, out.data() + s);
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(p.lat.size()));
}

void waterCoverage(benchmark::State& state) {
  const auto& ls = landSea();
  const Points p(true);
  std::vector<float> out(p.lat.size());
  for (auto _ : state) {
    for (std::size_t i = 0; i < p.lat.size(); ++i) out[i] = ls.waterCoverage(p.lat[i], p.lon[i]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(p.lat.size()));
}
}  // namespace

BENCHMARK_CAPTURE(classify, grid512_coherent, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(classify, grid512_random, false)->Unit(benchmark::kMicrosecond);
BENCHMARK(classifyParallel)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(waterCoverage)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
