// The viewer's heads-up display: a small translucent panel in the top-left
// corner with the camera's lat, lon, altitude, the frame rate and the sea
// height under the camera, drawn with Dear ImGui (Debian's libimgui, OpenGL 3
// backend) into whatever framebuffer is bound. Works in a GLFW window and in
// a headless EGL context alike. The control panel (PanelState) takes the
// mouse the viewer passes in (HudInput), so it works headless too (tests).
#pragma once

#include <memory>
#include <string>
#include <vector>

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
  // The sea state in a line or two (the viewer: model, wind, Hs, peak period); empty: not shown.
  std::string seaState;
};

// The viewer's control panel (P toggles it): the sea state and the light,
// changed live. The viewer applies what changed.
struct PanelState {
  int waveModel = 0;  // index into kPanelWaveModels
  float windMps = 10.0f, windFromDeg = 270.0f;
  float sunAzimuthDeg = 135.0f, sunElevationDeg = 40.0f;  // at the camera's nadir
  bool reflections = true, refraction = true, shadows = true;
  // The user's raster layers (--mask, --elevation, --imagery; the viewer
  // fills them), each drawn and queried only while shown; keys 1-9 too.
  std::vector<std::string> layerNames;
  std::vector<char> layerShown;  // char, not bool: ImGui's checkbox takes a bool*
};
inline constexpr const char* kPanelWaveModels[] = {"noise", "gerstner", "fft", "noise-paper"};
// Beaufort force of a wind speed at 10 m (m/s; WMO No. 8's class limits).
int beaufortOf(double windMps);
// What the panel changed in one frame: the sea state only when a control
// is released (a new sea state rebuilds the waves), the rest at once.
struct PanelChange {
  bool sea = false, light = false;
  bool layers = false;  // a layer was shown or hidden: the world is rebuilt
};
// Where the panel's controls were last drawn (window pixels, y down): tests
// click them.
struct PanelLayout {
  struct Rect {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  Rect window;  // the whole panel
  Rect waveModel, wind, windFrom, sunAzimuth, sunElevation, reflections, refraction, shadows;  // sliders: their frames
  std::vector<Rect> layers;  // PanelState::layerNames' checkboxes
  bool shown = false;
};
// The mouse as the window sees it this frame (pixels, y down).
struct HudInput {
  double x = -1.0, y = -1.0;
  bool left = false;
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
  // The same with the control panel at the top right, taking the mouse;
  // `panel` is changed in place by the controls. wantsMouse(): the mouse
  // was over the panel or dragging one of its controls (the globe must not
  // move with it).
  PanelChange draw(int widthPx, int heightPx, double dtS, const HudValues& v, const HudInput& in, PanelState& panel);
  bool wantsMouse() const { return wantsMouse_; }
  const PanelLayout& panelLayout() const { return layout_; }

  // The panel text, one line per value (also what the panel shows).
  static std::string text(const HudValues& v);

 private:
  Hud() = default;
  ImGuiContext* ctx_ = nullptr;
  int fontPx_ = 0;  // size of the font atlas now built
  bool wantsMouse_ = false;
  PanelLayout layout_;
  PanelChange frame(int widthPx, int heightPx, double dtS, const HudValues& v, const HudInput* in, PanelState* panel);
};

}  // namespace geocean::gl
