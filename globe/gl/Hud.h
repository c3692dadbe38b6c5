// The viewer's heads-up display: a small translucent panel in the top-left
// corner with the camera's lat, lon, altitude, the frame rate and the sea
// height under the camera, drawn with Dear ImGui (Debian's libimgui, OpenGL 3
// backend) into whatever framebuffer is bound. Works in a GLFW window and in
// a headless EGL context alike; takes no input (it only shows).
#pragma once

#include <memory>
#include <string>

struct ImGuiContext;

namespace geocean::gl {

struct HudValues {
  double latDeg = 0.0, lonDeg = 0.0;
  double altM = 0.0;  // camera height above the WGS84 ellipsoid
  double fps = 0.0;   // <= 0: not shown
  // Sea surface height above the ellipsoid under the camera (NaN on land or
  // lakes); from the ocean plugin's query, the same surface that is drawn.
  double seaHeightM = 0.0;
  bool seaKnown = false;  // false: no ocean (nothing to show)
};

class Hud {
 public:
  // Needs a current OpenGL 3.2+ core context (the one it will draw in).
  // Returns nullptr and sets `error` if the ImGui OpenGL backend cannot start.
  static std::unique_ptr<Hud> create(std::string& error);
  // Deletes the GL objects: call with the same context current.
  ~Hud();
  Hud(const Hud&) = delete;
  Hud& operator=(const Hud&) = delete;

  // Draws the panel over the framebuffer bound now (viewport width x height
  // pixels). `dtS` is the time since the previous frame. GL state is
  // restored by the backend.
  void draw(int widthPx, int heightPx, double dtS, const HudValues& v);

  // The panel text, one line per value (also what the panel shows).
  static std::string text(const HudValues& v);

 private:
  Hud() = default;
  ImGuiContext* ctx_ = nullptr;
  int fontPx_ = 0;  // size of the font atlas now built
};

}  // namespace geocean::gl
