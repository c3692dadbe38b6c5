// `geocean query` end to end: argument forms, JSON, streaming CSV, and
// every kind of bad input (message naming row and value, non-zero exit).
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <string>

using geocean::test::run;

namespace {
const std::string kGeocean = GEOCEAN_EXE;
}

TEST(QueryCli, NegativeCoordinatesAsPlainArguments) {
  auto r = run(kGeocean + " query -33.9 151.5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, "lat,lon,surface,elevation_m\n-33.9,151.5,ocean,-62.600002\n");
  r = run(kGeocean + " query 23 10 --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("\"lat\":23,\"lon\":10"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"surface\":\"land\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"elevation_m\":788"), std::string::npos) << r.out;
}

TEST(QueryCli, StreamsCsvRowsInOrderWithOptionalHeader) {
  auto r = run(kGeocean + " query --points - --format json", "lat,lon,time\n-1,33\n42,50.5,10\n\n0,-150\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto lake1 = r.out.find("\"lat\":-1,\"lon\":33,\"surface\":\"lake\"");
  const auto lake2 = r.out.find("\"lat\":42,\"lon\":50.5,\"time_s\":10,\"surface\":\"lake\"");
  const auto ocean = r.out.find("\"lat\":0,\"lon\":-150,\"surface\":\"ocean\"");
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
  EXPECT_EQ(r.out, "lat,lon,surface,elevation_m\n0,-150,ocean,-4125.25\n");
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
