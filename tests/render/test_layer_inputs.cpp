// The host/layer contract's extra inputs (globe/render/Layer.h): a layer
// that asks for a copy of the scene gets exactly what was drawn before it,
// and one that asks for a reflection gets the sky and terrain seen by the
// eye mirrored in the sea plane.
#include "RenderFixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace geocean::render::test {
namespace {

// Reads what the host handed over, and what the bound framebuffer holds
// at the moment the layer draws.
class ProbeLayer : public Layer {
 public:
  explicit ProbeLayer(unsigned wants) : wants_(wants) {}
  const char* name() const override { return "probe"; }
  LayerInfo info() const override { return {false, 0.0, wants_}; }
  void draw(const camera::Camera& cam, const camera::Lighting&, bool, const LayerInputs& in) override {
    const int w = cam.widthPx(), h = cam.heightPx();
    const std::size_t n = std::size_t(w) * h;
    got = in;
    gotCamera = true;
    frameColor.assign(n * 4, 0);
    frameDepth.assign(n, 0.0f);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, frameColor.data());
    glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, frameDepth.data());
    if (in.sceneColor) {
      copyColor.assign(n * 4, 0);
      copyDepth.assign(n, 0.0f);
      glGetTextureImage(in.sceneColor, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(n * 4), copyColor.data());
      glGetTextureImage(in.sceneDepth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * 4), copyDepth.data());
    }
    if (in.reflectionColor) {
      reflection.assign(n * 4, 0);
      glGetTextureImage(in.reflectionColor, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(n * 4), reflection.data());
    }
  }
  unsigned wants_;
  LayerInputs got;
  bool gotCamera = false;
  std::vector<unsigned char> frameColor, copyColor, reflection;  // bottom row first (GL)
  std::vector<float> frameDepth, copyDepth;
};

ViewPose level(double lat, double lon, double alt, double heading, int size) {
  ViewPose p;
  p.latDeg = lat, p.lonDeg = lon, p.altM = alt, p.headingDeg = heading, p.pitchDeg = 0.0;
  p.width = p.height = size;
  return p;
}

TEST(LayerInputs, SceneCopyIsTheFrameBeforeTheLayer) {
  Session& s = session();
  GlobeRenderer renderer(s.world);
  auto probe = std::make_shared<ProbeLayer>(kLayerWantsSceneCopy);
  renderer.addLayer(probe);
  const ViewPose p = level(36.1, -5.35, 400.0, 250.0, 128);  // Gibraltar: terrain, sea and sky
  gl::Framebuffer fb(p.width, p.height);
  fb.bind();
  glViewport(0, 0, p.width, p.height);
  FrameSettings fs;
  fs.sunEcef = sunForView(p);
  renderer.render(p, fs);
  ASSERT_NE(probe->got.sceneColor, 0u);
  ASSERT_NE(probe->got.sceneDepth, 0u);
  EXPECT_EQ(probe->got.reflectionColor, 0u);  // not asked for
  EXPECT_EQ(probe->copyColor, probe->frameColor);
  EXPECT_EQ(probe->copyDepth, probe->frameDepth);
  // Not trivially empty: sky and terrain differ, and something has depth.
  int withDepth = 0;
  for (float d : probe->frameDepth) withDepth += d > 0.0f;
  EXPECT_GT(withDepth, 100);
}

// Writes a GL-ordered (bottom row first) RGBA buffer as a PNG, top row first.
void writeGlRgba(const std::string& path, const std::vector<unsigned char>& px, int w, int h) {
  gl::Image img;
  img.width = w, img.height = h;
  img.rgba.resize(px.size());
  for (int y = 0; y < h; ++y)
    std::copy_n(&px[std::size_t(h - 1 - y) * w * 4], std::size_t(w) * 4, &img.rgba[std::size_t(y) * w * 4]);
  gl::writePng(path, img);
}

TEST(LayerInputs, ReflectionIsTheSkySeenByTheMirroredEye) {
  // A level camera 20 m over the open Pacific: nothing stands above the
  // sea, so the reflection is sky only. The mirrored camera is proper, so
  // its pixel (x, y) looks along the mirror image of the main camera's ray
  // through (W-1-x, H-1-y) (level: up is the surface normal); where that
  // main ray is sky, both pixels show the same sky. The eye 40 m lower
  // changes the haze by far less than the 2/255 allowed (8-bit rounding).
  Session& s = session();
  GlobeRenderer renderer(s.world);
  auto probe = std::make_shared<ProbeLayer>(kLayerWantsReflection);
  renderer.addLayer(probe);
  const ViewPose p = level(-10.0, -140.0, 20.0, 60.0, 96);
  const int W = p.width, H = p.height;
  gl::Framebuffer fb(W, H);
  fb.bind();
  glViewport(0, 0, W, H);
  FrameSettings fs;
  fs.sunEcef = sunForView(p, 135.0, 30.0);
  renderer.render(p, fs);
  ASSERT_NE(probe->got.reflectionColor, 0u);
  ASSERT_EQ(probe->reflection.size(), std::size_t(W) * H * 4);
  if (const char* dir = std::getenv("GEOCEAN_DUMP_DIR")) {  // to look at
    writeGlRgba(std::string(dir) + "/layer_main.png", probe->frameColor, W, H);
    writeGlRgba(std::string(dir) + "/layer_reflection.png", probe->reflection, W, H);
  }
  const camera::Camera& m = probe->got.reflectionCamera;
  EXPECT_NEAR(m.heightM(), -20.0, 1e-3);  // the eye mirrored in the sea plane
  // GL rows are bottom first: main pixel (x, y_top) is row H-1-y_top. Sky
  // rows of the main view: its upper third (the horizon dips 0.14 deg).
  int compared = 0, worst = 0;
  for (int yTop = 0; yTop < H / 3; ++yTop)
    for (int x = 0; x < W; ++x) {
      const std::size_t a = (std::size_t(H - 1 - yTop) * W + x) * 4;          // main (x, yTop)
      const std::size_t b = (std::size_t(yTop) * W + (W - 1 - x)) * 4;        // reflection (W-1-x, H-1-yTop)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(int(probe->frameColor[a + c]) - int(probe->reflection[b + c])));
      ++compared;
    }
  EXPECT_EQ(compared, W * (H / 3));
  EXPECT_LE(worst, 2);
  // And it is not the main image in the same place: the main view's lower
  // third is sea (the terrain's distant-sea shading), the reflection's the
  // sky high above (mean difference in 8-bit units over RGB).
  double diff = 0.0;
  for (int yBottom = 0; yBottom < H / 3; ++yBottom)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = (std::size_t(yBottom) * W + x) * 4;
      for (int c = 0; c < 3; ++c) diff += std::abs(int(probe->frameColor[i + c]) - int(probe->reflection[i + c]));
    }
  diff /= 3.0 * W * (H / 3);
  EXPECT_GT(diff, 8.0);
}


// Above kReflectionReachM no sea point is within the layers' reach of the
// eye (it is at least the eye's height away), so the host draws no
// mirrored pass there; just below, it does, and a map from before is not
// reused when the pass resumes.
TEST(LayerInputs, NoReflectionIsMadeForAnEyeAboveItsReach) {
  Session& s = session();
  GlobeRenderer renderer(s.world);
  auto probe = std::make_shared<ProbeLayer>(kLayerWantsReflection);
  renderer.addLayer(probe);
  gl::Framebuffer fb(64, 64);
  fb.bind();
  glViewport(0, 0, 64, 64);
  FrameSettings fs;
  fs.reflectionEvery = 4;
  const auto drawAt = [&](double altM) {
    const ViewPose p = level(36.1, -5.35, altM, 250.0, 64);
    fs.sunEcef = sunForView(p);
    return renderer.render(p, fs);
  };
  FrameTimes t = drawAt(0.99 * kReflectionReachM);
  EXPECT_TRUE(t.reflectionDrawn);
  EXPECT_NE(probe->got.reflectionColor, 0u);
  t = drawAt(1.01 * kReflectionReachM);
  EXPECT_FALSE(t.reflectionDrawn);
  EXPECT_EQ(probe->got.reflectionColor, 0u);
  EXPECT_EQ(t.reflectionCpuMs, 0.0);
  t = drawAt(0.98 * kReflectionReachM);  // within 4 frames of the last map: drawn anew all the same
  EXPECT_TRUE(t.reflectionDrawn);
  EXPECT_NE(probe->got.reflectionColor, 0u);
}

}  // namespace
}  // namespace geocean::render::test
