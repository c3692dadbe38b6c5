// `geocean render`: one frame, headless (EGL), to a PNG.
#include "globe/app/Command.h"
#include "globe/app/BoatOptions.h"
#include "globe/app/DrawnScene.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/QueryIo.h"
#include "globe/app/SeaOptions.h"
#include "globe/render/CliParse.h"
#include "globe/render/Session.h"
#include "globe/host/OceanLayer.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace geocean::app {
namespace {

struct RenderArgs {
  std::string camera = "0,-150,20000000,0,-90";
  std::string size = "1280x720";
  std::string out;
  std::string sun;  // AZ,EL at the camera's nadir
  double timeS = 0.0;
  double fovDeg = 45.0;
  double exaggeration = 1.0;
  DrawnSceneOptions scene;
};

int runRender(const RenderArgs& a) {
  camera::ViewPose pose;
  glm::dvec3 sun;
  try {
    render::parseCamera(a.camera, pose);
    render::parseSize(a.size, pose);
    if (!(a.fovDeg > 1.0 && a.fovDeg < 170.0))
      throw render::ArgError("--fov: " + std::to_string(a.fovDeg) + " must be in (1, 170) degrees");
    if (!(a.exaggeration >= 0.0 && a.exaggeration <= 100.0))
      throw render::ArgError("--exaggeration: " + std::to_string(a.exaggeration) + " must be in [0, 100]");
    if (!std::isfinite(a.timeS)) throw render::ArgError("--time " + std::to_string(a.timeS) + " is not a finite number");
    if (auto e = checkTime(a.timeS, "--time"); !e.empty()) throw render::ArgError(e);
    pose.fovYDeg = a.fovDeg;
    sun = render::sunForView(pose);
    if (!a.sun.empty()) {
      const auto v = render::parseNumbers(a.sun, 2, "--sun AZ,EL");
      sun = render::sunForView(pose, v[0], v[1]);
    }
    // The sea's options before the GL context (the plugin would say it by its field names).
    if (auto e = checkDrawnScene(a.scene); !e.empty()) throw render::ArgError(e);
  } catch (const render::ArgError& e) {
    std::fprintf(stderr, "geocean render: %s\n", e.what());
    return kExitBadInput;
  }
  double windMps = 0.0;
  if (const int rc = resolveWind("render", a.scene.wind, windMps); rc != kExitOk) return rc;
  std::vector<world::LayerSource> sources;
  world::WorldData data;
  if (const int rc = loadDrawnWorld("render", a.scene.layers, sources, data); rc != kExitOk) return rc;
  render::TerrainOptions terrain;
  terrain.exaggeration = a.exaggeration;
  terrain.waitForTiles = true;  // one picture: the streamed tiles it needs, not their ancestors
  render::Session s;
  try {
    s = render::Session::headless(std::move(data), pose.width, pose.height, terrain);
  } catch (const gl::ShaderError&) {
    throw;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "geocean render: %s\n", e.what());
    return kExitNoDisplay;
  }
  std::shared_ptr<host::PluginOceanLayer> ocean;
  if (const int rc = addDrawnOcean("render", a.scene, windMps, *s.renderer, sources, ocean); rc != kExitOk) return rc;
  if (ocean) ocean->setCompleteTiles(true);  // as terrain.waitForTiles
  std::shared_ptr<host::PluginBoats> boats;
  double targetLat = 0, targetLon = 0;
  host::viewTarget(pose, targetLat, targetLon);
  if (const int rc = addBoats("render", a.scene.boats, *s.renderer, ocean, targetLat, targetLon, boats); rc != kExitOk)
    return rc;
  if (boats && a.scene.boats.follow > 0) {
    boats->update(a.timeS);
    pose = boats->chase(std::size_t(a.scene.boats.follow - 1), pose);
  }
  render::FrameSettings fs;
  fs.timeS = a.timeS;
  fs.sunEcef = sun;
  applyDrawnScene(a.scene, fs);
  const auto t = s.render(pose, fs);
  gl::writePng(a.out, s.image());
  std::fprintf(stderr, "geocean render: wrote %s (%dx%d, %d terrain tiles, %.1f ms)\n", a.out.c_str(), pose.width,
               pose.height, t.terrain.tilesDrawn, t.totalMs);
  return kExitOk;
}

const Register reg{{"render", "Render one frame headless to a PNG",
                    [](CLI::App& sub) -> std::function<int()> {
                      auto a = std::make_shared<RenderArgs>();
                      sub.add_option("--camera", a->camera,
                                     "LAT,LON,ALT,HEADING,PITCH: degrees, metres above the ellipsoid; "
                                     "pitch -90 looks straight down")
                          ->allow_extra_args(false);
                      sub.add_option("--time", a->timeS, "simulation time, seconds");
                      sub.add_option("--size", a->size, "WIDTHxHEIGHT in pixels");
                      sub.add_option("--out", a->out, "output PNG")->required();
                      sub.add_option("--fov", a->fovDeg, "vertical field of view, degrees");
                      sub.add_option("--sun", a->sun, "AZ,EL of the sun at the camera's nadir, degrees");
                      sub.add_option("--exaggeration", a->exaggeration, "vertical exaggeration of the terrain");
                      addDrawnSceneOptions(sub, a->scene, DrawnCommand::Render);
                      return [a] { return runRender(*a); };
                    }}};

}  // namespace
}  // namespace geocean::app
