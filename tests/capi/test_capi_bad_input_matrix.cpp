// Issue 17 item 5, the C ABI half: one table over every entry point of
// geocean_ocean.h with NULL, NaN, infinities, out-of-range, empty and huge
// values (the CLI half is tests/app/test_bad_input_matrix.cpp). Each row
// runs on a fresh, fully set-up ocean (mask, elevation, Gerstner sea state,
// a bodies simulation with one boat) and expects the status the header
// states and a message "<function>: ..." naming the argument or field and
// its value. After every refused call the ocean must answer exactly as
// before (class, elevation and sea surface at fixed points, layer count,
// body count): a refused call changes nothing. Linked directly against the
// plugin, so each row calls the function by its C name.
#include "geocean/geocean_ocean.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string lastError() { return geocean_last_error(); }

// An 8 x 4 global mask (45 deg cells): ocean but for 3 x 3 cells of land
// around (22.5 N, 22.5 E), and a matching elevation (500 m / -3000 m).
struct Fixture {
  static constexpr int kW = 8, kH = 4;
  geocean_ocean* o = nullptr;
  geocean_bodies* bodies = nullptr;
  geocean_grid_placement place{-180.0, 90.0, 360.0 / kW, -180.0 / kH, 1, 0, 0.0};
  std::vector<float> mask = std::vector<float>(kW * kH, 0.0f), elev = std::vector<float>(kW * kH, -3000.0f);
  geocean_sea_state sea{};
  geocean_view view{};
  geocean_body_desc desc{};
  std::function<void()> after;  // a row's own clean-up, run after its message was read
  Fixture() {
    // 3 x 3 cells of land (a single cell would be ocean at its centre by the coverage rule's B-spline).
    for (int y = 0; y < 3; ++y)
      for (int x = 3; x < 6; ++x) mask[y * kW + x] = 1.0f, elev[y * kW + x] = 500.0f;
    EXPECT_EQ(geocean_create(GEOCEAN_ABI_VERSION, &o), GEOCEAN_OK);
    EXPECT_EQ(geocean_set_mask_pixels(o, mask.data(), kW, kH, &place), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_set_elevation_pixels(o, elev.data(), kW, kH, &place), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_sea_state_init(&sea), GEOCEAN_OK);
    sea.model = GEOCEAN_WAVES_GERSTNER;
    EXPECT_EQ(geocean_set_sea_state(o, &sea), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_view_init(&view), GEOCEAN_OK);
    EXPECT_EQ(geocean_update(o, &view), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_bodies_create(o, nullptr, &bodies), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_body_desc_init(&desc), GEOCEAN_OK);
    desc.lat_deg = -30.0, desc.lon_deg = -150.0;  // open ocean of the fixture
    EXPECT_EQ(geocean_bodies_add(bodies, &desc, nullptr), GEOCEAN_OK) << lastError();
  }
  ~Fixture() {
    geocean_bodies_destroy(bodies);
    geocean_destroy(o);
  }
  Fixture(const Fixture&) = delete;
  Fixture& operator=(const Fixture&) = delete;
};

// What the ocean answers at fixed points: compared bit for bit before and after a refused call.
struct Answers {
  std::vector<uint8_t> cls = std::vector<uint8_t>(3);
  std::vector<float> elev = std::vector<float>(3);
  std::vector<double> height = std::vector<double>(3);
  size_t layers = 99, bodies = 99;
  double hs = 0.0;
  static Answers of(const Fixture& f) {
    Answers a;
    const double lat[3] = {22.5, -30.0, 60.0}, lon[3] = {22.5, -150.0, 100.0};
    EXPECT_EQ(geocean_query_class(f.o, 3, lat, lon, a.cls.data()), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_query_elevation(f.o, 3, lat, lon, a.elev.data()), GEOCEAN_OK) << lastError();
    EXPECT_EQ(geocean_query_sea_surface(f.o, 3, lat, lon, 7.0, a.height.data(), nullptr, nullptr), GEOCEAN_OK)
        << lastError();
    EXPECT_EQ(geocean_layer_count(f.o, &a.layers), GEOCEAN_OK);
    EXPECT_EQ(geocean_bodies_count(f.bodies, &a.bodies), GEOCEAN_OK);
    EXPECT_EQ(geocean_significant_wave_height(f.o, &a.hs), GEOCEAN_OK);
    return a;
  }
  bool operator==(const Answers& b) const {
    return cls == b.cls && std::memcmp(elev.data(), b.elev.data(), 3 * sizeof(float)) == 0 &&
           std::memcmp(height.data(), b.height.data(), 3 * sizeof(double)) == 0 && layers == b.layers &&
           bodies == b.bodies && hs == b.hs;
  }
};

struct Row {
  const char* function;  // the message starts with "<function>: "
  const char* input;     // what is wrong, for the failure message
  std::function<geocean_status(Fixture&)> call;
  geocean_status expect;
  const char* message;  // a substring of the message after "<function>: "
};

geocean_sea_state seaWith(const Fixture& f, void (*edit)(geocean_sea_state&)) {
  geocean_sea_state s = f.sea;
  edit(s);
  return s;
}

constexpr auto NUL = GEOCEAN_ERROR_NULL_ARGUMENT;
constexpr auto BAD = GEOCEAN_ERROR_INVALID_ARGUMENT;

const double kLat1[1] = {0.0}, kLon1[1] = {0.0};
uint8_t gClass[4];
float gElev[4];
double gD[16];
const float kPx[1] = {0.0f};

std::vector<Row> rows() {
  using F = Fixture;
  const geocean_grid_placement good{-180.0, 90.0, 360.0, -180.0, 1, 0, 0.0};
  std::vector<Row> r = {
      // ---- version, create, destroy
      {"geocean_create", "host ABI 0", [](F&) { geocean_ocean* o; return geocean_create(0, &o); },
       GEOCEAN_ERROR_ABI_VERSION, "host ABI 0.0 is not served by this plugin"},
      {"geocean_create", "host ABI of the next major",
       [](F&) { geocean_ocean* o; return geocean_create(GEOCEAN_ABI_VERSION + (1u << 16), &o); },
       GEOCEAN_ERROR_ABI_VERSION, "is not served by this plugin"},
      {"geocean_create", "out NULL", [](F&) { return geocean_create(GEOCEAN_ABI_VERSION, nullptr); }, NUL,
       "out is NULL"},
      // ---- raster files
      {"geocean_set_mask_file", "ocean NULL", [](F&) { return geocean_set_mask_file(nullptr, "m.tif", GEOCEAN_GEOREF_FROM_FILE); },
       NUL, "ocean is NULL"},
      {"geocean_set_mask_file", "path NULL", [](F& f) { return geocean_set_mask_file(f.o, nullptr, GEOCEAN_GEOREF_FROM_FILE); },
       NUL, "path is NULL"},
      {"geocean_set_mask_file", "path empty", [](F& f) { return geocean_set_mask_file(f.o, "", GEOCEAN_GEOREF_FROM_FILE); },
       BAD, "path is empty"},
      {"geocean_set_mask_file", "path missing",
       [](F& f) { return geocean_set_mask_file(f.o, "/nonexistent/m.tif", GEOCEAN_GEOREF_FROM_FILE); },
       GEOCEAN_ERROR_RASTER, "/nonexistent/m.tif"},
      {"geocean_set_mask_file", "georef 7",
       [](F& f) { return geocean_set_mask_file(f.o, "m.tif", static_cast<geocean_georef>(7)); }, BAD,
       "georef 7 is not a geocean_georef"},
      {"geocean_set_mask_file", "georef -1",
       [](F& f) { return geocean_set_mask_file(f.o, "m.tif", static_cast<geocean_georef>(-1)); }, BAD,
       "georef -1 is not a geocean_georef"},
      {"geocean_set_elevation_file", "path empty",
       [](F& f) { return geocean_set_elevation_file(f.o, "", GEOCEAN_GEOREF_FROM_FILE); }, BAD, "path is empty"},
      {"geocean_set_elevation_file", "a directory",
       [](F& f) { return geocean_set_elevation_file(f.o, "/", GEOCEAN_GEOREF_FROM_FILE); }, GEOCEAN_ERROR_RASTER,
       "/"},
      {"geocean_raster_options_init", "NULL", [](F&) { return geocean_raster_options_init(nullptr); }, NUL,
       "options is NULL"},
      {"geocean_set_mask_file_with_options", "options NULL",
       [](F& f) { return geocean_set_mask_file_with_options(f.o, "m.tif", nullptr); }, NUL, "options is NULL"},
      {"geocean_set_mask_file_with_options", "struct_size 0",
       [](F& f) {
         geocean_raster_options ro{};
         return geocean_set_mask_file_with_options(f.o, "m.tif", &ro);
       },
       BAD, "options->struct_size 0 is smaller than"},
      {"geocean_set_elevation_file_with_options", "georef 2",
       [](F& f) {
         geocean_raster_options ro;
         geocean_raster_options_init(&ro);
         ro.georef = 2;
         return geocean_set_elevation_file_with_options(f.o, "e.tif", &ro);
       },
       BAD, "options->georef 2 is not a geocean_georef"},
      {"geocean_set_default_world_with_options", "options NULL",
       [](F& f) { return geocean_set_default_world_with_options(f.o, nullptr); }, NUL, "options is NULL"},
      {"geocean_set_default_world", "ocean NULL", [](F&) { return geocean_set_default_world(nullptr); }, NUL,
       "ocean is NULL"},
      {"geocean_clear_rasters", "ocean NULL", [](F&) { return geocean_clear_rasters(nullptr); }, NUL,
       "ocean is NULL"},
      // ---- rasters from memory
      {"geocean_set_mask_pixels", "values NULL",
       [good](F& f) { return geocean_set_mask_pixels(f.o, nullptr, 1, 1, &good); }, NUL, "values is NULL"},
      {"geocean_set_mask_pixels", "placement NULL",
       [](F& f) { return geocean_set_mask_pixels(f.o, kPx, 1, 1, nullptr); }, NUL, "placement is NULL"},
      {"geocean_set_mask_pixels", "width 0", [good](F& f) { return geocean_set_mask_pixels(f.o, kPx, 0, 1, &good); },
       BAD, "raster size 0 x 1 is not positive"},
      {"geocean_set_mask_pixels", "height -1",
       [good](F& f) { return geocean_set_mask_pixels(f.o, kPx, 1, -1, &good); }, BAD,
       "raster size 1 x -1 is not positive"},
      {"geocean_set_mask_pixels", "huge: INT32_MAX x INT32_MAX",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.global = 0;
         return geocean_set_mask_pixels(f.o, kPx, INT32_MAX, INT32_MAX, &p);
       },
       BAD, "raster size 2147483647 x 2147483647 is larger than any buffer"},
      {"geocean_set_mask_pixels", "origin NaN",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.origin_lat_deg = kNaN;
         return geocean_set_mask_pixels(f.o, kPx, 1, 1, &p);
       },
       BAD, "placement origin is not finite"},
      {"geocean_set_mask_pixels", "origin -inf",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.origin_lon_deg = -kInf;
         return geocean_set_mask_pixels(f.o, kPx, 1, 1, &p);
       },
       BAD, "placement origin is not finite"},
      {"geocean_set_mask_pixels", "lon_step_deg 0",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.lon_step_deg = 0.0;
         return geocean_set_mask_pixels(f.o, kPx, 1, 1, &p);
       },
       BAD, "placement lon_step_deg 0"},
      {"geocean_set_mask_pixels", "lon_step_deg inf",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.lon_step_deg = kInf;
         return geocean_set_mask_pixels(f.o, kPx, 1, 1, &p);
       },
       BAD, "placement lon_step_deg inf"},
      {"geocean_set_elevation_pixels", "lat_step_deg 0",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.lat_step_deg = 0.0;
         return geocean_set_elevation_pixels(f.o, kPx, 1, 1, &p);
       },
       BAD, "placement lat_step_deg 0"},
      {"geocean_set_elevation_pixels", "lat_step_deg NaN",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.lat_step_deg = kNaN;
         return geocean_set_elevation_pixels(f.o, kPx, 1, 1, &p);
       },
       BAD, "placement lat_step_deg nan"},
      {"geocean_set_elevation_pixels", "global but 2 x 90 deg",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.lon_step_deg = 90.0;
         const float px2[2] = {0, 0};
         return geocean_set_elevation_pixels(f.o, px2, 2, 1, &p);
       },
       BAD, "placement is global but width * lon_step_deg = 180"},
      {"geocean_set_elevation_pixels", "ocean NULL",
       [good](F&) { return geocean_set_elevation_pixels(nullptr, kPx, 1, 1, &good); }, NUL, "ocean is NULL"},
      // ---- mask encoding
      {"geocean_set_mask_encoding", "ocean NULL", [](F&) { return geocean_set_mask_encoding(nullptr, "0=ocean"); },
       NUL, "ocean is NULL"},
      {"geocean_set_mask_encoding", "unknown class", [](F& f) { return geocean_set_mask_encoding(f.o, "0=sea"); },
       BAD, "'sea'"},
      {"geocean_set_mask_encoding", "value NaN", [](F& f) { return geocean_set_mask_encoding(f.o, "nan=ocean"); },
       BAD, "nan"},
      {"geocean_set_mask_encoding", "huge: 1 MB of digits",
       [](F& f) { return geocean_set_mask_encoding(f.o, (std::string(1 << 20, '9') + "=ocean").c_str()); }, BAD,
       "999"},
      // ---- layers
      {"geocean_add_mask_layer_file", "path NULL",
       [](F& f) { return geocean_add_mask_layer_file(f.o, nullptr, 0, nullptr, nullptr); }, NUL, "path is NULL"},
      {"geocean_add_mask_layer_file", "path empty",
       [](F& f) { return geocean_add_mask_layer_file(f.o, "", 0, nullptr, nullptr); }, BAD, "path is empty"},
      {"geocean_add_mask_layer_file", "path missing",
       [](F& f) { return geocean_add_mask_layer_file(f.o, "/nonexistent/l.tif", 0, nullptr, nullptr); },
       GEOCEAN_ERROR_RASTER, "/nonexistent/l.tif"},
      {"geocean_add_mask_layer_file", "bad encoding",
       [](F& f) { return geocean_add_mask_layer_file(f.o, "/nonexistent/l.tif", 0, "1=rock", nullptr); }, BAD,
       "'rock'"},
      {"geocean_add_elevation_layer_file", "path empty",
       [](F& f) { return geocean_add_elevation_layer_file(f.o, "", 0, nullptr); }, BAD, "path is empty"},
      {"geocean_add_elevation_layer_file", "options struct_size 0",
       [](F& f) {
         geocean_raster_options ro{};
         return geocean_add_elevation_layer_file(f.o, "e.tif", 0, &ro);
       },
       BAD, "options->struct_size 0"},
      {"geocean_add_mask_layer_pixels", "name NULL",
       [good](F& f) { return geocean_add_mask_layer_pixels(f.o, nullptr, kPx, 1, 1, &good, 0, nullptr); }, NUL,
       "name is NULL"},
      {"geocean_add_mask_layer_pixels", "name empty",
       [good](F& f) { return geocean_add_mask_layer_pixels(f.o, "", kPx, 1, 1, &good, 0, nullptr); }, BAD,
       "name is empty"},
      {"geocean_add_mask_layer_pixels", "priority INT32_MIN",
       [good](F& f) { return geocean_add_mask_layer_pixels(f.o, "m", kPx, 1, 1, &good, INT32_MIN, nullptr); }, BAD,
       "priority -2147483648 is not above the default world's"},
      {"geocean_add_mask_layer_pixels", "width -5",
       [good](F& f) { return geocean_add_mask_layer_pixels(f.o, "m", kPx, -5, 1, &good, 0, nullptr); }, BAD,
       "raster size -5 x 1 is not positive"},
      {"geocean_add_elevation_layer_pixels", "origin inf",
       [good](F& f) {
         geocean_grid_placement p = good;
         p.origin_lat_deg = kInf;
         return geocean_add_elevation_layer_pixels(f.o, "e", kPx, 1, 1, &p, 0);
       },
       BAD, "placement origin is not finite"},
      {"geocean_add_elevation_layer_pixels", "values NULL",
       [good](F& f) { return geocean_add_elevation_layer_pixels(f.o, "e", nullptr, 1, 1, &good, 0); }, NUL,
       "values is NULL"},
      {"geocean_remove_layer", "path NULL", [](F& f) { return geocean_remove_layer(f.o, nullptr, nullptr); }, NUL,
       "path is NULL"},
      {"geocean_clear_layers", "ocean NULL", [](F&) { return geocean_clear_layers(nullptr); }, NUL, "ocean is NULL"},
      {"geocean_layer_count", "out NULL", [](F& f) { return geocean_layer_count(f.o, nullptr); }, NUL,
       "out_count is NULL"},
      // ---- class and elevation queries
      {"geocean_query_class", "ocean NULL", [](F&) { return geocean_query_class(nullptr, 1, kLat1, kLon1, gClass); },
       NUL, "ocean is NULL"},
      {"geocean_query_class", "lat NULL", [](F& f) { return geocean_query_class(f.o, 1, nullptr, kLon1, gClass); },
       NUL, "lat_deg is NULL"},
      {"geocean_query_class", "out NULL", [](F& f) { return geocean_query_class(f.o, 1, kLat1, kLon1, nullptr); },
       NUL, "out_class is NULL"},
      {"geocean_query_elevation", "lon NULL",
       [](F& f) { return geocean_query_elevation(f.o, 1, kLat1, nullptr, gElev); }, NUL, "lon_deg is NULL"},
      {"geocean_query_elevation", "out NULL",
       [](F& f) { return geocean_query_elevation(f.o, 1, kLat1, kLon1, nullptr); }, NUL, "out_elevation_m is NULL"},
      // ---- sea state
      {"geocean_sea_state_init", "NULL", [](F&) { return geocean_sea_state_init(nullptr); }, NUL,
       "sea_state is NULL"},
      {"geocean_sea_state_set_beaufort", "13",
       [](F& f) { return geocean_sea_state_set_beaufort(&f.sea, 13); }, BAD, "beaufort 13 is not in 0 .. 12"},
      {"geocean_sea_state_set_beaufort", "-1",
       [](F& f) { return geocean_sea_state_set_beaufort(&f.sea, -1); }, BAD, "beaufort -1 is not in 0 .. 12"},
      {"geocean_sea_state_set_beaufort", "NULL", [](F&) { return geocean_sea_state_set_beaufort(nullptr, 3); }, NUL,
       "sea_state is NULL"},
      {"geocean_set_sea_state", "NULL", [](F& f) { return geocean_set_sea_state(f.o, nullptr); }, NUL,
       "sea_state is NULL"},
      {"geocean_set_sea_state", "struct_size 4",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.struct_size = 4; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->struct_size 4 is smaller than"},
      {"geocean_set_sea_state", "model 99",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.model = 99; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->model 99 is not a geocean_wave_model"},
      {"geocean_set_sea_state", "wind NaN",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.wind_speed_mps = kNaN; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->wind_speed_mps nan is invalid (expected 0.2 .. 60 m/s)"},
      {"geocean_set_sea_state", "wind 1e300",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.wind_speed_mps = 1e300; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->wind_speed_mps 1e+300 is invalid"},
      {"geocean_set_sea_state", "wind -1",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.wind_speed_mps = -1.0; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->wind_speed_mps -1 is invalid"},
      {"geocean_set_sea_state", "wind_from inf",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.wind_from_deg = kInf; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->wind_from_deg inf is invalid"},
      {"geocean_set_sea_state", "fetch 0.5",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.fetch_m = 0.5; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->fetch_m 0.5 is invalid (expected 0 (fully developed) or >= 1 m)"},
      {"geocean_set_sea_state", "fetch -inf",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.fetch_m = -kInf; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->fetch_m -inf is invalid"},
      {"geocean_set_sea_state", "anchor lat 91",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.anchor_lat_deg = 91.0; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->anchor_lat_deg 91 is invalid"},
      {"geocean_set_sea_state", "anchor lon -1.7e308",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.anchor_lon_deg = -1.7e308; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->anchor_lon_deg -1.7e+308 is invalid"},
      {"geocean_set_sea_state", "reference depth NaN",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.reference_depth_m = kNaN; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->reference_depth_m nan is invalid"},
      {"geocean_set_sea_state", "gerstner components 0",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.gerstner_components = 0; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->gerstner_components 0 is invalid (expected 1 .. 64)"},
      {"geocean_set_sea_state", "gerstner components huge",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.gerstner_components = INT32_MAX; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->gerstner_components 2147483647 is invalid"},
      {"geocean_set_sea_state", "noise octaves -3",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.noise_octaves = -3; });
         return geocean_set_sea_state(f.o, &s);
       },
       BAD, "sea_state->noise_octaves -3 is invalid (expected 1 .. 12)"},
      // ---- sea queries
      {"geocean_query_sea_surface", "time NaN",
       [](F& f) { return geocean_query_sea_surface(f.o, 1, kLat1, kLon1, kNaN, gD, nullptr, nullptr); }, BAD,
       "time_s nan is not finite"},
      {"geocean_query_sea_surface", "time -inf",
       [](F& f) { return geocean_query_sea_surface(f.o, 1, kLat1, kLon1, -kInf, gD, nullptr, nullptr); }, BAD,
       "time_s -inf is not finite"},
      {"geocean_query_sea_surface", "time 1e13",
       [](F& f) { return geocean_query_sea_surface(f.o, 1, kLat1, kLon1, 1e13, gD, nullptr, nullptr); }, BAD,
       "time_s 1e+13 s is outside -1e12 .. 1e12 s"},
      {"geocean_query_sea_surface", "out_height NULL",
       [](F& f) { return geocean_query_sea_surface(f.o, 1, kLat1, kLon1, 0.0, nullptr, nullptr, nullptr); }, NUL,
       "out_height_m is NULL"},
      {"geocean_surface_outputs_init", "NULL", [](F&) { return geocean_surface_outputs_init(nullptr); }, NUL,
       "outputs is NULL"},
      {"geocean_query_surface", "outputs NULL",
       [](F& f) { return geocean_query_surface(f.o, 1, kLat1, kLon1, gD, 1, nullptr); }, NUL, "outputs is NULL"},
      {"geocean_query_surface", "struct_size 8",
       [](F& f) {
         geocean_surface_outputs out{};
         out.struct_size = 8;
         return geocean_query_surface(f.o, 1, kLat1, kLon1, gD, 1, &out);
       },
       BAD, "outputs->struct_size 8 is smaller than"},
      {"geocean_query_surface", "time_count 2 for 1 point",
       [](F& f) {
         geocean_surface_outputs out;
         geocean_surface_outputs_init(&out);
         out.height_m = gD + 8;
         const double t[2] = {0, 0};
         return geocean_query_surface(f.o, 1, kLat1, kLon1, t, 2, &out);
       },
       BAD, "time_count 2 is neither 1 nor count (1)"},
      {"geocean_query_surface", "time_s[1] inf",
       [](F& f) {
         geocean_surface_outputs out;
         geocean_surface_outputs_init(&out);
         out.height_m = gD + 8;
         const double lat[2] = {0, 1}, lon[2] = {0, 1}, t[2] = {0, kInf};
         return geocean_query_surface(f.o, 2, lat, lon, t, 2, &out);
       },
       BAD, "time_s[1] inf is not finite"},
      {"geocean_query_surface", "time_s NULL with a sea output",
       [](F& f) {
         geocean_surface_outputs out;
         geocean_surface_outputs_init(&out);
         out.height_m = gD + 8;
         return geocean_query_surface(f.o, 1, kLat1, kLon1, nullptr, 1, &out);
       },
       NUL, "time_s is NULL"},
      {"geocean_significant_wave_height", "out NULL",
       [](F& f) { return geocean_significant_wave_height(f.o, nullptr); }, NUL, "out_hs_m is NULL"},
      {"geocean_query_sea_state", "lat NULL",
       [](F& f) { return geocean_query_sea_state(f.o, 1, nullptr, kLon1, gD, gD + 1, gD + 2, gD + 3); }, NUL,
       "lat_deg is NULL"},
      {"geocean_query_sea_state", "ocean NULL",
       [](F&) { return geocean_query_sea_state(nullptr, 1, kLat1, kLon1, gD, gD + 1, gD + 2, gD + 3); }, NUL,
       "ocean is NULL"},
      // ---- near-shore region
      {"geocean_set_coast_region", "lat NaN", [](F& f) { return geocean_set_coast_region(f.o, kNaN, 0, 5000); }, BAD,
       "lat_deg nan is not in -90 .. 90"},
      {"geocean_set_coast_region", "lon inf", [](F& f) { return geocean_set_coast_region(f.o, 0, kInf, 5000); }, BAD,
       "lon_deg inf is not in -360 .. 360"},
      {"geocean_set_coast_region", "size 100 m", [](F& f) { return geocean_set_coast_region(f.o, 0, 0, 100); }, BAD,
       "size_m 100.000000 is not in 500 .. 40000"},
      {"geocean_set_coast_region", "size 1e300 m", [](F& f) { return geocean_set_coast_region(f.o, 0, 0, 1e300); },
       BAD, "size_m 1000000"},
      {"geocean_set_coast_region", "noise sea",
       [](F& f) {
         auto s = seaWith(f, [](geocean_sea_state& x) { x.model = GEOCEAN_WAVES_NOISE; });
         EXPECT_EQ(geocean_set_sea_state(f.o, &s), GEOCEAN_OK);
         f.after = [&f] { EXPECT_EQ(geocean_set_sea_state(f.o, &f.sea), GEOCEAN_OK); };  // back, so the answers compare
         return geocean_set_coast_region(f.o, 0, 0, 5000);
       },
       BAD, "the sea state's model is noise: a coast region needs GEOCEAN_WAVES_GERSTNER"},
      {"geocean_clear_coast_region", "ocean NULL", [](F&) { return geocean_clear_coast_region(nullptr); }, NUL,
       "ocean is NULL"},
      // ---- views and drawing
      {"geocean_view_init", "NULL", [](F&) { return geocean_view_init(nullptr); }, NUL, "view is NULL"},
      {"geocean_view_from_pose", "lat NaN",
       [](F& f) { return geocean_view_from_pose(&f.view, kNaN, 0, 1, 0, -90, 45, 64, 64); }, BAD,
       "lat_deg nan is not within -90 .. 90"},
      {"geocean_view_from_pose", "lon -inf",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, -kInf, 1, 0, -90, 45, 64, 64); }, BAD,
       "lon_deg -inf is not finite"},
      {"geocean_view_from_pose", "height 1e10",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, 0, 1e10, 0, -90, 45, 64, 64); }, BAD,
       "height_m 10000000000.000000 is not finite (|h| < 1e9 m)"},
      {"geocean_view_from_pose", "heading NaN",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, 0, 1, kNaN, -90, 45, 64, 64); }, BAD,
       "heading_deg nan is not finite"},
      {"geocean_view_from_pose", "pitch 91",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, 0, 1, 0, 91, 45, 64, 64); }, BAD,
       "pitch_deg 91.000000 is not within -90 .. 90"},
      {"geocean_view_from_pose", "fov 180",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, 0, 1, 0, -90, 180, 64, 64); }, BAD,
       "fov_y_deg 180.000000 is not within 1 .. 170"},
      {"geocean_view_from_pose", "width 16385",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, 0, 1, 0, -90, 45, 16385, 64); }, BAD,
       "width_px 16385"},
      {"geocean_view_from_pose", "height 0",
       [](F& f) { return geocean_view_from_pose(&f.view, 0, 0, 1, 0, -90, 45, 64, 0); }, BAD, "height_px 0"},
      {"geocean_update", "view NULL", [](F& f) { return geocean_update(f.o, nullptr); }, NUL, "view is NULL"},
      {"geocean_update", "struct_size 0",
       [](F& f) {
         geocean_view v = f.view;
         v.struct_size = 0;
         return geocean_update(f.o, &v);
       },
       BAD, "view->struct_size 0 is smaller than"},
      {"geocean_update", "eye NaN",
       [](F& f) {
         geocean_view v = f.view;
         v.eye_ecef_m[2] = kNaN;
         return geocean_update(f.o, &v);
       },
       BAD, "view->eye_ecef_m is not finite"},
      {"geocean_update", "time 1e300",
       [](F& f) {
         geocean_view v = f.view;
         v.time_s = 1e300;
         return geocean_update(f.o, &v);
       },
       BAD, "view->time_s 1e+300 s is outside -1e12 .. 1e12 s"},
      {"geocean_update", "viewport -1 wide",
       [](F& f) {
         geocean_view v = f.view;
         v.viewport_width_px = -1;
         return geocean_update(f.o, &v);
       },
       BAD, "view->viewport -1x720 is not within 1 .. 16384"},
      {"geocean_update", "unknown draw flag",
       [](F& f) {
         geocean_view v = f.view;
         v.draw_flags = 0x80000000u;
         return geocean_update(f.o, &v);
       },
       BAD, "draw_flags"},
      {"geocean_draw", "ocean NULL", [](F&) { return geocean_draw(nullptr); }, NUL, "ocean is NULL"},
      {"geocean_draw", "no GL context", [](F& f) { return geocean_draw(f.o); }, GEOCEAN_ERROR_NO_GL_CONTEXT,
       "no OpenGL context is current on this thread"},
      {"geocean_release_gl", "ocean NULL", [](F&) { return geocean_release_gl(nullptr); }, NUL, "ocean is NULL"},
      // ---- host/layer contract
      {"geocean_get_layer_info", "out NULL", [](F& f) { return geocean_get_layer_info(f.o, nullptr); }, NUL,
       "out is NULL"},
      {"geocean_get_layer_info", "struct_size 0",
       [](F& f) {
         geocean_layer_info li{};
         return geocean_get_layer_info(f.o, &li);
       },
       BAD, "out->struct_size 0 is smaller than"},
      {"geocean_covers_opaquely", "lat0 NaN",
       [](F& f) {
         int32_t c = 0;
         return geocean_covers_opaquely(f.o, kNaN, 1, 0, 1, 10, &c);
       },
       BAD, "lat0_deg nan is not finite"},
      {"geocean_covers_opaquely", "lon1 inf",
       [](F& f) {
         int32_t c = 0;
         return geocean_covers_opaquely(f.o, 0, 1, 0, kInf, 10, &c);
       },
       BAD, "lon1_deg inf is not finite"},
      {"geocean_covers_opaquely", "footprint 0",
       [](F& f) {
         int32_t c = 0;
         return geocean_covers_opaquely(f.o, 0, 1, 0, 1, 0, &c);
       },
       BAD, "pixel_footprint_m 0.000000 is not > 0"},
      {"geocean_covers_opaquely", "out NULL", [](F& f) { return geocean_covers_opaquely(f.o, 0, 1, 0, 1, 10, nullptr); },
       NUL, "out_covers is NULL"},
      {"geocean_set_layer_inputs", "struct_size 0",
       [](F& f) {
         geocean_layer_inputs in{};
         return geocean_set_layer_inputs(f.o, &in);
       },
       BAD, "inputs->struct_size 0"},
      {"geocean_set_layer_inputs", "texture without a GL context",
       [](F& f) {
         geocean_layer_inputs in{};
         in.struct_size = sizeof in;
         in.reflection_color_texture = 7;
         in.reflection_view = f.view;
         return geocean_set_layer_inputs(f.o, &in);
       },
       GEOCEAN_ERROR_NO_GL_CONTEXT, "inputs->reflection_color_texture is set but no GL context is current"},
      {"geocean_set_layer_inputs", "shadow map without a GL context (ABI 1.8)",
       [](F& f) {
         geocean_layer_inputs in{};
         in.struct_size = sizeof in;
         in.shadow_depth_texture = 9;
         in.shadow_size_px = 2048;
         return geocean_set_layer_inputs(f.o, &in);
       },
       GEOCEAN_ERROR_NO_GL_CONTEXT, "inputs->shadow_depth_texture is set but no GL context is current"},
      {"geocean_set_layer_inputs", "struct_size between 1.7's and 1.8's",
       [](F& f) {
         geocean_layer_inputs in{};
         in.struct_size = offsetof(geocean_layer_inputs, reflection_view) + sizeof(geocean_view) - 8;
         return geocean_set_layer_inputs(f.o, &in);
       },
       BAD, "is smaller than"},
      {"geocean_set_layer_inputs", "ocean NULL", [](F&) { return geocean_set_layer_inputs(nullptr, nullptr); }, NUL,
       "ocean is NULL"},
      // ---- floating bodies
      {"geocean_bodies_config_init", "NULL", [](F&) { return geocean_bodies_config_init(nullptr); }, NUL,
       "config is NULL"},
      {"geocean_body_desc_init", "NULL", [](F&) { return geocean_body_desc_init(nullptr); }, NUL, "desc is NULL"},
      {"geocean_bodies_create", "out NULL", [](F& f) { return geocean_bodies_create(f.o, nullptr, nullptr); }, NUL,
       "out is NULL"},
      {"geocean_bodies_create", "ocean NULL",
       [](F&) {
         geocean_bodies* b = nullptr;
         return geocean_bodies_create(nullptr, nullptr, &b);
       },
       NUL, "ocean is NULL"},
      {"geocean_bodies_create", "step NaN",
       [](F& f) {
         geocean_bodies_config c;
         geocean_bodies_config_init(&c);
         c.step_s = kNaN;
         geocean_bodies* b = nullptr;
         return geocean_bodies_create(f.o, &c, &b);
       },
       BAD, "config->step_s nan s is not in (0, 0.5]"},
      {"geocean_bodies_create", "step 1",
       [](F& f) {
         geocean_bodies_config c;
         geocean_bodies_config_init(&c);
         c.step_s = 1.0;
         geocean_bodies* b = nullptr;
         return geocean_bodies_create(f.o, &c, &b);
       },
       BAD, "config->step_s 1 s is not in (0, 0.5]"},
      {"geocean_bodies_create", "start 1e13 s",
       [](F& f) {
         geocean_bodies_config c;
         geocean_bodies_config_init(&c);
         c.start_s = 1e13;
         geocean_bodies* b = nullptr;
         return geocean_bodies_create(f.o, &c, &b);
       },
       BAD, "1e+13"},
      {"geocean_bodies_add", "desc NULL", [](F& f) { return geocean_bodies_add(f.bodies, nullptr, nullptr); }, NUL,
       "desc is NULL"},
      {"geocean_bodies_add", "hull 9",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.hull = 9;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "desc->hull 9 is not a geocean_hull"},
      {"geocean_bodies_add", "size NaN",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.size_m[0] = kNaN;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "nan m is not finite and > 0"},
      {"geocean_bodies_add", "size -1",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.size_m[0] = -1.0;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "-1 m is not finite and > 0"},
      {"geocean_bodies_add", "density above water",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.density_kg_m3 = 2000.0;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "desc->density_kg_m3 2000"},
      {"geocean_bodies_add", "lat 1e300",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.lat_deg = 1e300;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "desc->lat_deg 1e+300 is not in [-90, 90]"},
      {"geocean_bodies_add", "lon NaN",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.lon_deg = kNaN;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "nan"},
      {"geocean_bodies_add", "thrust inf",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.thrust_n = kInf;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "inf"},
      {"geocean_bodies_add", "on land",
       [](F& f) {
         geocean_body_desc d = f.desc;
         d.lat_deg = 22.5, d.lon_deg = 22.5;
         return geocean_bodies_add(f.bodies, &d, nullptr);
       },
       BAD, "desc->lat_deg, lon_deg 22.5, 22.5"},
      {"geocean_bodies_remove", "no such id", [](F& f) { return geocean_bodies_remove(f.bodies, 12345); }, BAD,
       "body id 12345: no such body"},
      {"geocean_bodies_remove", "bodies NULL", [](F&) { return geocean_bodies_remove(nullptr, 1); }, NUL,
       "bodies is NULL"},
      {"geocean_bodies_count", "out NULL", [](F& f) { return geocean_bodies_count(f.bodies, nullptr); }, NUL,
       "out_count is NULL"},
      {"geocean_bodies_advance_to", "time NaN", [](F& f) { return geocean_bodies_advance_to(f.bodies, kNaN, nullptr); },
       BAD, "time_s nan is not finite"},
      {"geocean_bodies_advance_to", "time 1e13", [](F& f) { return geocean_bodies_advance_to(f.bodies, 1e13, nullptr); },
       BAD, "1e+13"},
      {"geocean_bodies_advance_to", "time before the simulation's",
       [](F& f) { return geocean_bodies_advance_to(f.bodies, -1.0, nullptr); }, BAD, "-1"},
      {"geocean_bodies_time", "out NULL", [](F& f) { return geocean_bodies_time(f.bodies, nullptr); }, NUL,
       "out_time_s is NULL"},
      {"geocean_bodies_get_poses", "capacity 0 below the count",
       [](F& f) {
         size_t n = 0;
         geocean_body_pose p;
         return geocean_bodies_get_poses(f.bodies, 0, &p, 0, &n);
       },
       BAD, "capacity 0"},
      {"geocean_bodies_get_poses", "out NULL with capacity 5",
       [](F& f) {
         size_t n = 0;
         return geocean_bodies_get_poses(f.bodies, 0, nullptr, 5, &n);
       },
       NUL, "out is NULL"},
      {"geocean_bodies_get_hull", "no such id",
       [](F& f) {
         size_t nv = 0, ni = 0;
         return geocean_bodies_get_hull(f.bodies, 777, nullptr, 0, nullptr, 0, &nv, &ni);
       },
       BAD, "body id 777: no such body"},
      {"geocean_bodies_get_hull", "capacity below the size",
       [](F& f) {
         size_t nv = 0, ni = 0;
         double v[3];
         uint32_t idx[3];
         return geocean_bodies_get_hull(f.bodies, 1, v, 1, idx, 3, &nv, &ni);
       },
       BAD, "capacities 1 vertices, 3"},
  };
  return r;
}

TEST(CapiBadInputMatrix, EveryEntryPointRefusesBadInputNamingItAndChangesNothing) {
  std::set<std::string> covered;
  for (const Row& row : rows()) {
    SCOPED_TRACE(std::string(row.function) + " with " + row.input);
    Fixture f;
    const Answers before = Answers::of(f);
    const geocean_status st = row.call(f);
    const std::string msg = lastError();
    EXPECT_EQ(st, row.expect) << geocean_status_string(st) << ": " << msg;
    EXPECT_EQ(msg.rfind(std::string(row.function) + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(row.message), std::string::npos) << "message: " << msg << "\nwanted: " << row.message;
    if (f.after) f.after();
    EXPECT_TRUE(Answers::of(f) == before) << "the refused call changed the ocean's answers";
    covered.insert(row.function);
  }
  // Every entry point the header declares has a row here, or is one of
  // those without bad input (they take nothing, or NULL is allowed: the next test).
  const std::set<std::string> noBadInput = {"geocean_abi_version", "geocean_version_string", "geocean_last_error",
                                            "geocean_status_string", "geocean_destroy", "geocean_bodies_destroy"};
  std::ifstream header(GEOCEAN_SOURCE_DIR "/plugin/capi/include/geocean/geocean_ocean.h");
  ASSERT_TRUE(header) << "cannot read the header";
  const std::regex decl(R"(GEOCEAN_API\s+[^(]*?\b(geocean_[a-z0-9_]+)\s*\()");
  std::string text((std::istreambuf_iterator<char>(header)), std::istreambuf_iterator<char>());
  int declared = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), decl), end; it != end; ++it) {
    const std::string name = (*it)[1];
    ++declared;
    EXPECT_TRUE(covered.count(name) || noBadInput.count(name)) << name << " has no row in the matrix";
  }
  EXPECT_GT(declared, 50);
  std::printf("%zu bad-input rows over %zu of the header's %d entry points (%zu without bad input)\n", rows().size(),
              covered.size(), declared, noBadInput.size());
}

// Values that are not errors: empty batches, points off the globe, an
// unknown layer name, NULL destroys. The answer the header states, no crash.
TEST(CapiBadInputMatrix, EmptyAndOffTheGlobeInputsAnswerWhatTheHeaderSays) {
  Fixture f;
  EXPECT_EQ(geocean_query_class(f.o, 0, nullptr, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(geocean_query_elevation(f.o, 0, nullptr, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(geocean_query_sea_surface(f.o, 0, nullptr, nullptr, 0.0, nullptr, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(geocean_query_sea_state(f.o, 0, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr), GEOCEAN_OK);
  geocean_surface_outputs none;
  ASSERT_EQ(geocean_surface_outputs_init(&none), GEOCEAN_OK);
  EXPECT_EQ(geocean_query_surface(f.o, 0, nullptr, nullptr, nullptr, 0, &none), GEOCEAN_OK);
  EXPECT_EQ(geocean_set_mask_encoding(f.o, ""), GEOCEAN_OK);  // "" = the default encoding
  size_t removed = 9;
  EXPECT_EQ(geocean_remove_layer(f.o, "not a layer", &removed), GEOCEAN_OK);
  EXPECT_EQ(removed, 0u);
  geocean_destroy(nullptr);
  geocean_bodies_destroy(nullptr);
  EXPECT_STREQ(geocean_status_string(static_cast<geocean_status>(12345)), "GEOCEAN_ERROR_UNKNOWN_STATUS");

  // Off the globe (NaN, infinities, |lat| > 90, |lon| > 360): sea outputs NaN, never evaluated.
  const double lat[6] = {kNaN, kInf, -kInf, 1e308, 0.0, 0.0}, lon[6] = {0.0, 0.0, 0.0, 0.0, kNaN, -1e308};
  double h[6], nrm[18];
  uint8_t c[6];
  ASSERT_EQ(geocean_query_sea_surface(f.o, 6, lat, lon, 1.0, h, nrm, c), GEOCEAN_OK) << lastError();
  for (int i = 0; i < 6; ++i) {
    EXPECT_TRUE(std::isnan(h[i])) << i << ": " << h[i];
    EXPECT_TRUE(std::isnan(nrm[3 * i])) << i;
    EXPECT_LE(c[i], 2) << i;
  }
  double hs[6];
  ASSERT_EQ(geocean_query_sea_state(f.o, 6, lat, lon, hs, nullptr, nullptr, nullptr), GEOCEAN_OK);
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(std::isnan(hs[i])) << i << ": " << hs[i];
  // Elevation: no data (NaN) where it cannot sample, else a value between
  // the raster's (a global raster clamps latitude and wraps longitude), never garbage.
  float e[6];
  ASSERT_EQ(geocean_query_elevation(f.o, 6, lat, lon, e), GEOCEAN_OK) << lastError();
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(std::isnan(e[i]) || (e[i] >= -3000.0f && e[i] <= 500.0f)) << i << ": " << e[i];
  for (int i : {0, 1, 2, 4}) EXPECT_TRUE(std::isnan(e[i])) << i << ": " << e[i];  // NaN and infinities
  ASSERT_EQ(geocean_query_class(f.o, 6, lat, lon, c), GEOCEAN_OK) << lastError();
  for (int i = 0; i < 6; ++i) EXPECT_LE(c[i], 2) << i;
}

}  // namespace
