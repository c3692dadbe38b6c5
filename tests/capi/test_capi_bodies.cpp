// ABI 1.4 (1.6: repulsion), floating bodies, through the run-time loader as a host sees
// them: the poses equal those of a façade-level bodies::Simulation built
// the same way (same bits, so the ABI adds nothing to the physics), the
// fixed step holds through the ABI, and bad input gets a status and a
// message naming the field and the value.
#include "tests/capi/LoadedPlugin.h"
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Spawn.h"
#include "plugin/ocean/Ocean.h"
#include "globe/geo/Ellipsoid.h"

#include <glm/gtc/quaternion.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace {

using geocean::host::OceanPlugin;
namespace bodies = geocean::bodies;

using namespace geocean::capitest;
using Ocean = OceanHandle;
struct Bodies {
  geocean_bodies* h = nullptr;
  explicit Bodies(geocean_ocean* o, const geocean_bodies_config* c = nullptr) {
    EXPECT_EQ(api().bodiesCreate(o, c, &h), GEOCEAN_OK) << lastError();
  }
  ~Bodies() { api().bodiesDestroy(h); }
};

// The sea both sides float on: Gerstner, 12 m/s, anchored at the bodies.
constexpr double kLat = 38.0, kLon = -30.0;
geocean_sea_state capiSea() {
  geocean_sea_state s;
  api().seaStateInit(&s);
  s.model = GEOCEAN_WAVES_GERSTNER;
  s.wind_speed_mps = 12.0;
  s.seed = 7;
  s.anchor_lat_deg = kLat;
  s.anchor_lon_deg = kLon;
  return s;
}

// capiSea() on the façade side.
void setFacadeSea(geocean::ocean::Ocean& core) {
  geocean::waves::SeaState ws;
  ws.windSpeedMps = 12.0;
  ws.seed = 7;
  ws.anchorLatDeg = kLat;
  ws.anchorLonDeg = kLon;
  core.setSeaState(geocean::waves::Model::Gerstner, ws);
}

struct Spec {
  int32_t hull;
  double size[3];
  double density, lat, lon, heading, thrust;
};
const std::vector<Spec> kSpecs = {
    {GEOCEAN_HULL_BOAT, {20.0, 0, 0}, 450.0, kLat, kLon, 30.0, 2e4},
    {GEOCEAN_HULL_BOX, {6.0, 3.0, 2.0}, 600.0, kLat + 0.001, kLon, 90.0, 0.0},
    {GEOCEAN_HULL_CYLINDER, {1.5, 4.0, 0}, 300.0, kLat, kLon + 0.001, 0.0, 0.0},
};

bodies::HullMesh hullOf(const Spec& s) {
  switch (s.hull) {
    case GEOCEAN_HULL_BOX: return bodies::HullMesh::box({s.size[0], s.size[1], s.size[2]});
    case GEOCEAN_HULL_CYLINDER: return bodies::HullMesh::cylinder(s.size[0], s.size[1]);
    default: return bodies::HullMesh::boat(s.size[0]);
  }
}

TEST(CapiBodies, PosesAreTheFacadeSimulationsBits) {
  ASSERT_NE(api().bodiesCreate, nullptr);  // a 1.4 plugin resolves them all
  Ocean oc;
  const geocean_sea_state sea = capiSea();
  ASSERT_EQ(api().setSeaState(oc.h, &sea), GEOCEAN_OK) << lastError();
  Bodies b(oc.h);
  std::vector<geocean_body_id> ids;
  for (const Spec& s : kSpecs) {
    geocean_body_desc d;
    ASSERT_EQ(api().bodyDescInit(&d), GEOCEAN_OK);
    d.hull = s.hull;
    std::memcpy(d.size_m, s.size, sizeof s.size);
    d.density_kg_m3 = s.density;
    d.lat_deg = s.lat, d.lon_deg = s.lon, d.heading_deg = s.heading, d.thrust_n = s.thrust;
    geocean_body_id id = 0;
    ASSERT_EQ(api().bodiesAdd(b.h, &d, &id), GEOCEAN_OK) << lastError();
    ids.push_back(id);
  }
  EXPECT_EQ(ids, (std::vector<geocean_body_id>{1, 2, 3}));

  // The façade side, built as the ABI documents it.
  geocean::ocean::Ocean core;
  setFacadeSea(core);
  auto oceanSea = std::make_shared<bodies::OceanSea>(core.current());
  bodies::Simulation sim({.stepS = 1.0 / 60.0});
  for (const Spec& s : kSpecs) {
    auto hull = std::make_shared<const bodies::HullMesh>(hullOf(s));
    const auto id = sim.addBody(hull->massProperties(s.density),
                                bodies::restingUpright(*hull, s.density / 1025.0, s.lat, s.lon, s.heading));
    sim.addBodyForce(id, std::make_shared<bodies::HullForce>(hull, oceanSea));
    if (s.thrust != 0.0) sim.addBodyForce(id, std::make_shared<bodies::Thrust>(s.thrust));
  }

  // Irregular frames through the ABI, one call on the façade: the fixed step
  // makes them the same steps.
  double t = 0.0;
  for (int f = 0; t < 20.0; ++f) {
    t += 0.004 + 0.03 * ((f * 7919) % 13) / 13.0;
    ASSERT_EQ(api().bodiesAdvanceTo(b.h, t, nullptr), GEOCEAN_OK) << lastError();
  }
  sim.advanceTo(t);
  double simTime = 0;
  ASSERT_EQ(api().bodiesTime(b.h, &simTime), GEOCEAN_OK);
  EXPECT_EQ(simTime, sim.time());

  size_t n = 0;
  ASSERT_EQ(api().bodiesGetPoses(b.h, 0, nullptr, 0, &n), GEOCEAN_OK);
  ASSERT_EQ(n, 3u);
  for (int interp = 0; interp < 2; ++interp) {
    std::vector<geocean_body_pose> poses(n);
    ASSERT_EQ(api().bodiesGetPoses(b.h, interp, poses.data(), poses.size(), &n), GEOCEAN_OK) << lastError();
    for (std::size_t i = 0; i < n; ++i) {
      const bodies::Body& ref = sim.bodies()[i];
      const bodies::BodyState s = interp ? sim.drawState(ref.id) : ref.state;
      EXPECT_EQ(poses[i].id, ref.id);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(poses[i].position_ecef_m[k], s.positionEcef[k]) << i << " " << k;
        EXPECT_EQ(poses[i].velocity_ecef_mps[k], ref.state.velocityEcef[k]);
        EXPECT_EQ(poses[i].angular_velocity_body_rps[k], ref.state.angularVelocityBody[k]);
      }
      EXPECT_EQ(poses[i].orientation_wxyz[0], s.orientation.w);
      EXPECT_EQ(poses[i].orientation_wxyz[1], s.orientation.x);
      EXPECT_EQ(poses[i].orientation_wxyz[2], s.orientation.y);
      EXPECT_EQ(poses[i].orientation_wxyz[3], s.orientation.z);
    }
  }
  // The thrusting boat is under way, and all float: centres of mass within
  // a few metres of still water (Hs of a 12 m/s sea is about 3 m).
  std::vector<geocean_body_pose> poses(n);
  ASSERT_EQ(api().bodiesGetPoses(b.h, 0, poses.data(), n, &n), GEOCEAN_OK);
  EXPECT_GT(std::hypot(poses[0].velocity_ecef_mps[0], poses[0].velocity_ecef_mps[1], poses[0].velocity_ecef_mps[2]),
            0.5);
  for (const auto& p : poses) EXPECT_LT(std::abs(p.height_m), 5.0) << p.id;

  // Remove the box: the others keep their ids, the hull of the removed is gone.
  ASSERT_EQ(api().bodiesRemove(b.h, 2), GEOCEAN_OK);
  ASSERT_EQ(api().bodiesCount(b.h, &n), GEOCEAN_OK);
  EXPECT_EQ(n, 2u);
  size_t nv = 0, ni = 0;
  EXPECT_EQ(api().bodiesGetHull(b.h, 2, nullptr, 0, nullptr, 0, &nv, &ni), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("geocean_bodies_get_hull: body id 2: no such body"), std::string::npos) << lastError();
  ASSERT_EQ(api().bodiesGetHull(b.h, 1, nullptr, 0, nullptr, 0, &nv, &ni), GEOCEAN_OK) << lastError();
  const bodies::HullMesh boat = bodies::HullMesh::boat(20.0);
  EXPECT_EQ(nv, boat.vertices().size());
  EXPECT_EQ(ni, boat.indices().size());
  std::vector<double> v(3 * nv);
  std::vector<uint32_t> idx(ni);
  ASSERT_EQ(api().bodiesGetHull(b.h, 1, v.data(), nv, idx.data(), ni, &nv, &ni), GEOCEAN_OK) << lastError();
  EXPECT_EQ(v[3], boat.vertices()[1].x);
  EXPECT_EQ(idx, boat.indices());
}

TEST(CapiBodies, BadInputGetsAStatusAndAMessageNamingTheValue) {
  Ocean oc;
  geocean_bodies* none = reinterpret_cast<geocean_bodies*>(&none);
  EXPECT_EQ(api().bodiesCreate(nullptr, nullptr, &none), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(none, nullptr);
  EXPECT_NE(lastError().find("geocean_bodies_create: ocean is NULL"), std::string::npos) << lastError();
  geocean_bodies_config c;
  ASSERT_EQ(api().bodiesConfigInit(&c), GEOCEAN_OK);
  c.step_s = -0.01;
  EXPECT_EQ(api().bodiesCreate(oc.h, &c, &none), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("config->step_s -0.01 s is not in (0, 0.5]"), std::string::npos) << lastError();
  c.step_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(api().bodiesCreate(oc.h, &c, &none), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("config->step_s nan"), std::string::npos) << lastError();
  ASSERT_EQ(api().bodiesConfigInit(&c), GEOCEAN_OK);
  c.start_s = 3e12;  // beyond the sea's time bound (plugin/waves/TimeRange.h)
  EXPECT_EQ(api().bodiesCreate(oc.h, &c, &none), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("config->start_s 3e+12 s is outside -1e12 .. 1e12 s"), std::string::npos)
      << lastError();
  c = {};
  EXPECT_EQ(api().bodiesCreate(oc.h, &c, &none), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("call geocean_bodies_config_init first"), std::string::npos) << lastError();

  Bodies b(oc.h);
  geocean_body_desc d;
  api().bodyDescInit(&d);
  d.lat_deg = 10.0, d.lon_deg = -30.0;
  auto expectBad = [&](geocean_body_desc bad, const char* text) {
    geocean_body_id id = 99;
    EXPECT_EQ(api().bodiesAdd(b.h, &bad, &id), GEOCEAN_ERROR_INVALID_ARGUMENT) << text;
    EXPECT_EQ(id, 99u);
    EXPECT_NE(lastError().find(text), std::string::npos) << lastError();
  };
  geocean_body_desc x = d;
  x.size_m[0] = -4.0;
  expectBad(x, "desc->size_m[0] -4 m is not finite and > 0");
  x = d, x.hull = GEOCEAN_HULL_BOX, x.size_m[1] = std::numeric_limits<double>::quiet_NaN();
  expectBad(x, "desc->size_m[1] nan m is not finite and > 0");
  x = d, x.hull = 7;
  expectBad(x, "desc->hull 7 is not a geocean_hull");
  x = d, x.density_kg_m3 = 1100.0;
  expectBad(x, "desc->density_kg_m3 1100 kg/m^3 is not in (0, water density 1025)");
  x = d, x.lat_deg = 91.0;
  expectBad(x, "desc->lat_deg 91 is not in [-90, 90]");
  x = d, x.lon_deg = std::numeric_limits<double>::infinity();
  expectBad(x, "desc->lon_deg inf deg is not finite");
  x = d, x.thrust_n = std::numeric_limits<double>::quiet_NaN();
  expectBad(x, "desc->thrust_n nan N is not finite");
  x = d, x.struct_size = 8;
  expectBad(x, "desc->struct_size 8 is smaller than");
  size_t n = 1;
  ASSERT_EQ(api().bodiesCount(b.h, &n), GEOCEAN_OK);
  EXPECT_EQ(n, 0u);  // nothing was added by the refused calls

  EXPECT_EQ(api().bodiesAdd(nullptr, &d, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(api().bodiesAdd(b.h, nullptr, nullptr), GEOCEAN_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(api().bodiesRemove(b.h, 42), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("geocean_bodies_remove: body id 42: no such body"), std::string::npos) << lastError();

  ASSERT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_OK) << lastError();
  ASSERT_EQ(api().bodiesAdvanceTo(b.h, 1.0, nullptr), GEOCEAN_OK) << lastError();
  EXPECT_EQ(api().bodiesAdvanceTo(b.h, 0.5, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("time_s 0.5 is before the simulation time 1"), std::string::npos) << lastError();
  EXPECT_EQ(api().bodiesAdvanceTo(b.h, std::numeric_limits<double>::quiet_NaN(), nullptr),
            GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("time_s nan is not finite"), std::string::npos) << lastError();
  EXPECT_EQ(api().bodiesAdvanceTo(b.h, 1e300, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("geocean_bodies_advance_to: time_s 1e+300 s is outside -1e12 .. 1e12 s"),
            std::string::npos)
      << lastError();
  geocean_body_pose p;
  EXPECT_EQ(api().bodiesGetPoses(b.h, 0, nullptr, 1, &n), GEOCEAN_ERROR_NULL_ARGUMENT);
  ASSERT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_OK);
  EXPECT_EQ(api().bodiesGetPoses(b.h, 0, &p, 1, &n), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("capacity 1 is below the 2 bodies"), std::string::npos) << lastError();
  EXPECT_EQ(n, 2u);
}

TEST(CapiBodies, RefusesABodyOnLandAndFloatsOnTheFlatSeaWithoutASeaState) {
  Ocean oc;
  ASSERT_EQ(api().setDefaultWorld(oc.h), GEOCEAN_OK) << lastError();
  Bodies b(oc.h);
  geocean_body_desc d;
  api().bodyDescInit(&d);
  d.hull = GEOCEAN_HULL_BOX;
  d.size_m[0] = 4.0, d.size_m[1] = 2.0, d.size_m[2] = 1.0;
  d.lat_deg = 48.85, d.lon_deg = 2.35;  // Paris
  EXPECT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("desc->lat_deg, lon_deg 48.85, 2.35 is land, not ocean"),
            std::string::npos)
      << lastError();
  // Mid-Atlantic, no sea state: flat at 0 m; a box of density rho_w / 2
  // floats with its centre of mass at the waterline (draft H/2 = 0.5 m)
  // and stays there (Archimedes; the hydrostatic force is exact on a flat sea).
  d.lat_deg = 30.0, d.lon_deg = -40.0, d.density_kg_m3 = 512.5;
  ASSERT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_OK) << lastError();
  ASSERT_EQ(api().bodiesAdvanceTo(b.h, 30.0, nullptr), GEOCEAN_OK) << lastError();
  geocean_body_pose p;
  size_t n = 0;
  ASSERT_EQ(api().bodiesGetPoses(b.h, 0, &p, 1, &n), GEOCEAN_OK);
  EXPECT_NEAR(p.height_m, 0.0, 1e-6);
  EXPECT_NEAR(p.lat_deg, 30.0, 1e-9);
}

TEST(CapiBodies, PosesMayBeReadWhileAnotherThreadSteps) {
  Ocean oc;
  const geocean_sea_state sea = capiSea();
  ASSERT_EQ(api().setSeaState(oc.h, &sea), GEOCEAN_OK);
  Bodies b(oc.h);
  geocean_body_desc d;
  api().bodyDescInit(&d);
  d.lat_deg = kLat, d.lon_deg = kLon;
  for (int i = 0; i < 4; ++i) {
    d.lon_deg = kLon + 0.001 * i;
    ASSERT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_OK);
  }
  std::thread stepper([&] {
    for (int f = 1; f <= 120; ++f) EXPECT_EQ(api().bodiesAdvanceTo(b.h, f / 30.0, nullptr), GEOCEAN_OK);
  });
  // Reads (and sea queries on the same ocean) meanwhile see whole steps:
  // every pose is finite and its quaternion unit.
  for (int r = 0; r < 200; ++r) {
    geocean_body_pose p[4];
    size_t n = 0;
    ASSERT_EQ(api().bodiesGetPoses(b.h, 1, p, 4, &n), GEOCEAN_OK);
    for (const auto& q : p) {
      const double norm = q.orientation_wxyz[0] * q.orientation_wxyz[0] + q.orientation_wxyz[1] * q.orientation_wxyz[1] +
                          q.orientation_wxyz[2] * q.orientation_wxyz[2] + q.orientation_wxyz[3] * q.orientation_wxyz[3];
      EXPECT_NEAR(norm, 1.0, 1e-9);
      EXPECT_TRUE(std::isfinite(q.height_m));
    }
    double h = 0;
    EXPECT_EQ(api().querySeaSurface(oc.h, 1, &kLat, &kLon, 1.0, &h, nullptr, nullptr), GEOCEAN_OK);
  }
  stepper.join();
  double t = 0;
  ASSERT_EQ(api().bodiesTime(b.h, &t), GEOCEAN_OK);
  EXPECT_EQ(t, 240.0 / 60.0);
}

// ---- ABI 1.6: repulsion between bodies (paper 000 eq. 3-4, F_c) ----

// Two 6 x 3 x 2 m boxes side by side, bow north, their centres 2 m apart
// east-west (beam 3 m: the hulls overlap by 1 m), at rest on the flat sea;
// returns the poses after `seconds`.
std::vector<geocean_body_pose> sideBySide(const geocean_bodies_config* c, double seconds) {
  Ocean oc;
  Bodies b(oc.h, c);
  if (!b.h) return {};
  geocean_body_desc d;
  api().bodyDescInit(&d);
  d.hull = GEOCEAN_HULL_BOX;
  d.size_m[0] = 6.0, d.size_m[1] = 3.0, d.size_m[2] = 2.0;
  d.density_kg_m3 = 600.0;
  const double dLon = 1.0 / (111320.0 * std::cos(kLat * M_PI / 180.0));  // ~1 m of longitude
  for (double side : {-1.0, 1.0}) {
    d.lat_deg = kLat, d.lon_deg = kLon + side * dLon;
    EXPECT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_OK) << lastError();
  }
  EXPECT_EQ(api().bodiesAdvanceTo(b.h, seconds, nullptr), GEOCEAN_OK) << lastError();
  std::vector<geocean_body_pose> p(2);
  size_t n = 0;
  EXPECT_EQ(api().bodiesGetPoses(b.h, 0, p.data(), 2, &n), GEOCEAN_OK) << lastError();
  return p;
}

double apartM(const std::vector<geocean_body_pose>& p) {
  return std::sqrt(std::pow(p[1].position_ecef_m[0] - p[0].position_ecef_m[0], 2) +
                   std::pow(p[1].position_ecef_m[1] - p[0].position_ecef_m[1], 2) +
                   std::pow(p[1].position_ecef_m[2] - p[0].position_ecef_m[2], 2));
}

TEST(CapiBodies, RepulsionPushesOverlappingHullsApartAndKeepsThePairsMomentum) {
  geocean_bodies_config c;
  ASSERT_EQ(api().bodiesConfigInit(&c), GEOCEAN_OK);
  EXPECT_EQ(c.repulsion_stiffness_n_per_m, 0.0);  // off by default
  // Without repulsion the hulls stay where they are (control: the test can fail).
  const double start = apartM(sideBySide(&c, 0.0));
  EXPECT_NEAR(start, 2.0, 0.01);  // 1 m of longitude each way, spherically
  const auto still = sideBySide(&c, 10.0);
  ASSERT_EQ(still.size(), 2u);
  EXPECT_NEAR(apartM(still), start, 1e-6);

  c.repulsion_stiffness_n_per_m = 2e4;
  const auto p = sideBySide(&c, 10.0);
  ASSERT_EQ(p.size(), 2u);
  // Each box is two spheres of radius 1.5 m (ceil(6 / 3)) at x = -1.5, 1.5:
  // the spheres side by side overlap by 1 m, the diagonal pairs not at all.
  // Pushed apart, the boxes end at least a beam (3 m) apart, the water's
  // drag slowing them afterwards.
  EXPECT_GT(apartM(p), 3.0);
  // The spring's energy, k x 1 m^2 x 2 pairs / 2 = 2e4 J, bounds their
  // speed: each box of 21,600 kg at most sqrt(2e4 / 21,600) = 0.96 m/s;
  // at 10 s the water has slowed them below it.
  for (const auto& q : p) {
    const double v = std::sqrt(q.velocity_ecef_mps[0] * q.velocity_ecef_mps[0] +
                               q.velocity_ecef_mps[1] * q.velocity_ecef_mps[1] +
                               q.velocity_ecef_mps[2] * q.velocity_ecef_mps[2]);
    EXPECT_LT(v, 0.96) << q.id;
  }
  // Mirror-image bodies on a flat sea: the repulsion's pair of forces is
  // equal and opposite, and so are the water's forces on the two, so the
  // pair's horizontal momentum stays 0 (their heave is alike, it adds up):
  // the horizontal velocities cancel within 1e-6 of one body's (rounding
  // of the two bodies' ENU frames a metre apart).
  const double la = kLat * M_PI / 180.0, lo = kLon * M_PI / 180.0;
  const double east[3] = {-std::sin(lo), std::cos(lo), 0.0};
  const double north[3] = {-std::sin(la) * std::cos(lo), -std::sin(la) * std::sin(lo), std::cos(la)};
  auto along = [](const double* v, const double* axis) { return v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2]; };
  const double sumE = along(p[0].velocity_ecef_mps, east) + along(p[1].velocity_ecef_mps, east);
  const double sumN = along(p[0].velocity_ecef_mps, north) + along(p[1].velocity_ecef_mps, north);
  const double one = std::abs(along(p[0].velocity_ecef_mps, east));
  EXPECT_GT(one, 0.01) << "they moved apart (east-west)";
  EXPECT_LT(std::abs(sumE), 1e-6 * one) << sumE << " of " << one;
  // North, across the line of centres, nothing pushes: each drifts alike by
  // what the hydrostatics of a hull moving sideways give (measured 3e-5 m/s).
  const double stillN = along(still[0].velocity_ecef_mps, north);
  EXPECT_LT(std::abs(sumN), 1e-3 * one) << sumN << " still " << stillN;

  // A host built against 1.4/1.5 passes the shorter struct: the field it
  // does not have is not read (whatever follows in memory), repulsion off.
  c.struct_size = offsetof(geocean_bodies_config, repulsion_stiffness_n_per_m);
  const auto old = sideBySide(&c, 10.0);
  ASSERT_EQ(old.size(), 2u);
  EXPECT_NEAR(apartM(old), start, 1e-6);

  // Bad stiffness: named.
  Ocean oc;
  geocean_bodies* none = nullptr;
  ASSERT_EQ(api().bodiesConfigInit(&c), GEOCEAN_OK);
  c.repulsion_stiffness_n_per_m = -1.0;
  EXPECT_EQ(api().bodiesCreate(oc.h, &c, &none), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("config->repulsion_stiffness_n_per_m -1 N/m is not finite and >= 0"), std::string::npos)
      << lastError();
  c.repulsion_stiffness_n_per_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(api().bodiesCreate(oc.h, &c, &none), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("config->repulsion_stiffness_n_per_m inf"), std::string::npos) << lastError();
  EXPECT_EQ(none, nullptr);
}


// ---- ABI 1.6: paper 000's contact-point bodies ----

TEST(CapiBodies, ContactPointBodiesAreTheFacadeProxysBitsAndAShortDescIsAHull) {
  Ocean oc;
  const geocean_sea_state sea = capiSea();
  ASSERT_EQ(api().setSeaState(oc.h, &sea), GEOCEAN_OK) << lastError();
  Bodies b(oc.h);
  geocean_body_desc d;
  ASSERT_EQ(api().bodyDescInit(&d), GEOCEAN_OK);
  EXPECT_EQ(d.forces, GEOCEAN_BODY_FORCES_HULL);  // the default
  d.lat_deg = kLat, d.lon_deg = kLon, d.heading_deg = 30.0, d.density_kg_m3 = 450.0;
  d.forces = GEOCEAN_BODY_FORCES_CONTACT_POINTS;
  for (int i = 0; i < 3; ++i) {  // three of one size share one model (one centre query per step)
    d.lon_deg = kLon + 0.001 * i;
    ASSERT_EQ(api().bodiesAdd(b.h, &d, nullptr), GEOCEAN_OK) << lastError();
  }
  // A 1.4/1.5 host's desc ends before `forces`: whatever follows, a hull body.
  geocean_body_desc old = d;
  old.struct_size = offsetof(geocean_body_desc, forces);
  old.lon_deg = kLon + 0.003;
  ASSERT_EQ(api().bodiesAdd(b.h, &old, nullptr), GEOCEAN_OK) << lastError();

  // The façade, as the header documents it.
  geocean::ocean::Ocean core;
  setFacadeSea(core);
  auto oceanSea = std::make_shared<bodies::OceanSea>(core.current());
  bodies::Simulation sim({.stepS = 1.0 / 60.0});
  auto hull = std::make_shared<const bodies::HullMesh>(bodies::HullMesh::boat(20.0));
  const glm::dvec3 ext = hull->maxCorner() - hull->minCorner();
  const double R = std::min(0.5 * ext.y, ext.z), L = ext.x, ratio = 450.0 / 1025.0;
  auto proxy = bodies::ContactPointForce::hollowCylinderProxy(L, R, 4, oceanSea);
  for (int i = 0; i < 3; ++i) {
    bodies::BodyState s = bodies::restingUpright(*hull, ratio, kLat, kLon + 0.001 * i, 30.0);
    s.positionEcef = geocean::geo::toEcef({kLat, kLon + 0.001 * i, -(ratio - 0.5) * 2.0 * R});
    const auto id = sim.addBody(bodies::MassProperties::isotropicFrom(
                                    bodies::MassProperties::hollowCylinder(450.0 * M_PI * R * R * L, 0.8 * R, R, L)),
                                s);
    sim.addBodyForce(id, proxy);
  }
  const auto hid = sim.addBody(hull->massProperties(450.0), bodies::restingUpright(*hull, ratio, kLat, kLon + 0.003, 30.0));
  sim.addBodyForce(hid, std::make_shared<bodies::HullForce>(hull, oceanSea));

  ASSERT_EQ(api().bodiesAdvanceTo(b.h, 20.0, nullptr), GEOCEAN_OK) << lastError();
  sim.advanceTo(20.0);
  std::vector<geocean_body_pose> p(4);
  size_t n = 0;
  ASSERT_EQ(api().bodiesGetPoses(b.h, 0, p.data(), 4, &n), GEOCEAN_OK);
  ASSERT_EQ(n, 4u);
  for (size_t i = 0; i < 4; ++i) {
    const bodies::BodyState& s = sim.bodies()[i].state;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(p[i].position_ecef_m[k], s.positionEcef[k]) << i;
      EXPECT_EQ(p[i].velocity_ecef_mps[k], s.velocityEcef[k]) << i;
    }
    EXPECT_EQ(p[i].orientation_wxyz[0], s.orientation.w) << i;
  }
  // They float (near the sea, moving in the waves), the proxies at their own draft.
  for (size_t i = 0; i < 3; ++i) EXPECT_LT(std::abs(p[i].height_m), 3.0) << i;
  EXPECT_GT(std::abs(p[0].velocity_ecef_mps[0]) + std::abs(p[0].velocity_ecef_mps[1]) +
                std::abs(p[0].velocity_ecef_mps[2]),
            0.01);

  geocean_body_desc bad = d;
  bad.forces = 5;
  EXPECT_EQ(api().bodiesAdd(b.h, &bad, nullptr), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("desc->forces 5 is not a geocean_body_forces"), std::string::npos) << lastError();
}

}  // namespace

// Terrain contact through the ABI (issue 14 item 3 for the viewer's boats):
// the beach of BodyBeach (tests/bodies/test_beach.cpp) given as elevation
// pixels — sea to the west, the ground rising 1 in 10 through the waterline
// at longitude 0 — and a box driven east by its engine. The bodies take
// their terrain patch from the ocean's elevation, so the box grounds in
// about 1 m of water and stops; no hull vertex goes below the ground
// (checked against the closed-form beach, not the patch). Without the
// contact it drives up the beach and over the land.
TEST(CapiBodies, ABoxDrivenAtABeachStopsAtTheShoreWithNoVertexBelowTheGround) {
  constexpr double kMPerDegLon = 111319.49;  // WGS84 equator: a * pi / 180
  const int w = 1000, h = 500;
  const double step = 2e-5;
  std::vector<float> px(std::size_t(w) * h);
  auto ground = [](double eastM) { return std::clamp(eastM / 10.0, -20.0, 10.0); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) px[std::size_t(y) * w + x] = float(ground((-0.01 + (x + 0.5) * step) * kMPerDegLon));
  geocean_grid_placement pl{};
  pl.origin_lon_deg = -0.01, pl.origin_lat_deg = 0.005, pl.lon_step_deg = step, pl.lat_step_deg = -step;
  Ocean oc;
  ASSERT_EQ(api().setElevationPixels(oc.h, px.data(), w, h, &pl), GEOCEAN_OK) << lastError();
  Bodies b(oc.h);
  geocean_body_desc d;
  api().bodyDescInit(&d);
  d.hull = GEOCEAN_HULL_BOX;
  d.size_m[0] = 8.0, d.size_m[1] = 3.0, d.size_m[2] = 2.0;
  d.density_kg_m3 = 500.0, d.lat_deg = 0.0, d.lon_deg = -150.0 / kMPerDegLon, d.heading_deg = 90.0;
  d.thrust_n = 3000.0;
  geocean_body_id id = 0;
  ASSERT_EQ(api().bodiesAdd(b.h, &d, &id), GEOCEAN_OK) << lastError();
  size_t nv = 0, ni = 0;
  ASSERT_EQ(api().bodiesGetHull(b.h, id, nullptr, 0, nullptr, 0, &nv, &ni), GEOCEAN_OK) << lastError();
  std::vector<double> v(3 * nv);
  std::vector<uint32_t> idx(ni);
  ASSERT_EQ(api().bodiesGetHull(b.h, id, v.data(), nv, idx.data(), ni, &nv, &ni), GEOCEAN_OK) << lastError();

  double worstDepth = -1e9, eastmostM = -1e9;
  geocean_body_pose p{};
  for (int k = 1; k <= 320; ++k) {  // 160 s in frames of 0.5 s
    ASSERT_EQ(api().bodiesAdvanceTo(b.h, 0.5 * k, nullptr), GEOCEAN_OK) << lastError();
    size_t n = 0;
    ASSERT_EQ(api().bodiesGetPoses(b.h, 0, &p, 1, &n), GEOCEAN_OK) << lastError();
    const glm::dquat q(p.orientation_wxyz[0], p.orientation_wxyz[1], p.orientation_wxyz[2], p.orientation_wxyz[3]);
    const glm::dvec3 c(p.position_ecef_m[0], p.position_ecef_m[1], p.position_ecef_m[2]);
    for (size_t i = 0; i < nv; ++i) {
      const auto g = geocean::geo::fromEcef(c + q * glm::dvec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
      const double east = g.lonDeg * kMPerDegLon;
      worstDepth = std::max(worstDepth, ground(east) - g.heightM);
      eastmostM = std::max(eastmostM, east);
    }
  }
  const double speed = std::sqrt(p.velocity_ecef_mps[0] * p.velocity_ecef_mps[0] +
                                 p.velocity_ecef_mps[1] * p.velocity_ecef_mps[1] +
                                 p.velocity_ecef_mps[2] * p.velocity_ecef_mps[2]);
  // 1 cm: the patch's ENU heights vs geodetic ones (the ellipsoid's drop is
  // kept; the horizontal shift of a point 10 m up is under 1 mm at 500 m).
  EXPECT_LT(worstDepth, 0.01);
  EXPECT_LT(eastmostM, 0.0) << "the box reached the dry beach";   // stopped in the water
  EXPECT_GT(eastmostM, -30.0) << "the box never reached the shallows";
  EXPECT_LT(speed, 0.05);
}
