// libFuzzer: the C ABI's sea state (geocean_sea_state_init/_set_beaufort,
// geocean_set_sea_state with every field at any value, struct_size
// included) followed by sea-surface queries at any points and times, over a
// small in-memory world (ocean, land, lake; shallow and deep water).
// Contract (geocean_ocean.h): OK or a documented error naming the function;
// a refused sea state leaves the previous one; with a sea state, the
// significant wave height is finite and >= 0, ocean points get a finite
// height and a unit normal, land and lakes NaN; nothing crashes, leaks,
// hangs or invokes undefined behaviour.
#include "tests/fuzz/CapiFuzz.h"

#include <cstdint>
#include <vector>

using namespace geocean::fuzz;

namespace {
// 8 x 4 global cells: rows from the north; 0 ocean, 1 land, 2 lake.
const float kMask[32] = {0, 0, 1, 0, 0, 2, 0, 0,  //
                         0, 1, 1, 0, 0, 0, 0, 0,  //
                         0, 0, 0, 0, 2, 1, 0, 0,  //
                         1, 1, 0, 0, 0, 0, 0, 1};
const float kRelief[32] = {-4000, -50,  300,  -1,  -2, 10, -6000, -3,  //
                           -0.5f, 200, 1000, -20, -9000, -100, -5, -4000,  //
                           -3000, -2, -1, -10, 5, 50, -200, -7,  //
                           100,  300, -1, -1, -30, -3000, -50, 20};

void fuzzField(FuzzedDataProvider& p, double& field, double lo, double hi) {
  if (p.ConsumeBool()) field = pickDouble(p, lo, hi);
}
void fuzzField(FuzzedDataProvider& p, int32_t& field, int32_t lo, int32_t hi) {
  if (p.ConsumeBool()) field = p.ConsumeBool() ? p.ConsumeIntegralInRange<int32_t>(lo, hi) : p.ConsumeIntegral<int32_t>();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider p(data, size);
  geocean_ocean* ocean = nullptr;
  if (geocean_create(GEOCEAN_ABI_VERSION, &ocean) != GEOCEAN_OK) broken("geocean_create");
  geocean_grid_placement g{-180.0, 90.0, 45.0, -45.0, 1, 0, 0.0};
  if (p.ConsumeBool()) {
    if (geocean_set_mask_pixels(ocean, kMask, 8, 4, &g) != GEOCEAN_OK) broken("set_mask_pixels");
    if (geocean_set_elevation_pixels(ocean, kRelief, 8, 4, &g) != GEOCEAN_OK) broken("set_elevation_pixels");
  }

  bool haveSea = false;
  for (int round = p.ConsumeIntegralInRange<int>(1, 2); round > 0; --round) {
    geocean_sea_state s;
    if (geocean_sea_state_init(&s) != GEOCEAN_OK) broken("sea_state_init");
    if (p.ConsumeBool()) {
      const int32_t b = p.ConsumeIntegralInRange<int32_t>(-2, 14);
      const geocean_status sb = checked(geocean_sea_state_set_beaufort(&s, b), "geocean_sea_state_set_beaufort");
      if ((sb == GEOCEAN_OK) != (b >= 0 && b <= 12)) broken("beaufort range", b);
    }
    fuzzField(p, s.model, 0, 3);
    fuzzField(p, s.wind_speed_mps, 0.0, 70.0);
    fuzzField(p, s.wind_from_deg, -720.0, 720.0);
    fuzzField(p, s.fetch_m, -1.0, 2e6);
    if (p.ConsumeBool()) s.seed = p.ConsumeIntegral<uint32_t>();
    fuzzField(p, s.gerstner_components, 0, 65);
    fuzzField(p, s.noise_octaves, 0, 13);
    fuzzField(p, s.anchor_lat_deg, -100.0, 100.0);
    fuzzField(p, s.anchor_lon_deg, -400.0, 400.0);
    fuzzField(p, s.reference_depth_m, -10.0, 1e4);
    if (p.ConsumeIntegralInRange<int>(0, 15) == 0) s.struct_size = p.ConsumeIntegral<uint32_t>();
    const geocean_status ss = checked(geocean_set_sea_state(ocean, &s), "geocean_set_sea_state");
    if (ss == GEOCEAN_OK) haveSea = true;
  }

  double hs = -1;
  const geocean_status sh = checked(geocean_significant_wave_height(ocean, &hs), "geocean_significant_wave_height");
  if ((sh == GEOCEAN_OK) != haveSea) broken("significant_wave_height readiness");
  if (sh == GEOCEAN_OK && !(std::isfinite(hs) && hs >= 0.0)) broken("significant wave height", hs);

  const std::size_t count = p.ConsumeIntegralInRange<std::size_t>(0, 8);
  std::vector<double> lat(count), lon(count), height(count), normal(3 * count);
  std::vector<uint8_t> cls(count, 99);
  for (std::size_t i = 0; i < count; ++i) {
    lat[i] = pickDouble(p, -90.0, 90.0);
    lon[i] = pickDouble(p, -180.0, 360.0);
  }
  const double t = pickDouble(p, -1e6, 1e6);
  const geocean_status sq = checked(geocean_query_sea_surface(ocean, count, lat.data(), lon.data(), t, height.data(),
                                                              normal.data(), cls.data()),
                                    "geocean_query_sea_surface");
  if (sq == GEOCEAN_OK && haveSea) {
    for (std::size_t i = 0; i < count; ++i) {
      if (cls[i] > GEOCEAN_SURFACE_LAKE) broken("class out of range", cls[i]);
      // Points outside [-90, 90] x [-180, 360] are the host's error to
      // avoid; the ABI answers them but we do not judge the answer.
      if (!(lat[i] >= -90.0 && lat[i] <= 90.0 && lon[i] >= -180.0 && lon[i] <= 360.0)) continue;
      if (cls[i] == GEOCEAN_SURFACE_OCEAN) {
        const double* n = &normal[3 * i];
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!std::isfinite(height[i]) || std::abs(height[i]) > 200.0) broken("ocean height", height[i], double(i));
        if (!(std::abs(len - 1.0) < 1e-6) || !(n[2] > 0.0)) broken("ocean normal", len, n[2]);
      } else if (!std::isnan(height[i])) {
        broken("land or lake height is not NaN", height[i], cls[i]);
      }
    }
  }

  geocean_surface_outputs out;
  if (geocean_surface_outputs_init(&out) != GEOCEAN_OK) broken("outputs_init");
  std::vector<double> h2(count), vv(count), hv(2 * count);
  out.height_m = h2.data();
  out.vertical_velocity_mps = vv.data();
  out.horizontal_velocity_en_mps = hv.data();
  std::vector<double> times(count);
  for (auto& x : times) x = pickDouble(p, -1e5, 1e5);
  const size_t timeCount = p.ConsumeBool() ? count : 1;
  if (timeCount == 1 && count == 0) times.push_back(t);
  const geocean_status s2 = checked(
      geocean_query_surface(ocean, count, lat.data(), lon.data(), timeCount ? times.data() : nullptr, timeCount, &out),
      "geocean_query_surface");
  if (s2 == GEOCEAN_OK && !haveSea && count > 0) broken("sea outputs without a sea state");
  geocean_destroy(ocean);
  return 0;
}
