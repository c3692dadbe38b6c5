// `geocean pick` end to end on the default world: both spellings of
// negative components, 1 m above the sea, grazing rays against long double,
// camera pixels, terrain, batches from a file and stdin, and bad input.
#include "globe/geo/Ellipsoid.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

using geocean::test::run;
using namespace geocean;

namespace {
const std::string kGeocean = GEOCEAN_EXE;

std::string csv(const glm::dvec3& o, const glm::dvec3& d) {
  char b[256];
  std::snprintf(b, sizeof b, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", o.x, o.y, o.z, d.x, d.y, d.z);
  return b;
}

std::vector<nlohmann::json> jsonLines(const std::string& out) {
  std::vector<nlohmann::json> v;
  std::istringstream s(out);
  for (std::string line; std::getline(s, line);) v.push_back(nlohmann::json::parse(line));
  return v;
}
}  // namespace

TEST(PickCli, NegativeComponentsInBothSpellings) {
  for (const char* form : {" pick --ray=-6378237,0,0,1,0,0 --format json --no-terrain",
                           " pick --ray -6378237,0,0,1,0,0 --format json --no-terrain"}) {
    const auto r = run(kGeocean + form);
    ASSERT_EQ(r.exitCode, 0) << form << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["distance_m"].get<double>(), 100.0, 1e-6);  // x = -a exactly
    EXPECT_NEAR(j["lat"].get<double>(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(j["lon"].get<double>()), 180.0, 1e-12);
    EXPECT_EQ(j["surface"], "ocean");  // lat 0, lon 180: the central Pacific
  }
}

// A batch through the whole Embree scene (terrain included): 1 m above the
// Pacific, grazing rays over it, and a ray from inside the ellipsoid.
TEST(PickCli, BatchOfSeaRaysWithin1mm) {
  std::string rows = "ox,oy,oz,dx,dy,dz\n";
  std::vector<double> expected;
  const glm::dvec3 o1 = geo::toEcef({0.0, -150.0, 1.0});
  rows += csv(o1, -geo::surfaceNormal(0.0, -150.0)) + "\n";
  expected.push_back(1.0);
  // Tangent to an ellipsoid 1 cm / 1 m inside the sea surface at (0, -150),
  // from 300 km back: the exact roots from the long-double closed form.
  for (double depth : {0.01, 1.0}) {
    const geo::EnuFrame f = geo::enuFrame({0.0, -150.0, -depth});
    const glm::dvec3 o = f.originEcef - f.north * 3e5;
    rows += csv(o, f.north) + "\n";
    const long double a = geo::kWgs84A, b = (long double)geo::kWgs84A * (1.0L - 1.0L / 298.257223563L);
    const long double ox = o.x / a, oy = o.y / a, oz = o.z / b, dx = f.north.x / a, dy = f.north.y / a,
                      dz = f.north.z / b;
    const long double A = dx * dx + dy * dy + dz * dz, B = ox * dx + oy * dy + oz * dz,
                      C = ox * ox + oy * oy + oz * oz - 1.0L;
    expected.push_back(double((-B - std::sqrt(B * B - A * C)) / A));
  }
  // From 10 m below the sea surface straight up: the surface from below.
  rows += csv(geo::toEcef({0.0, -150.0, -10.0}), geo::surfaceNormal(0.0, -150.0)) + "\n";
  expected.push_back(10.0);
  const std::string path = std::string(GEOCEAN_BINARY_DIR) + "/pick_rays_test.csv";
  std::ofstream(path) << rows;
  for (const std::string& src : {path, std::string("-")}) {
    const auto r = run(kGeocean + " pick --format json --rays " + src, src == "-" ? rows : "");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto js = jsonLines(r.out);
    ASSERT_EQ(js.size(), expected.size()) << r.out;
    for (std::size_t i = 0; i < js.size(); ++i) {
      ASSERT_TRUE(js[i]["hit"].get<bool>()) << i;
      EXPECT_EQ(js[i]["surface"], "ocean") << i;
      EXPECT_NEAR(js[i]["distance_m"].get<double>(), expected[i], 1e-3) << i;  // issue 4: 1 mm
      EXPECT_NEAR(js[i]["height_m"].get<double>(), 0.0, 1e-3) << i;
    }
  }
}

TEST(PickCli, CameraPixelOnTheSeaAndOnEverest) {
  // 1281 x 721: pixel (640, 360) is the exact centre; pitch -90 looks down.
  auto r = run(kGeocean + " pick --camera 30,-40,50000,0,-90 --fov 60 --size 1281x721 --pixel 640,360 --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["distance_m"].get<double>(), 50000.0, 1e-3);
  EXPECT_NEAR(j["lat"].get<double>(), 30.0, 1e-9);
  EXPECT_EQ(j["surface"], "ocean");
  // Everest (27.988, 86.925, 8849 m): ETOPO at 20' smooths it to a few km,
  // but a pick from 20 km straight down must stop on land well above the sea.
  r = run(kGeocean + " pick --camera 27.988,86.925,20000,0,-90 --size 1281x721 --pixel 640,360 --format json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["surface"], "land");
  EXPECT_GT(j["height_m"].get<double>(), 3000.0);
  EXPECT_NEAR(j["distance_m"].get<double>() + j["height_m"].get<double>(), 20000.0, 1e-3);
  // Looking up into the sky: no hit, nulls.
  r = run(kGeocean + " pick --camera 0,0,100,0,80 --pixel 640,360 --format json --no-terrain");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["hit"].get<bool>());
  EXPECT_TRUE(j["lat"].is_null());
}

TEST(PickCli, BadInputNamesTheFieldAndFails) {
  struct Case {
    std::string args, input, needle;
  };
  for (const Case& c : std::vector<Case>{
           {" pick --ray 1,2,3", "", "expected 6"},
           {" pick --ray 1,2,x,0,0,1", "", "'x'"},
           {" pick --ray 7e6,0,0,0,0,0", "", "is zero"},
           {" pick --camera 0,0,100,0,-90 --pixel 2000,1", "", "outside"},
           {" pick --camera 0,0,100,0,-90 --pixel 1,1 --fov 200", "", "field of view"},
           {" pick --camera 0,0,100,0,-90 --pixel 1,1 --size 12x", "", "--size"},
           {" pick", "", "exactly one"},
           {" pick --rays - --no-terrain", "7e6,0,0,-1,0,0\n7e6,0,0,-1,0,zz\n", "row 2"},
           {" pick --rays /nonexistent.csv", "", "cannot open"},
       }) {
    const auto r = run(kGeocean + c.args, c.input);
    EXPECT_NE(r.exitCode, 0) << c.args;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << ": " << r.err;
  }
  // The good row before the bad one was answered.
  const auto r = run(kGeocean + " pick --rays - --no-terrain", "7e6,0,0,-1,0,0\n7e6,0,0,-1,0,zz\n");
  EXPECT_NE(r.out.find("true,0,0,0,621862.99"), std::string::npos) << r.out;
}
