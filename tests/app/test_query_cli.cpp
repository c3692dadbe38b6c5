// `geocean query` end to end: argument forms, JSON, streaming CSV, and
// every kind of bad input (message naming row and value, non-zero exit).
#include "tests/support/Jonswap.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using geocean::test::run;

namespace {
const std::string kGeocean = GEOCEAN_EXE;
constexpr double kG = 9.80665;

// One row of the CSV output; sea fields are NaN where the CLI printed null.
struct Row {
  double lat = 0, lon = 0, timeS = 0, seaHeightM = 0, ne = 0, nn = 0, nu = 0, wMps = 0;
  std::string surface;
};
double field(const std::string& s) { return s == "null" ? std::nan("") : std::stod(s); }
std::vector<Row> parseCsv(const std::string& out) {
  std::vector<Row> rows;
  std::istringstream in(out);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    EXPECT_EQ(f.size(), 14u) << line;  // ... vertical_velocity_mps, then the 4 sea-state columns
    if (f.size() != 14) continue;
    rows.push_back({field(f[0]), field(f[1]), field(f[4]), field(f[5]), field(f[6]), field(f[7]), field(f[8]),
                    field(f[9]), f[2]});
  }
  return rows;
}
std::vector<Row> query(const std::string& args, const std::string& csv) {
  auto r = run(kGeocean + " query --points - " + args, csv);
  EXPECT_EQ(r.exitCode, 0) << args << ": " << r.err;
  return parseCsv(r.out);
}

// Random points in the open central Pacific (deep water, few islands) at
// random times: far enough apart to be independent samples of the sea.
// timeSlots > 0: times from that many values only (the FFT model builds one
// table per distinct time).
std::string pacificRows(int n, std::uint64_t seed, int timeSlots = 0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> lat(-25, 25), lon(-175, -110), t(0, 3600);
  std::ostringstream os;
  os.precision(17);
  for (int i = 0; i < n; ++i)
    os << lat(rng) << ',' << lon(rng) << ',' << (timeSlots ? 450.0 * (i % timeSlots) : t(rng)) << '\n';
  return os.str();
}
}  // namespace

TEST(QueryCli, NegativeCoordinatesAsPlainArguments) {
  auto r = run(kGeocean + " query -33.9 151.5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_EQ(r.out.rfind("lat,lon,surface,elevation_m,time_s,sea_height_m,normal_e,normal_n,normal_u,"
                        "vertical_velocity_mps,hs_m,peak_period_s,peak_wavelength_m,wave_from_deg\n"
                        "-33.9,151.5,ocean,-62.600002,0,",
                        0),
            0u)
      << r.out;
  r = run(kGeocean + " query 23 10 --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("\"lat\":23,\"lon\":10"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"surface\":\"land\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"elevation_m\":788,\"sea_height_m\":null,\"normal\":null"), std::string::npos) << r.out;
}

TEST(QueryCli, StreamsCsvRowsInOrderWithOptionalHeader) {
  auto r = run(kGeocean + " query --points - --format json", "lat,lon,time\n-1,33\n42,50.5,10\n\n0,-150\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto lake1 = r.out.find("\"lat\":-1,\"lon\":33,\"time_s\":0,\"surface\":\"lake\"");
  const auto lake2 = r.out.find("\"lat\":42,\"lon\":50.5,\"time_s\":10,\"surface\":\"lake\"");
  const auto ocean = r.out.find("\"lat\":0,\"lon\":-150,\"time_s\":0,\"surface\":\"ocean\"");
  ASSERT_NE(lake1, std::string::npos) << r.out;
  ASSERT_NE(lake2, std::string::npos) << r.out;
  ASSERT_NE(ocean, std::string::npos) << r.out;
  EXPECT_LT(lake1, lake2);
  EXPECT_LT(lake2, ocean);
}

TEST(QueryCli, BadValuesNameTheRowAndValue) {
  struct Case {
    std::string input, mustSay;
  } cases[] = {
      {"10,10\n91,0\n", "row 2: latitude 91 is outside [-90, 90]"},
      {"abc,0\n", "row 1: latitude 'abc' is not a finite number"},
      {"0,nan\n", "row 1: longitude 'nan' is not a finite number"},
      {"lat,lon\n0,0\ninf,0\n", "row 3: latitude 'inf' is not a finite number"},
      {"0,0\n5\n", "row 2: expected 'lat,lon[,time]', got '5'"},
      {"0,0,1,2\n", "row 1: more than 3 fields"},
  };
  for (const auto& c : cases) {
    auto r = run(kGeocean + " query --points -", c.input);
    EXPECT_EQ(r.exitCode, 2) << c.input;
    EXPECT_NE(r.err.find(c.mustSay), std::string::npos) << r.err;
  }
  // Rows before the bad one are answered, then the batch stops loudly.
  auto r = run(kGeocean + " query --points -", "0,-150\n95,0\n0,-150\n");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.out.find("\n0,-150,ocean,-4125.25,0,"), r.out.find('\n')) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
  for (const char* args : {" query 91 0", " query abc 0", " query 0 nan", " query 0 inf", " query 0"}) {
    r = run(kGeocean + args);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

TEST(QueryCli, BadRasterFilesAreNamed) {
  auto r = run(kGeocean + " query 0 0 --mask /nonexistent/mask.tif");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("/nonexistent/mask.tif: no such file"), std::string::npos) << r.err;
  r = run(kGeocean + " query 0 0 --elevation " GEOCEAN_SOURCE_DIR "/README.md");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("README.md"), std::string::npos) << r.err;
  r = run(kGeocean + " query --points /nonexistent.csv");
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("/nonexistent.csv"), std::string::npos) << r.err;
}

TEST(QueryCli, FineMaskAndMaskEncoding) {
  // The 1.25' mask through the ImageCache gives the same answers at known places.
  auto r = run(kGeocean + " query 42 50.5 --mask " GEOCEAN_DATA_DIR "/landmask_1.25m.tif");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find(",lake,"), std::string::npos);
  // Remap: call lakes ocean.
  r = run(kGeocean + " query 42 50.5 --mask-encoding 0=ocean,1=land,2=ocean");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find(",ocean,"), std::string::npos);
  r = run(kGeocean + " query 42 50.5 --mask-encoding 2=sea");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("sea"), std::string::npos);
}

TEST(QueryCli, SignificantWaveHeightOfEveryModelMatchesPiersonMoskowitz) {
  // Issue #3: Hs = 4 std(sea height) within 10% of Hs = 0.21 U^2/g. 3000
  // independent points estimate the std to about 1.3% (sqrt(1/2n)); the
  // models themselves sit within a few % (tests/waves/test_wavefield.cpp).
  const std::string rows = pacificRows(3000, 11), rowsFewTimes = pacificRows(3000, 11, 8);
  struct Case {
    std::string args;
    double windMps;
  } cases[] = {
      {"--waves fft --wind 15", 15.0},
      {"--waves fft --wind 6 --fetch 50000", -1.0},  // fetch-limited: JONSWAP's Hs
      {"--waves noise --wind 15", 15.0},
      {"--waves noise-paper --wind 15", 15.0},
      {"--waves gerstner --wind 15", 15.0},
      {"--wind 8", 8.0},  // the default model
      // Beaufort 7 = 13.9 .. 17.1 m/s at 10 m: the middle, 15.5 m/s, times
      // 1.026 to the 19.5 m of Pierson-Moskowitz.
      {"--waves gerstner --beaufort 7", 15.5 * 1.026},
  };
  for (const auto& c : cases) {
    const bool fft = c.args.find("fft") != std::string::npos;
    const auto res = query(c.args, fft ? rowsFewTimes : rows);
    double sum = 0, sum2 = 0;
    int n = 0;
    for (const Row& r : res) {
      if (r.surface != "ocean") {
        EXPECT_TRUE(std::isnan(r.seaHeightM)) << c.args;
        continue;
      }
      sum += r.seaHeightM, sum2 += r.seaHeightM * r.seaHeightM, ++n;
    }
    ASSERT_GT(n, 2700) << c.args;  // the box is > 90% open ocean
    const double hs = 4.0 * std::sqrt(sum2 / n - (sum / n) * (sum / n));
    const double hsPm = c.windMps > 0 ? 0.21 * c.windMps * c.windMps / kG : geocean::test::textbookJonswapHs(6.0, 50000.0);
    EXPECT_NEAR(hs, hsPm, 0.10 * hsPm) << c.args;
  }
}

TEST(QueryCli, NormalsAreUnitAndWavesTravelDownwind) {
  // A wave pattern moving with velocity c satisfies d(eta)/dt = -c . grad(eta),
  // and the normal is (-grad(eta), 1) / norm: so the vertical velocity
  // correlates positively with the normal's component along the travel
  // direction. Wind FROM 270 -> waves travel east; FROM 0 -> south.
  // Points within 0.3 deg of the anchor, where --wind-dir holds exactly.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  std::ostringstream os;
  os.precision(17);
  // 8 times (the FFT model builds one table per distinct time).
  for (int i = 0; i < 1500; ++i) os << d(rng) << ',' << -150 + d(rng) << ',' << 75.0 * (i % 8) + 0.5 << '\n';
  for (const char* model : {"noise", "noise-paper", "gerstner", "fft"}) {
    for (int windFrom : {270, 90, 0, 180}) {
      const auto res =
          query(std::string("--waves ") + model + " --anchor 0,-150 --wind-dir " + std::to_string(windFrom), os.str());
      ASSERT_EQ(res.size(), 1500u);
      double swe = 0, swn = 0, sw2 = 0, se2 = 0, sn2 = 0;
      for (const Row& r : res) {
        ASSERT_EQ(r.surface, "ocean");
        // Unit normal: the CLI prints shortest round-trip doubles.
        EXPECT_NEAR(r.ne * r.ne + r.nn * r.nn + r.nu * r.nu, 1.0, 1e-12);
        EXPECT_GT(r.nu, 0.0);
        swe += r.wMps * r.ne, swn += r.wMps * r.nn;
        sw2 += r.wMps * r.wMps, se2 += r.ne * r.ne, sn2 += r.nn * r.nn;
      }
      const double corrE = swe / std::sqrt(sw2 * se2), corrN = swn / std::sqrt(sw2 * sn2);
      const double travelE = std::sin((windFrom + 180) * M_PI / 180), travelN = std::cos((windFrom + 180) * M_PI / 180);
      // Measured correlations are 0.6-0.9 along the travel direction; 0.3
      // leaves room for other seeds while still fixing the sign.
      const double along = corrE * travelE + corrN * travelN;
      EXPECT_GT(along, 0.3) << model << " wind from " << windFrom << " corrE " << corrE << " corrN " << corrN;
    }
  }
}

TEST(QueryCli, RowTimeOverridesTimeAndVerticalVelocityIsTheTimeDerivative) {
  for (const char* model : {"noise", "gerstner"}) {
    const std::string m = std::string(" --waves ") + model;
    auto a = query("--time 100" + m, "0,-150,5\n0,-150\n");
    auto b = query("--time 5" + m, "0,-150\n");
    ASSERT_EQ(a.size(), 2u);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(a[0].timeS, 5.0);
    EXPECT_EQ(a[1].timeS, 100.0);
    EXPECT_EQ(a[0].seaHeightM, b[0].seaHeightM) << model;
    EXPECT_NE(a[1].seaHeightM, b[0].seaHeightM) << model;
    // Central difference over +-0.05 s: truncation ~ dt^2/6 * omega^3 * a
    // (< 1e-3 m/s for these seas) plus the 0.1 mm inversion tolerance / dt.
    std::ostringstream rows;
    rows.precision(17);
    for (double t : {37.0, 611.5, 2000.25})
      for (double dt : {-0.05, 0.0, 0.05}) rows << "10.5,-140.25," << t + dt << '\n';
    auto r = query(m, rows.str());
    ASSERT_EQ(r.size(), 9u);
    for (int i = 0; i < 3; ++i) {
      const double fd = (r[3 * i + 2].seaHeightM - r[3 * i].seaHeightM) / 0.1;
      EXPECT_NEAR(r[3 * i + 1].wMps, fd, 0.01) << model << " t " << r[3 * i + 1].timeS;
    }
  }
}

TEST(QueryCli, SeedsAndModelsGiveDifferentSeasContinuousAcrossTheAntimeridian) {
  const std::string rows = "-17,179.999999999\n-17,-179.999999999\n-17,180\n-17,-180\n";
  for (const char* model : {"noise", "gerstner"}) {
    auto a = query(std::string("--waves ") + model, rows);
    auto b = query(std::string("--waves ") + model + " --seed 2", rows);
    ASSERT_EQ(a.size(), 4u);
    ASSERT_EQ(b.size(), 4u);
    EXPECT_NE(a[0].seaHeightM, b[0].seaHeightM) << model;
    // The points are 2e-9 deg = 0.22 mm apart across lon 180 (Fiji's sea;
    // 1000 m deep so no breaking); slopes stay below 1, plus the 0.1 mm
    // inversion tolerance of Gerstner: 0.4 mm. The paper's own model jumps
    // by metres there (tests/waves/test_sphere_defects.cpp).
    EXPECT_NEAR(a[0].seaHeightM, a[1].seaHeightM, 4e-4) << model;
    EXPECT_NEAR(a[2].seaHeightM, a[3].seaHeightM, 2e-4) << model;
  }
  auto n = query("--waves noise", rows), g = query("--waves gerstner", rows);
  EXPECT_NE(n[0].seaHeightM, g[0].seaHeightM);
}

TEST(QueryCli, BadSeaStateValuesExitTwoNamingTheValue) {
  struct Case {
    std::string args, mustSay;
  } cases[] = {
      {"--wind -3", "--wind -3 m/s is outside 0.2 .. 60 m/s"},
      {"--wind 61", "--wind 61 m/s is outside"},
      {"--wind abc", "--wind 'abc' is not a finite number"},
      {"--waves foo", "--waves 'foo' is not a wave model (noise, noise-paper, gerstner, fft, none)"},
      {"--time nan", "--time 'nan' is not a finite number"},
      {"--time inf", "--time 'inf' is not a finite number"},
      // Beyond the sea's time bound (plugin/waves/TimeRange.h, fuzz finding 5).
      {"--waves gerstner --time 1e33", "--time 1e+33 s is outside -1e12 .. 1e12 s"},
      {"--time -1.5e12", "--time -1.5e+12 s is outside -1e12 .. 1e12 s"},
      {"--wind-dir inf", "--wind-dir 'inf' is not a finite number"},
      {"--beaufort 13", "--beaufort 13 is not a Beaufort number 0..12"},
      {"--beaufort 2.5", "--beaufort 2.5 is not a Beaufort number"},
      {"--wind 5 --beaufort 3", "either --wind or --beaufort"},
      {"--seed -1", "--seed '-1' is not an integer"},
      {"--seed 1.5", "--seed '1.5' is not an integer"},
      {"--fetch -10", "--fetch -10 m is negative"},
      {"--anchor 95,0", "--anchor: latitude 95 is outside"},
      {"--anchor 5", "--anchor '5' is not LAT,LON"},
  };
  for (const auto& c : cases) {
    auto r = run(kGeocean + " query 0 -150 " + c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_NE(r.err.find(c.mustSay), std::string::npos) << c.args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
  // A NaN time in a row is named with its row.
  auto r = run(kGeocean + " query --points - --waves gerstner", "0,-150,1\n0,-150,nan\n");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("row 2: time 'nan' is not a finite number"), std::string::npos) << r.err;
  r = run(kGeocean + " query --points - --waves gerstner", "0,-150,1e12\n0,-150,7e307\n");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("row 2: time 7e+307 s is outside -1e12 .. 1e12 s"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;  // header and the row at the bound
}

TEST(QueryCli, WavesNoneGivesClassAndElevationOnly) {
  auto r = run(kGeocean + " query --points - --waves none", "0,-150\n23,10\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("0,-150,ocean,-4125.25,0,null,null,null,null,null,null,null,null,null\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("23,10,land,788,0,null,null,null,null,null,null,null,null,null\n"), std::string::npos) << r.out;
  r = run(kGeocean + " query 0 0 --waves bogus");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("'bogus'"), std::string::npos) << r.err;
}

// Issue 15 item 6: the sea state at the point, against Pierson-Moskowitz's
// closed forms (Hs = 4 sqrt(0.0081 / 5) g / wp^2, wp = 0.877 g / U, deep
// water L = g T^2 / 2 pi), in CSV and JSON; null on land.
TEST(QueryCli, SeaStateColumnsMatchPiersonMoskowitz) {
  const double g = 9.80665, u = 15.0, wp = 0.877 * g / u;
  const double hs = 4.0 * std::sqrt(0.0081 / 5.0) * g / (wp * wp), tp = 2.0 * M_PI / wp;
  for (const char* model : {"noise", "gerstner", "fft"}) {
    // (0 N, -150 E): 4.5 km deep Pacific, deep water for a 10 s sea.
    auto r = run(kGeocean + " query 0 -150 --waves " + model + " --wind 15 --wind-dir 300 --anchor 0,-150");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto nl = r.out.find('\n');
    ASSERT_NE(nl, std::string::npos) << r.out;
    std::vector<double> v;
    std::stringstream row(r.out.substr(nl + 1));
    std::string cell;
    for (int c = 0; std::getline(row, cell, ','); ++c)
      if (c >= 5) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 9u) << r.out;
    EXPECT_NEAR(v[5], hs, 2e-3 * hs) << model;           // Simpson over 0.2 .. 20 wp
    EXPECT_NEAR(v[6], tp, 1e-6 * tp) << model;            // printed to 17 digits
    EXPECT_NEAR(v[7], g * tp * tp / (2.0 * M_PI), 1e-3) << model;
    // Gerstner: the components' mean direction (cos^2 spreading, 16 draws).
    EXPECT_NEAR(v[8], 300.0, std::string(model) == "gerstner" ? 25.0 : 1e-6) << model;
  }
  auto r = run(kGeocean + " query 23 10 --waves gerstner --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("\"hs_m\":null,\"peak_period_s\":null,\"peak_wavelength_m\":null,\"wave_from_deg\":null"),
            std::string::npos)
      << r.out;
  r = run(kGeocean + " query 0 -150 --waves gerstner --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("\"hs_m\":2."), std::string::npos) << r.out;  // 0.209 U^2 / g at 10 m/s: 2.13 m
}

// Issue 15: --coast-region makes the waves feel the coast: inside it the
// peak wavelength is the dispersion relation's at the local depth
// (-elevation_m), w^2 = g k tanh(k h); bad values exit 2 naming them.
TEST(QueryCli, CoastRegionGivesTheLocalWavelength) {
  const std::string q = kGeocean + " query 36.0 -5.6 --waves gerstner --anchor 36,-5.6 --wind-dir 250";
  auto r = run(q + " --coast-region 36.0,-5.6");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<std::string> f;
  std::stringstream row(r.out.substr(r.out.find('\n') + 1));
  for (std::string c; std::getline(row, c, ',');) f.push_back(c);
  ASSERT_EQ(f.size(), 14u) << r.out;
  const double h = -std::stod(f[3]), lp = std::stod(f[12]), tp = std::stod(f[11]);
  ASSERT_GT(h, 1.0);
  const double g = 9.80665, w = 2.0 * M_PI / tp;
  double lo = w * w / g, hi = 10.0 * w / std::sqrt(g * h);
  for (int i = 0; i < 200; ++i) {
    const double k = 0.5 * (lo + hi);
    (g * k * std::tanh(k * h) < w * w ? lo : hi) = k;
  }
  EXPECT_NEAR(lp, 2.0 * M_PI / (0.5 * (lo + hi)), 1e-6 * lp) << r.out;
  EXPECT_LT(lp, g * tp * tp / (2.0 * M_PI));  // shorter than in deep water
  for (const auto& [arg, msg] : std::vector<std::pair<std::string, std::string>>{
           {" --coast-region 1,x", "'x'"}, {" --coast-region 1,2,100", "size 100 m"}, {" --coast-region 95,0", "95"}}) {
    r = run(q + arg);
    EXPECT_EQ(r.exitCode, 2) << arg;
    EXPECT_NE(r.err.find(msg), std::string::npos) << r.err;
  }
  r = run(kGeocean + " query 0 0 --coast-region 1,2");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("needs --waves gerstner"), std::string::npos) << r.err;
}
