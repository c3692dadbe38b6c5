// Soak of the C ABI (issue 17 item 3), through the run-time loader as a host
// engine uses it. Not a benchmark: it checks answers and heap, not speed.
//   soak_capi threads <seconds> <readers>
//       <readers> threads query class and sea surface while the main thread
//       replaces the mask (all ocean <-> all land) and the sea state (calm
//       <-> storm) every second. Every batch must equal, bit for bit, the
//       answer of one whole state (a torn batch mixes two); heap in use must
//       not grow after the first minute's worth of swaps.
//   soak_capi reload <times>
//       loads the plugin, creates an ocean, sets a mask and a sea state,
//       queries, destroys it and unloads the plugin, <times> times; heap in
//       use after the last must equal (within 64 KiB) that after the 10th.
// Prints one line of figures; exit 0 = nothing lost, 1 = a check failed.
#include "globe/host/OceanPlugin.h"

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace {

using geocean::host::OceanPlugin;
using Clock = std::chrono::steady_clock;

// glibc's count of bytes handed out by malloc and not freed (0 under ASan,
// whose allocator replaces malloc: the ASan run checks leaks instead).
long heapInUse() { return long(mallinfo2().uordblks); }

std::unique_ptr<OceanPlugin> loadPlugin() {
  std::string error;
  auto p = OceanPlugin::load(GEOCEAN_PLUGIN_BUILD_PATH, error);
  if (!p) std::fprintf(stderr, "soak_capi: cannot load %s: %s\n", GEOCEAN_PLUGIN_BUILD_PATH, error.c_str());
  return p;
}

struct Fixture {
  static constexpr int kW = 360, kH = 180;
  std::vector<float> ocean = std::vector<float>(kW * kH, 0.0f), land = std::vector<float>(kW * kH, 1.0f);
  geocean_grid_placement place{-180.0, 90.0, 360.0 / kW, -180.0 / kH, 1, 0, 0.0};
  geocean_sea_state calm{}, storm{};
  std::vector<double> lat, lon;
  explicit Fixture(const geocean::host::OceanApi& a, std::size_t n) : lat(n), lon(n) {
    a.seaStateInit(&calm), a.seaStateInit(&storm);
    calm.wind_speed_mps = 5.0, storm.wind_speed_mps = 20.0;
    for (std::size_t i = 0; i < n; ++i) {
      lat[i] = -60.0 + 120.0 * double(i) / double(n);
      lon[i] = -180.0 + 360.0 * double((i * 613) % n) / double(n);
    }
  }
};

// Bit for bit (land points answer NaN, which == never matches).
bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool ok(geocean_status s, const OceanPlugin& p, const char* what) {
  if (s == GEOCEAN_OK) return true;
  std::fprintf(stderr, "soak_capi: %s: %s\n", what, p.api().lastError());
  return false;
}

int soakThreads(double seconds, int readers) {
  auto p = loadPlugin();
  if (!p) return 1;
  const auto& a = p->api();
  geocean_ocean* o = nullptr;
  if (!ok(a.create(GEOCEAN_ABI_VERSION, &o), *p, "create")) return 1;
  const std::size_t n = 2000;
  Fixture fx(a, n);
  // The answers of the four whole states (mask x sea state).
  std::vector<double> ref[2][2];
  for (int m = 0; m < 2; ++m)
    for (int s = 0; s < 2; ++s) {
      ref[m][s].resize(n);
      if (!ok(a.setMaskPixels(o, (m ? fx.land : fx.ocean).data(), fx.kW, fx.kH, &fx.place), *p, "mask") ||
          !ok(a.setSeaState(o, s ? &fx.storm : &fx.calm), *p, "sea state") ||
          !ok(a.querySeaSurface(o, n, fx.lat.data(), fx.lon.data(), 3.0, ref[m][s].data(), nullptr, nullptr), *p,
              "query"))
        return 1;
    }
  std::atomic<bool> stop{false};
  std::atomic<long> batches{0}, torn{0}, tornClass{0}, failed{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < readers; ++t)
    pool.emplace_back([&, t] {
      std::vector<double> h(n);
      std::vector<uint8_t> c(n);
      for (long k = 0; !stop; ++k) {
        if ((k + t) % 2) {
          if (a.queryClass(o, n, fx.lat.data(), fx.lon.data(), c.data()) != GEOCEAN_OK) ++failed;
          const auto ones = std::count(c.begin(), c.end(), uint8_t(1));
          if (ones != 0 && ones != std::ptrdiff_t(n)) ++torn, ++tornClass;
        } else {
          if (a.querySeaSurface(o, n, fx.lat.data(), fx.lon.data(), 3.0, h.data(), nullptr, nullptr) != GEOCEAN_OK)
            ++failed;
          else if (!same(h, ref[0][0]) && !same(h, ref[0][1]) && !same(h, ref[1][0]) && !same(h, ref[1][1]))
            ++torn;
        }
        ++batches;
      }
    });
  const auto t0 = Clock::now();
  long swaps = 0, heapAfterWarmup = -1, heapMax = 0;
  const long warmup = std::min(60L, long(seconds / 2));
  bool writerOk = true;
  for (auto next = t0; Clock::now() - t0 < std::chrono::duration<double>(seconds); ++swaps) {
    next += std::chrono::seconds(1);
    writerOk &= ok(a.setMaskPixels(o, (swaps % 2 ? fx.ocean : fx.land).data(), fx.kW, fx.kH, &fx.place), *p, "mask");
    writerOk &= ok(a.setSeaState(o, (swaps / 2) % 2 ? &fx.calm : &fx.storm), *p, "sea state");
    if (swaps == warmup) heapAfterWarmup = heapInUse();
    if (swaps > warmup) heapMax = std::max(heapMax, heapInUse());
    std::this_thread::sleep_until(next);
  }
  stop = true;
  for (auto& th : pool) th.join();
  a.destroy(o);
  const double growthKiB = heapAfterWarmup < 0 ? 0.0 : double(heapMax - heapAfterWarmup) / 1024.0;
  std::printf("soak_capi threads: %.0f s, %d readers, %ld state swaps, %ld batches of %zu points, %ld torn, "
              "(%ld of them class batches), %ld failed, heap in use after %ld swaps %.1f MiB, max growth after %.1f KiB\n",
              seconds, readers, swaps, long(batches), n, long(torn), long(tornClass), long(failed), warmup,
              double(heapAfterWarmup) / 1048576.0, growthKiB);
  // 1 MiB: one leaked mask copy per swap (253 KiB) shows within 4 swaps.
  const bool pass = writerOk && torn == 0 && failed == 0 && batches > 2 * swaps && growthKiB < 1024.0;
  return pass ? 0 : 1;
}

// Whether the plugin is still mapped: glibc keeps a library loaded after
// dlclose when it has STB_GNU_UNIQUE symbols (C++ inline statics) or was
// opened RTLD_NODELETE, and then "unload" frees nothing.
bool pluginMapped() {
  std::FILE* f = std::fopen("/proc/self/maps", "r");
  if (!f) return false;
  char line[4096];
  bool found = false;
  while (!found && std::fgets(line, sizeof line, f)) found = std::strstr(line, "libgeocean_ocean.so") != nullptr;
  std::fclose(f);
  return found;
}

int soakReload(int times) {
  long heap10 = -1, heapEnd = 0;
  for (int i = 1; i <= times; ++i) {
    auto p = loadPlugin();
    if (!p) return 1;
    const auto& a = p->api();
    geocean_ocean* o = nullptr;
    if (!ok(a.create(GEOCEAN_ABI_VERSION, &o), *p, "create")) return 1;
    Fixture fx(a, 100);
    std::vector<double> h(100);
    std::vector<uint8_t> c(100);
    const bool good = ok(a.setMaskPixels(o, (i % 2 ? fx.land : fx.ocean).data(), fx.kW, fx.kH, &fx.place), *p, "mask") &&
                      ok(a.setSeaState(o, &fx.storm), *p, "sea state") &&
                      ok(a.queryClass(o, 100, fx.lat.data(), fx.lon.data(), c.data()), *p, "class") &&
                      ok(a.querySeaSurface(o, 100, fx.lat.data(), fx.lon.data(), 1.0, h.data(), nullptr, nullptr), *p,
                         "sea surface");
    a.destroy(o);
    if (!good || c[0] != (i % 2 ? 1 : 0)) {
      std::fprintf(stderr, "soak_capi reload: iteration %d answered wrong\n", i);
      return 1;
    }
    p.reset();  // dlclose
    if (i == times) std::printf("soak_capi reload: after the last dlclose the plugin is %s\n",
                                pluginMapped() ? "still mapped (not unloaded)" : "unmapped");
    if (i == 10) heap10 = heapInUse();
    heapEnd = heapInUse();
  }
  const double growthKiB = heap10 < 0 ? 0.0 : double(heapEnd - heap10) / 1024.0;
  std::printf("soak_capi reload: %d load/create/query/destroy/unload cycles, heap in use after 10 %.1f KiB, "
              "after %d %.1f KiB, growth %.1f KiB\n",
              times, double(heap10) / 1024.0, times, double(heapEnd) / 1024.0, growthKiB);
  return growthKiB < 64.0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "threads" && argc == 4) return soakThreads(std::atof(argv[2]), std::atoi(argv[3]));
  if (mode == "reload" && argc == 3) return soakReload(std::atoi(argv[2]));
  std::fprintf(stderr, "usage: soak_capi threads <seconds> <readers> | reload <times>\n");
  return 2;
}
