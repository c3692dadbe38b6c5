// `geocean query` cost as a user sees it: a cold process for one point
// (wall time and peak RSS) and a 1,000,000-point CSV batch on 2 threads.
// Compared in the same run with a bare program that only links OpenImageIO
// (the floor any OpenImageIO-based tool pays at start).
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

extern char** environ;

namespace {
// Runs argv with stdin/stdout redirected; returns peak RSS in KB.
long spawnAndWait(std::vector<std::string> args, const char* in, const char* out) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, in, O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid;
  if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ) != 0) return -1;
  posix_spawn_file_actions_destroy(&fa);
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  return (WIFEXITED(status) && WEXITSTATUS(status) == 0) ? ru.ru_maxrss : -1;
}

void run(benchmark::State& state, std::vector<std::string> args, const char* in, double items) {
  long peak = 0;
  for (auto _ : state) {
    const long kb = spawnAndWait(args, in, "/dev/null");
    if (kb < 0) {
      state.SkipWithError("command failed");
      return;
    }
    peak = std::max(peak, kb);
  }
  state.counters["peak_RSS_MB"] = double(peak) / 1024.0;
  if (items > 0) state.SetItemsProcessed(state.iterations() * std::int64_t(items));
}

const std::string kGeocean = GEOCEAN_EXE;
const std::string kBare = BARE_OIIO_EXE;

const char* millionPoints() {
  static const char* path = [] {
    static const char* p = "/tmp/geocean-bench-1m.csv";
    std::ofstream f(p);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> ulat(-90, 90), ulon(-180, 180);
    f.precision(8);
    f << "lat,lon\n";
    for (int i = 0; i < 1000000; ++i) f << ulat(rng) << ',' << ulon(rng) << '\n';
    return p;
  }();
  return path;
}
}  // namespace

static void BM_BareOpenImageIOProcess(benchmark::State& s) { run(s, {kBare}, "/dev/null", 0); }
static void BM_QueryOnePointColdProcess(benchmark::State& s) {
  run(s, {kGeocean, "query", "-33.9", "151.5"}, "/dev/null", 0);
}
static void BM_QueryMillionPointsCsv(benchmark::State& s) {
  run(s, {kGeocean, "query", "--points", "-"}, millionPoints(), 1e6);
}
static void BM_QueryMillionPointsCsvClassElevationOnly(benchmark::State& s) {
  run(s, {kGeocean, "query", "--points", "-", "--waves", "none"}, millionPoints(), 1e6);
}
static void BM_QueryMillionPointsJson(benchmark::State& s) {
  run(s, {kGeocean, "query", "--points", "-", "--format", "json"}, millionPoints(), 1e6);
}
BENCHMARK(BM_BareOpenImageIOProcess)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);
BENCHMARK(BM_QueryOnePointColdProcess)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);
BENCHMARK(BM_QueryMillionPointsCsv)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_QueryMillionPointsCsvClassElevationOnly)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_QueryMillionPointsJson)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_MAIN();
