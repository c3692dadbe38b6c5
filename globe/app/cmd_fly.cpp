// `geocean fly`: a scripted flight from orbit to 2 m above the sea, rendered
// headless to PNG frames plus a CSV of per-frame timings.
#include "globe/app/Command.h"
#include "globe/app/BoatOptions.h"
#include "globe/app/DrawnScene.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/SeaOptions.h"
#include "globe/render/CliParse.h"
#include "globe/render/Flight.h"
#include "globe/render/Session.h"
#if GEOCEAN_WITH_HUD
#include "globe/gl/Hud.h"
#endif
#include "globe/host/OceanLayer.h"
#include "plugin/ocean/TimeRange.h"

#include <epoxy/gl.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace geocean::app {
namespace {

struct FlyArgs {
  std::string to = "36.0,-5.6";
  std::string from;  // LAT,LON,ALT; default: 40 degrees west of the target, 20,000 km up
  std::string size = "1280x720";
  std::string out = "out/flight";
  std::string sun;
  int frames = 120;
  int repeat = 0;  // untimed draws of each frame before its timed one
  double fps = 30.0;
  double heading = 90.0;
  bool noImages = false;
  bool reference = false;
  bool hud = false;
  DrawnSceneOptions scene;
};

int runFly(const FlyArgs& a) {
  camera::ViewPose base;
  render::FlightPlan plan;
  std::vector<double> sunAzEl = {135.0, 35.0};
  try {
    render::parseSize(a.size, base);
    const auto to = render::parseNumbers(a.to, 2, "--to LAT,LON");
    if (std::abs(to[0]) > 90.0) throw render::ArgError("--to: latitude " + std::to_string(to[0]) + " is outside [-90, 90]");
    plan.toLatDeg = to[0];
    plan.toLonDeg = to[1];
    plan.fromLatDeg = to[0];
    plan.fromLonDeg = to[1] - 40.0;
    if (!a.from.empty()) {
      const auto f = render::parseNumbers(a.from, 3, "--from LAT,LON,ALT");
      if (std::abs(f[0]) > 90.0 || f[2] <= 2.0)
        throw render::ArgError("--from: latitude must be in [-90, 90] and altitude above 2 m");
      plan.fromLatDeg = f[0], plan.fromLonDeg = f[1], plan.fromAltM = f[2];
    }
    if (a.frames < 2 || a.frames > 1000000) throw render::ArgError("--frames: " + std::to_string(a.frames) + " must be in 2..1000000");
    if (!(a.fps > 0.0)) throw render::ArgError("--fps must be positive");
    // The last frame's time within the sea's bound (plugin/waves/TimeRange.h).
    if (!(a.frames / a.fps <= waves::kMaxTimeS)) {
      char b[160];
      std::snprintf(b, sizeof b, "--fps %g: the last frame's time %g s is above 1e12 s", a.fps, a.frames / a.fps);
      throw render::ArgError(b);
    }
    if (!a.sun.empty()) sunAzEl = render::parseNumbers(a.sun, 2, "--sun AZ,EL");
    // The sea's options before the GL context (the plugin would say it by its field names).
    if (auto e = checkDrawnScene(a.scene); !e.empty()) throw render::ArgError(e);
  } catch (const render::ArgError& e) {
    std::fprintf(stderr, "geocean fly: %s\n", e.what());
    return kExitBadInput;
  }
  double windMps = 0.0;
  if (const int rc = resolveWind("fly", a.scene.wind, windMps); rc != kExitOk) return rc;
  plan.headingDeg = a.heading;
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) {
    std::fprintf(stderr, "geocean fly: cannot create output directory '%s': %s\n", a.out.c_str(), ec.message().c_str());
    return kExitBadInput;
  }
  const std::string csvPath = a.out + "/timings.csv";
  std::ofstream csv(csvPath);
  if (!csv) {
    std::fprintf(stderr, "geocean fly: cannot write '%s'\n", csvPath.c_str());
    return kExitBadInput;
  }
  std::vector<world::LayerSource> sources;
  world::WorldData data;
  if (const int rc = loadDrawnWorld("fly", a.scene.layers, sources, data); rc != kExitOk) return rc;
  render::Session s;
  try {
    s = render::Session::headless(std::move(data), base.width, base.height);
  } catch (const gl::ShaderError&) {
    throw;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "geocean fly: %s\n", e.what());
    return kExitNoDisplay;
  }
  std::shared_ptr<host::PluginOceanLayer> ocean;
  if (const int rc = addDrawnOcean("fly", a.scene, windMps, *s.renderer, sources, ocean); rc != kExitOk) return rc;
  std::shared_ptr<host::PluginBoats> boats;
  if (const int rc = addBoats("fly", a.scene.boats, *s.renderer, ocean, plan.toLatDeg, plan.toLonDeg, boats); rc != kExitOk)
    return rc;
#if GEOCEAN_WITH_HUD
  std::unique_ptr<gl::Hud> hud;  // declared after the session: destroyed while its context lives
  if (a.hud) {
    std::string err;
    hud = gl::Hud::create(err);
    if (!hud) {
      std::fprintf(stderr, "geocean fly: --hud: %s\n", err.c_str());
      return kExitNoDisplay;
    }
  }
#else
  if (a.hud) {
    std::fprintf(stderr, "geocean fly: --hud: this geocean was built with GEOCEAN_BUILD_VIEWER=OFF (no HUD)\n");
    return kExitBadInput;
  }
#endif
  csv << "frame,time_s,lat,lon,alt_m,pitch_deg,tiles,sky_ms,terrain_ms,ocean_ms,total_ms";
  if (a.reference) csv << ",bare_terrain_ms,bare_ocean_ms,bare_total_ms";
  // The sea's mirrored pass and the sun's shadow map, inside ocean_ms (0 on frames that reuse or skip them).
  csv << ",reflection_ms,shadow_ms\n";
  // The sun stays where it is over the target: the flight descends into daylight.
  const glm::dvec3 sun = render::sunFromLocal(plan.toLatDeg, plan.toLonDeg, sunAzEl[0], sunAzEl[1]);
  for (int f = 0; f < a.frames; ++f) {
    const double sProgress = double(f) / double(a.frames - 1);
    camera::ViewPose pose = render::flightPose(plan, sProgress, base);
    render::FrameSettings fs;
    fs.timeS = f / a.fps;
    if (boats && a.scene.boats.follow > 0) {  // the chase camera instead of the flight
      boats->update(fs.timeS);
      pose = boats->chase(std::size_t(a.scene.boats.follow - 1), pose);
    }
    fs.sunEcef = sun;
    fs.timed = true;
    applyDrawnScene(a.scene, fs);
    // The same frame again first: llvmpipe compiles a program variant on its
    // first draw, so only the last draw is the frame's steady cost.
    for (int r = 0; r < a.repeat; ++r) s.render(pose, fs);
    const auto t = s.render(pose, fs);
#if GEOCEAN_WITH_HUD
    if (hud) {  // drawn after the timed passes, so timings.csv is the same with or without it
      gl::HudValues hv;
      hv.latDeg = pose.latDeg, hv.lonDeg = pose.lonDeg, hv.altM = pose.altM;
      hv.fps = t.totalMs > 0.0 ? 1000.0 / t.totalMs : 0.0;  // of this frame's render alone
      if (ocean) {
        double lat = pose.latDeg, lon = pose.lonDeg;
        hv.seaKnown = ocean->plugin().api().querySeaSurface(ocean->ocean(), 1, &lat, &lon, fs.timeS,
                                                            &hv.seaHeightM, nullptr, nullptr) == GEOCEAN_OK;
      }
      glViewport(0, 0, pose.width, pose.height);
      hud->draw(pose.width, pose.height, 1.0 / a.fps, hv);
    }
#endif
    if (!a.noImages) {
      char name[64];
      std::snprintf(name, sizeof name, "/frame_%05d.png", f);
      gl::writePng(a.out + name, s.image());
    }
    char row[256];
    std::snprintf(row, sizeof row, "%d,%.4f,%.7f,%.7f,%.3f,%.2f,%d,%.3f,%.3f,%.3f,%.3f", f, fs.timeS, pose.latDeg,
                  pose.lonDeg, pose.altM, pose.pitchDeg, t.terrain.tilesDrawn, t.skyMs, t.terrainMs, t.layersMs,
                  t.totalMs);
    csv << row;
    if (a.reference) {
      fs.bare = true;
      const auto b = s.render(pose, fs);
      std::snprintf(row, sizeof row, ",%.3f,%.3f,%.3f", b.terrainMs, b.layersMs, b.totalMs);
      csv << row;
    }
    std::snprintf(row, sizeof row, ",%.3f,%.3f\n", t.reflectionMs, t.shadowMs);
    csv << row;
  }
  std::fprintf(stderr, "geocean fly: wrote %d frames and %s\n", a.frames, csvPath.c_str());
  return csv ? kExitOk : kExitDataError;
}

const Register reg{{"fly", "Render a scripted flight from orbit to 2 m above the sea (PNG frames + timings CSV)",
                    [](CLI::App& sub) -> std::function<int()> {
                      auto a = std::make_shared<FlyArgs>();
                      sub.add_option("--to", a->to, "LAT,LON of the sea point to fly to");
                      sub.add_option("--from", a->from, "LAT,LON,ALT start (default: 40 deg west, 20,000 km up)");
                      sub.add_option("--frames", a->frames, "number of frames");
                      sub.add_option("--fps", a->fps, "simulation frames per second (time step)");
                      sub.add_option("--size", a->size, "WIDTHxHEIGHT in pixels");
                      sub.add_option("--out", a->out, "output directory");
                      sub.add_option("--heading", a->heading, "view heading at the end, degrees");
                      sub.add_option("--sun", a->sun, "AZ,EL of the sun at the target, degrees");
                      sub.add_flag("--no-images", a->noImages, "time the frames without writing PNGs");
                      sub.add_option("--repeat", a->repeat,
                                     "draw each frame N more times before the timed draw (steady-state timings: "
                                     "no first-draw shader compiles)")
                          ->check(CLI::Range(0, 100));
                      sub.add_flag("--reference", a->reference,
                                   "also draw each frame with trivial shaders (the ratio reference)");
                      sub.add_flag("--hud", a->hud,
                                   "draw the viewer's HUD (lat, lon, altitude, render fps, sea height) in the frames");
                      addDrawnSceneOptions(sub, a->scene, DrawnCommand::Fly);
                      return [a] { return runFly(*a); };
                    }}};

}  // namespace
}  // namespace geocean::app
