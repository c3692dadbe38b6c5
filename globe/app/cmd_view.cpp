// `geocean view`: the interactive globe in a GLFW window. Without a display
// it says so and points to the headless commands (exit code 4).
#include "globe/app/Command.h"
#include "globe/host/OceanLayer.h"
#include "globe/render/CliParse.h"
#include "globe/render/Flight.h"
#include "globe/render/Framebuffer.h"
#include "globe/render/GlDebug.h"
#include "globe/render/GlobeRenderer.h"
#include "plugin/waves/WaveField.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace geocean::app {
namespace {

struct ViewArgs {
  std::string flyTo;  // LAT,LON
  std::string size = "1280x720";
};

// Google Earth / Cesium style navigation: left-drag turns the globe under the
// cursor, the wheel zooms by a fraction of the altitude, right-drag or the
// arrow keys tilt and turn, WASD moves at a speed proportional to altitude,
// R (or Home) goes back to orbit.
struct Controller {
  render::ViewPose pose;
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

int runView(const ViewArgs& a) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    std::fprintf(stderr,
                 "geocean view: no display (DISPLAY is not set). Render headless instead:\n"
                 "  geocean render --camera 0,-150,20000000,0,-90 --out earth.png\n"
                 "  geocean fly --to 36,-5.6 --frames 120 --out out/flight\n");
    return kExitNoDisplay;
  }
  Controller c;
  render::FlightPlan plan;
  bool flying = false;
  try {
    render::parseSize(a.size, c.pose);
    c.pose.latDeg = 20.0, c.pose.lonDeg = -30.0, c.pose.altM = 2.0e7;
    if (!a.flyTo.empty()) {
      const auto v = render::parseNumbers(a.flyTo, 2, "--fly-to LAT,LON");
      plan.fromLatDeg = v[0], plan.fromLonDeg = v[1] - 40.0;
      plan.toLatDeg = v[0], plan.toLonDeg = v[1];
      plan.headingDeg = 90.0;
      flying = true;
    }
  } catch (const render::ArgError& e) {
    std::fprintf(stderr, "geocean view: %s\n", e.what());
    return kExitBadInput;
  }
  if (!glfwInit()) {
    std::fprintf(stderr, "geocean view: cannot open the display '%s'; use geocean render\n", display ? display : "");
    return kExitNoDisplay;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, render::glDebugWanted() ? GLFW_TRUE : GLFW_FALSE);
  GLFWwindow* win = glfwCreateWindow(c.pose.width, c.pose.height, "Geocean", nullptr, nullptr);
  if (!win) {
    glfwTerminate();
    std::fprintf(stderr, "geocean view: no OpenGL 4.5 core window; use geocean render\n");
    return kExitNoDisplay;
  }
  glfwMakeContextCurrent(win);
  glfwSwapInterval(1);
  render::enableGlDebug();
  int rc = kExitOk;
  {
    auto world = std::make_shared<render::WorldTextures>(render::loadDefaultWorld());
    render::GlobeRenderer renderer(world);
    // The ocean through the plugin's C ABI, as any host engine loads it.
    if (const std::string oceanErr = host::addPluginOcean(renderer, "noise", 10.0, 270.0); !oceanErr.empty()) {
      std::fprintf(stderr, "geocean view: %s\n", oceanErr.c_str());
      rc = kExitBadInput;
      glfwSetWindowShouldClose(win, GLFW_TRUE);  // leave through the normal cleanup, context still current
    }
    std::string err;
    auto waves = waves::WaveField::create(waves::Model::Noise, waves::SeaState{}, err);
    glfwSetWindowUserPointer(win, &c);
    glfwSetScrollCallback(win, [](GLFWwindow* w, double, double dy) {
      static_cast<Controller*>(glfwGetWindowUserPointer(w))->wheel += dy;
    });
    auto t0 = std::chrono::steady_clock::now(), last = t0;
    double fpsSmoothed = 0.0, flightS = 0.0;
    std::unique_ptr<render::Framebuffer> fb;
    while (!glfwWindowShouldClose(win)) {
      glfwPollEvents();
      const auto now = std::chrono::steady_clock::now();
      const double dt = std::chrono::duration<double>(now - last).count();
      last = now;
      const double simT = std::chrono::duration<double>(now - t0).count();
      double x, y;
      glfwGetCursorPos(win, &x, &y);
      const bool l = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
      const bool r = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
      if (l && c.left) c.drag(x - c.lastX, y - c.lastY), flying = false;
      if (r && c.right) c.look(x - c.lastX, y - c.lastY), flying = false;
      c.left = l, c.right = r, c.lastX = x, c.lastY = y;
      if (c.wheel != 0.0) c.zoom(c.wheel), c.wheel = 0.0, flying = false;
      auto key = [&](int k) { return glfwGetKey(win, k) == GLFW_PRESS; };
      c.move((key(GLFW_KEY_W) ? 1 : 0) - (key(GLFW_KEY_S) ? 1 : 0), (key(GLFW_KEY_D) ? 1 : 0) - (key(GLFW_KEY_A) ? 1 : 0), dt);
      c.look((key(GLFW_KEY_RIGHT) ? 200 : 0) * dt - (key(GLFW_KEY_LEFT) ? 200 : 0) * dt,
             (key(GLFW_KEY_DOWN) ? 200 : 0) * dt - (key(GLFW_KEY_UP) ? 200 : 0) * dt);
      if (key(GLFW_KEY_R) || key(GLFW_KEY_HOME)) c.orbit(), flying = false;
      if (key(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(win, 1);
      if (flying) {
        flightS = std::min(1.0, flightS + dt / 30.0);  // the scripted flight takes 30 s
        c.pose = render::flightPose(plan, flightS, c.pose);
      }
      int w, h;
      glfwGetFramebufferSize(win, &w, &h);
      if (w <= 0 || h <= 0) continue;
      c.pose.width = w, c.pose.height = h;
      if (!fb || fb->width() != w || fb->height() != h) fb = std::make_unique<render::Framebuffer>(w, h);
      fb->bind();
      render::FrameSettings fs;
      fs.timeS = simT;
      fs.sunEcef = render::sunFromLocal(c.pose.latDeg, c.pose.lonDeg, 135.0, 40.0);
      renderer.render(c.pose, fs);
      // The float-depth target is blitted to the window (its own depth is fixed point).
      glBindFramebuffer(GL_READ_FRAMEBUFFER, fb->id());
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      glfwSwapBuffers(win);
      fpsSmoothed = fpsSmoothed == 0.0 ? 1.0 / std::max(dt, 1e-6) : 0.9 * fpsSmoothed + 0.1 / std::max(dt, 1e-6);
      char title[256];
      std::string sea = "land";
      if (waves && world->waterAt(c.pose.latDeg, c.pose.lonDeg) > 0.5)
        sea = std::to_string(waves->surfaceAt(c.pose.latDeg, c.pose.lonDeg, simT).heightM).substr(0, 6) + " m";
      std::snprintf(title, sizeof title, "Geocean  lat %.5f  lon %.5f  alt %.1f m  sea %s  %.1f fps",
                    c.pose.latDeg, c.pose.lonDeg, c.pose.altM, sea.c_str(), fpsSmoothed);
      glfwSetWindowTitle(win, title);
    }
  }
  glfwDestroyWindow(win);
  glfwTerminate();
  return rc;
}

const Register reg{{"view", "Interactive globe viewer (needs a display; otherwise use render/fly)",
                    [](CLI::App& sub) -> std::function<int()> {
                      auto a = std::make_shared<ViewArgs>();
                      sub.add_option("--fly-to", a->flyTo, "LAT,LON: fly from orbit to 2 m above this sea point");
                      sub.add_option("--size", a->size, "window WIDTHxHEIGHT");
                      return [a] { return runView(*a); };
                    }}};

}  // namespace
}  // namespace geocean::app
