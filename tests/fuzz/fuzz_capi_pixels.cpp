// libFuzzer: the C ABI's rasters from memory (geocean_set_mask_pixels,
// geocean_set_elevation_pixels: size, placement, values, nodata, global)
// followed by class, elevation and surface queries at any points (NaN, inf,
// beyond the poles and the date line). Contract (geocean_ocean.h): every
// call returns OK or a documented error with a message naming the
// function; a rejected raster leaves the previous state; classes are 0, 1
// or 2; nothing crashes, leaks or invokes undefined behaviour.
#include "tests/fuzz/CapiFuzz.h"

#include <cstdint>
#include <vector>

using namespace geocean::fuzz;

namespace {
geocean_grid_placement placement(FuzzedDataProvider& p, int32_t width) {
  geocean_grid_placement g{};
  g.origin_lon_deg = pickDouble(p, -360.0, 360.0);
  g.origin_lat_deg = pickDouble(p, -100.0, 100.0);
  // Often a grid that covers the globe exactly, else anything.
  if (p.ConsumeBool() && width > 0) {
    g.lon_step_deg = 360.0 / width;
    g.origin_lon_deg = -180.0;
    g.global = 1;
  } else {
    g.lon_step_deg = pickDouble(p, 1e-6, 90.0);
    g.global = p.ConsumeIntegral<int32_t>();
  }
  g.lat_step_deg = pickDouble(p, -90.0, 90.0);
  g.has_nodata = p.ConsumeIntegralInRange<int32_t>(0, 1);
  g.nodata = pickDouble(p, -10.0, 10.0);
  return g;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider p(data, size);
  geocean_ocean* ocean = nullptr;
  if (geocean_create(GEOCEAN_ABI_VERSION, &ocean) != GEOCEAN_OK) broken("geocean_create");
  bool haveMask = false, haveElevation = false;
  for (int round = p.ConsumeIntegralInRange<int>(1, 3); round > 0; --round) {
    const bool mask = p.ConsumeBool();
    // Mostly small valid sizes; sometimes any int32 (the ABI must refuse <= 0).
    int32_t w = p.ConsumeIntegralInRange<int32_t>(1, 48), h = p.ConsumeIntegralInRange<int32_t>(1, 48);
    if (p.ConsumeIntegralInRange<int>(0, 15) == 0) w = p.ConsumeIntegral<int32_t>();
    if (p.ConsumeIntegralInRange<int>(0, 15) == 0) h = p.ConsumeIntegral<int32_t>();
    const geocean_grid_placement g = placement(p, w);
    // The host owns width x height floats: sizes we cannot back are not passed.
    const bool positive = w > 0 && h > 0;
    if (positive && std::int64_t(w) * h > 48 * 48) continue;
    const std::size_t n = positive ? std::size_t(w) * std::size_t(h) : 1;
    std::vector<float> v(n);
    for (auto& x : v)
      x = mask ? float(p.ConsumeIntegralInRange<int>(-1, 300)) : float(pickDouble(p, -11000.0, 9000.0));
    const geocean_status s = mask ? checked(geocean_set_mask_pixels(ocean, v.data(), w, h, &g), "geocean_set_mask_pixels")
                                  : checked(geocean_set_elevation_pixels(ocean, v.data(), w, h, &g),
                                            "geocean_set_elevation_pixels");
    if (!positive && s != GEOCEAN_ERROR_INVALID_ARGUMENT) broken("a size <= 0 was not refused", w, h);
    if (s == GEOCEAN_OK) (mask ? haveMask : haveElevation) = true;
    if (p.ConsumeIntegralInRange<int>(0, 7) == 0) {
      checked(geocean_set_mask_encoding(ocean, p.ConsumeBool() ? "0=ocean,1=land,2=lake,7=lake,255=ocean" : "2=ocean"),
              "geocean_set_mask_encoding");
    }
  }

  const std::size_t count = p.ConsumeIntegralInRange<std::size_t>(0, 16);
  std::vector<double> lat(count), lon(count);
  for (std::size_t i = 0; i < count; ++i) {
    lat[i] = pickDouble(p, -95.0, 95.0);
    lon[i] = pickDouble(p, -200.0, 400.0);
  }
  std::vector<uint8_t> cls(count, 99);
  std::vector<float> elev(count);
  const geocean_status sc = checked(geocean_query_class(ocean, count, lat.data(), lon.data(), cls.data()), "geocean_query_class");
  if ((sc == GEOCEAN_OK) != (haveMask || haveElevation || count == 0)) broken("query_class readiness");
  if (sc == GEOCEAN_OK)
    for (std::size_t i = 0; i < count; ++i)
      if (cls[i] > GEOCEAN_SURFACE_LAKE) broken("class out of range", cls[i], double(i));
  const geocean_status se =
      checked(geocean_query_elevation(ocean, count, lat.data(), lon.data(), elev.data()), "geocean_query_elevation");
  if (haveElevation && count > 0 && se != GEOCEAN_OK) broken("query_elevation with an elevation raster");

  geocean_surface_outputs out;
  if (geocean_surface_outputs_init(&out) != GEOCEAN_OK) broken("outputs_init");
  std::vector<uint8_t> cls2(count, 99);
  std::vector<float> elev2(count);
  out.surface_class = cls2.data();
  out.elevation_m = elev2.data();
  if (checked(geocean_query_surface(ocean, count, lat.data(), lon.data(), nullptr, 0, &out), "geocean_query_surface") ==
      GEOCEAN_OK) {
    // The one-pass query classifies like the class query (same snapshot).
    if (sc == GEOCEAN_OK)
      for (std::size_t i = 0; i < count; ++i)
        if (cls2[i] != cls[i]) broken("query_surface class differs from query_class", double(i), cls2[i]);
  }
  geocean_destroy(ocean);
  return 0;
}
