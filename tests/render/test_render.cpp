// Renders of the real world checked against geometry we know (disc size of
// the Earth, where land and sea are) and against golden images.
#include "RenderFixture.h"

#include "globe/gl/Framebuffer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>
#include <filesystem>

namespace geocean::render::test {

namespace {
std::shared_ptr<ocean_render::OceanRenderer> g_ocean;
std::shared_ptr<DirectOceanLayer> g_layer;
}

Session& session() {
  static std::unique_ptr<Session> s = [] {
    auto p = std::make_unique<Session>(Session::headless(loadDefaultWorld(), 256, 256));
    const std::string err = addDirectOcean(*p->renderer, p->world->grids(), "noise", 10.0, 270.0, &g_ocean, &g_layer);
    if (!err.empty()) throw std::runtime_error(err);
    return p;
  }();
  // The session's own references go before the session (atexit handlers
  // registered after a static's construction run before its destructor):
  // their last OceanRenderer must be deleted while the context lives.
  static const bool released = (std::atexit([] { g_layer.reset(), g_ocean.reset(); }), true);
  (void)released;
  return *s;
}

ocean_render::OceanRenderer& sessionOcean() {
  session();
  return *g_ocean;
}

DirectOceanLayer& directLayer() {
  session();
  return *g_layer;
}

void useOcean(std::shared_ptr<ocean_render::OceanRenderer> ocean) {
  session();
  g_layer->setOcean(ocean ? std::move(ocean) : g_ocean);
}

std::shared_ptr<ocean_render::OceanRenderer> sessionOceanWith(const ocean_render::OceanOptions& options) {
  return std::make_shared<ocean_render::OceanRenderer>(session().world->grids(), ocean_render::defaultLandSea(),
                                                       options);
}

ImageDiff compare(const Image& a, const Image& b) {
  ImageDiff d;
  if (a.width != b.width || a.height != b.height) {
    d.mean = d.max = 255;
    d.fractionOver16 = 1.0;
    return d;
  }
  std::size_t over = 0;
  double sum = 0.0;
  const std::size_t n = std::size_t(a.width) * a.height;
  for (std::size_t i = 0; i < n; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int e = std::abs(int(a.rgba[i * 4 + c]) - int(b.rgba[i * 4 + c]));
      sum += e;
      worst = std::max(worst, e);
    }
    d.max = std::max(d.max, worst);
    over += worst > 16;
  }
  d.mean = sum / (3.0 * n);
  d.fractionOver16 = double(over) / n;
  return d;
}

void expectMatchesGolden(const Image& img, const std::string& name, double maxMean, double maxFractionOver16) {
  const std::string path = std::string(GEOCEAN_GOLDEN_DIR) + "/" + name + ".png";
  const std::string actual = std::string(::testing::TempDir()) + "/" + name + ".actual.png";
  writePng(actual, img);
  if (std::getenv("GEOCEAN_UPDATE_GOLDEN")) {
    writePng(path, img);
    GTEST_SKIP() << "golden rewritten: " << path;
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << "missing golden " << path << " (actual: " << actual << ")";
  const ImageDiff d = compare(img, readImage(path));
  EXPECT_LE(d.mean, maxMean) << name << ": mean difference; actual image " << actual;
  EXPECT_LE(d.fractionOver16, maxFractionOver16) << name << ": pixels off by > 16; actual " << actual;
}

bool projectToPixel(const camera::Camera& cam, const ViewPose& pose, const glm::dvec3& ecef, double& x, double& y) {
  const glm::dvec4 c = cam.gpu().viewProjD * glm::dvec4(ecef - cam.eyeEcef(), 1.0);
  if (c.w <= 0.0) return false;
  x = (c.x / c.w * 0.5 + 0.5) * pose.width;
  y = (0.5 - c.y / c.w * 0.5) * pose.height;
  return true;
}

namespace {

// Golden thresholds: llvmpipe images are bit-identical between runs and
// thread counts on this platform (docs: PLATFORM.md); the margin allows a
// different Mesa/LLVM build to round shading differently: on average under
// 2 of 255 per channel, and at most 0.5% of pixels visibly (> 16) off.
constexpr double kGoldenMean = 2.0;
constexpr double kGoldenOver16 = 0.005;

const std::uint8_t* px(const Image& img, int x, int y) {
  x = std::clamp(x, 0, img.width - 1);  // a point off screen reads the edge, never outside
  y = std::clamp(y, 0, img.height - 1);
  return &img.rgba[(std::size_t(y) * img.width + x) * 4]; }
bool isBlack(const std::uint8_t* p) { return p[0] + p[1] + p[2] < 12; }
bool isSea(const std::uint8_t* p) { return p[2] > p[0] + 40 && p[2] > 60; }

ViewPose pose(double lat, double lon, double alt, double heading, double pitch, int size = 256) {
  ViewPose p;
  p.latDeg = lat, p.lonDeg = lon, p.altM = alt, p.headingDeg = heading, p.pitchDeg = pitch;
  p.width = p.height = size;
  return p;
}

TEST(Render, WholeEarthFrom20000KmIsADiscOfTheRightSize) {
  Session& s = session();
  const ViewPose p = pose(0.0, -150.0, 2.0e7, 0.0, -90.0);
  FrameSettings fs;
  fs.sunEcef = sunForView(p);
  s.render(p, fs);
  const Image img = s.image();
  // The Earth's angular radius from distance d to the centre: asin(R / d).
  // Equatorial radius across the screen's x axis (the view is over the equator).
  const double d = geo::kWgs84A + 2.0e7;
  const double tanHalf = std::tan(std::asin(geo::kWgs84A / d));
  const double fpx = 0.5 * p.height / std::tan(0.5 * p.fovYDeg * 3.14159265358979 / 180.0);
  const double radiusPx = tanHalf * fpx;
  const int cx = p.width / 2, cy = p.height / 2;
  // Inside the disc (2 px margin for anti-aliasing and the limb): lit sea at
  // the centre of the Pacific; beyond the limb glow (+6 px): black space.
  EXPECT_TRUE(isSea(px(img, cx, cy)));
  EXPECT_FALSE(isBlack(px(img, cx + int(radiusPx) - 3, cy)));
  EXPECT_TRUE(isBlack(px(img, std::min(p.width - 1, cx + int(radiusPx) + 6), cy)));
  EXPECT_TRUE(isBlack(px(img, 2, 2)));
  expectMatchesGolden(img, "earth_20000km", kGoldenMean, kGoldenOver16);
}

TEST(Render, GibraltarFrom50KmShowsLandAndSeaWhereTheyAre) {
  Session& s = session();
  const ViewPose p = pose(36.0, -5.45, 5.0e4, 0.0, -90.0);
  FrameSettings fs;
  fs.sunEcef = sunForView(p);
  s.render(p, fs);
  const Image img = s.image();
  const camera::Camera cam = s.renderer->camera(p);
  double x, y;
  // Known places (GSHHG shorelines, `geocean query` agrees): the Strait
  // between Spain north of the Rock and Jebel Musa in Morocco. The 4' Blue
  // Marble blurs coastal land towards blue, so land is told from sea by its
  // colour distance from the sea pixel rather than by hue alone.
  ASSERT_TRUE(projectToPixel(cam, p, geo::toEcef({35.97, -5.50, 0.0}), x, y));
  const std::uint8_t* sea = px(img, int(x), int(y));
  EXPECT_TRUE(isSea(sea)) << x << "," << y;
  for (const auto& ll : {glm::dvec2(36.17, -5.40), glm::dvec2(35.88, -5.40)}) {
    ASSERT_TRUE(projectToPixel(cam, p, geo::toEcef({ll.x, ll.y, 0.0}), x, y));
    const std::uint8_t* land = px(img, int(x), int(y));
    const int dist = std::abs(land[0] - sea[0]) + std::abs(land[1] - sea[1]) + std::abs(land[2] - sea[2]);
    EXPECT_GT(dist, 30) << "land at " << ll.x << "," << ll.y << " looks like sea";
    EXPECT_GT(land[0], sea[0] + 10) << "land is redder than the sea";
  }
  expectMatchesGolden(img, "gibraltar_50km", kGoldenMean, kGoldenOver16);
}

// An island of one mask texel between the samples a level-7 terrain tile
// once took (9 x 9 bilinear lookups all above 0.55 water) made that tile
// "all water", which capped its LOD at level 7 (2.4 km cells). Found in the
// default world, the island is refined from 3 km up like any land.
TEST(Render, TerrainRefinesAnIslandBetweenATilesSamples) {
  Session& s = session();
  const WorldTextures& w = *s.world;
  const double span = 90.0 / 128.0;  // level 7
  double islandLat = 0.0, islandLon = 0.0;
  bool found = false;
  const double texel = w.waterIndex().latStepDeg();
  const auto samplesWater = [&](int tx, int ty) {
    const double lon0 = -180.0 + tx * span, lat0 = 90.0 - (ty + 1) * span;
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 9; ++i)
        if (!(w.waterAt(lat0 + span * j / 8.0, lon0 + span * i / 8.0) > 0.55f)) return false;
    return true;
  };
  for (int ty = 32; ty < 96 && !found; ++ty)  // 67.5 N to 22.5 S
    for (int tx = 1; tx < 511 && !found; ++tx) {
      const double lon0 = -180.0 + tx * span, lat1 = 90.0 - ty * span, lat0 = lat1 - span;
      if (!samplesWater(tx, ty)) continue;
      // A land texel centre inside the tile, away from its edges.
      for (double la = lat0 + texel; la < lat1 - texel && !found; la += texel / 2)
        for (double lo = lon0 + texel; lo < lon0 + span - texel && !found; lo += texel / 2)
          if (w.waterAt(la, lo) < 0.5f) islandLat = la, islandLon = lo, found = true;
    }
  ASSERT_TRUE(found) << "no island between level-7 samples in the default world's mask";
  std::printf("island at %.4f, %.4f\n", islandLat, islandLon);
  const ViewPose p = pose(islandLat, islandLon, 3000.0, 0.0, -90.0, 128);
  FrameSettings fs;
  fs.sunEcef = sunForView(p);
  const auto t = s.render(p, fs);
  std::printf("terrain: %d tiles, max level %d\n", t.terrain.tilesDrawn, t.terrain.maxLevel);
  // The first such island is Big Diomede (65.78 N, 169.06 W). 3 km up, its
  // tile's cells are ~1,300 px: land refines to the data's finest level
  // (10). The 9 x 9 rule drew it at 7; the view's finest tile was then 8,
  // a coastal neighbour's all-water children.
  EXPECT_GT(t.terrain.maxLevel, 8);
}

TEST(Render, DepthWorksFromOrbitTo1mWithoutErrors) {
  Session& s = session();
  for (double alt : {2.0e7, 1.0e6, 1.0e4, 100.0, 1.0}) {
    const ViewPose p = pose(10.0, -140.0, alt, 30.0, alt > 1e5 ? -90.0 : -10.0, 64);
    FrameSettings fs;
    fs.sunEcef = sunForView(p);
    const auto t = s.render(p, fs);
    EXPECT_GT(t.terrain.tilesDrawn, 0) << alt;
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << alt;
    const Image img = s.image();
    // Straight down from orbit the centre, and just below the horizon
    // lower down the bottom row, sees the surface: never black space or a hole.
    EXPECT_FALSE(isBlack(px(img, 32, alt > 1e5 ? 32 : 63))) << alt;
  }
}

TEST(Render, EyeMoved1mmAt1mAltitudeGivesTheSameImage) {
  Session& s = session();
  ViewPose a = pose(0.0, 179.99, 1.0, 45.0, -20.0);
  ViewPose b = a;
  b.lonDeg += 1.0e-3 / (geo::kWgs84A * 3.14159265358979 / 180.0);  // 1 mm east
  FrameSettings fs;
  fs.sunEcef = sunForView(a);
  s.render(a, fs);
  const Image ia = s.image();
  s.render(b, fs);
  const Image ib = s.image();
  const ImageDiff d = compare(ia, ib);
  // A 1 mm move changes the view of a surface 1 m away by at most a
  // hundredth of a pixel: any float jitter would show as many changed pixels.
  EXPECT_LE(d.mean, 0.5);
  EXPECT_LE(d.fractionOver16, 0.001);
}


// The shortcuts (terrain tiles under open water left out; ocean cells over
// open water, or much smaller than a water texel, without the per-pixel
// coverage lookup; ocean cells that stay off screen culled) must not change
// what is seen, and shading far open water per vertex only a little:
// each view drawn with and without them. Views with islands and coasts at
// every scale (the shortcuts' margins are what keeps small islands and the
// shoreline's filters intact); a wrong margin loses islands or cuts the
// anti-aliased coast, thousands of pixels; a wrong cull leaves holes at the
// screen's edges near the sea.
TEST(Render, ShortcutsDoNotChangeTheImage) {
  Session& s = session();
  struct View {
    const char* name;
    ViewPose pose;
  };
  const View views[] = {
      {"Pacific from 20,000 km", pose(0.0, -150.0, 2.0e7, 0.0, -90.0, 512)},
      {"Aegean islands from 300 km", pose(37.5, 25.0, 3.0e5, 0.0, -90.0, 512)},
      {"Indonesia obliquely from 800 km", pose(-2.0, 118.0, 8.0e5, 90.0, -25.0, 512)},
      {"Gibraltar from 50 km", pose(36.0, -5.45, 5.0e4, 270.0, -50.0, 512)},
      {"the Strait from 2 m", pose(36.0, -5.6, 2.0, 250.0, -3.0, 512)},
      {"Tarifa's coast from 2 m", pose(36.0, -5.6, 2.0, 20.0, -1.0, 512)},
      {"a coast from 300 m", pose(35.95, -5.5, 300.0, 330.0, -8.0, 512)},
      {"a coast from 900 m", pose(36.1, -5.4, 900.0, 200.0, -15.0, 512)},
      {"Gibraltar from 3 km", pose(36.1, -5.3, 3000.0, 250.0, -30.0, 512)},
  };
  const auto shortcuts = [&](bool on, bool farVertexShading) {
    s.renderer->terrain().setSkipOpenWater(on);
    sessionOcean().setCheapCoverage(on);
    sessionOcean().setCullOffscreen(on);
    sessionOcean().setFarVertexShading(farVertexShading);
  };
  for (const View& v : views) {
    FrameSettings fs;
    fs.sunEcef = sunForView(v.pose);
    shortcuts(false, false);
    s.render(v.pose, fs);
    const Image full = s.image();
    shortcuts(true, false);
    const auto t = s.render(v.pose, fs);
    const Image exact = s.image();
    shortcuts(true, true);
    s.render(v.pose, fs);
    const Image fast = s.image();
    const ImageDiff d = compare(full, exact), f = compare(exact, fast);
    std::printf("%s: %d terrain tiles, exact shortcuts: mean %.4f, max %d, over 16: %.5f; far per vertex: mean %.4f, "
                "max %d\n",
                v.name, t.terrain.tilesDrawn, d.mean, d.max, d.fractionOver16, f.mean, f.max);
    // Where the ocean is opaque the two paths give the same bits; blending
    // at the coast may round differently by one unit.
    EXPECT_LE(d.mean, 0.01) << v.name;
    EXPECT_EQ(d.fractionOver16, 0.0) << v.name;
    // Far open water shaded per vertex instead of per pixel: the waves have
    // faded there, and what is left (normalisations, the glint's power)
    // bends across an 8 px cell by a few units; measured mean <= 0.02 and
    // max 15 (the broad glint from orbit).
    EXPECT_LE(f.mean, 0.1) << v.name;
    EXPECT_LE(f.max, 24) << v.name;
  }
  shortcuts(true, true);
}


// Issue 15 item 4, "no visible boundary between bands": the renderer's one
// distance band edge over open water is where cells turn far (their every
// vertex beyond 1.01 x the far footprint over ScreenCull::cellRadians; with
// reflections at least 40 km) and are shaded per vertex (farShaded_). A
// strip across it, the same view drawn with per-vertex far shading (A) and
// per pixel everywhere (B, no band). The band's rows are where A and B
// differ; per screen row the mean luma (Rec. 709 on the 8-bit values) is
// fitted by a line on 24 rows each side (4 rows left out at the edge): the
// step is the gap of the two fits at the edge, A's minus B's (B's is the
// view-angle trend's own curvature). Spectrum: per row, the power of the
// luma along the row in the band 1/16 .. 1/2 cycles per pixel (what 8 px
// vertex shading cannot carry) over the total AC power, after the edge
// over before, A's ratio over B's.
TEST(Render, FarShadingBandEdgeHasNoStep) {
  Session& s = session();
  struct View {
    const char* name;
    ViewPose pose;
    bool reflections, glint;  // glint: the sun ahead at the edge's depression, its glint across the edge
  };
  const View views[] = {
      {"open Pacific from 10 km, reflections (edge 40 km)", pose(0.0, -150.0, 1.0e4, 0.0, -14.0, 512), true, false},
      {"open Pacific from 1 km, no reflections", pose(0.0, -150.0, 1.0e3, 0.0, -14.0, 512), false, false},
      {"the same, the sun's glint on the edge", pose(0.0, -150.0, 1.0e4, 0.0, -14.0, 512), true, true},
      {"the same from 1 km, the sun's glint on the edge", pose(0.0, -150.0, 1.0e3, 0.0, -14.0, 512), false, true}};
  for (const View& v : views) {
    FrameSettings fs;
    fs.sunEcef = v.glint ? sunFromLocal(v.pose.latDeg, v.pose.lonDeg, 0.0, 14.0) : sunForView(v.pose);
    fs.reflections = v.reflections;
    sessionOcean().setFarVertexShading(true);
    s.render(v.pose, fs);
    const Image a = s.image();
    sessionOcean().setFarVertexShading(false);
    s.render(v.pose, fs);
    const Image b = s.image();
    sessionOcean().setFarVertexShading(true);
    gl::writePng(::testing::TempDir() + "/band_edge_" + std::to_string(&v - views) + ".png", a);
    const int w = a.width, h = a.height;
    auto luma = [&](const Image& im, int x, int y) {
      const std::uint8_t* p = &im.rgba[(std::size_t(y) * w + x) * 4];
      return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    };
    // The band: rows (top first) where any pixel differs; the edge is the
    // nearest such row's lower boundary (far rows are above near ones).
    int edge = -1;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (std::memcmp(&a.rgba[(std::size_t(y) * w + x) * 4], &b.rgba[(std::size_t(y) * w + x) * 4], 3) != 0)
          edge = y;
    ASSERT_GT(edge, 40) << v.name << ": no far band on screen";
    ASSERT_LT(edge, h - 40) << v.name;
    auto rowMean = [&](const Image& im, int y) {
      double m = 0.0;
      for (int x = 0; x < w; ++x) m += luma(im, x, y);
      return m / w;
    };
    auto fitAt = [&](const Image& im, int from, int to, double at) {  // least-squares line over rows [from, to)
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      const int n = to - from;
      for (int y = from; y < to; ++y) {
        const double m = rowMean(im, y);
        sx += y, sy += m, sxx += double(y) * y, sxy += y * m;
      }
      const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
      return (sy - slope * sx) / n + slope * at;
    };
    const double at = edge + 0.5;
    auto step = [&](const Image& im) { return fitAt(im, edge - 27, edge - 3, at) - fitAt(im, edge + 4, edge + 28, at); };
    // Per row: the power share of 1/16 .. 1/2 cycles per pixel in the row's AC power.
    auto rowShare = [&](const Image& im, int y) {
      std::vector<double> l(static_cast<std::size_t>(w));
      double mean = 0.0, hi = 0.0, all = 0.0;
      for (int x = 0; x < w; ++x) mean += (l[std::size_t(x)] = luma(im, x, y)) / w;
      for (int k = 1; k <= w / 2; ++k) {
        double re = 0.0, imag = 0.0;
        for (int x = 0; x < w; ++x) {
          const double ph = 2.0 * 3.14159265358979 * k * x / w;
          re += (l[std::size_t(x)] - mean) * std::cos(ph), imag -= (l[std::size_t(x)] - mean) * std::sin(ph);
        }
        all += re * re + imag * imag;
        if (k >= w / 16) hi += re * re + imag * imag;
      }
      return all > 0.0 ? hi / all : 0.0;
    };
    struct Share {
      double mean = 0.0, relErr = 0.0;  // over 24 rows; the mean's standard error over the mean
    };
    auto share = [&](const Image& im, int from) {
      std::vector<double> r;
      for (int y = from; y < from + 24; ++y) r.push_back(rowShare(im, y));
      Share sh;
      for (double x : r) sh.mean += x / r.size();
      double var = 0.0;
      for (double x : r) var += (x - sh.mean) * (x - sh.mean) / (r.size() - 1);
      sh.relErr = sh.mean > 0.0 ? std::sqrt(var / r.size()) / sh.mean : 0.0;
      return sh;
    };
    const double stepA = step(a), stepB = step(b);
    const Share farA = share(a, edge - 24), nearA = share(a, edge + 1), farB = share(b, edge - 24),
                nearB = share(b, edge + 1);
    const double ratio = (farA.mean / nearA.mean) / (farB.mean / nearB.mean);
    const double relErr = std::sqrt(farA.relErr * farA.relErr + nearA.relErr * nearA.relErr +
                                    farB.relErr * farB.relErr + nearB.relErr * nearB.relErr);
    std::printf("%s: edge at row %d; luma step across it %.3f with the band, %.3f without (%.3f beyond the trend); "
                "high-frequency share far/near %.4f/%.4f with, %.4f/%.4f without: ratio %.3f (standard error %.3f)\n",
                v.name, edge, stepA, stepB, stepA - stepB, farA.mean, nearA.mean, farB.mean, nearB.mean, ratio,
                relErr);
    // Half a unit of the 8-bit output: a row's mean cannot step by less on screen.
    EXPECT_LT(std::abs(stepA - stepB), 0.5) << v.name;
    // The spectrum's step: within 3 standard errors of the rows' own scatter.
    EXPECT_LT(std::abs(std::log(ratio)), 3.0 * relErr) << v.name;
  }
}

}  // namespace
}  // namespace geocean::render::test
