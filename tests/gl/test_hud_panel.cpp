// The viewer's control panel (globe/gl/Hud, issue 13 item 8) driven as a
// user drives it: the mouse pressed and released over its controls, frame
// by frame, headless (EGL on llvmpipe) — the same code the window feeds
// with GLFW's cursor.
#include "globe/gl/Framebuffer.h"
#include "globe/gl/HeadlessContext.h"
#include "globe/gl/Hud.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace geocean::gl {
namespace {

struct Panel {
  std::unique_ptr<HeadlessContext> ctx;
  std::unique_ptr<Framebuffer> fb;
  std::unique_ptr<Hud> hud;
  PanelState state;
  HudValues values;
  Panel() {
    std::string err;
    ctx = HeadlessContext::create(err);
    EXPECT_TRUE(ctx) << err;
    fb = std::make_unique<Framebuffer>(960, 540);
    fb->bind();
    hud = Hud::create(err);
    EXPECT_TRUE(hud) << err;
    values.latDeg = 36.0, values.lonDeg = -5.6, values.altM = 300.0;
  }
  // One frame with the mouse at (x, y), the left button down or up.
  PanelChange frame(double x, double y, bool down) {
    glViewport(0, 0, 960, 540);
    glClearColor(0.1f, 0.2f, 0.3f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    return hud->draw(960, 540, 1.0 / 30.0, values, HudInput{x, y, down}, state);
  }
  // Press and release at a control's centre (x at `along` of its width).
  std::pair<PanelChange, PanelChange> click(const PanelLayout::Rect& r, double along = 0.5) {
    const double x = r.x0 + along * (r.x1 - r.x0), y = 0.5 * (r.y0 + r.y1);
    frame(x, y, false);  // hover first, as a real cursor arrives
    const PanelChange press = frame(x, y, true);
    const PanelChange release = frame(x, y, false);
    return {press, release};
  }
};

TEST(HudPanel, ClicksChangeTheLightAtOnceAndTheSeaStateWhenTheSliderIsLetGo) {
  Panel p;
  ASSERT_TRUE(p.hud);
  p.frame(-1, -1, false);
  p.frame(-1, -1, false);  // the auto-sized window has its size from the second frame
  const PanelLayout& lay = p.hud->panelLayout();
  ASSERT_TRUE(lay.shown);
  // At the top right of the window, clear of the HUD at the top left.
  EXPECT_GT(lay.reflections.x0, 480.0f);
  EXPECT_LT(lay.reflections.y1, 270.0f);
  ASSERT_TRUE(p.state.reflections && p.state.refraction);

  auto [press, release] = p.click(lay.reflections);
  EXPECT_FALSE(p.state.reflections) << "a click on the checkbox turns reflections off";
  EXPECT_TRUE(press.light || release.light);
  EXPECT_FALSE(press.sea || release.sea);
  EXPECT_TRUE(p.state.refraction);

  // Shadows: their own checkbox under refraction, a light change alone.
  ASSERT_TRUE(p.state.shadows);
  EXPECT_GT(lay.shadows.y0, lay.refraction.y1 - 1.0f);
  auto [sPress, sRelease] = p.click(lay.shadows);
  EXPECT_FALSE(p.state.shadows) << "a click on the checkbox turns shadows off";
  EXPECT_TRUE(sPress.light || sRelease.light);
  EXPECT_FALSE(sPress.sea || sRelease.sea);
  EXPECT_TRUE(p.state.refraction);
  EXPECT_FALSE(p.state.reflections);

  // The wind slider at 3/4 of its width: 30 m/s x 3/4, within the grab's
  // half width (ImGui's grab is a few pixels of a ~200 px track: 1 m/s).
  const float windBefore = p.state.windMps;
  auto [wPress, wRelease] = p.click(lay.wind, 0.75);
  EXPECT_NEAR(p.state.windMps, 22.5, 1.0) << "was " << windBefore;
  EXPECT_FALSE(wPress.sea) << "no new sea state while the slider is held";
  EXPECT_TRUE(wRelease.sea) << "a new sea state when it is let go";

  // The sun's elevation at its left end (2 % in: the frame's border): -10 degrees, night.
  p.click(lay.sunElevation, 0.02);
  EXPECT_NEAR(p.state.sunElevationDeg, -10.0, 1.0);

  // The mouse over the panel is the panel's; elsewhere the globe's.
  p.frame(0.5 * (lay.wind.x0 + lay.wind.x1), 0.5 * (lay.wind.y0 + lay.wind.y1), false);
  p.frame(0.5 * (lay.wind.x0 + lay.wind.x1), 0.5 * (lay.wind.y0 + lay.wind.y1), false);
  EXPECT_TRUE(p.hud->wantsMouse());
  p.frame(480, 400, false);
  p.frame(480, 400, false);
  EXPECT_FALSE(p.hud->wantsMouse());
}

TEST(HudPanel, ThePanelIsDrawnAtTheTopRightAndTheHudAlone) {
  Panel p;
  ASSERT_TRUE(p.hud);
  for (int i = 0; i < 3; ++i) p.frame(-1, -1, false);
  const Image withPanel = p.fb->readColor();
  for (int i = 0; i < 3; ++i) {
    glClear(GL_COLOR_BUFFER_BIT);  // the HUD is translucent: one layer, as each frame of p.frame
    p.hud->draw(960, 540, 1.0 / 30.0, p.values);
  }
  const Image hudOnly = p.fb->readColor();
  const PanelLayout::Rect r = p.hud->panelLayout().window;
  int inside = 0, outside = 0;
  for (int y = 0; y < 540; ++y)
    for (int x = 0; x < 960; ++x) {
      const std::size_t i = (std::size_t(y) * 960 + x) * 4;
      const bool d = withPanel.rgba[i] != hudOnly.rgba[i] || withPanel.rgba[i + 1] != hudOnly.rgba[i + 1];
      const bool in = x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
      (in ? inside : outside) += d;
    }
  // At the top right, clear of the HUD at the top left.
  EXPECT_GT(r.x0, 480.0f);
  EXPECT_NEAR(r.x1, 950.0f, 1.0f) << "10 px from the right edge";
  EXPECT_GT(inside, 5000) << "the panel covers its window";
  EXPECT_EQ(outside, 0) << "and nothing else changes (the HUD is the same)";
}

// The user's raster layers (issue 13 item 8: "raster layers shown"): one
// checkbox each, all shown at first; a click hides that one layer alone and
// asks for the world to be rebuilt (PanelChange::layers), nothing else.
TEST(HudPanel, EachRasterLayerHasACheckboxThatHidesItAlone) {
  Panel p;
  ASSERT_TRUE(p.hud);
  p.state.layerNames = {"mask       gibraltar_3s.tif", "elevation  island.tif", "imagery    bay.tif"};
  p.state.layerShown.assign(3, 1);
  p.frame(-1, -1, false);
  p.frame(-1, -1, false);
  const PanelLayout lay = p.hud->panelLayout();
  ASSERT_EQ(lay.layers.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(lay.layers[i].y0, lay.shadows.y1) << "listed below the light's controls";
    EXPECT_LT(lay.layers[i].y1, lay.window.y1) << "inside the panel";
    if (i) {
      EXPECT_GT(lay.layers[i].y0, lay.layers[i - 1].y1 - 1.0f) << "one under the other";
    }
  }
  auto [press, release] = p.click(lay.layers[1], 0.05);  // the box at the label's left
  EXPECT_EQ(p.state.layerShown, (std::vector<char>{1, 0, 1}));
  EXPECT_TRUE(press.layers || release.layers);
  EXPECT_FALSE(press.sea || release.sea || press.light || release.light);
  p.click(p.hud->panelLayout().layers[1], 0.05);
  EXPECT_EQ(p.state.layerShown, (std::vector<char>{1, 1, 1})) << "a second click shows it again";
}

TEST(HudPanel, BeaufortForcesAreTheWmoClasses) {
  // WMO No. 8: force 0 below 0.5 m/s, 3 from 3.4, 5 from 8.0, 12 from 32.7.
  EXPECT_EQ(beaufortOf(0.4), 0);
  EXPECT_EQ(beaufortOf(3.4), 3);
  EXPECT_EQ(beaufortOf(5.4), 3);
  EXPECT_EQ(beaufortOf(8.0), 5);
  EXPECT_EQ(beaufortOf(10.0), 5);
  EXPECT_EQ(beaufortOf(20.0), 8);
  EXPECT_EQ(beaufortOf(33.0), 12);
}

}  // namespace
}  // namespace geocean::gl
