// The C ABI through the run-time loader (globe/host), as a host engine sees
// it: version checks, misuse (NULL handles, wrong order, bad rasters, bad
// arguments), results at known places, thread-local errors.
#include "tests/capi/LoadedPlugin.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace {

using geocean::host::OceanPlugin;

using namespace geocean::capitest;
using Ocean = OceanHandle;

geocean_grid_placement globalPlacement(int width, int height) {
  return {-180.0, 90.0, 360.0 / width, -180.0 / height, 1, 0, 0.0};
}

TEST(CapiLoader, LoadsTheBuiltPluginAndChecksItsVersion) {
  EXPECT_EQ(plugin().pluginAbiVersion(), GEOCEAN_ABI_VERSION);
  EXPECT_STREQ(plugin().api().versionString(), "0.1.0");
}

TEST(CapiLoader, RefusesAHostOfAnotherMajorOrANewerMinor) {
  std::string error;
  EXPECT_EQ(OceanPlugin::load(GEOCEAN_PLUGIN_BUILD_PATH, error, 2u << 16), nullptr);
  EXPECT_NE(error.find("plugin ABI 1.8 cannot serve a host built for ABI 2.0"), std::string::npos) << error;
  error.clear();
  EXPECT_EQ(OceanPlugin::load(GEOCEAN_PLUGIN_BUILD_PATH, error, GEOCEAN_ABI_VERSION + 1), nullptr);
  EXPECT_NE(error.find("ABI 1.8"), std::string::npos) << error;
  // An older minor of the same major is served.
  EXPECT_TRUE(OceanPlugin::compatible(1u << 16, (1u << 16) | 3u));
  EXPECT_FALSE(OceanPlugin::compatible((1u << 16) | 3u, 1u << 16));
}

TEST(CapiLoader, NamesAMissingLibrary) {
  std::string error;
  EXPECT_EQ(OceanPlugin::load("/nonexistent/libgeocean_ocean.so", error), nullptr);
  EXPECT_NE(error.find("/nonexistent/libgeocean_ocean.so"), std::string::npos) << error;
}

TEST(CapiMisuse, CreateRefusesAWrongAbiVersion) {
  geocean_ocean* h = reinterpret_cast<geocean_ocean*>(&h);  // garbage that must be overwritten
  EXPECT_EQ(plugin().api().create(0, &h), GEOCEAN_ERROR_ABI_VERSION);
  EXPECT_EQ(h, nullptr);
  EXPECT_NE(lastError().find("host ABI 0.0 is not served by this plugin (ABI 1.8)"), std::string::npos);
  EXPECT_EQ(plugin().api().create(GEOCEAN_ABI_VERSION, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_NE(lastError().find("geocean_create: out is NULL"), std::string::npos) << lastError();
}

TEST(CapiMisuse, EveryFunctionRejectsANullOcean) {
  const auto& a = plugin().api();
  const double lat = 0, lon = 0;
  uint8_t c = 0;
  float e = 0;
  const float px = 0;
  const auto pl = globalPlacement(1, 1);
  const std::vector<std::pair<const char*, geocean_status>> calls = {
      {"geocean_set_mask_file", a.setMaskFile(nullptr, "x.tif", GEOCEAN_GEOREF_FROM_FILE)},
      {"geocean_set_elevation_file", a.setElevationFile(nullptr, "x.tif", GEOCEAN_GEOREF_FROM_FILE)},
      {"geocean_set_mask_pixels", a.setMaskPixels(nullptr, &px, 1, 1, &pl)},
      {"geocean_set_elevation_pixels", a.setElevationPixels(nullptr, &px, 1, 1, &pl)},
      {"geocean_set_default_world", a.setDefaultWorld(nullptr)},
      {"geocean_clear_rasters", a.clearRasters(nullptr)},
      {"geocean_query_class", a.queryClass(nullptr, 1, &lat, &lon, &c)},
      {"geocean_query_elevation", a.queryElevation(nullptr, 1, &lat, &lon, &e)},
      {"geocean_update", a.update(nullptr, nullptr)},
      {"geocean_draw", a.draw(nullptr)},
      {"geocean_release_gl", a.releaseGl(nullptr)},
      {"geocean_view_init", a.viewInit(nullptr)},
      {"geocean_view_from_pose", a.viewFromPose(nullptr, 0, 0, 1, 0, -90, 45, 1, 1)},
      {"geocean_query_elevation", a.queryElevation(nullptr, 1, &lat, &lon, &e)},
  };
  for (const auto& [name, status] : calls) EXPECT_EQ(status, GEOCEAN_ERROR_NULL_ARGUMENT) << name;
  // The message names the last function called.
  EXPECT_EQ(lastError(), "geocean_query_elevation: ocean is NULL");
  a.destroy(nullptr);  // allowed
}

TEST(CapiMisuse, NullArraysAreRejectedUnlessCountIsZero) {
  Ocean o;
  const auto& a = plugin().api();
  const auto pl = globalPlacement(1, 1);
  const float zero = 0.0f;
  ASSERT_EQ(a.setMaskPixels(o.h, &zero, 1, 1, &pl), GEOCEAN_OK);
  ASSERT_EQ(a.setElevationPixels(o.h, &zero, 1, 1, &pl), GEOCEAN_OK);
  const double lat = 0, lon = 0;
  uint8_t c = 0;
  float e = 0;
  EXPECT_EQ(a.queryElevation(o.h, 1, &lat, nullptr, &e), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.queryClass(o.h, 1, nullptr, &lon, &c), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_query_class: lat_deg is NULL");
  EXPECT_EQ(a.queryClass(o.h, 1, &lat, nullptr, &c), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.queryClass(o.h, 1, &lat, &lon, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.queryElevation(o.h, 1, &lat, &lon, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_query_elevation: out_elevation_m is NULL");
  EXPECT_EQ(a.queryClass(o.h, 0, nullptr, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(a.queryElevation(o.h, 0, nullptr, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(a.setMaskFile(o.h, nullptr, GEOCEAN_GEOREF_FROM_FILE), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.setMaskPixels(o.h, nullptr, 1, 1, &pl), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.setMaskPixels(o.h, &zero, 1, 1, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_set_mask_pixels: placement is NULL");
}

TEST(CapiMisuse, QueriesBeforeRastersSayWhatIsMissing) {
  Ocean o;
  const auto& a = plugin().api();
  const double lat = 0, lon = 0;
  uint8_t c = 0;
  float e = 0;
  EXPECT_EQ(a.queryClass(o.h, 1, &lat, &lon, &c), GEOCEAN_ERROR_NOT_READY);
  EXPECT_NE(lastError().find("no mask or elevation raster"), std::string::npos) << lastError();
  const auto pl = globalPlacement(1, 1);
  const float one = 1.0f;
  ASSERT_EQ(a.setMaskPixels(o.h, &one, 1, 1, &pl), GEOCEAN_OK);
  EXPECT_EQ(lastError(), "");  // success clears the thread's message
  EXPECT_EQ(a.queryClass(o.h, 1, &lat, &lon, &c), GEOCEAN_OK);
  EXPECT_EQ(c, GEOCEAN_SURFACE_LAND);
  // A mask alone gives classes but no elevation.
  EXPECT_EQ(a.queryElevation(o.h, 1, &lat, &lon, &e), GEOCEAN_ERROR_NOT_READY);
  EXPECT_NE(lastError().find("no elevation raster"), std::string::npos) << lastError();
  ASSERT_EQ(a.clearRasters(o.h), GEOCEAN_OK);
  EXPECT_EQ(a.queryClass(o.h, 1, &lat, &lon, &c), GEOCEAN_ERROR_NOT_READY);
}

TEST(CapiMisuse, BadRasterFileNamesTheFileAndKeepsThePreviousRaster) {
  Ocean o;
  const auto& a = plugin().api();
  const auto pl = globalPlacement(1, 1);
  const float lake = 2.0f;
  ASSERT_EQ(a.setMaskPixels(o.h, &lake, 1, 1, &pl), GEOCEAN_OK);
  EXPECT_EQ(a.setMaskFile(o.h, "/nonexistent/mask.tif", GEOCEAN_GEOREF_FROM_FILE), GEOCEAN_ERROR_RASTER);
  EXPECT_EQ(lastError().rfind("geocean_set_mask_file: ", 0), 0u) << lastError();
  EXPECT_NE(lastError().find("/nonexistent/mask.tif"), std::string::npos) << lastError();
  // A file that exists but is not an image.
  const std::string notImage = std::string(GEOCEAN_SOURCE_DIR) + "/tests/capi/test_capi.cpp";
  EXPECT_EQ(a.setElevationFile(o.h, notImage.c_str(), GEOCEAN_GEOREF_FROM_FILE), GEOCEAN_ERROR_RASTER);
  EXPECT_NE(lastError().find("test_capi.cpp"), std::string::npos) << lastError();
  const double lat = 10, lon = 20;
  uint8_t c = 0;
  EXPECT_EQ(a.queryClass(o.h, 1, &lat, &lon, &c), GEOCEAN_OK);
  EXPECT_EQ(c, GEOCEAN_SURFACE_LAKE);
  EXPECT_EQ(a.setMaskFile(o.h, "x.tif", static_cast<geocean_georef>(7)), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_set_mask_file: georef 7 is not a geocean_georef");
}

TEST(CapiMisuse, BadPlacementsNameTheField) {
  Ocean o;
  const auto& a = plugin().api();
  const std::vector<float> px(8, 0.0f);
  auto pl = globalPlacement(4, 2);
  EXPECT_EQ(a.setMaskPixels(o.h, px.data(), 0, 2, &pl), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("raster size 0 x 2"), std::string::npos) << lastError();
  pl.lon_step_deg = -90.0;
  EXPECT_EQ(a.setMaskPixels(o.h, px.data(), 4, 2, &pl), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("lon_step_deg"), std::string::npos) << lastError();
  pl = globalPlacement(4, 2);
  pl.lat_step_deg = NAN;
  EXPECT_EQ(a.setMaskPixels(o.h, px.data(), 4, 2, &pl), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("lat_step_deg"), std::string::npos) << lastError();
  // Rows beyond a pole by more than the file reader's pixel of slack: a
  // "global" raster there was clamped to its edge row everywhere (fuzz).
  pl = globalPlacement(4, 2);
  pl.origin_lat_deg = -1.1e307;
  EXPECT_EQ(a.setElevationPixels(o.h, px.data(), 4, 2, &pl), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("origin_lat_deg -1.1e+307"), std::string::npos) << lastError();
  pl = globalPlacement(4, 2);
  pl.origin_lat_deg = 92.0;  // 2 rows of 90 deg: [-88, 92], within one pixel of the pole (GMT's pixel-is-point)
  EXPECT_EQ(a.setMaskPixels(o.h, px.data(), 4, 2, &pl), GEOCEAN_OK) << lastError();
  pl.origin_lat_deg = 181.0;  // [1, 181]
  EXPECT_EQ(a.setMaskPixels(o.h, px.data(), 4, 2, &pl), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("latitude range [1, 181]"), std::string::npos) << lastError();
  pl = globalPlacement(4, 2);
  pl.lon_step_deg = 45.0;  // 4 x 45 = 180: not a global raster
  EXPECT_EQ(a.setMaskPixels(o.h, px.data(), 4, 2, &pl), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("not 360"), std::string::npos) << lastError();
}

// Elevation from memory: a plane in (lon, lat) is reproduced exactly by
// bilinear interpolation, so the answer is known without our code.
TEST(CapiQuery, ElevationFromMemoryInterpolatesAPlane) {
  Ocean o;
  const auto& a = plugin().api();
  const int w = 20, h = 10;  // 1-degree cells over lon [0, 20), lat (40, 50]
  std::vector<float> z(w * h);
  auto plane = [](double lonDeg, double latDeg) { return 100.0 * lonDeg - 30.0 * latDeg; };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) z[j * w + i] = float(plane(i + 0.5, 50.0 - (j + 0.5)));
  const geocean_grid_placement pl{0.0, 50.0, 1.0, -1.0, 0, 0, 0.0};
  ASSERT_EQ(a.setElevationPixels(o.h, z.data(), w, h, &pl), GEOCEAN_OK) << lastError();
  const std::vector<double> lat = {45.0, 41.3, 49.25}, lon = {10.0, 3.7, 18.5};
  std::vector<float> e(3);
  ASSERT_EQ(a.queryElevation(o.h, 3, lat.data(), lon.data(), e.data()), GEOCEAN_OK) << lastError();
  // Float pixel values and float output: relative 1e-6 of ~2000 m (float has 24 bits).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], plane(lon[k], lat[k]), 2e-3) << k;
  // Elevation alone classifies: below 0 is ocean.
  std::vector<uint8_t> c(3);
  const std::vector<double> latC = {49.5, 40.5}, lonC = {0.5, 19.5};  // z = -1485, +735
  ASSERT_EQ(a.queryClass(o.h, 2, latC.data(), lonC.data(), c.data()), GEOCEAN_OK);
  EXPECT_EQ(c[0], GEOCEAN_SURFACE_OCEAN);
  EXPECT_EQ(c[1], GEOCEAN_SURFACE_LAND);
}

// The default world at places whose nature is not in doubt.
TEST(CapiQuery, DefaultWorldAtKnownPlaces) {
  setenv("GEOCEAN_DATA", GEOCEAN_DATA_DIR, 1);
  Ocean o;
  const auto& a = plugin().api();
  ASSERT_EQ(a.setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  // Mid-Atlantic, Sahara, Lake Superior, Challenger Deep, Everest.
  const std::vector<double> lat = {30.0, 23.0, 47.6, 11.35, 27.99}, lon = {-40.0, 10.0, -87.5, 142.2, 86.93};
  const std::vector<uint8_t> expected = {GEOCEAN_SURFACE_OCEAN, GEOCEAN_SURFACE_LAND, GEOCEAN_SURFACE_LAKE,
                                         GEOCEAN_SURFACE_OCEAN, GEOCEAN_SURFACE_LAND};
  std::vector<uint8_t> c(5);
  std::vector<float> e(5);
  ASSERT_EQ(a.queryClass(o.h, 5, lat.data(), lon.data(), c.data()), GEOCEAN_OK);
  ASSERT_EQ(a.queryElevation(o.h, 5, lat.data(), lon.data(), e.data()), GEOCEAN_OK);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(c[k], expected[k]) << k;
  // 20' cells average the extremes (-10994 m, 8849 m) away: loose bounds.
  EXPECT_LT(e[3], -5000.0f);
  EXPECT_GT(e[4], 4000.0f);
  EXPECT_LT(e[0], -2000.0f);  // the Atlantic there is 4-5 km deep
}

TEST(CapiErrors, MessagesAreThreadLocal) {
  const auto& a = plugin().api();
  ASSERT_EQ(a.create(0, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  std::string other = "unset";
  std::thread t([&] {
    geocean_ocean* h = nullptr;
    EXPECT_EQ(a.create(GEOCEAN_ABI_VERSION, &h), GEOCEAN_OK);
    other = a.lastError();
    a.destroy(h);
  });
  t.join();
  EXPECT_EQ(other, "");
  EXPECT_EQ(lastError(), "geocean_create: out is NULL");
  EXPECT_STREQ(a.statusString(static_cast<geocean_status>(42)), "GEOCEAN_ERROR_UNKNOWN_STATUS");
}

// Queries from several threads while another thread replaces the mask: each
// batch must see one mask or the other, never a mix or a torn state.
TEST(CapiThreads, QueriesSeeWholeStatesWhileTheMaskIsReplaced) {
  Ocean o;
  const auto& a = plugin().api();
  const int w = 360, h = 180;
  const std::vector<float> ocean(w * h, 0.0f), land(w * h, 1.0f);
  const auto pl = globalPlacement(w, h);
  ASSERT_EQ(a.setMaskPixels(o.h, ocean.data(), w, h, &pl), GEOCEAN_OK);
  const std::size_t n = 20000;
  std::vector<double> lat(n), lon(n);
  for (std::size_t i = 0; i < n; ++i) {
    lat[i] = -89.5 + 179.0 * double(i) / n;
    lon[i] = -180.0 + 360.0 * double((i * 7919) % n) / n;
  }
  std::atomic<bool> stop{false};
  std::atomic<int> mixed{0}, failed{0}, sawOcean{0}, sawLand{0};
  std::vector<std::thread> readers;
  for (int t = 0; t < 3; ++t)
    readers.emplace_back([&] {
      std::vector<uint8_t> c(n);
      while (!stop) {
        if (a.queryClass(o.h, n, lat.data(), lon.data(), c.data()) != GEOCEAN_OK) ++failed;
        const auto ones = std::count(c.begin(), c.end(), uint8_t(1));
        if (ones != 0 && ones != std::ptrdiff_t(n)) ++mixed;
        (ones ? sawLand : sawOcean)++;
      }
    });
  for (int k = 0; k < 200; ++k) {
    ASSERT_EQ(a.setMaskPixels(o.h, (k % 2 ? ocean : land).data(), w, h, &pl), GEOCEAN_OK) << lastError();
    // Let each state be seen: 4 more batches among 3 readers means one reader
    // began a batch after the swap. Without this, on a loaded machine the
    // readers could see only one state (the test then proves nothing).
    const int seen = sawOcean + sawLand;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (sawOcean + sawLand < seen + 4 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
  }
  stop = true;
  for (auto& r : readers) r.join();
  EXPECT_EQ(failed, 0);
  EXPECT_EQ(mixed, 0);
  EXPECT_GT(sawOcean, 0);  // both states were seen: the test exercised the swap
  EXPECT_GT(sawLand, 0);
}

geocean_sea_state seaState(double windMps, geocean_wave_model model = GEOCEAN_WAVES_NOISE) {
  geocean_sea_state s;
  EXPECT_EQ(plugin().api().seaStateInit(&s), GEOCEAN_OK);
  s.wind_speed_mps = windMps;
  s.model = model;
  return s;
}

TEST(CapiSea, QueriesNeedASeaStateAndBadOnesNameTheField) {
  Ocean o;
  const auto& a = plugin().api();
  const double lat = 0, lon = 0;
  double h = 0, hs = 0;
  EXPECT_EQ(a.querySeaSurface(o.h, 1, &lat, &lon, 0.0, &h, nullptr, nullptr), GEOCEAN_ERROR_NOT_READY);
  EXPECT_EQ(lastError(), "geocean_query_sea_surface: no sea state: call geocean_set_sea_state first");
  EXPECT_EQ(a.significantWaveHeight(o.h, &hs), GEOCEAN_ERROR_NOT_READY);
  auto s = seaState(100.0);
  EXPECT_EQ(a.setSeaState(o.h, &s), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_set_sea_state: sea_state->wind_speed_mps 100 is invalid (expected 0.2 .. 60 m/s)");
  s = seaState(10.0);
  s.model = 9;
  EXPECT_EQ(a.setSeaState(o.h, &s), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("sea_state->model 9"), std::string::npos) << lastError();
  s = seaState(10.0);
  s.struct_size = 8;  // a host that never called geocean_sea_state_init
  EXPECT_EQ(a.setSeaState(o.h, &s), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("struct_size 8"), std::string::npos) << lastError();
  EXPECT_EQ(a.setSeaState(o.h, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.seaStateSetBeaufort(&s, 13), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(a.seaStateInit(nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  s = seaState(10.0);
  ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
  EXPECT_EQ(a.querySeaSurface(o.h, 1, &lat, &lon, NAN, &h, nullptr, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(a.querySeaSurface(o.h, 1, &lat, &lon, 0.0, nullptr, nullptr, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.querySeaSurface(nullptr, 1, &lat, &lon, 0.0, &h, nullptr, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
}

TEST(CapiSea, BeaufortSixIsAStrongBreeze) {
  geocean_sea_state s = seaState(1.0);
  ASSERT_EQ(plugin().api().seaStateSetBeaufort(&s, 6), GEOCEAN_OK);
  // WMO Beaufort 6: 10.8 .. 13.8 m/s at 10 m; at 19.5 m about 1.026 x that.
  EXPECT_GT(s.wind_speed_mps, 10.8);
  EXPECT_LT(s.wind_speed_mps, 13.8 * 1.03);
}

// Physics, not our code: a fully developed sea has Hs ~ 0.21 U^2 / g
// (Pierson-Moskowitz), and 4 std(height) of the simulated sea estimates Hs.
TEST(CapiSea, HeightsHaveThePiersonMoskowitzSignificantHeight) {
  const auto& a = plugin().api();
  for (auto model : {GEOCEAN_WAVES_NOISE, GEOCEAN_WAVES_GERSTNER}) {
    Ocean o;  // no rasters: deep ocean everywhere
    const double windMps = 12.0, hsPm = 0.21 * windMps * windMps / 9.80665;
    const auto s = seaState(windMps, model);
    ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
    double hs = 0;
    ASSERT_EQ(a.significantWaveHeight(o.h, &hs), GEOCEAN_OK);
    EXPECT_NEAR(hs, hsPm, 0.10 * hsPm) << model;  // the 10% goal for the spectrum
    // Points 1..20 km apart over a 2 x 2 degree box and 8 times: many independent waves.
    const std::size_t n = 8000;
    std::vector<double> lat(n), lon(n), h(n), nrm(3 * n);
    std::vector<uint8_t> c(n);
    double sum = 0, sum2 = 0;
    for (int t = 0; t < 8; ++t) {
      for (std::size_t i = 0; i < n; ++i) {
        lat[i] = 10.0 + 2.0 * double((i * 37) % n) / n;
        lon[i] = -30.0 + 2.0 * double((i * 101) % n) / n;
      }
      ASSERT_EQ(a.querySeaSurface(o.h, n, lat.data(), lon.data(), 100.0 * t, h.data(), nrm.data(), c.data()),
                GEOCEAN_OK)
          << lastError();
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(c[i], GEOCEAN_SURFACE_OCEAN);
        sum += h[i];
        sum2 += h[i] * h[i];
        const double len = std::hypot(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
        ASSERT_NEAR(len, 1.0, 1e-9);  // unit normal, double rounding only
        ASSERT_GT(nrm[3 * i + 2], 0.0);
      }
    }
    const double m = 8.0 * n, mean = sum / m, sd = std::sqrt(sum2 / m - mean * mean);
    // 64k samples of a smooth field are not independent: allow 15% around the 10% model goal.
    EXPECT_NEAR(4.0 * sd, hsPm, 0.15 * hsPm) << model;
    EXPECT_NEAR(mean, 0.0, 0.1 * hsPm) << model;
  }
}

TEST(CapiSea, LandAndLakesAreNotSea) {
  setenv("GEOCEAN_DATA", GEOCEAN_DATA_DIR, 1);
  Ocean o;
  const auto& a = plugin().api();
  ASSERT_EQ(a.setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  const auto s = seaState(10.0, GEOCEAN_WAVES_GERSTNER);
  ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
  const std::vector<double> lat = {30.0, 23.0, 47.6}, lon = {-40.0, 10.0, -87.5};  // Atlantic, Sahara, Superior
  std::vector<double> h(3), n(9);
  std::vector<uint8_t> c(3);
  ASSERT_EQ(a.querySeaSurface(o.h, 3, lat.data(), lon.data(), 12.5, h.data(), n.data(), c.data()), GEOCEAN_OK);
  EXPECT_EQ(c[0], GEOCEAN_SURFACE_OCEAN);
  EXPECT_TRUE(std::isfinite(h[0]));
  EXPECT_LT(std::abs(h[0]), 10.0);  // 10 m/s: Hs ~ 2 m, crests far below 10 m
  EXPECT_EQ(c[1], GEOCEAN_SURFACE_LAND);
  EXPECT_TRUE(std::isnan(h[1]) && std::isnan(n[3]));
  EXPECT_EQ(c[2], GEOCEAN_SURFACE_LAKE);
  EXPECT_TRUE(std::isnan(h[2]));
  // Deterministic in t: asking again gives the same bits.
  double again = 0;
  ASSERT_EQ(a.querySeaSurface(o.h, 1, lat.data(), lon.data(), 12.5, &again, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(again, h[0]);
}

// Sea-surface queries from several threads while the sea state is replaced:
// each batch equals, bit for bit, the answer of one whole sea state.
TEST(CapiThreads, SeaQueriesSeeWholeSeaStatesWhileTheStateIsReplaced) {
  Ocean o;
  const auto& a = plugin().api();
  const std::size_t n = 2000;
  std::vector<double> lat(n), lon(n);
  for (std::size_t i = 0; i < n; ++i) {
    lat[i] = -60.0 + 120.0 * double(i) / n;
    lon[i] = -180.0 + 360.0 * double((i * 613) % n) / n;
  }
  const auto calm = seaState(5.0), storm = seaState(20.0);
  std::vector<double> refCalm(n), refStorm(n);
  ASSERT_EQ(a.setSeaState(o.h, &storm), GEOCEAN_OK);
  ASSERT_EQ(a.querySeaSurface(o.h, n, lat.data(), lon.data(), 3.0, refStorm.data(), nullptr, nullptr), GEOCEAN_OK);
  ASSERT_EQ(a.setSeaState(o.h, &calm), GEOCEAN_OK);
  ASSERT_EQ(a.querySeaSurface(o.h, n, lat.data(), lon.data(), 3.0, refCalm.data(), nullptr, nullptr), GEOCEAN_OK);
  ASSERT_NE(refCalm, refStorm);
  std::atomic<bool> stop{false};
  std::atomic<int> bad{0}, batches{0};
  std::vector<std::thread> readers;
  for (int t = 0; t < 3; ++t)
    readers.emplace_back([&] {
      std::vector<double> h(n);
      while (!stop) {
        if (a.querySeaSurface(o.h, n, lat.data(), lon.data(), 3.0, h.data(), nullptr, nullptr) != GEOCEAN_OK ||
            (h != refCalm && h != refStorm))
          ++bad;
        ++batches;
      }
    });
  // Keep replacing until the readers have finished enough batches (the machine may be busy).
  for (int k = 0; k < 100 || batches < 30; ++k) ASSERT_EQ(a.setSeaState(o.h, k % 2 ? &calm : &storm), GEOCEAN_OK);
  stop = true;
  for (auto& r : readers) r.join();
  EXPECT_EQ(bad, 0);
}

}  // namespace

namespace {
geocean_view poseView(double latDeg, double lonDeg, double heightM, double pitchDeg = -90.0) {
  geocean_view v;
  EXPECT_EQ(plugin().api().viewInit(&v), GEOCEAN_OK);
  EXPECT_EQ(plugin().api().viewFromPose(&v, latDeg, lonDeg, heightM, 0.0, pitchDeg, 45.0, 256, 256), GEOCEAN_OK)
      << lastError();
  return v;
}
}  // namespace

TEST(CapiRenderMisuse, DrawWithoutAGlContextSaysSo) {
  // This test process never loads EGL or GLX: no context can be current.
  Ocean o;
  const auto& a = plugin().api();
  geocean_sea_state s;
  ASSERT_EQ(a.seaStateInit(&s), GEOCEAN_OK);
  ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK);
  const geocean_view v = poseView(30.0, -40.0, 100.0);
  ASSERT_EQ(a.update(o.h, &v), GEOCEAN_OK) << lastError();
  EXPECT_EQ(a.draw(o.h), GEOCEAN_ERROR_NO_GL_CONTEXT);
  EXPECT_NE(lastError().find("geocean_draw: no OpenGL context is current"), std::string::npos) << lastError();
  // Nothing was created, so there is nothing to release: not an error.
  EXPECT_EQ(a.releaseGl(o.h), GEOCEAN_OK);
}

TEST(CapiRenderMisuse, UpdateRejectsBadViewsAndKeepsThePreviousOne) {
  Ocean o;
  const auto& a = plugin().api();
  const geocean_view good = poseView(30.0, -40.0, 100.0);
  ASSERT_EQ(a.update(o.h, &good), GEOCEAN_OK);
  EXPECT_EQ(a.update(o.h, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_update: view is NULL");
  struct Case {
    const char* expect;
    void (*edit)(geocean_view&);
  };
  const Case cases[] = {
      {"view->struct_size 4 is smaller than", [](geocean_view& v) { v.struct_size = 4; }},
      {"view->eye_ecef_m is not finite", [](geocean_view& v) { v.eye_ecef_m[1] = std::nan(""); }},
      {"view->time_s inf is not finite", [](geocean_view& v) { v.time_s = INFINITY; }},
      {"view->view_matrix is not finite", [](geocean_view& v) { v.view_matrix[5] = std::nan(""); }},
      {"view->projection_matrix is not finite", [](geocean_view& v) { v.projection_matrix[0] = -INFINITY; }},
      {"view->viewport 0x256 is not within 1 .. 16384", [](geocean_view& v) { v.viewport_width_px = 0; }},
      {"view->sun_dir_ecef is zero",
       [](geocean_view& v) { v.sun_dir_ecef[0] = v.sun_dir_ecef[1] = v.sun_dir_ecef[2] = 0.0; }},
      {"view->view_matrix rotation is not orthonormal",
       [](geocean_view& v) {
         for (int i = 0; i < 12; ++i) v.view_matrix[i] *= 2.0;  // a scaled view
       }},
      {"view->view_matrix rotation is not orthonormal and right-handed",
       [](geocean_view& v) {
         for (int c = 0; c < 3; ++c) v.view_matrix[4 * c] = -v.view_matrix[4 * c];  // mirrored
       }},
      {"view->projection_matrix is not a symmetric perspective",
       [](geocean_view& v) { v.projection_matrix[11] = 0.0; }},  // orthographic
      {"view->projection_matrix aspect 1.000000 does not match the viewport's 2.000000",
       [](geocean_view& v) { v.viewport_width_px = 512; }},
  };
  for (const Case& c : cases) {
    geocean_view v = good;
    c.edit(v);
    EXPECT_EQ(a.update(o.h, &v), GEOCEAN_ERROR_INVALID_ARGUMENT) << c.expect;
    EXPECT_NE(lastError().find(c.expect), std::string::npos) << lastError();
  }
}

TEST(CapiRenderMisuse, ViewFromPoseNamesTheBadValue) {
  const auto& a = plugin().api();
  geocean_view v;
  ASSERT_EQ(a.viewInit(&v), GEOCEAN_OK);
  EXPECT_EQ(v.struct_size, sizeof(geocean_view));
  EXPECT_EQ(a.viewFromPose(&v, 91.0, 0, 1, 0, -90, 45, 256, 256), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("lat_deg 91.000000 is not within -90 .. 90"), std::string::npos) << lastError();
  EXPECT_EQ(a.viewFromPose(&v, 0, 0, std::nan(""), 0, -90, 45, 256, 256), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("height_m nan"), std::string::npos) << lastError();
  EXPECT_EQ(a.viewFromPose(&v, 0, 0, 1, 0, -90, 0.5, 256, 256), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("fov_y_deg"), std::string::npos) << lastError();
  EXPECT_EQ(a.viewFromPose(&v, 0, 0, 1, 0, -90, 45, 256, -3), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("height_px -3"), std::string::npos) << lastError();
}

TEST(CapiRender, ViewFromPoseLooksWhereThePoseSays) {
  // Independent of the plugin's math: the eye from GeographicLib's formula
  // for the equator (N = a), the forward vector of a nadir view is -up.
  const geocean_view v = poseView(0.0, 90.0, 1000.0);
  EXPECT_NEAR(v.eye_ecef_m[0], 0.0, 1e-6);
  EXPECT_NEAR(v.eye_ecef_m[1], 6378137.0 + 1000.0, 1e-6);  // 1e-6 m: double rounding at 6.4e6 m
  EXPECT_NEAR(v.eye_ecef_m[2], 0.0, 1e-6);
  // Third row of the view rotation is "back" (-forward) = +Y (up at 0 N 90 E).
  EXPECT_NEAR(v.view_matrix[2], 0.0, 1e-12);
  EXPECT_NEAR(v.view_matrix[6], 1.0, 1e-12);
  EXPECT_NEAR(v.view_matrix[10], 0.0, 1e-12);
  // 45 deg vertical field of view: P[1][1] = 1 / tan(22.5 deg).
  EXPECT_NEAR(v.projection_matrix[5], 1.0 / std::tan(22.5 * M_PI / 180.0), 1e-12);
  EXPECT_EQ(v.projection_matrix[11], -1.0);
}

// ---- ABI 1.2: read options, mask encoding, the one-pass surface query ----

namespace {

// All outputs of geocean_query_surface for n points.
struct SurfaceAnswers {
  std::vector<uint8_t> cls;
  std::vector<float> elevation;
  std::vector<double> height, normal, w, uv;
  geocean_surface_outputs out{};
  explicit SurfaceAnswers(std::size_t n) : cls(n), elevation(n), height(n), normal(3 * n), w(n), uv(2 * n) {
    EXPECT_EQ(plugin().api().surfaceOutputsInit(&out), GEOCEAN_OK);
    out.surface_class = cls.data();
    out.elevation_m = elevation.data();
    out.height_m = height.data();
    out.normal_enu = normal.data();
    out.vertical_velocity_mps = w.data();
    out.horizontal_velocity_en_mps = uv.data();
  }
};

TEST(CapiV12, NewFunctionsRejectNullsAndBadStructsNamingTheField) {
  const auto& a = plugin().api();
  ASSERT_NE(a.querySurface, nullptr);  // a 1.2 plugin resolves them all
  EXPECT_EQ(a.rasterOptionsInit(nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.surfaceOutputsInit(nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  geocean_raster_options ro;
  ASSERT_EQ(a.rasterOptionsInit(&ro), GEOCEAN_OK);
  EXPECT_EQ(ro.struct_size, sizeof(geocean_raster_options));
  EXPECT_EQ(ro.georef, GEOCEAN_GEOREF_FROM_FILE);
  EXPECT_EQ(ro.few_lookups, 0);
  EXPECT_EQ(a.setMaskFileWithOptions(nullptr, "x.tif", &ro), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.setMaskEncoding(nullptr, "0=ocean"), GEOCEAN_ERROR_NULL_ARGUMENT);
  Ocean o;
  EXPECT_EQ(a.setElevationFileWithOptions(o.h, "x.tif", nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_set_elevation_file_with_options: options is NULL");
  EXPECT_EQ(a.setDefaultWorldWithOptions(o.h, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  ro.georef = 7;
  EXPECT_EQ(a.setMaskFileWithOptions(o.h, "x.tif", &ro), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_set_mask_file_with_options: options->georef 7 is not a geocean_georef");
  ro.georef = GEOCEAN_GEOREF_FROM_FILE;
  ro.struct_size = 4;
  EXPECT_EQ(a.setMaskFileWithOptions(o.h, "x.tif", &ro), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("options->struct_size 4"), std::string::npos) << lastError();
  ASSERT_EQ(a.rasterOptionsInit(&ro), GEOCEAN_OK);
  EXPECT_EQ(a.setMaskFileWithOptions(o.h, "/nonexistent/m.tif", &ro), GEOCEAN_ERROR_RASTER);
  EXPECT_NE(lastError().find("/nonexistent/m.tif"), std::string::npos) << lastError();
  EXPECT_EQ(a.setMaskEncoding(o.h, "0=sea"), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("'sea'"), std::string::npos) << lastError();

  const double lat[2] = {0, 1}, lon[2] = {0, 1}, t[2] = {0, std::nan("")};
  SurfaceAnswers s(2);
  EXPECT_EQ(a.querySurface(nullptr, 2, lat, lon, t, 1, &s.out), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, t, 1, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  // No sea state: sea outputs are not ready, class and elevation are.
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, t, 1, &s.out), GEOCEAN_ERROR_NOT_READY);
  EXPECT_EQ(lastError(), "geocean_query_surface: no sea state: call geocean_set_sea_state first");
  geocean_surface_outputs classOnly;
  ASSERT_EQ(a.surfaceOutputsInit(&classOnly), GEOCEAN_OK);
  classOnly.surface_class = s.cls.data();
  classOnly.elevation_m = s.elevation.data();
  s.cls = {9, 9};
  ASSERT_EQ(a.querySurface(o.h, 2, lat, lon, nullptr, 0, &classOnly), GEOCEAN_OK) << lastError();
  EXPECT_EQ(s.cls, (std::vector<uint8_t>{GEOCEAN_SURFACE_OCEAN, GEOCEAN_SURFACE_OCEAN}));  // no rasters: deep ocean
  EXPECT_TRUE(std::isnan(s.elevation[0]));
  const auto sea = seaState(10.0);
  ASSERT_EQ(a.setSeaState(o.h, &sea), GEOCEAN_OK);
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, t, 3, &s.out), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("time_count 3 is neither 1 nor count (2)"), std::string::npos) << lastError();
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, t, 2, &s.out), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("time_s[1] nan is not finite"), std::string::npos) << lastError();
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, nullptr, 1, &s.out), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.querySurface(o.h, 2, nullptr, lon, t, 1, &s.out), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(a.querySurface(o.h, 0, nullptr, nullptr, nullptr, 0, &s.out), GEOCEAN_OK);
  geocean_surface_outputs old = s.out;
  old.struct_size = 8;
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, t, 1, &old), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("outputs->struct_size 8"), std::string::npos) << lastError();
  ASSERT_EQ(a.querySurface(o.h, 2, lat, lon, t, 1, &s.out), GEOCEAN_OK) << lastError();
  EXPECT_TRUE(std::isfinite(s.height[0]) && std::isfinite(s.height[1]));
}

// Known places: the open Pacific is ocean and the Swiss plateau land; an
// encoding that swaps the mask's 0 and 1 swaps them; NULL restores it.
TEST(CapiV12, MaskEncodingSwapsKnownPlaces) {
  setenv("GEOCEAN_DATA", GEOCEAN_DATA_DIR, 1);
  Ocean o;
  const auto& a = plugin().api();
  ASSERT_EQ(a.setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  const double lat[2] = {0.0, 46.8}, lon[2] = {-150.0, 8.2};
  uint8_t c[2] = {9, 9};
  ASSERT_EQ(a.queryClass(o.h, 2, lat, lon, c), GEOCEAN_OK);
  EXPECT_EQ(c[0], GEOCEAN_SURFACE_OCEAN);
  EXPECT_EQ(c[1], GEOCEAN_SURFACE_LAND);
  ASSERT_EQ(a.setMaskEncoding(o.h, "0=land,1=ocean,2=lake"), GEOCEAN_OK) << lastError();
  ASSERT_EQ(a.queryClass(o.h, 2, lat, lon, c), GEOCEAN_OK);
  EXPECT_EQ(c[0], GEOCEAN_SURFACE_LAND);
  EXPECT_EQ(c[1], GEOCEAN_SURFACE_OCEAN);
  ASSERT_EQ(a.setMaskEncoding(o.h, nullptr), GEOCEAN_OK);
  ASSERT_EQ(a.queryClass(o.h, 2, lat, lon, c), GEOCEAN_OK);
  EXPECT_EQ(c[0], GEOCEAN_SURFACE_OCEAN);
  EXPECT_EQ(c[1], GEOCEAN_SURFACE_LAND);
}

// One JSON row of `geocean query --format json`; NaN where it printed null.
struct CliRow {
  std::string surface;
  double elevation = 0, height = 0, normal[3] = {0, 0, 0}, w = 0;
};
// The CLI prints floats (elevation) in float's shortest form: read those as float.
double jsonNumber(const std::string& line, const std::string& key, bool isFloat = false) {
  const std::size_t k = line.find("\"" + key + "\":");
  EXPECT_NE(k, std::string::npos) << key << " in " << line;
  const char* p = line.c_str() + k + key.size() + 3;
  if (std::string_view(p).substr(0, 4) == "null") return std::nan("");
  return isFloat ? double(std::strtof(p, nullptr)) : std::strtod(p, nullptr);
}
std::vector<CliRow> parseCliJson(const std::string& out) {
  std::vector<CliRow> rows;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    CliRow r;
    const std::size_t s = line.find("\"surface\":\"") + 11;
    r.surface = line.substr(s, line.find('"', s) - s);
    r.elevation = jsonNumber(line, "elevation_m", true);
    r.height = jsonNumber(line, "sea_height_m");
    r.w = jsonNumber(line, "vertical_velocity_mps");
    const std::size_t n = line.find("\"normal\":[");
    if (n == std::string::npos) {
      r.normal[0] = r.normal[1] = r.normal[2] = std::nan("");
    } else {
      const char* p = line.c_str() + n + 10;
      for (double& v : r.normal) {
        char* e = nullptr;
        v = std::strtod(p, &e);
        p = e + 1;  // the comma or the bracket
      }
    }
    rows.push_back(r);
  }
  return rows;
}
const char* className(uint8_t c) { return c == GEOCEAN_SURFACE_OCEAN ? "ocean" : c == GEOCEAN_SURFACE_LAND ? "land" : "lake"; }
// Same bits, or both NaN (the CLI's null).
bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

// The ABI gives exactly what `geocean query` prints (the CLI prints the
// shortest round-trip form, so parsing it back gives the same double), for
// every model, per-row times and rows without one (--time), in a batch and
// for one point (which reads only its tiles: few_lookups).
TEST(CapiV12, QuerySurfaceGivesExactlyTheCliAnswers) {
  setenv("GEOCEAN_DATA", GEOCEAN_DATA_DIR, 1);
  const auto& a = plugin().api();
  // Open ocean, coasts, land, a lake, poles, the antimeridian, the Caspian.
  const std::vector<double> lat = {0.0, 10.0, -33.9, 46.8, 35.95, -48.88, 47.7, 90.0, -90.0, -17.0, 42.0, 60.1, -0.5};
  const std::vector<double> lon = {-150.0, -140.0, 151.5, 8.2, -5.6, -123.39, -87.5, 0.0, 0.0, 180.0, 50.5, -179.99, 33.0};
  const double defaultTime = 17.25;
  std::vector<std::optional<double>> rowTime(lat.size());
  for (std::size_t i = 0; i < lat.size(); ++i)
    if (i % 4 != 3) rowTime[i] = 2.5 * double(i % 5);  // few distinct times: the FFT builds a table per time
  std::ostringstream csv;
  csv.precision(17);
  std::vector<double> t(lat.size());
  for (std::size_t i = 0; i < lat.size(); ++i) {
    csv << lat[i] << ',' << lon[i];
    if (rowTime[i]) csv << ',' << *rowTime[i];
    csv << '\n';
    t[i] = rowTime[i].value_or(defaultTime);
  }
  const char* cliSea = " --wind 12 --wind-dir 200 --fetch 50000 --seed 7 --anchor 10,-140";
  for (auto model : {GEOCEAN_WAVES_NOISE, GEOCEAN_WAVES_NOISE_PAPER, GEOCEAN_WAVES_GERSTNER, GEOCEAN_WAVES_FFT}) {
    const char* name[] = {"noise", "noise-paper", "gerstner", "fft"};
    auto s = seaState(12.0, model);
    s.wind_from_deg = 200.0;
    s.fetch_m = 50000.0;
    s.seed = 7;
    s.anchor_lat_deg = 10.0;
    s.anchor_lon_deg = -140.0;
    const std::string args = std::string(" --format json --waves ") + name[model] + cliSea;
    const auto r = geocean::test::run(std::string(GEOCEAN_EXE) + " query --points - --time 17.25" + args, csv.str());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = parseCliJson(r.out);
    ASSERT_EQ(rows.size(), lat.size()) << r.out;
    Ocean o;
    ASSERT_EQ(a.setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
    ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
    SurfaceAnswers ans(lat.size());
    ASSERT_EQ(a.querySurface(o.h, lat.size(), lat.data(), lon.data(), t.data(), t.size(), &ans.out), GEOCEAN_OK)
        << lastError();
    int sea = 0;
    for (std::size_t i = 0; i < lat.size(); ++i) {
      EXPECT_EQ(rows[i].surface, className(ans.cls[i])) << name[model] << " row " << i;
      EXPECT_TRUE(same(rows[i].elevation, double(ans.elevation[i]))) << name[model] << " row " << i;
      EXPECT_TRUE(same(rows[i].height, ans.height[i])) << name[model] << " row " << i << ": " << rows[i].height
                                                       << " vs " << ans.height[i];
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(same(rows[i].normal[k], ans.normal[3 * i + k])) << name[model] << " row " << i;
      EXPECT_TRUE(same(rows[i].w, ans.w[i])) << name[model] << " row " << i;
      sea += std::isfinite(ans.height[i]);
    }
    EXPECT_GE(sea, 6) << name[model];  // the comparison covered real sea points
    EXPECT_LE(sea, int(lat.size()) - 4) << name[model];  // and land and lakes

    // One point from the command line: its tiles only, on both sides.
    const auto one = geocean::test::run(std::string(GEOCEAN_EXE) + " query -33.9 151.5 --time 4.5" + args);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    const auto oneRow = parseCliJson(one.out);
    ASSERT_EQ(oneRow.size(), 1u);
    Ocean few;
    geocean_raster_options ro;
    ASSERT_EQ(a.rasterOptionsInit(&ro), GEOCEAN_OK);
    ro.few_lookups = 1;
    ASSERT_EQ(a.setDefaultWorldWithOptions(few.h, &ro), GEOCEAN_OK) << lastError();
    ASSERT_EQ(a.setSeaState(few.h, &s), GEOCEAN_OK);
    SurfaceAnswers p(1);
    const double pl = -33.9, pn = 151.5, pt = 4.5;
    ASSERT_EQ(a.querySurface(few.h, 1, &pl, &pn, &pt, 1, &p.out), GEOCEAN_OK) << lastError();
    EXPECT_EQ(oneRow[0].surface, "ocean");
    EXPECT_EQ(oneRow[0].height, p.height[0]) << name[model];
    EXPECT_EQ(oneRow[0].w, p.w[0]) << name[model];
    EXPECT_EQ(oneRow[0].elevation, double(p.elevation[0])) << name[model];
  }
}

// A single Gerstner component in deep water, through the ABI only. Linear
// wave theory: the surface particle's horizontal velocity is omega * eta
// along the travel direction, and the surface at a fixed point repeats
// with period 2 pi / omega. So the ratio velocity / height, fitted over
// many points and times, must be one constant omega, and the heights must
// repeat after 2 pi / omega. Tolerances: 1e-6 of a * omega for the fit
// (the rest point is found to 1e-5 m), 1e-5 of the crest height for the
// period (omega's fit error times 2 pi).
TEST(CapiV12, HorizontalVelocityOfOneWaveIsOmegaTimesHeight) {
  const auto& a = plugin().api();
  Ocean o;  // no rasters: deep ocean
  auto s = seaState(8.0, GEOCEAN_WAVES_GERSTNER);
  s.gerstner_components = 1;
  ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
  std::vector<double> lat, lon, t;
  for (int i = 0; i < 50; ++i) {
    lat.push_back(0.002 * (i % 10));
    lon.push_back(0.003 * (i / 10));
    t.push_back(0.61 * i);
  }
  SurfaceAnswers r(lat.size());
  ASSERT_EQ(a.querySurface(o.h, lat.size(), lat.data(), lon.data(), t.data(), t.size(), &r.out), GEOCEAN_OK);
  // Direction from the largest velocity; omega by least squares of u = omega * eta.
  std::size_t best = 0;
  for (std::size_t i = 0; i < lat.size(); ++i)
    if (std::hypot(r.uv[2 * i], r.uv[2 * i + 1]) > std::hypot(r.uv[2 * best], r.uv[2 * best + 1])) best = i;
  const double sg = r.height[best] > 0 ? 1.0 : -1.0;
  const double de = sg * r.uv[2 * best] / std::hypot(r.uv[2 * best], r.uv[2 * best + 1]);
  const double dn = sg * r.uv[2 * best + 1] / std::hypot(r.uv[2 * best], r.uv[2 * best + 1]);
  double sxy = 0, sxx = 0, crest = 0, maxU = 0;
  for (std::size_t i = 0; i < lat.size(); ++i) {
    sxy += r.height[i] * (r.uv[2 * i] * de + r.uv[2 * i + 1] * dn);
    sxx += r.height[i] * r.height[i];
    crest = std::max(crest, std::abs(r.height[i]));
    maxU = std::max(maxU, std::hypot(r.uv[2 * i], r.uv[2 * i + 1]));
  }
  const double omega = sxy / sxx;
  ASSERT_GT(omega, 0.1);  // a wind sea at 8 m/s: 0.3 .. 10 rad/s
  ASSERT_LT(omega, 10.0);
  for (std::size_t i = 0; i < lat.size(); ++i) {
    EXPECT_NEAR(r.uv[2 * i], omega * r.height[i] * de, 1e-6 * maxU) << i;
    EXPECT_NEAR(r.uv[2 * i + 1], omega * r.height[i] * dn, 1e-6 * maxU) << i;
  }
  // The same points one period later.
  std::vector<double> t2(t);
  for (double& x : t2) x += 2.0 * M_PI / omega;
  SurfaceAnswers r2(lat.size());
  ASSERT_EQ(a.querySurface(o.h, lat.size(), lat.data(), lon.data(), t2.data(), t2.size(), &r2.out), GEOCEAN_OK);
  for (std::size_t i = 0; i < lat.size(); ++i) EXPECT_NEAR(r2.height[i], r.height[i], 1e-5 * crest) << i;
}

}  // namespace

// ---- ABI 1.3: raster layers over the base rasters ----

namespace {
// A 290 m island peak at (0.25, 0.25) in a 200 m deep sea, 15" cells over
// -0.5 .. 1 degrees: finer than the 5' default mask, which says ocean there.
std::vector<float> islandPixels(geocean_grid_placement& p) {
  constexpr int n = 360;
  constexpr double step = 1.0 / 240.0;
  p = {-0.5, 1.0, step, -step, 0, 0, 0.0};
  std::vector<float> v(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double lat = 1.0 - (y + 0.5) * step, lon = -0.5 + (x + 0.5) * step;
      const double r2 = ((lat - 0.25) * (lat - 0.25) + (lon - 0.25) * (lon - 0.25)) / (0.15 * 0.15);
      v[std::size_t(y) * n + x] = float(-200.0 + 490.0 * std::exp(-r2));
    }
  return v;
}
uint8_t classAt(const geocean_ocean* o, double lat, double lon) {
  uint8_t c = 9;
  EXPECT_EQ(plugin().api().queryClass(o, 1, &lat, &lon, &c), GEOCEAN_OK) << lastError();
  return c;
}
}  // namespace

TEST(CapiV13, LayerFunctionsRejectNullsAndBadArgumentsNamingThem) {
  const auto& a = plugin().api();
  ASSERT_NE(a.layerCount, nullptr);  // a 1.3 plugin resolves them all
  const float px = 0;
  const auto pl = globalPlacement(1, 1);
  size_t n = 0;
  const std::vector<std::pair<const char*, geocean_status>> calls = {
      {"geocean_add_mask_layer_file", a.addMaskLayerFile(nullptr, "x.tif", 0, nullptr, nullptr)},
      {"geocean_add_elevation_layer_file", a.addElevationLayerFile(nullptr, "x.tif", 0, nullptr)},
      {"geocean_add_mask_layer_pixels", a.addMaskLayerPixels(nullptr, "m", &px, 1, 1, &pl, 0, nullptr)},
      {"geocean_add_elevation_layer_pixels", a.addElevationLayerPixels(nullptr, "e", &px, 1, 1, &pl, 0)},
      {"geocean_remove_layer", a.removeLayer(nullptr, "x.tif", &n)},
      {"geocean_clear_layers", a.clearLayers(nullptr)},
      {"geocean_layer_count", a.layerCount(nullptr, &n)},
  };
  for (const auto& [name, status] : calls) {
    EXPECT_EQ(status, GEOCEAN_ERROR_NULL_ARGUMENT) << name;
  }
  EXPECT_EQ(lastError(), "geocean_layer_count: ocean is NULL");
  Ocean o;
  EXPECT_EQ(a.addMaskLayerFile(o.h, nullptr, 0, nullptr, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_add_mask_layer_file: path is NULL");
  EXPECT_EQ(a.addMaskLayerPixels(o.h, nullptr, &px, 1, 1, &pl, 0, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(lastError(), "geocean_add_mask_layer_pixels: name is NULL");
  EXPECT_EQ(a.addMaskLayerFile(o.h, "/nonexistent/layer.tif", 0, nullptr, nullptr), GEOCEAN_ERROR_RASTER);
  EXPECT_NE(lastError().find("/nonexistent/layer.tif"), std::string::npos) << lastError();
  EXPECT_EQ(a.addMaskLayerPixels(o.h, "m", &px, 1, 1, &pl, INT32_MIN, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("priority -2147483648 is not above the default world's"), std::string::npos)
      << lastError();
  EXPECT_EQ(a.addMaskLayerPixels(o.h, "m", &px, 1, 1, &pl, 0, "0=sea"), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("'sea'"), std::string::npos) << lastError();
  ASSERT_EQ(a.addMaskLayerPixels(o.h, "m", &px, 1, 1, &pl, 0, nullptr), GEOCEAN_OK) << lastError();
  EXPECT_EQ(a.addMaskLayerPixels(o.h, "m", &px, 1, 1, &pl, 3, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("m: already a mask layer"), std::string::npos) << lastError();
  geocean_raster_options bad{};
  EXPECT_EQ(a.addElevationLayerFile(o.h, GEOCEAN_DATA_DIR "/etopo_20m.tif", 0, &bad), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("options->struct_size 0"), std::string::npos) << lastError();
  ASSERT_EQ(a.layerCount(o.h, &n), GEOCEAN_OK);
  EXPECT_EQ(n, 1u);  // failed calls left the stack as it was
}

TEST(CapiV13, AnIslandLayerIsLandOverTheDefaultWorldUntilRemoved) {
  setenv("GEOCEAN_DATA", GEOCEAN_DATA_DIR, 1);
  Ocean o;
  const auto& a = plugin().api();
  ASSERT_EQ(a.setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  ASSERT_EQ(classAt(o.h, 0.25, 0.25), GEOCEAN_SURFACE_OCEAN);  // the 5' mask's answer
  geocean_grid_placement p;
  const auto px = islandPixels(p);
  ASSERT_EQ(a.addElevationLayerPixels(o.h, "island", px.data(), 360, 360, &p, 0), GEOCEAN_OK) << lastError();
  EXPECT_EQ(classAt(o.h, 0.25, 0.25), GEOCEAN_SURFACE_LAND);
  EXPECT_EQ(classAt(o.h, 0.9, 0.9), GEOCEAN_SURFACE_OCEAN);
  EXPECT_EQ(classAt(o.h, 42.0, 50.5), GEOCEAN_SURFACE_LAKE);  // the default world outside the layer
  const double lat = 0.25, lon = 0.25;
  float e = 0;
  ASSERT_EQ(a.queryElevation(o.h, 1, &lat, &lon, &e), GEOCEAN_OK);
  EXPECT_NEAR(e, 290.0, 2.0);
  // A mask file layer too (the 1.25' world, through the cache), then removal by path.
  const std::string fine = GEOCEAN_DATA_DIR "/landmask_1.25m.tif";
  ASSERT_EQ(a.addMaskLayerFile(o.h, fine.c_str(), 0, "0=ocean,1=land,2=ocean", nullptr), GEOCEAN_OK) << lastError();
  EXPECT_EQ(classAt(o.h, 42.0, 50.5), GEOCEAN_SURFACE_OCEAN);  // its own encoding: lakes are ocean
  EXPECT_EQ(classAt(o.h, 0.25, 0.25), GEOCEAN_SURFACE_LAND);   // 15" relief is finer than 1.25'
  size_t n = 0, removed = 9;
  ASSERT_EQ(a.layerCount(o.h, &n), GEOCEAN_OK);
  EXPECT_EQ(n, 2u);
  ASSERT_EQ(a.removeLayer(o.h, fine.c_str(), &removed), GEOCEAN_OK);
  EXPECT_EQ(removed, 1u);
  EXPECT_EQ(classAt(o.h, 42.0, 50.5), GEOCEAN_SURFACE_LAKE);
  ASSERT_EQ(a.removeLayer(o.h, "no such layer", &removed), GEOCEAN_OK);
  EXPECT_EQ(removed, 0u);
  ASSERT_EQ(a.clearLayers(o.h), GEOCEAN_OK);
  EXPECT_EQ(classAt(o.h, 0.25, 0.25), GEOCEAN_SURFACE_OCEAN);
  ASSERT_EQ(a.layerCount(o.h, &n), GEOCEAN_OK);
  EXPECT_EQ(n, 0u);
}

// ---- ABI 1.5: the sea state at points (issue 15) ----

TEST(CapiV15, SeaStateAtPointsMatchesPiersonMoskowitzAndIsNaNOnLand) {
  const auto& a = plugin().api();
  const auto fn = a.querySeaState;
  ASSERT_NE(fn, nullptr);
  Ocean o;
  const double lat[2] = {0.0, 23.0}, lon[2] = {-150.0, 10.0};  // deep Pacific; Sahara
  double hs[2], tp[2], lp[2], from[2];
  EXPECT_EQ(fn(nullptr, 2, lat, lon, hs, tp, lp, from), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(fn(o.h, 2, lat, lon, hs, tp, lp, from), GEOCEAN_ERROR_NOT_READY);
  ASSERT_EQ(a.setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  geocean_sea_state s = seaState(12.0, GEOCEAN_WAVES_GERSTNER);
  s.wind_from_deg = 120.0;
  ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
  EXPECT_EQ(fn(o.h, 2, nullptr, lon, hs, tp, lp, from), GEOCEAN_ERROR_NULL_ARGUMENT);
  ASSERT_EQ(fn(o.h, 2, lat, lon, hs, tp, lp, from), GEOCEAN_OK) << lastError();
  // Pierson-Moskowitz: Hs = 4 sqrt(0.0081 / 5) g / wp^2, wp = 0.877 g / U.
  const double g = 9.80665, wp = 0.877 * g / 12.0;
  double hsRef = 0.0;
  ASSERT_EQ(a.significantWaveHeight(o.h, &hsRef), GEOCEAN_OK);
  EXPECT_NEAR(hsRef, 4.0 * std::sqrt(0.0081 / 5.0) * g / (wp * wp), 2e-3 * hsRef);
  // Far from the anchor (0, 0): the great-circle taper is 1 and the sea deep.
  EXPECT_NEAR(hs[0], hsRef, 1e-9 * hsRef);
  EXPECT_NEAR(tp[0], 2.0 * M_PI / wp, 1e-12);
  EXPECT_NEAR(lp[0], g * tp[0] * tp[0] / (2.0 * M_PI), 1e-9);
  EXPECT_GE(from[0], 0.0);
  EXPECT_LT(from[0], 360.0);
  EXPECT_TRUE(std::isnan(hs[1]) && std::isnan(tp[1]) && std::isnan(lp[1]) && std::isnan(from[1]));
  EXPECT_EQ(fn(o.h, 1, lat, lon, nullptr, nullptr, nullptr, nullptr), GEOCEAN_OK);  // nothing asked
}

// Fuzz finding 5 (tests/fuzz/regressions/fuzz_capi_sea_state/gerstner_time_7e307_nan_height.bin):
// a Gerstner sea (the finding's: 10 m/s from 270, seed 1, anchor -19.2,
// -76.9, reference depth 4033 m) queried at 7.1e307 s answered NaN, and at
// 1e33 s heights of 1e7 m: the SIMD batch's phase reduction has no digits
// left there (plugin/waves/TimeRange.h). Every call taking a time now
// refuses |t| > 1e12 s naming the field and the value; at the bound the sea
// is still a sea (|h| below 4 Hs, unit normals).
TEST(CapiTimes, TimesBeyondTheBoundAreRefusedNamingTheField) {
  Ocean o;
  const auto& a = plugin().api();
  geocean_sea_state s = seaState(10.0, GEOCEAN_WAVES_GERSTNER);
  s.wind_from_deg = 270.0, s.fetch_m = 0.0, s.seed = 1, s.gerstner_components = 37;
  s.anchor_lat_deg = -19.215686274509807, s.anchor_lon_deg = -76.862745098039227;
  s.reference_depth_m = 4033.2549019607845;
  ASSERT_EQ(a.setSeaState(o.h, &s), GEOCEAN_OK) << lastError();
  double hs = 0.0;
  ASSERT_EQ(a.significantWaveHeight(o.h, &hs), GEOCEAN_OK);
  const double lat[2] = {-17.294117647058826, -17.294117643278753}, lon[2] = {38.117647058823536, 86.823529411735763};
  for (double t : {1e12, -1e12, 1.8e9}) {
    double h[2], n[6];
    ASSERT_EQ(a.querySeaSurface(o.h, 2, lat, lon, t, h, n, nullptr), GEOCEAN_OK) << lastError();
    for (int i = 0; i < 2; ++i) {
      EXPECT_LT(std::abs(h[i]), 4.0 * hs) << "t " << t;
      EXPECT_NEAR(std::hypot(n[3 * i], n[3 * i + 1], n[3 * i + 2]), 1.0, 1e-9) << "t " << t;
    }
  }
  const struct {
    double t;
    const char* text;  // shortest round trip, as the host would print it
  } beyond[] = {{7.1233136299299067e307, "7.123313629929907e+307"}, {1e33, "1e+33"},
                {1.000001e12, "1.000001e+12"}, {-2e12, "-2e+12"}};
  for (const auto& b : beyond) {
    double h[2];
    EXPECT_EQ(a.querySeaSurface(o.h, 2, lat, lon, b.t, h, nullptr, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT) << b.t;
    EXPECT_EQ(lastError(), std::string("geocean_query_sea_surface: time_s ") + b.text +
                               " s is outside -1e12 .. 1e12 s (beyond, the waves' phase w t keeps no precision)");
  }
  SurfaceAnswers ans(2);
  const double times[2] = {5.0, 1e33};
  EXPECT_EQ(a.querySurface(o.h, 2, lat, lon, times, 2, &ans.out), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("geocean_query_surface: time_s[1] 1e+33 s is outside -1e12 .. 1e12 s"), std::string::npos)
      << lastError();
  ASSERT_EQ(a.querySurface(o.h, 2, lat, lon, times, 1, &ans.out), GEOCEAN_OK) << lastError();

  geocean_view v = poseView(30.0, -40.0, 100.0);
  v.time_s = -1e13;
  EXPECT_EQ(a.update(o.h, &v), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("geocean_update: view->time_s -1e+13 s is outside"), std::string::npos) << lastError();
  v.time_s = 1e12;
  EXPECT_EQ(a.update(o.h, &v), GEOCEAN_OK) << lastError();
}
