// Issue 17 item 4: out-of-memory from a huge batch is bounded by chunking,
// not by luck. This program replaces the global operator new/delete (the
// plugin, linked directly, allocates through them) to count the bytes in
// use and their peak during one call, and to refuse allocations on demand.
//  - Every batch query, over a layered raster stack (the samplers that
//    allocate per point), with 2^18 points costs at most 256 KiB of heap
//    beyond the caller's arrays: memory does not grow with the batch.
//  - An allocation that fails inside an entry point is GEOCEAN_ERROR_OUT_OF_MEMORY
//    with a message, and the ocean answers as before.
#include "geocean/geocean_ocean.h"

#include <gtest/gtest.h>
#include <malloc.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <new>
#include <string>
#include <vector>

namespace {
std::atomic<long long> gLive{0}, gPeak{0}, gLargest{0};
std::atomic<std::size_t> gRefuseAbove{~std::size_t(0)};  // allocations larger than this fail

void* counted(void* p) {
  if (!p) return p;
  const long long n = (long long)malloc_usable_size(p);
  const long long now = gLive.fetch_add(n) + n;
  for (long long peak = gPeak.load(); now > peak && !gPeak.compare_exchange_weak(peak, now);) {}
  for (long long big = gLargest.load(); n > big && !gLargest.compare_exchange_weak(big, n);) {}
  return p;
}
void* allocate(std::size_t n, std::size_t align, bool nothrow) {
  void* p = nullptr;
  if (n <= gRefuseAbove.load())
    p = align <= alignof(std::max_align_t) ? std::malloc(n ? n : 1)
                                           : std::aligned_alloc(align, (std::max<std::size_t>(n, 1) + align - 1) / align * align);
  if (!p && !nothrow) throw std::bad_alloc();
  return counted(p);
}
void release(void* p) {
  if (!p) return;
  gLive.fetch_sub((long long)malloc_usable_size(p));
  std::free(p);
}
}  // namespace

void* operator new(std::size_t n) { return allocate(n, 0, false); }
void* operator new[](std::size_t n) { return allocate(n, 0, false); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n, 0, true); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n, 0, true); }
void* operator new(std::size_t n, std::align_val_t a) { return allocate(n, std::size_t(a), false); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocate(n, std::size_t(a), false); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }

namespace {

// Peak bytes in use during f() above those in use before it, and the largest block.
template <class F>
std::pair<long long, long long> heapDuring(F&& f) {
  const long long before = gLive.load();
  gPeak = before;
  gLargest = 0;
  f();
  return {gPeak.load() - before, gLargest.load()};
}

struct Fixture {
  geocean_ocean* o = nullptr;
  std::vector<float> mask = std::vector<float>(360 * 180), elev = std::vector<float>(360 * 180);
  Fixture() {
    for (int y = 0; y < 180; ++y)
      for (int x = 0; x < 360; ++x) {
        const bool land = (x / 10 + y / 10) % 3 == 0;
        mask[std::size_t(y) * 360 + x] = land ? 1.0f : 0.0f;
        elev[std::size_t(y) * 360 + x] = land ? 200.0f : -2000.0f;
      }
    EXPECT_EQ(geocean_create(GEOCEAN_ABI_VERSION, &o), GEOCEAN_OK);
    const geocean_grid_placement world{-180.0, 90.0, 1.0, -1.0, 1, 0, 0.0};
    const geocean_grid_placement region{-20.0, 40.0, 0.5, -0.5, 0, 0, 0.0};  // 40 x 40 deg layers over the world
    EXPECT_EQ(geocean_set_mask_pixels(o, mask.data(), 360, 180, &world), GEOCEAN_OK) << geocean_last_error();
    EXPECT_EQ(geocean_set_elevation_pixels(o, elev.data(), 360, 180, &world), GEOCEAN_OK) << geocean_last_error();
    EXPECT_EQ(geocean_add_mask_layer_pixels(o, "m", mask.data(), 80, 80, &region, 1, nullptr), GEOCEAN_OK)
        << geocean_last_error();
    EXPECT_EQ(geocean_add_elevation_layer_pixels(o, "e", elev.data(), 80, 80, &region, 1), GEOCEAN_OK)
        << geocean_last_error();
    geocean_sea_state s;
    EXPECT_EQ(geocean_sea_state_init(&s), GEOCEAN_OK);
    s.model = GEOCEAN_WAVES_GERSTNER;
    EXPECT_EQ(geocean_set_sea_state(o, &s), GEOCEAN_OK) << geocean_last_error();
  }
  ~Fixture() { geocean_destroy(o); }
};

TEST(CapiBatchMemory, EveryBatchQueryUsesBoundedHeapWhateverItsSize) {
  Fixture f;
  // 2^18 points, most inside the layers (where the stack samples per point).
  const std::size_t n = std::size_t(1) << 18;
  std::vector<double> lat(n), lon(n), t(1, 3.0), d1(n), d3(3 * n), d2(2 * n), a(n), b(n), c(n);
  std::vector<uint8_t> cls(n);
  std::vector<float> e(n);
  for (std::size_t i = 0; i < n; ++i) {
    lat[i] = -60.0 + 100.0 * double((i * 7919) % n) / double(n);
    lon[i] = -25.0 + 50.0 * double(i) / double(n);
  }
  geocean_surface_outputs all;
  ASSERT_EQ(geocean_surface_outputs_init(&all), GEOCEAN_OK);
  all.surface_class = cls.data(), all.elevation_m = e.data(), all.height_m = d1.data(), all.normal_enu = d3.data();
  all.vertical_velocity_mps = a.data(), all.horizontal_velocity_en_mps = d2.data();
  struct Query {
    const char* name;
    std::function<geocean_status(std::size_t)> call;
  };
  const Query queries[] = {
      {"geocean_query_class", [&](std::size_t m) { return geocean_query_class(f.o, m, lat.data(), lon.data(), cls.data()); }},
      {"geocean_query_elevation",
       [&](std::size_t m) { return geocean_query_elevation(f.o, m, lat.data(), lon.data(), e.data()); }},
      {"geocean_query_sea_surface",
       [&](std::size_t m) {
         return geocean_query_sea_surface(f.o, m, lat.data(), lon.data(), 3.0, d1.data(), d3.data(), cls.data());
       }},
      {"geocean_query_surface",
       [&](std::size_t m) { return geocean_query_surface(f.o, m, lat.data(), lon.data(), t.data(), 1, &all); }},
      {"geocean_query_sea_state",
       [&](std::size_t m) {
         return geocean_query_sea_state(f.o, m, lat.data(), lon.data(), a.data(), b.data(), c.data(), d1.data());
       }},
  };
  // What it is held to: 256 KiB, while one per-point array of the batch
  // (4 bytes x 2^18) is 1 MiB. Measured (Release): 17-33 KiB, largest
  // block 8 KiB; unchunked, geocean_query_elevation took 7.4 MB here
  // (largest block 2.1 MB), and this test failed.
  constexpr long long kBound = 256 << 10;
  for (const Query& q : queries) {
    ASSERT_EQ(q.call(4096), GEOCEAN_OK) << q.name << ": " << geocean_last_error();  // lazy tables built once
    geocean_status st = GEOCEAN_OK;
    const auto [peak, largest] = heapDuring([&] { st = q.call(n); });
    ASSERT_EQ(st, GEOCEAN_OK) << q.name << ": " << geocean_last_error();
    std::printf("%s, %zu points: peak heap above the caller's %lld B, largest block %lld B\n", q.name, n, peak,
                largest);
    EXPECT_LE(peak, kBound) << q.name;
  }
}

TEST(CapiBatchMemory, AnAllocationFailureIsOutOfMemoryAndChangesNothing) {
  Fixture f;
  const double lat[2] = {10.5, 50.5}, lon[2] = {-10.5, 100.5};
  double before[2], after[2];
  ASSERT_EQ(geocean_query_sea_surface(f.o, 2, lat, lon, 1.0, before, nullptr, nullptr), GEOCEAN_OK);
  // A 1024 x 512 raster (2 MiB copy) with every allocation above 1 MiB refused.
  std::vector<float> big(1024 * 512, 1.0f);
  const geocean_grid_placement p{-180.0, 90.0, 360.0 / 1024, -180.0 / 512, 1, 0, 0.0};
  gRefuseAbove = 1 << 20;
  const geocean_status st = geocean_set_mask_pixels(f.o, big.data(), 1024, 512, &p);
  gRefuseAbove = ~std::size_t(0);
  EXPECT_EQ(st, GEOCEAN_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(std::string(geocean_last_error()), "geocean_set_mask_pixels: out of memory");
  ASSERT_EQ(geocean_query_sea_surface(f.o, 2, lat, lon, 1.0, after, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(std::memcmp(before, after, sizeof before), 0) << "the failed setter changed the ocean";
  // With the memory back, the same call succeeds (nothing was left half set).
  EXPECT_EQ(geocean_set_mask_pixels(f.o, big.data(), 1024, 512, &p), GEOCEAN_OK) << geocean_last_error();
}

}  // namespace
