// Sea-height query throughput per model: the scalar query (surfaceAt), the
// SIMD batch (WaveField::surfaceBatch) on one thread, and the TBB batches
// (SeaQuery::queryBatch = SIMD, and a TBB loop over surfaceAt = scalar) on
// 1 and 2 threads; each rate as a fraction of this machine's floating-point
// limit, measured in the same run (BM_FpPeak: FMA chains at the widest
// dispatched width). Not run by ctest; results in docs/PERFORMANCE.md.
//
// Flops a query needs, counted by hand in the SIMD code (WaveBatch.cpp) per
// point: add, sub, mul, div, sqrt, floor, min, max 1; FMA 2 (the unit of the
// peak). Not counted: integer hash ops, compares, selects, conversions,
// sign-bit xors (the noise query has ~1 700 of those per point).
//  - noise, per octave: lattice position 27, corner offsets 3, 8 corner
//    dot products with the permuted gradients 40 (AVX-512; the selects of
//    the other targets use 48), fade 39, lerp-tree value and gradient 109,
//    accumulation 29: 247. Per query: locate (2 sincos of 39) 97, normal 20.
//    8 octaves: 2 093.
//  - Gerstner, per component and query: waveAt (arc, atan2 ~50, phase,
//    frame) 100. Per evaluation: 69 + 16 x 187 (arc offset 32, small-angle
//    atan 13, phase 2, direction 32, taper 9, sincos 39, accumulation 47,
//    second derivatives 13) + 54 = 3 115; the first evaluation (offset 0:
//    no arc offset, no atan) 69 + 16 x 146 + 54 = 2 455; per Chebyshev step
//    62; frame 124.
//    The query evaluates 1 + iterations times (counter "iter": the mean over
//    points of the SIMD path's steps, i.e. what a query needs; the lanes of
//    one vector run until the slowest converges: "vec_evals"). The scalar
//    path takes Newton steps (more of them, cheaper): its rows are rated
//    with the same per-query count, the work the batch shows a query needs.
//  - paper noise, per octave: 2D noise 110 + accumulation 20; per query 120
//    (scalar only).
//  - FFT, counted in the SIMD code: per query locate and frame 122, texel
//    fractions and cells of the 6 (plane, cascade) entries 144; per
//    evaluation 62 (frame, weights, tangents) + 50 (slope, normal) + per
//    plane 338 (per cascade 122: tile coordinates, 6 bilinear values, 3 u
//    and v derivatives; then axes, accumulation, Jacobian) for the 1.5
//    planes a point needs on average (|up_i| > 0.5 on half the sphere per
//    axis; 8 random lanes make the SIMD path evaluate all 3); per Newton
//    step 40. The query evaluates 1 + iterations times. All queries at one
//    time (the tables are cached per time; BM_FftTables is a new time).
#include "plugin/waves/SeaQuery.h"
#include "plugin/waves/WaveBatch.h"
#include "tests/waves/bench_fp_peak.h"

#include <benchmark/benchmark.h>
#include <hwy/targets.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <random>
#include <vector>

using namespace geocean::waves;

namespace {
// FMA peak (flop/s, one core) measured at start-up in CPU time of this
// thread, like the per-query rates: best of 15 runs of ~0.1 s (the machine
// is shared; the best run is the least disturbed one).
double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double measurePeak() {
  double best = 0;
  for (int r = 0; r < 15; ++r) {
    const double t0 = cpuSeconds();
    const double flops = geocean::waves::bench::fmaChains(20'000'000);
    best = std::max(best, flops / (cpuSeconds() - t0));
  }
  return best;
}
const double kPeakFlopsPerCore = measurePeak();

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
  const double evals = 1.0 + iterations;
  switch (m) {
    case Model::Noise: return 117.0 + 8 * 247.0;
    case Model::NoisePaper: return 120.0 + 8 * 130.0;
    case Model::Gerstner: return 124.0 + 16 * 100.0 + 2455.0 + iterations * (3115.0 + 62.0);
    case Model::Fft: return 266.0 + evals * (112.0 + 1.5 * 338.0) + iterations * 40.0;
  }
  return 0;
}

void report(benchmark::State& state, Model m, double queries, double iterations, int threads) {
  state.SetItemsProcessed(int64_t(queries));
  state.counters["iter"] = iterations;
  state.counters["flop/query"] = flopsPerQuery(m, iterations);
  // Fraction of the FP limit reached: (queries/s * flops/query) / (cores * peak).
  state.counters["peak_GFLOPs"] = kPeakFlopsPerCore * 1e-9;
  state.counters["of_fp_limit"] = benchmark::Counter(
      queries * flopsPerQuery(m, iterations) / (threads * kPeakFlopsPerCore), benchmark::Counter::kIsRate);
}

// Mean iterations per point of the Newton inversion (what a query needs).
// (the batch's steps; surfaceAt's for noise-paper).
double meanIterations(const WaveField& f, const Points& p, bool oneTime) {
  std::vector<SurfacePoint> out(1024);
  f.surfaceBatch(p.lat.data(), p.lon.data(), p.t.data(), !oneTime, nullptr, out.size(), out.data());
  double iters = 0;
  for (const SurfacePoint& s : out) iters += s.iterations;
  return iters / double(out.size());
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
  state.SetLabel(std::string(toString(m)) + " scalar");
  state.counters["scalar_iter"] = iters / queries;
  report(state, m, queries, meanIterations(f, p, m == Model::Fft), 1);
}
BENCHMARK(BM_Query)->Arg(int(Model::Noise))->Arg(int(Model::NoisePaper))->Arg(int(Model::Gerstner))->Arg(int(Model::Fft));

// The SIMD batch on the calling thread (no TBB, no land mask).
void BM_SimdBatch(benchmark::State& state) {
  const Model m = Model(state.range(0));
  // range(1): a Highway target to force (HWY_AVX2, HWY_SSE4, ...), 0 = the best this CPU runs.
  if (state.range(1) != 0) hwy::SetSupportedTargetsForTest(state.range(1));
  const WaveField f = field(m);
  const std::size_t n = 4096;
  const Points p(n);
  std::vector<SurfacePoint> out(n);
  double queries = 0;
  for (auto _ : state) {
    f.surfaceBatch(p.lat.data(), p.lon.data(), p.t.data(), m != Model::Fft, nullptr, n, out.data());
    benchmark::DoNotOptimize(out.data());
    queries += double(n);
  }
  // Newton evaluations per vector (the slowest lane of each): the lanes' waste.
  const std::size_t lanes = geocean::waves::batch::lanes();
  double vecEvals = 0;
  for (std::size_t i = 0; i < n; i += lanes) {
    int mx = 0;
    for (std::size_t k = i; k < std::min(n, i + lanes); ++k) mx = std::max(mx, out[k].iterations);
    vecEvals += 1 + mx;
  }
  state.counters["vec_evals"] = vecEvals / double((n + lanes - 1) / lanes);
  state.SetLabel(std::string(toString(m)) + " simd " + geocean::waves::batch::targetName() + " x" +
                 std::to_string(lanes));
  report(state, m, queries, meanIterations(f, p, m == Model::Fft), 1);
  hwy::SetSupportedTargetsForTest(0);
}
BENCHMARK(BM_SimdBatch)
    ->Args({int(Model::Noise), 0})->Args({int(Model::Gerstner), 0})->Args({int(Model::Fft), 0})
    ->Args({int(Model::Noise), HWY_AVX2})->Args({int(Model::Gerstner), HWY_AVX2})
    ->Args({int(Model::Noise), HWY_SSE4})->Args({int(Model::Gerstner), HWY_SSE4});

// The batch forms (no land mask: pure wave cost) on 1 and 2 threads, real
// time: SeaQuery::queryBatch (SIMD but for noise-paper) and, for
// comparison, the same TBB blocks calling the scalar surfaceAt.
void BM_Batch(benchmark::State& state) {
  const Model m = Model(state.range(0));
  const int threads = int(state.range(1));
  const bool simd = state.range(2) != 0;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const SeaQuery q(field(m), nullptr);
  const std::size_t n = 1 << 16;
  const Points p(n);
  std::vector<SeaQueryResult> out(n);
  double queries = 0;
  for (auto _ : state) {
    if (simd) {
      q.queryBatch(p.lat.data(), p.lon.data(), p.t.data(), m != Model::Fft, n, out.data());
    } else {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
          out[i].seaHeightM = q.field().surfaceAt(p.lat[i], p.lon[i], m == Model::Fft ? p.t[0] : p.t[i]).heightM;
      });
    }
    benchmark::DoNotOptimize(out.data());
    queries += double(n);
  }
  // range(3) = 1: the time is the process's CPU time over all threads (rate
  // per core-second: equal for 1 and 2 threads = no contention between the
  // threads, what "scales to both cores" needs when the cores are free;
  // the wall-clock rows need an idle machine to show it).
  const bool perCore = state.range(3) != 0;
  state.SetLabel(std::string(toString(m)) + (simd ? " simd" : " scalar") + " threads=" + std::to_string(threads) +
                 (perCore ? " per-core-second" : " wall"));
  report(state, m, queries, meanIterations(q.field(), p, m == Model::Fft), perCore ? 1 : threads);
}
BENCHMARK(BM_Batch)
    ->Args({int(Model::Noise), 1, 1, 0})->Args({int(Model::Noise), 2, 1, 0})
    ->Args({int(Model::Noise), 1, 0, 0})->Args({int(Model::Noise), 2, 0, 0})
    ->Args({int(Model::Gerstner), 1, 1, 0})->Args({int(Model::Gerstner), 2, 1, 0})
    ->Args({int(Model::Gerstner), 1, 0, 0})->Args({int(Model::Gerstner), 2, 0, 0})
    ->Args({int(Model::Fft), 1, 1, 0})->Args({int(Model::Fft), 2, 1, 0})
    ->Args({int(Model::Fft), 1, 0, 0})->Args({int(Model::Fft), 2, 0, 0})
    ->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Batch)
    ->Args({int(Model::Noise), 1, 1, 1})->Args({int(Model::Noise), 2, 1, 1})
    ->Args({int(Model::Gerstner), 1, 1, 1})->Args({int(Model::Gerstner), 2, 1, 1})
    ->Args({int(Model::Fft), 1, 1, 1})->Args({int(Model::Fft), 2, 1, 1})
    ->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);

// The FP limit itself, 1 and 2 threads (per-core peak x 2 if both cores are
// free), and per dispatch target (range(0): forced Highway target, 0 = best).
void BM_FpPeak(benchmark::State& state) {
  if (state.range(0) != 0 && state.thread_index() == 0) hwy::SetSupportedTargetsForTest(state.range(0));
  double flops = 0;
  for (auto _ : state) flops += geocean::waves::bench::fmaChains(1'000'000);
  state.counters["GFLOPs"] = benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsRate);
  state.SetLabel(std::string(geocean::waves::batch::targetName()) + " x" +
                 std::to_string(geocean::waves::batch::lanes()));
  if (state.range(0) != 0 && state.thread_index() == 0) hwy::SetSupportedTargetsForTest(0);
}
BENCHMARK(BM_FpPeak)->Arg(0)->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK(BM_FpPeak)->Arg(HWY_AVX2)->Arg(HWY_SSE4);

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
