// The globe viewer's ocean through the plugin's C ABI (globe/host
// PluginOceanLayer, the path `geocean render/fly` take) draws the same
// picture as the ocean renderer linked directly (plugin/render), which the
// golden images in tests/render pin down.
#include "globe/host/OceanLayer.h"
#include "globe/render/Session.h"
#include "tests/render/DirectOcean.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstdlib>

namespace {

using namespace geocean;

struct Diff {
  int max = 0;
  long differing = 0;
};

Diff compare(const gl::Image& a, const gl::Image& b) {
  Diff d;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    const int e = std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    d.max = std::max(d.max, e);
    d.differing += e != 0;
  }
  return d;
}

TEST(CapiViewer, PluginOceanDrawsWhatTheLinkedRendererDraws) {
  // The test executable is not beside the plugin: point the loader at it.
  setenv("GEOCEAN_PLUGIN", GEOCEAN_PLUGIN_BUILD_PATH, 1);
  constexpr int kW = 192, kH = 128;
  render::Session s = render::Session::headless(world::loadDefaultWorld(), kW, kH);
  ASSERT_EQ(render::test::addDirectOcean(*s.renderer, s.world->grids(), "gerstner", 12.0, 250.0), "");
  render::GlobeRenderer viaPlugin(s.world);
  std::shared_ptr<host::PluginOceanLayer> layer;
  ASSERT_EQ(host::addPluginOcean(viaPlugin, "gerstner", 12.0, 250.0, &layer), "");

  // Strait of Gibraltar from 3 km looking east (coast, shoreline cut, waves),
  // and 15 m over the open Atlantic at the horizon (grazing grid, glint).
  camera::ViewPose coast;
  coast.latDeg = 36.0, coast.lonDeg = -5.75, coast.altM = 3000.0, coast.headingDeg = 90.0, coast.pitchDeg = -25.0;
  camera::ViewPose horizon;
  horizon.latDeg = 30.0, horizon.lonDeg = -40.0, horizon.altM = 15.0, horizon.headingDeg = 200.0,
  horizon.pitchDeg = -3.0;
  for (camera::ViewPose pose : {coast, horizon}) {
    pose.width = kW, pose.height = kH;
    render::FrameSettings fs;
    fs.timeS = 12.5;
    fs.sunEcef = render::sunForView(pose, 120.0, 30.0);
    s.render(pose, fs);
    const gl::Image linked = s.image();
    s.target->bind();
    glViewport(0, 0, kW, kH);
    viaPlugin.render(pose, fs);
    const gl::Image plugin = s.image();
    const Diff d = compare(linked, plugin);
    // Same shaders, same matrices to the last bit, same textures: identical.
    EXPECT_EQ(d.max, 0) << "lat " << pose.latDeg << ": " << d.differing << " channel values differ";
    // And the frame does show sea (not two empty pictures agreeing).
    long blue = 0;
    for (std::size_t i = 0; i < plugin.rgba.size(); i += 4) blue += plugin.rgba[i + 2] > plugin.rgba[i];
    EXPECT_GT(blue, kW * kH / 4);
  }
  layer.reset();  // ~GlobeRenderer drops its reference too; context still current
}

}  // namespace
