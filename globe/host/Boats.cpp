#include "globe/host/Boats.h"

#include "globe/geo/Ellipsoid.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace geocean::host {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// splitmix64: a fixed, portable stream for a seed (std distributions are not).
struct Stream {
  std::uint64_t s;
  double next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
};

}  // namespace

void viewTarget(const camera::ViewPose& pose, double& latDeg, double& lonDeg) {
  const camera::Camera cam = camera::Camera::fromView(pose);
  const geo::RayHit hit = geo::intersectEllipsoid(cam.eyeEcef(), cam.forward());
  if (hit.hit && hit.tFirst() >= 0.0) {
    const geo::Geodetic g = geo::fromEcef(cam.eyeEcef() + hit.tFirst() * cam.forward());
    latDeg = g.latDeg, lonDeg = g.lonDeg;
  } else {
    latDeg = pose.latDeg, lonDeg = pose.lonDeg;
  }
}

std::shared_ptr<PluginBoats> PluginBoats::spawn(std::shared_ptr<PluginOceanLayer> ocean, int n, double latDeg,
                                                double lonDeg, std::uint32_t seed, std::string& error) {
  const OceanApi& a = ocean->plugin().api();
  if (!a.bodiesCreate) {
    error = ocean->plugin().path() + ": plugin ABI below 1.4 has no floating bodies (--boats)";
    return nullptr;
  }
  if (n < 1 || n > 10000) {
    error = "--boats " + std::to_string(n) + " is not in 1..10000";
    return nullptr;
  }
  std::shared_ptr<PluginBoats> b(new PluginBoats);
  b->ocean_ = ocean;
  // Boats that meet push apart (ABI 1.6 repulsion): 2e5 N/m stops two 30 m
  // boats (~81 t) closing at 5 m/s within 2.3 m, less than their spheres'
  // 4.3 m radius, and keeps sqrt(2k/m) dt at 0.15 for the 12 m ones at 1/60 s.
  geocean_bodies_config config;
  a.bodiesConfigInit(&config);
  config.repulsion_stiffness_n_per_m = 2e5;
  if (a.bodiesCreate(ocean->ocean(), &config, &b->bodies_) != GEOCEAN_OK) {
    error = a.lastError();
    return nullptr;
  }
  b->renderer_ = std::make_unique<render::BoatRenderer>();
  static const glm::vec3 palette[] = {{0.85f, 0.85f, 0.82f}, {0.75f, 0.12f, 0.10f}, {0.10f, 0.22f, 0.55f},
                                      {0.90f, 0.70f, 0.10f}, {0.15f, 0.45f, 0.25f}};
  Stream rng{seed};
  const double spacingM = 110.0;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const geo::EnuFrame f = geo::enuFrame(geo::Geodetic{latDeg, lonDeg, 0.0});
  // Sunflower points until n boats are on water (at most 4 n tries).
  for (int k = 0; int(b->lengths_.size()) < n && k < 4 * n; ++k) {
    const double r = spacingM * std::sqrt(k + 0.5), phi = k * golden;
    const geo::Geodetic g = geo::fromEcef(f.originEcef + f.toEcef(glm::dvec3(r * std::cos(phi), r * std::sin(phi), 0.0)));
    const double L = 12.0 + 18.0 * rng.next(), heading = 360.0 * rng.next(), engine = rng.next();
    const int color = int(rng.next() * 5.0) % 5;
    uint8_t cls = 0;
    // Without rasters the query is NOT_READY and every point is ocean (the ABI's rule).
    if (a.queryClass(ocean->ocean(), 1, &g.latDeg, &g.lonDeg, &cls) == GEOCEAN_OK && cls != GEOCEAN_SURFACE_OCEAN)
      continue;
    geocean_body_desc d;
    a.bodyDescInit(&d);
    d.hull = GEOCEAN_HULL_BOAT;
    d.size_m[0] = L;
    d.density_kg_m3 = 450.0;
    d.lat_deg = g.latDeg, d.lon_deg = g.lonDeg, d.heading_deg = heading;
    // An engine pushing about 0.05 g on the displacement (L^3 / 150 m^3 of
    // this hull at 450 kg/m^3), for a third of the boats none.
    d.thrust_n = engine < 0.33 ? 0.0 : 0.4 * L * L * L;
    geocean_body_id id = 0;
    if (a.bodiesAdd(b->bodies_, &d, &id) != GEOCEAN_OK) {
      error = a.lastError();
      return nullptr;
    }
    size_t nv = 0, ni = 0;
    if (a.bodiesGetHull(b->bodies_, id, nullptr, 0, nullptr, 0, &nv, &ni) != GEOCEAN_OK) {
      error = a.lastError();
      return nullptr;
    }
    std::vector<double> v(3 * nv);
    std::vector<uint32_t> idx(ni);
    if (a.bodiesGetHull(b->bodies_, id, v.data(), nv, idx.data(), ni, &nv, &ni) != GEOCEAN_OK) {
      error = a.lastError();
      return nullptr;
    }
    b->meshes_.push_back(b->renderer_->addMesh(v, idx));
    b->lengths_.push_back(L);
    b->colors_.push_back(palette[color]);
  }
  if (b->lengths_.empty()) {
    error = "--boats: no water within " + std::to_string(int(spacingM * std::sqrt(4.0 * n))) + " m of " +
            std::to_string(latDeg) + ", " + std::to_string(lonDeg);
    return nullptr;
  }
  b->update(0.0);
  return b;
}

PluginBoats::~PluginBoats() {
  if (bodies_) ocean_->plugin().api().bodiesDestroy(bodies_);
}

void PluginBoats::update(double timeS) {
  const OceanApi& a = ocean_->plugin().api();
  double now = 0.0;
  if (a.bodiesTime(bodies_, &now) != GEOCEAN_OK) throw std::runtime_error(a.lastError());
  // A frame earlier than the simulation (a flight restarting) keeps the poses.
  if (timeS >= now && a.bodiesAdvanceTo(bodies_, timeS, nullptr) != GEOCEAN_OK)
    throw std::runtime_error(std::string("ocean plugin: ") + a.lastError());
  size_t n = lengths_.size();
  poses_.resize(n);
  if (a.bodiesGetPoses(bodies_, 1, poses_.data(), poses_.size(), &n) != GEOCEAN_OK)
    throw std::runtime_error(std::string("ocean plugin: ") + a.lastError());
  std::vector<render::BoatInstance> inst(n);
  for (std::size_t i = 0; i < n; ++i) {
    const geocean_body_pose& p = poses_[i];
    inst[i].mesh = meshes_[i];
    inst[i].positionEcef = {p.position_ecef_m[0], p.position_ecef_m[1], p.position_ecef_m[2]};
    inst[i].orientation = glm::dquat(p.orientation_wxyz[0], p.orientation_wxyz[1], p.orientation_wxyz[2],
                                     p.orientation_wxyz[3]);
    inst[i].color = colors_[i];
  }
  renderer_->setInstances(std::move(inst));
}

void PluginBoats::draw(const camera::Camera& cam, const camera::Lighting& light, bool, const camera::Camera* mirroredFrom) {
  renderer_->draw(cam, light, mirroredFrom);
}

camera::ViewPose PluginBoats::chase(std::size_t i, const camera::ViewPose& base) const {
  const geocean_body_pose& p = poses_.at(i);
  const glm::dvec3 com(p.position_ecef_m[0], p.position_ecef_m[1], p.position_ecef_m[2]);
  const glm::dquat q(p.orientation_wxyz[0], p.orientation_wxyz[1], p.orientation_wxyz[2], p.orientation_wxyz[3]);
  const geo::EnuFrame f = geo::enuFrame(geo::Geodetic{p.lat_deg, p.lon_deg, 0.0});
  glm::dvec3 bow = f.toLocal(q * glm::dvec3(1.0, 0.0, 0.0));
  bow.z = 0.0;
  bow = glm::length(bow) > 1e-6 ? glm::normalize(bow) : glm::dvec3(0.0, 1.0, 0.0);
  const double L = lengths_[i], back = 3.0 * L, up = 1.2 * L;
  const glm::dvec3 eye = com + f.toEcef(-back * bow) + up * f.up;
  const geo::Geodetic g = geo::fromEcef(eye);
  camera::ViewPose v = base;
  v.latDeg = g.latDeg, v.lonDeg = g.lonDeg, v.altM = g.heightM;
  v.headingDeg = std::fmod(std::atan2(bow.x, bow.y) / kDeg + 360.0, 360.0);
  v.pitchDeg = -std::atan2(up, back) / kDeg;
  v.rollDeg = 0.0;
  return v;
}

}  // namespace geocean::host
