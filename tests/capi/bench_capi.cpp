// Cost of the C ABI boundary: the same batch queries through the plugin
// (snapshot pointer copy, catch-all, argument checks) and through the C++
// libraries directly, in one run. Built, not run by ctest; results in
// docs/PERFORMANCE.md ("Plugin C ABI").
#include "geocean/geocean_ocean.h"
#include "globe/raster/Raster.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/waves/SeaQuery.h"
#include "plugin/waves/WaveField.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

struct Points {
  std::vector<double> lat, lon;
  explicit Points(std::size_t n) : lat(n), lon(n) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> la(-80.0, 80.0), lo(-180.0, 180.0);
    for (std::size_t i = 0; i < n; ++i) lat[i] = la(rng), lon[i] = lo(rng);
  }
};

geocean_ocean* makeOcean(bool world) {
  geocean_ocean* o = nullptr;
  if (geocean_create(GEOCEAN_ABI_VERSION, &o) != GEOCEAN_OK) std::abort();
  setenv("GEOCEAN_DATA", GEOCEAN_DATA_DIR, 1);
  if (world && geocean_set_default_world(o) != GEOCEAN_OK) std::abort();
  geocean_sea_state s;
  geocean_sea_state_init(&s);
  if (geocean_set_sea_state(o, &s) != GEOCEAN_OK) std::abort();
  return o;
}

void BM_ClassCapi(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0));
  geocean_ocean* o = makeOcean(true);
  Points p(n);
  std::vector<uint8_t> out(n);
  for (auto _ : state) {
    geocean_query_class(o, n, p.lat.data(), p.lon.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  geocean_destroy(o);
}
BENCHMARK(BM_ClassCapi)->Arg(1)->Arg(4096);

void BM_ClassDirect(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0));
  const std::string d = GEOCEAN_DATA_DIR;
  geocean::ocean::LandSea ls(geocean::raster::Raster::open(d + "/landmask_5m.tif"),
                             geocean::raster::Raster::open(d + "/etopo_20m.tif"));
  Points p(n);
  std::vector<geocean::ocean::Surface> out(n);
  for (auto _ : state) {
    ls.classifyBatch(p.lat.data(), p.lon.data(), n, out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_ClassDirect)->Arg(1)->Arg(4096);

void BM_SeaSurfaceCapi(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0));
  geocean_ocean* o = makeOcean(false);  // deep ocean everywhere: the wave cost alone
  Points p(n);
  std::vector<double> h(n);
  double t = 0.0;
  for (auto _ : state) {
    geocean_query_sea_surface(o, n, p.lat.data(), p.lon.data(), t += 0.01, h.data(), nullptr, nullptr);
    benchmark::DoNotOptimize(h.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  geocean_destroy(o);
}
BENCHMARK(BM_SeaSurfaceCapi)->Arg(1)->Arg(1024);

void BM_SeaSurfaceDirect(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0));
  std::string error;
  const geocean::waves::SeaQuery q(*geocean::waves::WaveField::create(geocean::waves::Model::Noise, {}, error),
                                    nullptr);
  Points p(n);
  std::vector<geocean::waves::SeaQueryResult> r(n);
  double t = 0.0;
  for (auto _ : state) {
    t += 0.01;
    q.queryBatch(p.lat.data(), p.lon.data(), &t, false, n, r.data());
    benchmark::DoNotOptimize(r.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_SeaSurfaceDirect)->Arg(1)->Arg(1024);

}  // namespace

BENCHMARK_MAIN();
