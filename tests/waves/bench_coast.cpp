// Cost of the near-shore terms (issue 15 item 8), in one run: the Gerstner
// sea-height query (WaveField::surfaceAt, scalar double) at the same 4096
// points over a planar shelf without a coast field (the deep-water phase with
// local shoaling: the reference) and with one (depth-dependent phase,
// refraction, Kr, Miche), and the coast field's CPU build time for 16
// components, and the island table's build on CPU and GPU. Not run by ctest; results in docs/PERFORMANCE.md.
#include "globe/geo/Ellipsoid.h"
#include "globe/gl/HeadlessContext.h"
#include "plugin/render/CoastIslandsGpu.h"
#include "plugin/waves/CoastField.h"
#include "plugin/waves/WaveField.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

using namespace geocean::waves;
namespace geo = geocean::geo;

namespace {
double shelfDepth(double e, double) { return std::clamp(0.02 * (3000.0 - e), 0.5, 200.0); }

SeaState sea() {
  SeaState s;
  s.windSpeedMps = 15.0;
  s.windFromDeg = 250.0;
  s.anchorLatDeg = 0.3;
  s.anchorLonDeg = 0.3;
  return s;
}

CoastField::Region region(int nodes) {
  CoastField::Region r;
  r.latDeg = 0.3;
  r.lonDeg = 0.3;
  r.nodes = nodes;
  r.cellM = 10000.0 / (nodes - 1);  // a 10 km square
  return r;
}

struct Points {
  std::vector<double> lat, lon, depth;
};
// 4096 points over the shelf (east -4.9 .. 2.9 km, depth 156 .. 2 m).
Points points(const CoastField& c, bool deep) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> e(-4900.0, 2900.0), n(-4900.0, 4900.0);
  Points p;
  for (int i = 0; i < 4096; ++i) {
    const double x = deep ? e(rng) - 6000.0 : e(rng), y = n(rng);
    const geo::Geodetic g = geo::fromEcef(c.centreEcef() + c.east() * x + c.north() * y);
    p.lat.push_back(g.latDeg);
    p.lon.push_back(g.lonDeg);
    p.depth.push_back(deep ? 4000.0 : shelfDepth(x, y));
  }
  return p;
}
}  // namespace

// Arg 0: no coast field, 1: with a coast field (201^2 nodes), over the shelf.
void BM_ShelfQuery(benchmark::State& state) {
  std::string err;
  WaveField w = *WaveField::create(Model::Gerstner, sea(), err);
  auto coast = std::make_shared<const CoastField>(CoastField::build(w, region(201), shelfDepth, err));
  const Points p = points(*coast, false);
  if (state.range(0) == 1) w.setCoast(coast);
  std::size_t i = 0;
  double sum = 0.0;
  for (auto _ : state) {
    sum += w.surfaceAt(p.lat[i], p.lon[i], 3.5, p.depth[i]).heightM;
    i = (i + 1) & 4095;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShelfQuery)->Arg(0)->Arg(1);

// The same points with a field built over 4 km of water everywhere (all its
// nodes 0): what the field costs where it changes nothing. Arg as above.
void BM_DeepQuery(benchmark::State& state) {
  std::string err;
  WaveField w = *WaveField::create(Model::Gerstner, sea(), err);
  auto deepEverywhere = [](double, double) { return 4000.0; };
  auto coast = std::make_shared<const CoastField>(CoastField::build(w, region(201), deepEverywhere, err));
  Points p = points(*coast, false);
  for (auto& d : p.depth) d = 4000.0;
  if (state.range(0) == 1) w.setCoast(coast);
  std::size_t i = 0;
  double sum = 0.0;
  for (auto _ : state) {
    sum += w.surfaceAt(p.lat[i], p.lon[i], 3.5, p.depth[i]).heightM;
    i = (i + 1) & 4095;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DeepQuery)->Arg(0)->Arg(1);

// Curl and breaking (paper 003 eq. 5-6): 4096 points 3 .. 8 m deep on a
// plunging beach (slope 0.1, Iribarren 0.62: curl on every shallow
// component, collapse and foam where the cap acts), field 201^2 nodes of
// 2 m. Arg 0: the field built with Region::breaking = false (the same
// field, curl and collapse weights 0: the terms skipped), 1: with them, 2:
// no field (reference-depth phase + local shoaling). Counter evals: kernel
// evaluations per query (the inversion's).
void BM_BreakingQuery(benchmark::State& state) {
  std::string err;
  WaveField w = *WaveField::create(Model::Gerstner, sea(), err);
  const double slope = 0.1;
  auto beach = [slope](double e, double) { return slope * (150.0 - e); };
  CoastField::Region r = region(201);
  r.cellM = 2.0;
  r.islandRadiusM = 8.0;
  r.breaking = state.range(0) != 0;
  auto coast = std::make_shared<const CoastField>(CoastField::build(w, r, beach, err));
  if (state.range(0) != 2) w.setCoast(coast);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> h(3.0, 8.0), n(-150.0, 150.0);
  Points p;
  for (int i = 0; i < 4096; ++i) {
    const double d = h(rng), x = 150.0 - d / slope;
    const geo::Geodetic g = geo::fromEcef(coast->centreEcef() + coast->east() * x + coast->north() * n(rng));
    p.lat.push_back(g.latDeg);
    p.lon.push_back(g.lonDeg);
    p.depth.push_back(d);
  }
  std::size_t i = 0;
  double sum = 0.0, evals = 0.0;
  for (auto _ : state) {
    const SurfacePoint sp = w.surfaceAt(p.lat[i], p.lon[i], 3.5, p.depth[i]);
    sum += sp.heightM;
    evals += sp.iterations + 1;  // the first evaluation and one per step
    i = (i + 1) & 4095;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
  state.counters["evals"] = evals / double(state.iterations());
}
BENCHMARK(BM_BreakingQuery)->Arg(0)->Arg(1)->Arg(2);

// Building the field on the CPU: 16 components, N^2 nodes over 10 km.
void BM_CoastBuild(benchmark::State& state) {
  std::string err;
  const WaveField w = *WaveField::create(Model::Gerstner, sea(), err);
  for (auto _ : state) benchmark::DoNotOptimize(CoastField::build(w, region(int(state.range(0))), shelfDepth, err));
}
BENCHMARK(BM_CoastBuild)->Arg(201)->Arg(401)->Unit(benchmark::kMillisecond);

// The island table (paper 003 sec. 3) over a round island of 1 km radius in
// 30 m of water, 10 km square: Args (nodes per side, components). CPU: the
// table alone (CoastField::islandTable, TBB over rows); GPU: the compute
// shader on this machine's GL (llvmpipe here), including its compile, upload
// and read-back (plugin/render/CoastIslandsGpu). 513^2 x 3 is the paper's case.
double islandDepth(double e, double n) { return std::hypot(e, n) < 1000.0 ? -5.0 : 30.0; }

CoastField::IslandInputs islandInputs(int nodes, int comps) {
  SeaState s = sea();
  s.gerstnerComponents = comps;
  std::string err;
  const WaveField w = *WaveField::create(Model::Gerstner, s, err);
  CoastField::Region r = region(nodes);
  // The field's own inputs (the build also runs the eikonal; only the table is timed).
  return CoastField::build(w, r, islandDepth, err).islandInputs();
}

void BM_IslandTableCpu(benchmark::State& state) {
  const CoastField::IslandInputs in = islandInputs(int(state.range(0)), int(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(CoastField::islandTable(in));
}
BENCHMARK(BM_IslandTableCpu)->Args({201, 16})->Args({513, 3})->Args({513, 16})->Unit(benchmark::kMillisecond);

void BM_IslandTableGpu(benchmark::State& state) {
  std::string err;
  auto ctx = geocean::gl::HeadlessContext::create(err);
  if (!ctx) {
    state.SkipWithError(err.c_str());
    return;
  }
  const CoastField::IslandInputs in = islandInputs(int(state.range(0)), int(state.range(1)));
  for (auto _ : state) {
    auto t = geocean::ocean_render::buildIslandTableGpu(in, err);
    if (t.empty()) state.SkipWithError(err.c_str());
    benchmark::DoNotOptimize(t);
  }
}
BENCHMARK(BM_IslandTableGpu)->Args({201, 16})->Args({513, 3})->Args({513, 16})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
