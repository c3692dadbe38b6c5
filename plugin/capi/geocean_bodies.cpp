// The C ABI of floating bodies (ABI 1.4; repulsion 1.6) over plugin/bodies: a Simulation
// whose hulls float on the ocean's current snapshot (bodies::OceanSea, the
// surface the queries give and the draw draws). Each entry point checks its
// C arguments and runs inside guard() (CapiSupport.h); one mutex per
// geocean_bodies serialises its calls, so poses are read between steps.
#include "geocean/geocean_ocean.h"
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Spawn.h"
#include "plugin/bodies/Terrain.h"
#include "plugin/capi/CapiSupport.h"
#include "plugin/render/OceanRenderer.h"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstddef>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <string>

using namespace geocean::capi;
namespace bodies = geocean::bodies;

namespace {

// The ocean's sea as it is at each step: advance_to swaps in the current
// snapshot (a new sea state or new rasters) before it steps, so the hull
// forces always read one consistent snapshot per step.
class LiveSea final : public bodies::SeaSurface {
 public:
  void refresh(std::shared_ptr<const Snapshot> s) {
    if (s == snap_) return;
    snap_ = std::move(s);
    sea_ = std::make_shared<bodies::OceanSea>(snap_);
  }
  void sample(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n, bool velocities,
              bodies::SeaSample* out) const override {
    sea_->sample(latDeg, lonDeg, tS, n, velocities, out);
  }
  double decayWaveNumberPerM() const override { return sea_->decayWaveNumberPerM(); }
  void sampleSlopes(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n,
                    bodies::SeaSample* out) const override {
    sea_->sampleSlopes(latDeg, lonDeg, tS, n, out);
  }
  double shortestWavelengthM() const override { return sea_->shortestWavelengthM(); }
  const Snapshot& snapshot() const { return *snap_; }

 private:
  std::shared_ptr<const Snapshot> snap_;
  std::shared_ptr<const bodies::OceanSea> sea_;
};

// Shortest round-trip form: the value the host passed, as it wrote it.
std::string num(double v) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

void requireFiniteField(double v, const char* name, const char* unit) {
  if (!std::isfinite(v)) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(name) + " " + num(v) + " " + unit + " is not finite");
}

bodies::HullMesh hullOf(const geocean_body_desc& d) {
  const char* names[3] = {"desc->size_m[0]", "desc->size_m[1]", "desc->size_m[2]"};
  auto need = [&](int n) {
    for (int i = 0; i < n; ++i)
      if (!(d.size_m[i] > 0.0) || !std::isfinite(d.size_m[i]))
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(names[i]) + " " + num(d.size_m[i]) + " m is not finite and > 0");
  };
  switch (d.hull) {
    case GEOCEAN_HULL_BOX: need(3); return bodies::HullMesh::box({d.size_m[0], d.size_m[1], d.size_m[2]});
    case GEOCEAN_HULL_CYLINDER: need(2); return bodies::HullMesh::cylinder(d.size_m[0], d.size_m[1]);
    case GEOCEAN_HULL_BOAT: need(1); return bodies::HullMesh::boat(d.size_m[0]);
  }
  fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->hull " + std::to_string(d.hull) + " is not a geocean_hull");
}

}  // namespace

struct geocean_bodies {
  geocean_ocean* ocean = nullptr;
  double waterDensity = 1025.0;
  mutable std::mutex mutex;  // every call on this handle
  std::shared_ptr<LiveSea> sea = std::make_shared<LiveSea>();
  bodies::Simulation sim;
  std::map<bodies::BodyId, std::shared_ptr<const bodies::HullMesh>> hulls;
  std::shared_ptr<bodies::Repulsion> repulsion;  // ABI 1.6; null: off
  // ABI 1.6 contact-point models, one per proxy size: bodies that share one
  // have their centres queried together each step (ContactPointForce::beginStep).
  std::map<std::pair<double, double>, std::shared_ptr<const bodies::ContactPointForce>> proxies;
  // Terrain contact on each body's hull vertices, from the ocean's
  // elevation (bodies::terrainContactAround: a patch that follows the body),
  // as `geocean float` does; `contactElevation` is the elevation they were cut from.
  std::map<bodies::BodyId, std::shared_ptr<const bodies::TerrainContact>> contacts;
  const void* contactElevation = nullptr;

  geocean_bodies(geocean_ocean* o, const bodies::SimulationConfig& c, double rhoW, double repulsionNpm)
      : ocean(o), waterDensity(rhoW), sim(c) {
    sea->refresh(o->current());
    if (repulsionNpm > 0.0) {
      // Every body gets its hull's spheres when added; the default radius is never used.
      repulsion = std::make_shared<bodies::Repulsion>(sim, 1.0, repulsionNpm);
      sim.addForceModel(repulsion);
    }
    std::lock_guard lock(o->bodySetsMutex);
    o->bodySets.push_back(this);
  }
  ~geocean_bodies() {
    std::lock_guard lock(ocean->bodySetsMutex);
    std::erase(ocean->bodySets, this);
  }
  geocean_bodies(const geocean_bodies&) = delete;
  geocean_bodies& operator=(const geocean_bodies&) = delete;
};

namespace geocean::capi {

void appendWakes(const geocean_bodies& b, std::vector<ocean_render::Wake>& out) {
  std::lock_guard lock(b.mutex);
  const auto& all = b.sim.bodies();
  if (all.empty()) return;
  std::vector<double> lat(all.size()), lon(all.size()), t(all.size(), b.sim.time());
  std::vector<bodies::BodyState> states;
  for (std::size_t i = 0; i < all.size(); ++i) {
    states.push_back(b.sim.drawState(all[i].id));
    states.back().velocityEcef = all[i].state.velocityEcef;
    const geocean::geo::Geodetic g = geocean::geo::fromEcef(states.back().positionEcef);
    lat[i] = g.latDeg, lon[i] = g.lonDeg;
  }
  // Speed through the water: the surface particle's own velocity off (a
  // boat heaving and surging with the waves makes no wake).
  std::vector<bodies::SeaSample> water(all.size());
  b.sea->sample(lat.data(), lon.data(), t.data(), all.size(), true, water.data());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto hull = b.hulls.find(all[i].id);
    if (hull == b.hulls.end() || hull->second->vertices().empty()) continue;
    glm::dvec2 lo(hull->second->vertices()[0]), hi = lo;
    for (const glm::dvec3& v : hull->second->vertices()) lo = glm::min(lo, glm::dvec2(v)), hi = glm::max(hi, glm::dvec2(v));
    const bodies::BodyState& s = states[i];
    const geocean::geo::EnuFrame f = geocean::geo::enuFrame({lat[i], lon[i], 0.0});
    glm::dvec3 waterV(0.0);
    if (std::isfinite(water[i].heightM))  // no water velocity on land
      waterV = f.toEcef({water[i].horizontalVelocityEnMps.x, water[i].horizontalVelocityEnMps.y, 0.0});
    ocean_render::Wake w;
    w.centreEcef = s.positionEcef + s.orientation * glm::dvec3(0.5 * (lo + hi), 0.0);
    w.bowEcef = s.orientation * glm::dvec3(1.0, 0.0, 0.0);
    w.velocityEcef = s.velocityEcef - waterV;
    w.halfLengthM = 0.5 * (hi.x - lo.x), w.halfBeamM = 0.5 * (hi.y - lo.y);
    out.push_back(w);
  }
}

}  // namespace geocean::capi

namespace {

// (Re)cuts body id's terrain contact around its pose; none where the
// snapshot has no elevation, or no data under the patch (the body then
// floats without touching anything, as on the open sea).
void placeContact(geocean_bodies& b, bodies::BodyId id) {
  bodies::Body& body = b.sim.body(id);
  auto& cs = body.constraints;
  if (auto old = b.contacts.find(id); old != b.contacts.end()) {
    cs.erase(std::remove(cs.begin(), cs.end(), std::shared_ptr<const bodies::StepConstraint>(old->second)), cs.end());
    b.contacts.erase(old);
  }
  const Snapshot& snap = b.sea->snapshot();
  if (!snap.elevation) return;
  try {
    auto c = bodies::terrainContactAround(snap, body.state, b.hulls.at(id)->vertices(), bodies::kWetSandFriction);
    b.contacts[id] = c;
    b.sim.addBodyConstraint(id, c);
  } catch (const std::invalid_argument&) {
  }
}

geocean_body_pose poseOf(bodies::BodyId id, const bodies::BodyState& s) {
  geocean_body_pose p{};
  p.id = id;
  for (int k = 0; k < 3; ++k) {
    p.position_ecef_m[k] = s.positionEcef[k];
    p.velocity_ecef_mps[k] = s.velocityEcef[k];
    p.angular_velocity_body_rps[k] = s.angularVelocityBody[k];
  }
  p.orientation_wxyz[0] = s.orientation.w;
  p.orientation_wxyz[1] = s.orientation.x;
  p.orientation_wxyz[2] = s.orientation.y;
  p.orientation_wxyz[3] = s.orientation.z;
  const geocean::geo::Geodetic g = geocean::geo::fromEcef(s.positionEcef);
  p.lat_deg = g.latDeg;
  p.lon_deg = g.lonDeg;
  p.height_m = g.heightM;
  return p;
}

}  // namespace

extern "C" {

GEOCEAN_API geocean_status geocean_bodies_config_init(geocean_bodies_config* config) {
  return guard("geocean_bodies_config_init", [&] {
    requireNonNull(config, "config");
    *config = geocean_bodies_config{};
    config->struct_size = sizeof(geocean_bodies_config);
    config->step_s = 1.0 / 60.0;
    config->start_s = 0.0;
    config->water_density_kg_m3 = 1025.0;
  });
}

GEOCEAN_API geocean_status geocean_body_desc_init(geocean_body_desc* desc) {
  return guard("geocean_body_desc_init", [&] {
    requireNonNull(desc, "desc");
    *desc = geocean_body_desc{};
    desc->struct_size = sizeof(geocean_body_desc);
    desc->hull = GEOCEAN_HULL_BOAT;
    desc->size_m[0] = 20.0;
    desc->density_kg_m3 = 500.0;
  });
}

GEOCEAN_API geocean_status geocean_bodies_create(geocean_ocean* ocean, const geocean_bodies_config* config,
                                                 geocean_bodies** out) {
  return guard("geocean_bodies_create", [&] {
    requireNonNull(out, "out");
    *out = nullptr;
    requireNonNull(ocean, "ocean");
    geocean_bodies_config c{};
    geocean_bodies_config_init(&c);
    if (config) {
      // A 1.4/1.5 host's struct ends before the 1.6 field: read what it has.
      constexpr std::size_t kSize14 = offsetof(geocean_bodies_config, repulsion_stiffness_n_per_m);
      if (config->struct_size < kSize14)
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "config->struct_size " + std::to_string(config->struct_size) +
                                                 " is smaller than " + std::to_string(kSize14) +
                                                 ": call geocean_bodies_config_init first");
      std::memcpy(&c, config, std::min<std::size_t>(config->struct_size, sizeof c));
      c.struct_size = sizeof c;
    }
    if (!(c.step_s > 0.0 && c.step_s <= 0.5))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "config->step_s " + num(c.step_s) + " s is not in (0, 0.5]");
    requireFiniteField(c.start_s, "config->start_s", "s");
    requireTimeInRange(c.start_s, "config->start_s");
    if (!(c.water_density_kg_m3 > 0.0) || !std::isfinite(c.water_density_kg_m3))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
           "config->water_density_kg_m3 " + num(c.water_density_kg_m3) + " kg/m^3 is not finite and > 0");
    if (!(c.repulsion_stiffness_n_per_m >= 0.0) || !std::isfinite(c.repulsion_stiffness_n_per_m))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "config->repulsion_stiffness_n_per_m " +
                                               num(c.repulsion_stiffness_n_per_m) + " N/m is not finite and >= 0");
    *out = new geocean_bodies(ocean, bodies::SimulationConfig{.stepS = c.step_s, .startS = c.start_s},
                              c.water_density_kg_m3, c.repulsion_stiffness_n_per_m);
  });
}

GEOCEAN_API void geocean_bodies_destroy(geocean_bodies* b) {
  guard("geocean_bodies_destroy", [&] { delete b; });
}

GEOCEAN_API geocean_status geocean_bodies_add(geocean_bodies* b, const geocean_body_desc* desc,
                                              geocean_body_id* out_id) {
  return guard("geocean_bodies_add", [&] {
    requireNonNull(b, "bodies");
    requireNonNull(desc, "desc");
    constexpr std::size_t kSize14 = offsetof(geocean_body_desc, forces);  // a 1.4/1.5 host's struct
    if (desc->struct_size < kSize14)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->struct_size " + std::to_string(desc->struct_size) +
                                               " is smaller than " + std::to_string(kSize14) +
                                               ": call geocean_body_desc_init first");
    geocean_body_desc d{};
    geocean_body_desc_init(&d);
    std::memcpy(&d, desc, std::min<std::size_t>(desc->struct_size, sizeof d));
    if (d.forces != GEOCEAN_BODY_FORCES_HULL && d.forces != GEOCEAN_BODY_FORCES_CONTACT_POINTS)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->forces " + std::to_string(d.forces) + " is not a geocean_body_forces");
    requireFiniteField(d.lat_deg, "desc->lat_deg", "deg");
    requireFiniteField(d.lon_deg, "desc->lon_deg", "deg");
    if (std::abs(d.lat_deg) > 90.0) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->lat_deg " + num(d.lat_deg) + " is not in [-90, 90]");
    if (std::abs(d.lon_deg) > 360.0)
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->lon_deg " + num(d.lon_deg) + " is not in [-360, 360]");
    requireFiniteField(d.heading_deg, "desc->heading_deg", "deg");
    requireFiniteField(d.thrust_n, "desc->thrust_n", "N");
    auto hull = std::make_shared<const bodies::HullMesh>(hullOf(d));
    std::lock_guard lock(b->mutex);
    if (!(d.density_kg_m3 > 0.0 && d.density_kg_m3 < b->waterDensity))
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->density_kg_m3 " + num(d.density_kg_m3) +
                                               " kg/m^3 is not in (0, water density " + num(b->waterDensity) + ")");
    b->sea->refresh(b->ocean->current());
    const Snapshot& snap = b->sea->snapshot();
    if (snap.landSea) {
      geocean::ocean::Surface c;
      snap.classify(&d.lat_deg, &d.lon_deg, 1, &c);
      if (c != geocean::ocean::Surface::Ocean)
        fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "desc->lat_deg, lon_deg " + num(d.lat_deg) + ", " + num(d.lon_deg) +
                                                 " is " + geocean::ocean::toString(c) + ", not ocean");
    }
    const double ratio = d.density_kg_m3 / b->waterDensity;
    bodies::BodyState s = bodies::restingUpright(*hull, ratio, d.lat_deg, d.lon_deg, d.heading_deg);
    bodies::BodyId id = 0;
    if (d.forces == GEOCEAN_BODY_FORCES_HULL) {
      bodies::HullForceOptions hopt;
      hopt.water.densityKgM3 = b->waterDensity;
      id = b->sim.addBody(hull->massProperties(d.density_kg_m3), s);
      b->sim.addBodyForce(id, std::make_shared<bodies::HullForce>(hull, b->sea, hopt));
    } else {
      // As `geocean float --model points`: the proxy of the hull's length and beam.
      const glm::dvec3 ext = hull->maxCorner() - hull->minCorner();
      const double R = 0.5 * std::min(ext.y, ext.z * 2.0), L = ext.x;
      const double m = d.density_kg_m3 * std::numbers::pi * R * R * L;
      // Its own draft: every column's submerged fraction is the density ratio,
      // the points' plane (at the centre of mass) (ratio - 1/2) 2R under water.
      s.positionEcef = geocean::geo::toEcef({d.lat_deg, d.lon_deg, -(ratio - 0.5) * 2.0 * R});
      auto& proxy = b->proxies[{L, R}];
      if (!proxy)
        proxy = bodies::ContactPointForce::hollowCylinderProxy(L, R, 4, b->sea, {.water = {.densityKgM3 = b->waterDensity}});
      id = b->sim.addBody(bodies::MassProperties::isotropicFrom(bodies::MassProperties::hollowCylinder(m, 0.8 * R, R, L)), s);
      b->sim.addBodyForce(id, proxy);
    }
    if (d.thrust_n != 0.0) b->sim.addBodyForce(id, std::make_shared<bodies::Thrust>(d.thrust_n));
    if (b->repulsion) b->repulsion->setSpheres(id, bodies::Repulsion::spheresAlongHull(*hull));
    b->hulls[id] = hull;
    b->contactElevation = snap.elevation.get();
    placeContact(*b, id);
    if (out_id) *out_id = id;
  });
}

GEOCEAN_API geocean_status geocean_bodies_remove(geocean_bodies* b, geocean_body_id id) {
  return guard("geocean_bodies_remove", [&] {
    requireNonNull(b, "bodies");
    std::lock_guard lock(b->mutex);
    if (!b->hulls.count(id)) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "body id " + std::to_string(id) + ": no such body");
    b->sim.removeBody(id);
    b->hulls.erase(id);
    b->contacts.erase(id);
    if (b->repulsion) b->repulsion->forgetBody(id);
  });
}

GEOCEAN_API geocean_status geocean_bodies_count(const geocean_bodies* b, size_t* out_count) {
  return guard("geocean_bodies_count", [&] {
    requireNonNull(b, "bodies");
    requireNonNull(out_count, "out_count");
    std::lock_guard lock(b->mutex);
    *out_count = b->sim.bodies().size();
  });
}

GEOCEAN_API geocean_status geocean_bodies_advance_to(geocean_bodies* b, double time_s, int64_t* out_steps) {
  return guard("geocean_bodies_advance_to", [&] {
    requireNonNull(b, "bodies");
    std::lock_guard lock(b->mutex);
    if (!std::isfinite(time_s)) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "time_s " + num(time_s) + " is not finite");
    requireTimeInRange(time_s, "time_s");
    if (time_s < b->sim.time())
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
           "time_s " + num(time_s) + " is before the simulation time " + num(b->sim.time()));
    b->sea->refresh(b->ocean->current());
    if (b->sea->snapshot().elevation.get() != b->contactElevation) {  // new rasters: cut every contact anew
      b->contactElevation = b->sea->snapshot().elevation.get();
      for (const auto& [hid, hull] : b->hulls) placeContact(*b, hid);
    }
    std::int64_t n = 0;
    // At most a second at a time while any body touches terrain, so each
    // patch can follow its body (the fixed step gives the same steps
    // whatever the chunks).
    while (!b->contacts.empty()) {
      for (const auto& [hid, hull] : b->hulls)
        if (auto c = b->contacts.find(hid); c != b->contacts.end() && bodies::nearPatchEdge(*c->second, b->sim.body(hid).state))
          placeContact(*b, hid);
      if (b->sim.time() + 1.0 >= time_s) break;
      n += b->sim.advanceTo(b->sim.time() + 1.0);
    }
    n += b->sim.advanceTo(time_s);
    if (out_steps) *out_steps = n;
  });
}

GEOCEAN_API geocean_status geocean_bodies_time(const geocean_bodies* b, double* out_time_s) {
  return guard("geocean_bodies_time", [&] {
    requireNonNull(b, "bodies");
    requireNonNull(out_time_s, "out_time_s");
    std::lock_guard lock(b->mutex);
    *out_time_s = b->sim.time();
  });
}

GEOCEAN_API geocean_status geocean_bodies_get_poses(const geocean_bodies* b, int32_t interpolate,
                                                    geocean_body_pose* out, size_t capacity, size_t* out_count) {
  return guard("geocean_bodies_get_poses", [&] {
    requireNonNull(b, "bodies");
    requireNonNull(out_count, "out_count");
    if (capacity > 0) requireNonNull(out, "out");
    std::lock_guard lock(b->mutex);
    const auto& all = b->sim.bodies();
    *out_count = all.size();
    if (capacity == 0 && !out) return;
    if (capacity < all.size())
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT,
           "capacity " + std::to_string(capacity) + " is below the " + std::to_string(all.size()) + " bodies");
    for (std::size_t i = 0; i < all.size(); ++i) {
      bodies::BodyState s = interpolate ? b->sim.drawState(all[i].id) : all[i].state;
      if (interpolate) {
        s.velocityEcef = all[i].state.velocityEcef;
        s.angularVelocityBody = all[i].state.angularVelocityBody;
      }
      out[i] = poseOf(all[i].id, s);
    }
  });
}

GEOCEAN_API geocean_status geocean_bodies_get_hull(const geocean_bodies* b, geocean_body_id id,
                                                   double* vertices_xyz_m, size_t vertex_capacity,
                                                   uint32_t* indices, size_t index_capacity,
                                                   size_t* out_vertex_count, size_t* out_index_count) {
  return guard("geocean_bodies_get_hull", [&] {
    requireNonNull(b, "bodies");
    requireNonNull(out_vertex_count, "out_vertex_count");
    requireNonNull(out_index_count, "out_index_count");
    if (vertex_capacity > 0) requireNonNull(vertices_xyz_m, "vertices_xyz_m");
    if (index_capacity > 0) requireNonNull(indices, "indices");
    std::lock_guard lock(b->mutex);
    const auto it = b->hulls.find(id);
    if (it == b->hulls.end()) fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "body id " + std::to_string(id) + ": no such body");
    const bodies::HullMesh& h = *it->second;
    *out_vertex_count = h.vertices().size();
    *out_index_count = h.indices().size();
    if (vertex_capacity == 0 && index_capacity == 0 && !vertices_xyz_m && !indices) return;
    if (vertex_capacity < h.vertices().size() || index_capacity < h.indices().size())
      fail(GEOCEAN_ERROR_INVALID_ARGUMENT, "capacities " + std::to_string(vertex_capacity) + " vertices, " +
                                               std::to_string(index_capacity) + " indices are below the hull's " +
                                               std::to_string(h.vertices().size()) + ", " +
                                               std::to_string(h.indices().size()));
    for (std::size_t i = 0; i < h.vertices().size(); ++i)
      for (int k = 0; k < 3; ++k) vertices_xyz_m[3 * i + k] = h.vertices()[i][k];
    std::copy(h.indices().begin(), h.indices().end(), indices);
  });
}

}  // extern "C"
