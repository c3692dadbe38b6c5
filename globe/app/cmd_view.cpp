// `geocean view`: the interactive globe in a GLFW window with a HUD (lat,
// lon, altitude, fps, sea height under the camera). Without a display it
// says so and points to the headless commands (exit code 4). --frames N
// runs a scripted number of frames and exits (tests under Xvfb, memory).
#include "globe/app/Command.h"
#include "globe/app/BoatOptions.h"
#include "globe/app/CoastOption.h"
#include "globe/app/DrawnScene.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/QueryIo.h"
#include "globe/app/SeaOptions.h"
#include "globe/host/OceanLayer.h"
#include "globe/render/CliParse.h"
#include "globe/render/Flight.h"
#include "globe/gl/Framebuffer.h"
#include "globe/gl/GlDebug.h"
#include "globe/render/GlobeRenderer.h"
#include "globe/gl/Hud.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <malloc.h>
#include <unistd.h>
#include <utility>

namespace geocean::app {
namespace {

// The shader warm-up's descent (runView): enough poses to pass every
// altitude where a new program or state first draws (orbit, the paged
// coast from ~30 km, the near bands below 500 m, the sea at 2 m), small.
constexpr int kWarmUpFrames = 12;
constexpr int kWarmUpSize[2] = {96, 54};

struct ViewArgs {
  std::string flyTo;  // LAT,LON
  std::string camera;  // LAT,LON,ALT,HEADING,PITCH: the first view (as render's)
  std::string size = "1280x720";
  double flightS = 30.0;   // interactive --fly-to duration
  int frames = 0;          // > 0: draw this many frames, then exit
  int flightFrames = 0;    // with --frames: the flight lasts this many frames, then restarts (0: all of them)
  std::string screenshot;  // PNG of the last of --frames
  std::string statsCsv;    // per-frame CSV (position, sea, fps, resident memory)
  bool noWarmUp = false;   // no off-screen descent before the first frame
  bool noHud = false;
  bool panel = false;  // the control panel open from the start (P toggles it)
  std::string sun;     // AZ,EL at the camera's nadir (default 135,40)
  double timeS = 0.0;  // simulation time of the first frame
  DrawnSceneOptions scene;  // as render and fly
};

// Height of the drawn sea surface above the ellipsoid exactly under the
// camera, from the plugin's own query (the same surface geocean_draw
// displaces). NaN on land or lakes. False if the query fails.
bool seaHeightUnder(const host::PluginOceanLayer& ocean, double latDeg, double lonDeg, double timeS, double& heightM) {
  uint8_t cls = 0;
  if (ocean.plugin().api().querySeaSurface(ocean.ocean(), 1, &latDeg, &lonDeg, timeS, &heightM, nullptr, &cls) !=
      GEOCEAN_OK)
    return false;
  return true;
}

// The HUD's sea-state line: the panel's model and wind (with its Beaufort
// force) and, where the camera is over the ocean, the plugin's significant
// wave height and peak period there.
std::string seaStateLine(const host::PluginOceanLayer& ocean, const gl::PanelState& p, double latDeg, double lonDeg) {
  // Short lines, as the HUD's others: the panel stays in a corner of small windows.
  char b[160];
  int n = std::snprintf(b, sizeof b, "%s  Bft %d\nwind %4.1f from %03.0f\xC2\xB0", gl::kPanelWaveModels[p.waveModel],
                        gl::beaufortOf(p.windMps), p.windMps, p.windFromDeg);
  const auto& api = ocean.plugin().api();
  double hs = std::nan(""), tp = std::nan("");
  if (api.querySeaState && api.querySeaState(ocean.ocean(), 1, &latDeg, &lonDeg, &hs, &tp, nullptr, nullptr) == GEOCEAN_OK &&
      std::isfinite(hs) && n > 0 && n < int(sizeof b))
    std::snprintf(b + n, sizeof b - size_t(n), "\nHs %.2f m Tp %.1f s", hs, tp);
  return b;
}

// Google Earth / Cesium style navigation: left-drag turns the globe under the
// cursor, the wheel zooms by a fraction of the altitude, right-drag or the
// arrow keys tilt and turn, WASD moves at a speed proportional to altitude,
// R (or Home) goes back to orbit.
struct Controller {
  camera::ViewPose pose;
  double lastX = 0, lastY = 0;
  bool left = false, right = false;
  double wheel = 0;

  void drag(double dx, double dy) {
    // Degrees of arc per pixel at the altitude (small-angle view of the ground).
    const double metresPerPx = pose.altM * 2.0 * std::tan(0.5 * pose.fovYDeg * 3.14159265 / 180.0) / pose.height;
    const double degPerPx = std::min(1.0, metresPerPx / 111320.0);
    const double h = pose.headingDeg * 3.14159265 / 180.0;
    const double east = -dx * std::cos(h) - dy * std::sin(h), north = dy * std::cos(h) - dx * std::sin(h);
    pose.latDeg = std::clamp(pose.latDeg + north * degPerPx, -89.9, 89.9);
    pose.lonDeg = geo::wrapLonDeg(pose.lonDeg + east * degPerPx / std::max(0.05, std::cos(pose.latDeg * 3.14159265 / 180.0)));
  }
  void look(double dx, double dy) {
    pose.headingDeg = std::fmod(pose.headingDeg + dx * 0.2 + 360.0, 360.0);
    pose.pitchDeg = std::clamp(pose.pitchDeg - dy * 0.2, -90.0, 10.0);
  }
  void zoom(double steps) { pose.altM = std::clamp(pose.altM * std::pow(0.85, steps), 1.0, 5.0e7); }
  void move(double fwd, double side, double dt) {
    const double speed = std::max(pose.altM, 1.0) * dt;  // one altitude per second
    const double h = pose.headingDeg * 3.14159265 / 180.0;
    const double n = (fwd * std::cos(h) - side * std::sin(h)) * speed, e = (fwd * std::sin(h) + side * std::cos(h)) * speed;
    pose.latDeg = std::clamp(pose.latDeg + n / 111320.0, -89.9, 89.9);
    pose.lonDeg = geo::wrapLonDeg(pose.lonDeg + e / (111320.0 * std::max(0.05, std::cos(pose.latDeg * 3.14159265 / 180.0))));
  }
  void orbit() {
    pose.altM = 2.0e7;
    pose.pitchDeg = -90.0;
    pose.headingDeg = 0.0;
  }
};

// Resident set size of this process in kB (/proc/self/statm), 0 if unknown.
long residentKb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long pages = 0, resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  return n == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1024) : 0;
}

// glibc's malloc, in kB (mallinfo2): bytes in use (arena chunks plus
// mmapped blocks) and bytes held from the system (arenas plus mmapped
// blocks; freed memory an arena keeps is still resident). Tells a leak (in
// use grows) from allocator retention (only held grows).
struct HeapKb {
  long inUse = 0, held = 0;
};
HeapKb heapKb() {
  const struct mallinfo2 m = mallinfo2();
  return {long((m.uordblks + m.hblkhd) / 1024), long((m.arena + m.hblkhd) / 1024)};
}

// The window's back buffer (what is about to be shown: globe + HUD) as an image.
gl::Image readWindow(int w, int h) {
  gl::Image img;
  img.width = w, img.height = h;
  std::vector<std::uint8_t> rows(size_t(w) * size_t(h) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  img.rgba.resize(rows.size());
  for (int y = 0; y < h; ++y)  // GL's first row is the bottom one
    std::copy_n(rows.data() + size_t(h - 1 - y) * size_t(w) * 4, size_t(w) * 4, img.rgba.data() + size_t(y) * size_t(w) * 4);
  for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;  // the window has no meaningful alpha
  return img;
}

int runView(const ViewArgs& a) {
  Controller c;
  render::FlightPlan plan;
  bool flying = false;
  std::vector<double> sunAzEl = {135.0, 40.0};
  try {
    render::parseSize(a.size, c.pose);
    c.pose.latDeg = 20.0, c.pose.lonDeg = -30.0, c.pose.altM = 2.0e7;
    if (!a.camera.empty()) {
      if (!a.flyTo.empty()) throw render::ArgError("--camera and --fly-to: give one (both set the first view)");
      render::parseCamera(a.camera, c.pose);
    }
    if (!a.flyTo.empty()) {
      const auto v = render::parseNumbers(a.flyTo, 2, "--fly-to LAT,LON");
      if (auto e = checkLatLon(v[0], v[1], "--fly-to"); !e.empty()) throw render::ArgError(e);
      plan.fromLatDeg = v[0], plan.fromLonDeg = v[1] - 40.0;
      plan.toLatDeg = v[0], plan.toLonDeg = v[1];
      plan.headingDeg = 90.0;
      flying = true;
    }
    if (a.frames < 0) throw render::ArgError("--frames: " + std::to_string(a.frames) + " must be >= 0 (0: until closed)");
    if (!(a.flightS > 0.0) || !std::isfinite(a.flightS))
      throw render::ArgError("--flight-seconds: " + std::to_string(a.flightS) + " must be positive");
    if (!a.screenshot.empty() && a.frames == 0) throw render::ArgError("--screenshot needs --frames N (the frame it shows)");
    if (a.flightFrames < 0 || a.flightFrames == 1 || (a.flightFrames > 0 && a.frames == 0))
      throw render::ArgError("--flight-frames: " + std::to_string(a.flightFrames) +
                             " must be >= 2 and needs --frames N (0: the flight takes all N frames)");
    if (!a.sun.empty()) sunAzEl = render::parseNumbers(a.sun, 2, "--sun AZ,EL");
    if (auto e = checkTime(a.timeS, "--time"); !e.empty()) throw render::ArgError(e);
    // The last scripted frame's time too (1/30 s per frame).
    if (auto e = checkTime(a.timeS + a.frames / 30.0, "--time + --frames / 30"); !e.empty()) throw render::ArgError(e);
    // Bad input is exit 2 with or without a display: every check that needs
    // no window comes before the display's (--beaufort: resolveWind below).
    if (auto e = checkDrawnScene(a.scene); !e.empty()) throw render::ArgError(e);
  } catch (const render::ArgError& e) {
    std::fprintf(stderr, "geocean view: %s\n", e.what());
    return kExitBadInput;
  }
  double windMps = 0.0;
  if (const int rc = resolveWind("view", a.scene.wind, windMps); rc != kExitOk) return rc;
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    std::fprintf(stderr,
                 "geocean view: no display (DISPLAY is not set). Render headless instead:\n"
                 "  geocean render --camera 0,-150,20000000,0,-90 --out earth.png\n"
                 "  geocean fly --to 36,-5.6 --frames 120 --out out/flight\n");
    return kExitNoDisplay;
  }
  std::ofstream stats;
  if (!a.statsCsv.empty()) {
    stats.open(a.statsCsv);
    if (!stats) {
      std::fprintf(stderr, "geocean view: cannot write --stats '%s'\n", a.statsCsv.c_str());
      return kExitBadInput;
    }
    stats << "frame,wall_s,lat,lon,alt_m,sea_height_m,fps,rss_kb,heap_in_use_kb,heap_held_kb,tiles,tiles_built\n";
  }
  std::vector<world::LayerSource> sources;
  world::WorldData data;
  if (const int rc = loadDrawnWorld("view", a.scene.layers, sources, data); rc != kExitOk) return rc;
  if (!glfwInit()) {
    std::fprintf(stderr, "geocean view: cannot open the display '%s'; use geocean render\n", display ? display : "");
    return kExitNoDisplay;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, gl::glDebugWanted() ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, a.frames > 0 ? GLFW_FALSE : GLFW_TRUE);  // scripted runs keep their size
  GLFWwindow* win = glfwCreateWindow(c.pose.width, c.pose.height, "Geocean", nullptr, nullptr);
  if (!win) {
    glfwTerminate();
    std::fprintf(stderr, "geocean view: no OpenGL 4.5 core window; use geocean render\n");
    return kExitNoDisplay;
  }
  glfwMakeContextCurrent(win);
  glfwSwapInterval(a.frames > 0 ? 0 : 1);  // scripted runs go as fast as they can
  // A key tapped between two polls still reads as pressed once: at a few
  // frames per second (llvmpipe, big windows) a quick H or F was lost.
  glfwSetInputMode(win, GLFW_STICKY_KEYS, GLFW_TRUE);
  gl::enableGlDebug();
  int rc = kExitOk;
  {
    // A pointer: hiding or showing a raster layer (panel, keys 1-9) makes a
    // new world and so a new renderer with the same ocean and boats.
    auto renderer = std::make_unique<render::GlobeRenderer>(std::make_shared<render::WorldTextures>(std::move(data)));
    // The ocean through the plugin's C ABI, as any host engine loads it.
    std::shared_ptr<host::PluginOceanLayer> ocean;
    rc = addDrawnOcean("view", a.scene, windMps, *renderer, sources, ocean);
    if (rc != kExitOk) glfwSetWindowShouldClose(win, GLFW_TRUE);  // leave through the normal cleanup, context still current
    // Boats around the --fly-to point (else under the first view); F cycles
    // the boat the camera chases (none, 1, .., N).
    std::shared_ptr<host::PluginBoats> boats;
    int follow = a.scene.boats.follow;
    bool fKeyWasDown = false;
    if (rc == kExitOk) {
      double tLat = plan.toLatDeg, tLon = plan.toLonDeg;
      if (!flying) host::viewTarget(c.pose, tLat, tLon);
      if (const int brc = addBoats("view", a.scene.boats, *renderer, ocean, tLat, tLon, boats); brc != kExitOk) {
        rc = brc;
        glfwSetWindowShouldClose(win, GLFW_TRUE);
      }
    }
    std::unique_ptr<gl::Hud> hud;
    if (!a.noHud) {
      std::string hudErr;
      hud = gl::Hud::create(hudErr);
      if (!hud) std::fprintf(stderr, "geocean view: %s; going on without it\n", hudErr.c_str());
    }
    bool showHud = true, hKeyWasDown = false;
    // The control panel: the sea state and the light, live (P toggles it).
    gl::PanelState panel;
    for (int i = 0; i < int(std::size(gl::kPanelWaveModels)); ++i)
      if (a.scene.waves == gl::kPanelWaveModels[i]) panel.waveModel = i;
    panel.windMps = float(windMps), panel.windFromDeg = float(a.scene.windFromDeg);
    panel.sunAzimuthDeg = float(sunAzEl[0]), panel.sunElevationDeg = float(sunAzEl[1]);
    panel.reflections = !a.scene.noReflections, panel.refraction = !a.scene.noRefraction, panel.shadows = !a.scene.light.noShadows;
    panel.layerNames = layerLabels(a.scene.layers);
    panel.layerShown.assign(panel.layerNames.size(), 1);
    // The layers as the panel shows them, drawn and queried alike: the host's
    // world from the shown files and the ocean's stack from the same (a
    // failure keeps the picture as it was and says why).
    std::vector<char> layersDrawn = panel.layerShown;
    auto applyShownLayers = [&] {
      const LayerOptions shown = shownLayers(a.scene.layers, panel.layerShown);
      std::vector<world::LayerSource> s;
      world::WorldData d;
      if (loadDrawnWorld("view", shown, s, d) != kExitOk) {
        panel.layerShown = layersDrawn;
        return;
      }
      if (ocean) {
        if (const std::string err = host::setPluginLayers(*ocean, s); !err.empty()) {
          std::fprintf(stderr, "geocean view: %s\n", err.c_str());
          // Back to what is drawn, so query and picture stay one stack.
          (void)host::setPluginLayers(*ocean, layerSources(shownLayers(a.scene.layers, layersDrawn)));
          panel.layerShown = layersDrawn;
          return;
        }
      }
      renderer = std::make_unique<render::GlobeRenderer>(std::make_shared<render::WorldTextures>(std::move(d)));
      if (ocean) renderer->addLayer(ocean);
      if (boats) renderer->addSceneObject(boats);
      layersDrawn = panel.layerShown;
    };
    bool digitWasDown[9] = {};
    bool showPanel = a.panel && hud, pKeyWasDown = false;
    glfwSetWindowUserPointer(win, &c);
    glfwSetScrollCallback(win, [](GLFWwindow* w, double, double dy) {
      static_cast<Controller*>(glfwGetWindowUserPointer(w))->wheel += dy;
    });
    auto frameSettings = [&](double simT, const camera::ViewPose& pose) {
      render::FrameSettings fs;
      fs.timeS = simT;
      fs.sunEcef = render::sunFromLocal(pose.latDeg, pose.lonDeg, panel.sunAzimuthDeg, panel.sunElevationDeg);
      applyDrawnScene(a.scene, fs);
      // The panel's switches (the options are their initial state).
      fs.reflections = panel.reflections;
      fs.refraction = panel.refraction;
      fs.shadows = panel.shadows;
      return fs;
    };
    // llvmpipe JIT-compiles each shader variant on its first draw: 1-2 s
    // each with a cold Mesa cache (docs/PERFORMANCE.md), stalls in the
    // middle of a descent. The descent from the first view to the sea,
    // drawn once small and off screen, takes them before the first frame.
    if (rc == kExitOk && !a.noWarmUp) {
      render::FlightPlan warm;
      warm.fromLatDeg = c.pose.latDeg, warm.fromLonDeg = c.pose.lonDeg, warm.fromAltM = c.pose.altM;
      warm.toLatDeg = plan.toLatDeg, warm.toLonDeg = plan.toLonDeg;
      if (!flying) host::viewTarget(c.pose, warm.toLatDeg, warm.toLonDeg);
      warm.headingDeg = flying ? plan.headingDeg : c.pose.headingDeg;
      camera::ViewPose base = c.pose;
      base.width = kWarmUpSize[0], base.height = kWarmUpSize[1];
      gl::Framebuffer small(base.width, base.height);
      small.bind();
      for (int i = 0; i < kWarmUpFrames; ++i) {
        const camera::ViewPose pose = render::flightPose(warm, double(i) / (kWarmUpFrames - 1), base);
        render::FrameSettings fs = frameSettings(a.timeS, pose);
        fs.reflectionEvery = 1;  // the first shown frame then starts its own cycle
        renderer->render(pose, fs);
      }
      glFinish();
    }
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    double fpsSmoothed = 0.0, flightS = 0.0;
    long tilesBuilt = 0;  // terrain tiles made since the start (each fills a pool slot)
    const int flightFrames = a.flightFrames > 0 ? a.flightFrames : a.frames;
    std::unique_ptr<gl::Framebuffer> fb;
    for (int frame = 0; !glfwWindowShouldClose(win) && (a.frames == 0 || frame < a.frames); ++frame) {
      glfwPollEvents();
      const auto now = std::chrono::steady_clock::now();
      const double dt = std::chrono::duration<double>(now - last).count();
      last = now;
      // Scripted runs (--frames) step time and flight per frame, so they do
      // not depend on how fast the machine draws; interactive runs use the clock.
      const double simT = a.timeS + (a.frames > 0 ? frame / 30.0 : std::chrono::duration<double>(now - t0).count());
      double x, y;
      glfwGetCursorPos(win, &x, &y);
      const bool l = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
      const bool r = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
      // The panel's controls take the mouse over it (last frame's layout): the globe stays.
      const bool panelMouse = showPanel && hud->wantsMouse();
      if (l && c.left && !panelMouse) c.drag(x - c.lastX, y - c.lastY), flying = false;
      if (r && c.right && !panelMouse) c.look(x - c.lastX, y - c.lastY), flying = false;
      c.left = l, c.right = r, c.lastX = x, c.lastY = y;
      if (c.wheel != 0.0 && !panelMouse) c.zoom(c.wheel), flying = false;
      c.wheel = 0.0;
      auto key = [&](int k) { return glfwGetKey(win, k) == GLFW_PRESS; };
      c.move((key(GLFW_KEY_W) ? 1 : 0) - (key(GLFW_KEY_S) ? 1 : 0), (key(GLFW_KEY_D) ? 1 : 0) - (key(GLFW_KEY_A) ? 1 : 0), dt);
      c.look((key(GLFW_KEY_RIGHT) ? 200 : 0) * dt - (key(GLFW_KEY_LEFT) ? 200 : 0) * dt,
             (key(GLFW_KEY_DOWN) ? 200 : 0) * dt - (key(GLFW_KEY_UP) ? 200 : 0) * dt);
      if (key(GLFW_KEY_R) || key(GLFW_KEY_HOME)) c.orbit(), flying = false;
      if (key(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(win, 1);
      const bool hKey = key(GLFW_KEY_H);
      if (hKey && !hKeyWasDown) showHud = !showHud;  // H toggles the HUD
      hKeyWasDown = hKey;
      const bool pKey = key(GLFW_KEY_P);
      if (pKey && !pKeyWasDown && hud) showPanel = !showPanel;  // P toggles the control panel
      pKeyWasDown = pKey;
      bool layerKey = false;  // 1-9 show or hide the panel's layer of that number
      for (int i = 0; i < 9; ++i) {
        const bool d = key(GLFW_KEY_1 + i);
        if (d && !digitWasDown[i] && i < int(panel.layerShown.size()))
          panel.layerShown[size_t(i)] = !panel.layerShown[size_t(i)], layerKey = true;
        digitWasDown[i] = d;
      }
      if (layerKey) applyShownLayers();
      const bool fKey = key(GLFW_KEY_F);
      if (fKey && !fKeyWasDown && boats) follow = (follow + 1) % (int(boats->count()) + 1);
      fKeyWasDown = fKey;
      if (flying) {
        if (a.frames > 0)  // loops every flightFrames frames (--flight-frames)
          flightS = flightFrames > 1 ? double(frame % flightFrames) / double(flightFrames - 1) : 1.0;
        else
          flightS = std::min(1.0, flightS + dt / a.flightS);
        c.pose = render::flightPose(plan, flightS, c.pose);
      }
      int w, h;
      glfwGetFramebufferSize(win, &w, &h);
      if (w <= 0 || h <= 0) continue;
      c.pose.width = w, c.pose.height = h;
      if (boats && follow > 0) {  // the chase camera; the controller takes over where it leaves off
        boats->update(simT);
        c.pose = boats->chase(std::size_t(follow - 1), c.pose);
        flying = false;
      }
      if (!fb || fb->width() != w || fb->height() != h) fb = std::make_unique<gl::Framebuffer>(w, h);
      fb->bind();
      const render::FrameTimes times = renderer->render(c.pose, frameSettings(simT, c.pose));
      tilesBuilt += times.terrain.tilesBuilt;
      // The float-depth target is blitted to the window (its own depth is fixed point).
      glBindFramebuffer(GL_READ_FRAMEBUFFER, fb->id());
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      if (frame > 0 && dt > 0.0)
        fpsSmoothed = fpsSmoothed == 0.0 ? 1.0 / dt : 0.9 * fpsSmoothed + 0.1 / dt;
      gl::HudValues hv;
      hv.latDeg = c.pose.latDeg, hv.lonDeg = c.pose.lonDeg, hv.altM = c.pose.altM, hv.fps = fpsSmoothed;
      if (ocean) {
        hv.seaKnown = seaHeightUnder(*ocean, c.pose.latDeg, c.pose.lonDeg, simT, hv.seaHeightM);
        hv.seaState = seaStateLine(*ocean, panel, c.pose.latDeg, c.pose.lonDeg);
      }
      if (hud && showPanel) {
        glViewport(0, 0, w, h);
        int ww = 0, wh = 0;  // the cursor is in window coordinates, the panel in framebuffer pixels
        glfwGetWindowSize(win, &ww, &wh);
        gl::HudInput in;
        in.x = ww > 0 ? x * w / ww : x, in.y = wh > 0 ? y * h / wh : y, in.left = l;
        const gl::PanelChange change = hud->draw(w, h, dt, hv, in, panel);
        if (change.sea && ocean) {
          const std::string err = host::setPluginSeaState(*ocean, gl::kPanelWaveModels[panel.waveModel], panel.windMps,
                                                          panel.windFromDeg);
          if (!err.empty()) std::fprintf(stderr, "geocean view: %s\n", err.c_str());
        }
        if (change.layers) applyShownLayers();
      } else if (hud && showHud) {
        glViewport(0, 0, w, h);
        hud->draw(w, h, dt, hv);
      }
      if (a.frames > 0 && frame == a.frames - 1 && !a.screenshot.empty()) {
        try {
          gl::writePng(a.screenshot, readWindow(w, h));
        } catch (const std::exception& e) {
          std::fprintf(stderr, "geocean view: %s\n", e.what());
          rc = kExitBadInput;
        }
      }
      glfwSwapBuffers(win);
      if (stats) {
        const HeapKb heap = heapKb();
        char row[256];
        std::snprintf(row, sizeof row, "%d,%.4f,%.7f,%.7f,%.3f,%.4f,%.2f,%ld,%ld,%ld,%d,%ld\n", frame,
                      std::chrono::duration<double>(now - t0).count(), c.pose.latDeg, c.pose.lonDeg, c.pose.altM,
                      hv.seaKnown ? hv.seaHeightM : std::nan(""), fpsSmoothed, residentKb(), heap.inUse, heap.held, times.terrain.tilesDrawn,
                      tilesBuilt);
        stats << row;
        if (frame % 100 == 99) stats.flush();  // a long run can be watched (and killed) midway
      }
      // The window title repeats the HUD on one line (task bars, window lists).
      std::string title = "Geocean  " + gl::Hud::text(hv);
      std::replace(title.begin(), title.end(), '\n', ' ');
      glfwSetWindowTitle(win, title.c_str());
    }
    if (!a.statsCsv.empty() && !stats.flush()) {  // also when a write failed midway
      std::fprintf(stderr, "geocean view: writing --stats '%s' failed\n", a.statsCsv.c_str());
      rc = kExitDataError;
    }
  }
  glfwDestroyWindow(win);
  glfwTerminate();
  return rc;
}

const Register reg{{"view", "Interactive globe viewer (needs a display; otherwise use render/fly)",
                    [](CLI::App& sub) -> std::function<int()> {
                      auto a = std::make_shared<ViewArgs>();
                      sub.add_option("--fly-to", a->flyTo, "LAT,LON: fly from orbit to 2 m above this sea point")
                          ->check(nonEmpty);
                      sub.add_option("--camera", a->camera,
                                     "LAT,LON,ALT,HEADING,PITCH: the first view, as render's (default: orbit over "
                                     "20,-30)")
                          ->allow_extra_args(false);
                      sub.add_option("--size", a->size, "window WIDTHxHEIGHT");
                      sub.add_option("--flight-seconds", a->flightS, "duration of the --fly-to flight (default 30)");
                      sub.add_option("--frames", a->frames,
                                     "draw N frames and exit (time and the --fly-to flight then advance per frame: "
                                     "1/30 s, and the flight ends on the last frame); 0 = until closed");
                      sub.add_option("--flight-frames", a->flightFrames,
                                     "with --frames: the --fly-to flight takes M frames and starts over (e.g. "
                                     "--frames 2000 --flight-frames 1000 flies twice)");
                      sub.add_option("--screenshot", a->screenshot, "with --frames: PNG of the last frame as shown");
                      sub.add_option("--stats", a->statsCsv,
                                     "CSV per frame: frame,wall_s,lat,lon,alt_m,sea_height_m,fps,rss_kb,heap_in_use_kb,"
                                     "heap_held_kb,tiles,tiles_built (resident set; malloc'd bytes in use and held "
                                     "from the system, kB; terrain tiles drawn, tiles made so far)");
                      sub.add_flag("--no-hud", a->noHud, "no HUD panel (H toggles it in the window)");
                      sub.add_flag("--no-warm-up", a->noWarmUp,
                                   "draw the first frame at once, without first drawing the descent to the sea off "
                                   "screen (which takes the shaders' first-use compiling before the window shows the globe)");
                      sub.add_flag("--panel", a->panel,
                                   "open the control panel (P toggles it): wave model, wind, sun, reflections, "
                                   "refraction, shadows, raster layers shown (also keys 1-9), changed live");
                      sub.add_option("--sun", a->sun,
                                     "AZ,EL of the sun at the camera's nadir, degrees (default 135,40; it follows "
                                     "the camera)");
                      sub.add_option("--time", a->timeS, "simulation time of the first frame, seconds");
                      addDrawnSceneOptions(sub, a->scene, DrawnCommand::View);
                      return [a] { return runView(*a); };
                    }}};

}  // namespace
}  // namespace geocean::app
