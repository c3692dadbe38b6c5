#include "globe/gl/Hud.h"

#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cfloat>
#include <cstdio>
#include <iterator>

namespace geocean::gl {

std::unique_ptr<Hud> Hud::create(std::string& error) {
  IMGUI_CHECKVERSION();
  std::unique_ptr<Hud> h(new Hud);
  ImGuiContext* previous = ImGui::GetCurrentContext();
  h->ctx_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(h->ctx_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // a HUD has no layout to remember: never write imgui.ini
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  // The backend's own loader (gl3w) resolves GL through libGL.so.1, which
  // glvnd dispatches to whichever context is current, EGL or GLX.
  if (!ImGui_ImplOpenGL3_Init("#version 410 core")) {
    ImGui::DestroyContext(h->ctx_);
    h->ctx_ = nullptr;
    ImGui::SetCurrentContext(previous);
    error = "HUD: the Dear ImGui OpenGL 3 backend could not start (needs libGL.so.1 and a GL 4.1+ core context)";
    return nullptr;
  }
  ImGui::SetCurrentContext(previous);
  return h;
}

Hud::~Hud() {
  if (!ctx_) return;
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(ctx_);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(ctx_);
  ImGui::SetCurrentContext(previous == ctx_ ? nullptr : previous);
}

std::string Hud::text(const HudValues& v) {
  char buf[512];
  int n = 0;
  auto add = [&](const char* fmt, auto... args) {
    if (n < int(sizeof buf)) n += std::snprintf(buf + n, sizeof buf - size_t(n), fmt, args...);
  };
  // 5 decimals of a degree: ~1 m on the ground.
  add("lat %+10.5f\xC2\xB0\n", v.latDeg);
  add("lon %+10.5f\xC2\xB0\n", v.lonDeg);
  if (std::abs(v.altM) >= 10000.0)
    add("alt %10.1f km\n", v.altM / 1000.0);
  else
    add("alt %10.2f m\n", v.altM);
  if (v.seaKnown) {
    if (std::isfinite(v.seaHeightM)) {
      add("sea %+10.3f m\n", v.seaHeightM);
      // Near the sea, the camera's clearance over the wave under it; short
      // lines keep the panel in a corner of small windows.
      if (v.altM < 10000.0) add("clearance %5.2f m\n", v.altM - v.seaHeightM);
    } else {
      add("sea %10s\n", "land");
    }
  }
  if (!v.seaState.empty()) add("%s\n", v.seaState.c_str());
  if (v.fps > 0.0) add("fps %10.1f", v.fps);
  std::string s(buf, size_t(std::min(n, int(sizeof buf) - 1)));
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

void Hud::draw(int widthPx, int heightPx, double dtS, const HudValues& v) { frame(widthPx, heightPx, dtS, v, nullptr, nullptr); }

PanelChange Hud::draw(int widthPx, int heightPx, double dtS, const HudValues& v, const HudInput& in, PanelState& panel) {
  return frame(widthPx, heightPx, dtS, v, &in, &panel);
}

namespace {
PanelLayout::Rect lastItem() {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  return {a.x, a.y, b.x, b.y};
}
// A slider's or combo's frame, without its label (to its right).
PanelLayout::Rect lastFrame() {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  return {a.x, a.y, a.x + ImGui::CalcItemWidth(), b.y};
}
}  // namespace

PanelChange Hud::frame(int widthPx, int heightPx, double dtS, const HudValues& v, const HudInput* in, PanelState* panel) {
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(ctx_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(widthPx), float(heightPx));
  io.DeltaTime = float(std::clamp(dtS, 1e-4, 1.0));  // ImGui asserts a positive step
  // ImGui 1.86 (Debian 12) reads the mouse from these fields.
  io.MousePos = in && in->x >= 0.0 ? ImVec2(float(in->x), float(in->y)) : ImVec2(-FLT_MAX, -FLT_MAX);
  io.MouseDown[0] = in && in->left;
  // The built-in 13 px font grows with the window (17 px at 720p, 26 px at
  // 1080p): at 13 px the HUD was hard to read on a large window. The atlas
  // is rebuilt only when the whole-pixel size changes.
  const int fontPx = int(std::lround(13.0 * std::max(1.0, heightPx / 540.0)));
  if (fontPx != fontPx_) {
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    io.Fonts->Clear();
    ImFontConfig cfg;
    cfg.SizePixels = float(fontPx);
    io.Fonts->AddFontDefault(&cfg);
    ImGui_ImplOpenGL3_CreateFontsTexture();
    fontPx_ = fontPx;
  }
  ImGui_ImplOpenGL3_NewFrame();
  PanelChange change;
  // An auto-sized window takes the size its content had in the previous
  // layout (and is hidden in its first): lay every frame out twice, so the
  // panel always fits this frame's text (a flight's lines grow as the
  // camera comes down). The HUD is a few lines: the extra layout is free.
  // The controls take the mouse in the first pass (a click is seen when the
  // button goes down, in the first NewFrame); the second only draws.
  for (int pass = 2; pass > 0; --pass) {
    ImGui::NewFrame();
    const float margin = widthPx >= 480 ? 10.0f : 2.0f;
    ImGui::SetNextWindowPos(ImVec2(margin, margin));
    ImGui::SetNextWindowBgAlpha(0.45f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("geocean-hud", nullptr, flags)) ImGui::TextUnformatted(text(v).c_str());
    ImGui::End();
    if (panel) {
      ImGui::SetNextWindowPos(ImVec2(float(widthPx) - margin, margin), ImGuiCond_Always, ImVec2(1.0f, 0.0f));
      ImGui::SetNextWindowBgAlpha(0.6f);
      if (ImGui::Begin("Sea and light (P)", nullptr,
                       ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                           ImGuiWindowFlags_NoCollapse)) {
        ImGui::PushItemWidth(float(fontPx) * 12.0f);
        if (ImGui::Combo("waves", &panel->waveModel, kPanelWaveModels, int(std::size(kPanelWaveModels))))
          change.sea = true;
        layout_.waveModel = lastFrame();
        // Sliders change the sea state when let go: each new state rebuilds the waves.
        ImGui::SliderFloat("wind m/s", &panel->windMps, 0.0f, 30.0f, "%.1f");
        change.sea |= ImGui::IsItemDeactivatedAfterEdit();
        layout_.wind = lastFrame();
        ImGui::SameLine();
        ImGui::Text("Bft %d", beaufortOf(panel->windMps));
        ImGui::SliderFloat("wind from", &panel->windFromDeg, 0.0f, 360.0f, "%.0f deg");
        change.sea |= ImGui::IsItemDeactivatedAfterEdit();
        layout_.windFrom = lastFrame();
        change.light |= ImGui::SliderFloat("sun azimuth", &panel->sunAzimuthDeg, 0.0f, 360.0f, "%.0f deg");
        layout_.sunAzimuth = lastFrame();
        change.light |= ImGui::SliderFloat("sun elevation", &panel->sunElevationDeg, -10.0f, 90.0f, "%.0f deg");
        layout_.sunElevation = lastFrame();
        change.light |= ImGui::Checkbox("reflections", &panel->reflections);
        layout_.reflections = lastItem();
        change.light |= ImGui::Checkbox("refraction", &panel->refraction);
        layout_.refraction = lastItem();
        change.light |= ImGui::Checkbox("shadows", &panel->shadows);
        layout_.shadows = lastItem();
        ImGui::Separator();
        if (panel->layerNames.empty()) {
          ImGui::TextDisabled("no raster layers (--mask ...)");
        } else {
          ImGui::TextUnformatted("raster layers shown (keys 1-9)");
          panel->layerShown.resize(panel->layerNames.size(), 1);
          layout_.layers.resize(panel->layerNames.size());
          for (std::size_t i = 0; i < panel->layerNames.size(); ++i) {
            ImGui::PushID(int(i));
            bool shown = panel->layerShown[i] != 0;
            const std::string label = (i < 9 ? std::to_string(i + 1) + " " : std::string("  ")) + panel->layerNames[i];
            if (ImGui::Checkbox(label.c_str(), &shown)) {
              panel->layerShown[i] = shown ? 1 : 0;
              change.layers = true;
            }
            layout_.layers[i] = lastItem();
            ImGui::PopID();
          }
        }
        ImGui::PopItemWidth();
        const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        layout_.window = {at.x, at.y, at.x + size.x, at.y + size.y};
      }
      ImGui::End();
      layout_.shown = true;
    } else {
      layout_.shown = false;
    }
    if (pass == 2) wantsMouse_ = io.WantCaptureMouse;
    if (pass > 1) ImGui::EndFrame();
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  ImGui::SetCurrentContext(previous);
  return change;
}

int beaufortOf(double windMps) {
  // Upper limits of forces 0-11 (m/s at 10 m, WMO No. 8 table).
  static const double limits[] = {0.5, 1.5, 3.3, 5.5, 7.9, 10.7, 13.8, 17.1, 20.7, 24.4, 28.4, 32.6};
  int b = 0;
  while (b < 12 && windMps >= limits[b]) ++b;
  return b;
}

}  // namespace geocean::gl
