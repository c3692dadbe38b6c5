// Sea-height query throughput per model, one thread and the TBB batch on all
// threads, with each rate as a fraction of the floating-point limit for the
// operations a query needs. Not run by ctest; results in docs/PERFORMANCE.md.
//
// Flops per query are counted by hand from shaders/waves.glsl and
// WaveField.cpp (adds, muls, compares-as-selects each 1; sqrt, division 1;
// each libm sin/cos/atan2/fmod call 20, about its polynomial's length):
//  - solid noise, per octave: lattice coordinate at the origin 21, floor and
//    fraction 6, patch-relative offset 24, wv_perlin3 268 (fade 39, eight
//    corner dot products 56, interpolation of value 39 and gradient 134),
//    accumulation 28: 347. Per query: frame, ECEF and ENU 200. 8 octaves: 2976.
//  - Gerstner, per component: patch data at the point (waveAt) 65; one
//    kernel evaluation 220 (arc offset 40, small-angle atan 16, direction 45,
//    sin+cos 40, taper 10, accumulation 69). Per evaluation 200 more; the
//    query evaluates 1 + iterations times (counter "iter").
//  - paper noise, per octave: 2D noise 110 + accumulation 20; per query 120.
//  - FFT: plane entries at the point 120; per evaluation 60 (frame, weights)
//    + per plane (2 on average at most) 100 + per cascade 140 (8 texel
//    fetches, bilinear value, u and v derivatives, velocity): 820; the
//    query evaluates 1 + iterations times. All queries at one time (the
//    tables are cached per time; BM_FftTables is the cost of a new time).
#include "plugin/waves/SeaQuery.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <random>
#include <vector>

using namespace geocean::waves;

namespace {
// PLATFORM.md: 65 GFLOP/s double per core with 256-bit FMA (AVX2). The
// library is built for the x86-64-v2 baseline (SSE4.2, no FMA: 2-wide add +
// 2-wide mul per cycle, a quarter of that).
constexpr double kPeakFlopsPerCore = 65e9;

struct Points {
  std::vector<double> lat, lon, t;
  explicit Points(std::size_t n) : lat(n), lon(n), t(n) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1), l(-180, 180), tt(0, 3600);
    for (std::size_t i = 0; i < n; ++i) lat[i] = std::asin(u(rng)) * 180 / M_PI, lon[i] = l(rng), t[i] = tt(rng);
  }
};

WaveField field(Model m) {
  std::string err;
  return *WaveField::create(m, SeaState{}, err);
}

double flopsPerQuery(Model m, double iterations) {
  switch (m) {
    case Model::Noise: return 200.0 + 8 * 347.0;
    case Model::NoisePaper: return 120.0 + 8 * 130.0;
    case Model::Gerstner: return 16 * 65.0 + (1.0 + iterations) * (200.0 + 16 * 220.0);
    case Model::Fft: return 120.0 + (1.0 + iterations) * 820.0;
  }
  return 0;
}

void report(benchmark::State& state, Model m, double queries, double iterations, int threads) {
  state.SetItemsProcessed(int64_t(queries));
  state.counters["iter"] = iterations;
  state.counters["flop/query"] = flopsPerQuery(m, iterations);
  // Fraction of the FP limit reached: (queries/s * flops/query) / (cores * peak).
  state.counters["of_fp_limit"] = benchmark::Counter(
      queries * flopsPerQuery(m, iterations) / (threads * kPeakFlopsPerCore), benchmark::Counter::kIsRate);
}

void BM_Query(benchmark::State& state) {
  const Model m = Model(state.range(0));
  const WaveField f = field(m);
  const Points p(4096);
  std::size_t i = 0;
  double queries = 0, iters = 0;
  for (auto _ : state) {
    const SurfacePoint s = f.surfaceAt(p.lat[i], p.lon[i], m == Model::Fft ? 0.0 : p.t[i]);
    benchmark::DoNotOptimize(s.heightM);
    iters += s.iterations;
    queries += 1;
    i = (i + 1) & 4095;
  }
  state.SetLabel(toString(m));
  report(state, m, queries, iters / queries, 1);
}
BENCHMARK(BM_Query)->Arg(int(Model::Noise))->Arg(int(Model::NoisePaper))->Arg(int(Model::Gerstner))->Arg(int(Model::Fft));

// The batch form (no land mask: pure wave cost) on 1 and 2 threads; real time.
void BM_Batch(benchmark::State& state) {
  const Model m = Model(state.range(0));
  const int threads = int(state.range(1));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const SeaQuery q(field(m), nullptr);
  const std::size_t n = 1 << 16;
  const Points p(n);
  std::vector<SeaQueryResult> out(n);
  double queries = 0;
  for (auto _ : state) {
    q.queryBatch(p.lat.data(), p.lon.data(), p.t.data(), m != Model::Fft, n, out.data());
    benchmark::DoNotOptimize(out.data());
    queries += double(n);
  }
  double iters = 0;
  for (std::size_t i = 0; i < 1024; ++i)
    iters += q.field().surfaceAt(p.lat[i], p.lon[i], m == Model::Fft ? p.t[0] : p.t[i]).iterations;
  state.SetLabel(std::string(toString(m)) + " threads=" + std::to_string(threads));
  report(state, m, queries, iters / 1024, threads);
}
BENCHMARK(BM_Batch)
    ->Args({int(Model::Noise), 1})->Args({int(Model::Noise), 2})
    ->Args({int(Model::Gerstner), 1})->Args({int(Model::Gerstner), 2})
    ->Args({int(Model::Fft), 1})->Args({int(Model::Fft), 2})
    ->UseRealTime()->Unit(benchmark::kMillisecond);
// FFT table synthesis for one new time (2 cascades x 4 inverse 128^2 FFTs).
void BM_FftTables(benchmark::State& state) {
  const WaveField f = field(Model::Fft);
  double t = 0.0;
  for (auto _ : state) {
    t += 0.01;  // a new time every iteration: no cache hit
    benchmark::DoNotOptimize(f.surfaceAt(10.0, 20.0, t).heightM);
  }
}
BENCHMARK(BM_FftTables)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
