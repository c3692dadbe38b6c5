// The host/layer contract's extra inputs (globe/render/Layer.h): a layer
// that asks for a copy of the scene gets exactly what was drawn before it,
// and one that asks for a reflection gets the sky and terrain seen by the
// eye mirrored in the sea plane.
#include "RenderFixture.h"

#include <algorithm>
#include <cmath>
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

// Writes a GL-ordered (bottom row first) RGBA buffer as a PNG, top row first.
void writeGlRgba(const std::string& path, const std::vector<unsigned char>& px, int w, int h) {
  gl::Image img;
  img.width = w, img.height = h;
  img.rgba.resize(px.size());
  for (int y = 0; y < h; ++y)
    std::copy_n(&px[std::size_t(h - 1 - y) * w * 4], std::size_t(w) * 4, &img.rgba[std::size_t(y) * w * 4]);
  gl::writePng(path, img);
}

TEST(LayerInputs, ReflectionMirrorsTheTerrainAboveTheSea) {
  // The coastal Andes at Arica seen level from 20 m, 15 km offshore (in
  // the 20' relief smaller coasts such as Gibraltar's Rock do not stand
  // above the horizon): land stands above the sea, so the mirrored pass
  // holds it upside down.
  // Where the main view shows land above its horizon at (x, y), the
  // reflection shows land at (W-1-x, H-1-y) (the mirrored ray, as above);
  // the mirrored eye is lower, so haze and height on screen differ a
  // little: most such pixels (> 80 %) within 24/255. GEOCEAN_DUMP_DIR=dir writes both images to look at.
  Session& s = session();
  GlobeRenderer renderer(s.world);
  auto probe = std::make_shared<ProbeLayer>(kLayerWantsReflection);
  renderer.addLayer(probe);
  const ViewPose p = level(-18.5, -70.45, 20.0, 90.0, 160);
  const int W = p.width, H = p.height;
  gl::Framebuffer fb(W, H);
  fb.bind();
  glViewport(0, 0, W, H);
  FrameSettings fs;
  fs.sunEcef = sunForView(p, 135.0, 40.0);
  renderer.render(p, fs);
  ASSERT_EQ(probe->reflection.size(), std::size_t(W) * H * 4);
  if (const char* dir = std::getenv("GEOCEAN_DUMP_DIR")) {
    writeGlRgba(std::string(dir) + "/layer_main.png", probe->frameColor, W, H);
    writeGlRgba(std::string(dir) + "/layer_reflection.png", probe->reflection, W, H);
  }
  const auto at = [&](const std::vector<unsigned char>& v, int x, int yTop) {
    return &v[(std::size_t(H - 1 - yTop) * W + x) * 4];
  };
  // Land: what differs by more than 24 from the sky at the left edge of its
  // own row (the view's left edge looks out to sea).
  int land = 0, matched = 0;
  for (int yTop = 0; yTop < H / 2 - 2; ++yTop) {
    const unsigned char* skyRef = at(probe->frameColor, 0, yTop);
    for (int x = 0; x < W; ++x) {
      const unsigned char* m = at(probe->frameColor, x, yTop);
      int dSky = 0;
      for (int c = 0; c < 3; ++c) dSky = std::max(dSky, std::abs(int(m[c]) - int(skyRef[c])));
      if (dSky <= 24) continue;
      ++land;
      // The mirrored eye sits 2h lower: the land rises by 2h/distance in its
      // view, under 2 rows here (h = 20 m, land >= 15 km away, 0.28 deg/row).
      int best = 255;
      for (int dy = -2; dy <= 2; ++dy) {
        const int yr = std::clamp(H - 1 - yTop + dy, 0, H - 1);
        const unsigned char* r = at(probe->reflection, W - 1 - x, yr);
        int d = 0;
        for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(m[c]) - int(r[c])));
        best = std::min(best, d);
      }
      matched += best <= 24;
    }
  }
  EXPECT_GT(land, 100) << "the view must show land above the horizon";
  EXPECT_GT(matched, land * 8 / 10) << matched << " of " << land << " land pixels mirrored";
}

}  // namespace
}  // namespace geocean::render::test
