// `geocean float`: rigid bodies floating on the ocean façade's sea
// (plugin/bodies: the hull clipped against the very surface `geocean query`
// prints and the renderer draws), one row or JSON object per body per
// output step.
#include "globe/app/Command.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/QueryIo.h"
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/World.h"
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Spawn.h"
#include "plugin/bodies/Terrain.h"
#include "plugin/ocean/Ocean.h"
#include "plugin/ocean/TimeRange.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace geocean::app {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct FloatOptions {
  std::vector<std::string> body, at, density, heading, thrust;
  std::string scene, seconds = "60", dt = "0.0166666666666666667", every = "1", waves = "none", wind = "10",
              windDir = "270", seed = "1", waterDensity = "1025", model = "mesh", format = "text";
  bool noWorld = false;
  LayerOptions layers;
};

struct BodySpec {
  std::string text;  // as given
  bodies::HullMesh hull;
  double density = 0, lat = 0, lon = 0, headingDeg = 0, thrustN = 0;
};

struct Error {
  std::string text;
};

double number(const std::string& what, const std::string& v) {
  const auto x = parseNumber(v);
  if (!x) throw Error{what + " '" + v + "' is not a finite number"};
  return *x;
}

double positive(const std::string& what, const std::string& v, const char* unit) {
  const double x = number(what, v);
  if (!(x > 0.0)) throw Error{what + " " + v + " " + unit + " must be > 0"};
  return x;
}

// box:LxBxH | cylinder:RxH | boat[:LENGTH]
bodies::HullMesh parseHull(const std::string& s) {
  const auto colon = s.find(':');
  const std::string kind = s.substr(0, colon), dims = colon == std::string::npos ? "" : s.substr(colon + 1);
  std::vector<double> v;
  if (!dims.empty()) {
    std::stringstream ss(dims);
    for (std::string tok; std::getline(ss, tok, 'x');) {
      const auto x = parseNumber(tok);
      if (!x) throw Error{"--body '" + s + "': size '" + tok + "' is not a finite number"};
      if (!(*x > 0.0)) throw Error{"--body '" + s + "': size " + tok + " m must be > 0"};
      v.push_back(*x);
    }
  }
  auto need = [&](std::size_t n, const char* form) {
    if (v.size() != n) throw Error{"--body '" + s + "': expected " + form};
  };
  if (kind == "box") {
    need(3, "box:LxBxH (length, beam, height in m)");
    return bodies::HullMesh::box({v[0], v[1], v[2]});
  }
  if (kind == "cylinder") {
    need(2, "cylinder:RxH (radius, height in m; vertical axis)");
    return bodies::HullMesh::cylinder(v[0], v[1]);
  }
  if (kind == "boat") {
    if (dims.empty()) return bodies::HullMesh::boat(20.0);
    need(1, "boat or boat:LENGTH (m)");
    return bodies::HullMesh::boat(v[0]);
  }
  throw Error{"--body '" + s + "': kind '" + kind + "' is not box, cylinder or boat"};
}

// The i-th of a repeated option: one value for every body, or one per body.
std::string pick(const std::vector<std::string>& v, std::size_t i, std::size_t n, const std::string& what,
                 const std::string& fallback) {
  if (v.empty()) return fallback;
  if (v.size() == 1) return v[0];
  if (v.size() != n)
    throw Error{what + " is given " + std::to_string(v.size()) + " times for " + std::to_string(n) +
                " bodies (give it once or once per body)"};
  return v[i];
}

BodySpec makeBody(const std::string& body, const std::string& at, const std::string& density,
                  const std::string& heading, const std::string& thrust) {
  BodySpec b{body, parseHull(body)};
  std::vector<double> ll;
  if (auto e = parseNumberList(at, 2, "--at", ll); !e.empty()) throw Error{e};
  if (auto e = checkLatLon(ll[0], ll[1], "--at"); !e.empty()) throw Error{e};
  b.lat = ll[0], b.lon = ll[1];
  b.density = positive("--density", density, "kg/m^3");
  b.headingDeg = number("--heading", heading);
  b.thrustN = number("--thrust", thrust);
  return b;
}

// Scene file: CSV rows body,density,lat,lon[,heading[,thrust]]; '#' comments and a header are skipped.
std::vector<BodySpec> readScene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error{"--scene '" + path + "' cannot be read"};
  std::vector<BodySpec> out;
  std::string line;
  for (long row = 1; std::getline(in, line); ++row) {
    if (line.empty() || line[0] == '#' || line.rfind("body", 0) == 0) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (f.size() < 4 || f.size() > 6)
      throw Error{"--scene '" + path + "' row " + std::to_string(row) +
                  ": expected body,density,lat,lon[,heading[,thrust]], got '" + line + "'"};
    try {
      out.push_back(makeBody(f[0], f[2] + "," + f[3], f[1], f.size() > 4 ? f[4] : "0", f.size() > 5 ? f[5] : "0"));
    } catch (const Error& e) {
      throw Error{"--scene '" + path + "' row " + std::to_string(row) + ": " + e.text};
    } catch (const std::invalid_argument& e) {
      throw Error{"--scene '" + path + "' row " + std::to_string(row) + ": " + e.what()};
    }
  }
  if (out.empty()) throw Error{"--scene '" + path + "' has no bodies"};
  return out;
}

void appendNumber(std::string& s, double v) {
  if (!std::isfinite(v)) {
    s += "null";
    return;
  }
  char b[32];
  auto r = std::to_chars(b, b + sizeof b, v == 0.0 ? 0.0 : v);  // shortest round trip; no "-0"
  s.append(b, r.ptr);
}

// grounded: the lowest hull vertex within this of the terrain (the contact
// leaves a touching vertex 1e-9 m above it; a floating hull clears it by
// the water under its keel).
constexpr double kGroundedClearanceM = 0.01;

// The terrain under a body for its contact, on the hull's vertices
// (bodies::terrainContactAround: 400 m patch, re-centred near its edge).
std::shared_ptr<bodies::TerrainContact> contactAround(const ocean::Snapshot& snap, const bodies::BodyState& s,
                                                     const bodies::HullMesh& hull) {
  return bodies::terrainContactAround(snap, s, hull.vertices(), bodies::kWetSandFriction);
}

int runFloat(const FloatOptions& o) {
  try {
    if (o.format != "text" && o.format != "json") throw Error{"--format '" + o.format + "' is not text or json"};
    if (o.model != "mesh" && o.model != "points")
      throw Error{"--model '" + o.model + "' is not mesh (hull clipped against the sea) or points (paper 000)"};
    const double seconds = number("--seconds", o.seconds);
    if (!(seconds >= 0.0)) throw Error{"--seconds " + o.seconds + " must be >= 0"};
    // The sea's time bound (plugin/waves/TimeRange.h); 1e300 also overflowed
    // the output count's conversion to long (header only, exit 0).
    if (seconds > waves::kMaxTimeS) throw Error{"--seconds " + o.seconds + " s is above 1e12 s"};
    const double dt = positive("--dt", o.dt, "s");
    if (dt > 0.5) throw Error{"--dt " + o.dt + " s is above 0.5 s"};
    const double every = positive("--every", o.every, "s");
    const double rhoW = positive("--water-density", o.waterDensity, "kg/m^3");
    const double wind = positive("--wind", o.wind, "m/s");
    const double windDir = number("--wind-dir", o.windDir);
    std::uint32_t seed = 0;
    if (auto [p, ec] = std::from_chars(o.seed.data(), o.seed.data() + o.seed.size(), seed);
        o.seed.empty() || ec != std::errc() || p != o.seed.data() + o.seed.size())
      throw Error{"--seed '" + o.seed + "' is not an integer 0 .. 4294967295"};
    const bool noSea = o.waves == "none";
    const auto model = waves::parseModel(o.waves);
    if (!noSea && !model) throw Error{"--waves '" + o.waves + "' is not none, noise, noise-paper, gerstner or fft"};

    std::vector<BodySpec> specs;
    if (!o.scene.empty()) {
      if (!o.body.empty() || !o.at.empty()) throw Error{"give either --scene or --body/--at, not both"};
      specs = readScene(o.scene);
    } else {
      if (o.body.empty()) throw Error{"give --body (box:LxBxH, cylinder:RxH or boat[:LENGTH]) or --scene FILE"};
      if (o.at.size() != o.body.size())
        throw Error{"--at is given " + std::to_string(o.at.size()) + " times for " + std::to_string(o.body.size()) +
                    " --body (one LAT,LON per body)"};
      if (o.density.empty()) throw Error{"--density KG_M3 is required"};
      const std::size_t n = o.body.size();
      for (std::size_t i = 0; i < n; ++i)
        specs.push_back(makeBody(o.body[i], o.at[i], pick(o.density, i, n, "--density", ""),
                                 pick(o.heading, i, n, "--heading", "0"), pick(o.thrust, i, n, "--thrust", "0")));
    }
    for (const auto& b : specs)
      if (!(b.density < rhoW))
        throw Error{"--density " + std::to_string(b.density) + " kg/m^3 of '" + b.text +
                    "' is not below the water density " + std::to_string(rhoW) + ": it would sink"};

    ocean::Ocean oc;
    if (o.noWorld && (!o.layers.masks.empty() || !o.layers.elevations.empty() || o.layers.noDefaultWorld))
      throw Error{"--no-world takes no --mask, --elevation or --no-default-world (it means no rasters at all)"};
    if (!o.noWorld) {
      try {
        applyLayers(oc, o.layers, raster::OpenOptions{});
      } catch (const raster::RasterError& e) {
        std::fprintf(stderr, "geocean float: %s (use --no-world for open sea everywhere)\n", e.what());
        return kExitDataError;
      }
    }
    if (!noSea) {
      waves::SeaState sea;
      sea.windSpeedMps = wind;
      sea.windFromDeg = windDir;
      sea.seed = seed;
      sea.anchorLatDeg = specs[0].lat;
      sea.anchorLonDeg = specs[0].lon;
      oc.setSeaState(*model, sea);
    }
    const auto snap = oc.current();
    if (snap->landSea) {
      for (const auto& b : specs) {
        ocean::Surface c;
        snap->classify(&b.lat, &b.lon, 1, &c);
        if (c != ocean::Surface::Ocean)
          throw Error{"--at " + std::to_string(b.lat) + "," + std::to_string(b.lon) + " of '" + b.text + "' is " +
                      ocean::toString(c) + ", not ocean"};
      }
    }
    auto sea = std::make_shared<bodies::OceanSea>(snap);

    bodies::Simulation sim({.stepS = dt});
    std::vector<bodies::BodyId> ids;
    std::vector<std::shared_ptr<bodies::HullForce>> hulls;
    // Per body: its terrain contact (null without an elevation) and where it sits in body.constraints.
    std::vector<std::shared_ptr<bodies::TerrainContact>> contacts;
    const bool terrain = snap->elevation != nullptr;
    bodies::HullForceOptions hopt;
    hopt.water.densityKgM3 = rhoW;
    for (const auto& b : specs) {
      const glm::dvec3 ext = b.hull.maxCorner() - b.hull.minCorner();
      auto hull = std::make_shared<bodies::HullForce>(std::make_shared<bodies::HullMesh>(b.hull), sea, hopt);
      // Upright at its still-water draft, bow along the heading.
      const bodies::BodyState s = bodies::restingUpright(b.hull, b.density / rhoW, b.lat, b.lon, b.headingDeg);
      bodies::BodyId id;
      if (o.model == "mesh") {
        id = sim.addBody(b.hull.massProperties(b.density), s);
        sim.addBodyForce(id, hull);
      } else {
        // Paper 000: hollow-cylinder proxy of the hull's length and beam, isotropic inertia (eq. 2).
        const double R = 0.5 * std::min(ext.y, ext.z * 2.0), L = ext.x;
        const double m = b.density * std::numbers::pi * R * R * L;
        id = sim.addBody(bodies::MassProperties::isotropicFrom(bodies::MassProperties::hollowCylinder(m, 0.8 * R, R, L)),
                         s);
        sim.addBodyForce(id, bodies::ContactPointForce::hollowCylinderProxy(L, R, 4, sea, {.water = hopt.water}));
      }
      if (b.thrustN != 0.0) sim.addBodyForce(id, std::make_shared<bodies::Thrust>(b.thrustN));
      ids.push_back(id);
      hulls.push_back(hull);
      contacts.push_back(terrain ? contactAround(*snap, s, b.hull) : nullptr);
      if (contacts.back()) sim.addBodyConstraint(id, contacts.back());
    }
    if (specs.size() > 1) {
      // Paper 000's F_c, as the C ABI's: spheres along each hull (Hydro.h).
      auto rep = std::make_shared<bodies::Repulsion>(sim, 1.0, 1e5);
      for (std::size_t i = 0; i < ids.size(); ++i)
        rep->setSpheres(ids[i], bodies::Repulsion::spheresAlongHull(specs[i].hull));
      sim.addForceModel(rep);
    }

    std::string out;
    if (o.format == "text") out += "t_s,id,lat,lon,height_m,draft_m,roll_deg,pitch_deg,heading_deg,speed_mps,grounded\n";
    const long nOut = static_cast<long>(std::floor(seconds / every + 1e-9));
    for (long k = 0; k <= nOut; ++k) {
      const double t = k * every;
      // At most a second at a time, so the terrain patches can follow the bodies
      // (the fixed step gives the same steps whatever the chunks).
      while (true) {
        for (std::size_t i = 0; i < ids.size(); ++i) {
          bodies::Body& b = sim.body(ids[i]);
          if (!contacts[i] || !bodies::nearPatchEdge(*contacts[i], b.state)) continue;
          auto c = contactAround(*snap, b.state, specs[i].hull);
          std::replace(b.constraints.begin(), b.constraints.end(),
                       std::shared_ptr<const bodies::StepConstraint>(contacts[i]),
                       std::shared_ptr<const bodies::StepConstraint>(c));
          contacts[i] = c;
        }
        if (sim.time() + 1.0 >= t) break;
        sim.advanceTo(sim.time() + 1.0);
      }
      sim.advanceTo(t);
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const bodies::Body& b = sim.body(ids[i]);
        const bodies::StepContext ctx = sim.context(b.state);
        const bodies::HullEvaluation e = hulls[i]->evaluate(b.state, b.mass, ctx);
        const glm::dvec3 bx = ctx.enu.toLocal(b.state.bodyToEcef({1, 0, 0}));
        const glm::dvec3 by = ctx.enu.toLocal(b.state.bodyToEcef({0, 1, 0}));
        const glm::dvec3 bz = ctx.enu.toLocal(b.state.bodyToEcef({0, 0, 1}));
        const glm::dvec3 v = ctx.enu.toLocal(b.state.velocityEcef);
        double heading = std::atan2(bx.x, bx.y) / kDeg;
        if (heading < 0) heading += 360.0;
        // Touching the terrain its contact stops it on (a hull vertex on the patch).
        const bool grounded = contacts[i] && contacts[i]->clearanceM(b.state) <= kGroundedClearanceM;
        const double vals[] = {ctx.geodetic.latDeg,
                               ctx.geodetic.lonDeg,
                               ctx.geodetic.heightM,
                               e.keelDepthM,
                               std::atan2(by.z, bz.z) / kDeg,
                               std::asin(std::clamp(bx.z, -1.0, 1.0)) / kDeg,
                               heading,
                               std::hypot(v.x, v.y)};
        if (o.format == "json") {
          static const char* keys[] = {"\"lat\":", "\"lon\":", "\"height_m\":", "\"draft_m\":",
                                       "\"roll_deg\":", "\"pitch_deg\":", "\"heading_deg\":", "\"speed_mps\":"};
          out += "{\"t_s\":";
          appendNumber(out, sim.time());
          out += ",\"id\":" + std::to_string(ids[i]);
          for (int j = 0; j < 8; ++j) {
            out += ',';
            out += keys[j];
            appendNumber(out, vals[j]);
          }
          out += grounded ? ",\"grounded\":true}\n" : ",\"grounded\":false}\n";
        } else {
          appendNumber(out, sim.time());
          out += ',' + std::to_string(ids[i]);
          for (double x : vals) {
            out += ',';
            appendNumber(out, x);
          }
          out += grounded ? ",true\n" : ",false\n";
        }
      }
      if (out.size() > (1u << 16)) {
        std::fwrite(out.data(), 1, out.size(), stdout);
        out.clear();
      }
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    return kExitOk;
  } catch (const Error& e) {
    std::fprintf(stderr, "geocean float: %s\n", e.text.c_str());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "geocean float: %s\n", e.what());
    return kExitBadInput;
  }
}

const Register kRegister{
    {"float", "Rigid bodies floating on the sea (hull clipped against the queried surface), one row per body per step",
     [](CLI::App& sub) -> std::function<int()> {
       auto o = std::make_shared<FloatOptions>();
       sub.add_option("--body", o->body, "box:LxBxH | cylinder:RxH | boat[:LENGTH] (m); repeat for more bodies");
       sub.add_option("--at", o->at, "LAT,LON of the body (one per --body)");
       sub.add_option("--density", o->density, "body density kg/m^3 (once, or once per body)");
       sub.add_option("--heading", o->heading, "bow direction, degrees clockwise from north (default 0)");
       sub.add_option("--thrust", o->thrust, "engine force along the hull, N (default 0)");
       sub.add_option("--scene", o->scene, "CSV rows body,density,lat,lon[,heading[,thrust]] instead of --body/--at");
       sub.add_option("--seconds", o->seconds, "simulated time, s (default 60)");
       sub.add_option("--dt", o->dt, "fixed step, s (default 1/60)");
       sub.add_option("--every", o->every, "output interval, s (default 1)");
       sub.add_option("--waves", o->waves, "none (flat sea, default), noise, noise-paper (paper 002), gerstner, fft");
       sub.add_option("--wind", o->wind, "wind speed at 19.5 m, m/s (default 10)");
       sub.add_option("--wind-dir", o->windDir, "direction the wind blows FROM, deg (default 270)");
       sub.add_option("--seed", o->seed, "random seed of the sea (default 1)");
       sub.add_option("--water-density", o->waterDensity, "kg/m^3 (default 1025)");
       sub.add_option("--model", o->model, "mesh (hull clipped against the sea, default) or points (paper 000 eq. 3-4)");
       sub.add_option("--format", o->format, "text (CSV) or json (one object per line)");
       sub.add_flag("--no-world", o->noWorld, "no rasters: open sea everywhere, no terrain, grounded always false");
       addLayerOptions(sub, o->layers);
       return [o] { return runFloat(*o); };
     }}};

}  // namespace
}  // namespace geocean::app
