// The sun's shadows on the water and its Phong option (issue 13 item 6,
// paper 001), against geometry: a floating box's shadow lies where rays
// from the sea towards the sun meet the box (a slab test in double, not our
// shaders), the paper's darkening is 0.5 of the unshadowed picture, the
// default removes the glitter in shadow, and Phong's highlight is centred on
// the mirror direction with the width its exponent gives. Set
// GEOCEAN_DUMP_DIR to keep the pictures (they were looked at).
#include "RenderFixture.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/gl/Framebuffer.h"
#include "globe/render/Boats.h"
#include "globe/raster/GeoTiffWriter.h"
#include "globe/render/Terrain.h"
#include "tests/support/Subprocess.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace geocean::render::test {
namespace {

constexpr double kPi = 3.14159265358979;
constexpr int kW = 256, kH = 256;

void dump(const Image& img, const std::string& name) {
  if (const char* dir = std::getenv("GEOCEAN_DUMP_DIR")) writePng(std::string(dir) + "/" + name + ".png", img);
}

// Display value back to linear radiance (atmosphere.glsl toDisplay).
double linear(std::uint8_t v) {
  const double d = std::pow(std::min(double(v), 254.5) / 255.0, 2.2);
  return -std::log(1.0 - d) / 1.6;
}
double grey(const Image& img, std::size_t i) {
  return (linear(img.rgba[4 * i]) + linear(img.rgba[4 * i + 1]) + linear(img.rgba[4 * i + 2])) / 3.0;
}

// A box floating upright (body axes east, north, up), drawn by the host's
// BoatRenderer as the plugin's bodies are, in the main, mirrored and shadow
// passes; `on` switches it out (the session is shared).
class FloatingBox final : public SceneObject {
 public:
  FloatingBox(double latDeg, double lonDeg, glm::dvec3 half, double draftM) : half_(half) {
    const glm::dvec3 h = half;
    std::vector<double> v;
    for (int i = 0; i < 8; ++i) {
      v.push_back(i & 1 ? h.x : -h.x);
      v.push_back(i & 2 ? h.y : -h.y);
      v.push_back(i & 4 ? h.z : -h.z);
    }
    const std::vector<std::uint32_t> idx = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                            2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    renderer_.addMesh(v, idx);
    const geo::EnuFrame f = geo::enuFrame({latDeg, lonDeg, 0.0});
    rot_ = glm::dmat3(f.east, f.north, f.up);
    centre_ = geo::toEcef({latDeg, lonDeg, h.z - draftM});
    renderer_.setInstances({BoatInstance{0, centre_, glm::quat_cast(rot_), glm::vec3(0.7f, 0.3f, 0.2f)}});
  }
  void draw(const camera::Camera& cam, const camera::Lighting& light, bool, const camera::Camera* mirroredFrom) override {
    if (on) renderer_.draw(cam, light, mirroredFrom);
  }
  void drawDepth(const glm::mat4& viewProj, const glm::dvec3& originEcef) override {
    if (on) renderer_.drawDepth(viewProj, originEcef);
  }
  // Whether the ray from p towards the sun meets the box (slab test).
  bool shades(const glm::dvec3& p, const glm::dvec3& sun) const {
    const glm::dvec3 o = glm::transpose(rot_) * (p - centre_), d = glm::transpose(rot_) * sun;
    double t0 = 0.0, t1 = 1e9;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-12) {
        if (std::abs(o[k]) > half_[k]) return false;
        continue;
      }
      double a = (-half_[k] - o[k]) / d[k], b = (half_[k] - o[k]) / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a), t1 = std::min(t1, b);
    }
    return t0 <= t1;
  }
  bool on = false;

 private:
  BoatRenderer renderer_;
  glm::dvec3 half_;
  glm::dmat3 rot_{1.0};
  glm::dvec3 centre_{0.0};
};

// A 24 x 8 m box, 6 m high with 1 m under the sea, in open water (0 N, 150 W).
constexpr double kLat = 0.0, kLon = -150.0;
FloatingBox& box() {
  static FloatingBox* b = [] {
    auto p = std::make_shared<FloatingBox>(kLat, kLon, glm::dvec3(12.0, 4.0, 3.0), 1.0);
    session().renderer->addSceneObject(p);
    return p.get();
  }();
  return *b;
}

// The shared session with a data attachment (the sea's eye-relative
// position per pixel, w = 1; the box's w = 2) and a calm noise sea, for a
// test's span.
struct Scene {
  Scene() {
    Session& s = session();
    saved = std::move(s.target);
    s.target = std::make_unique<Framebuffer>(kW, kH, true);
    ocean_render::OceanOptions oo;
    oo.sea.windSpeedMps = 3.0;
    ocean = sessionOceanWith(oo);
    ocean->setWriteData(true);
    useOcean(ocean);
    box().on = true;
  }
  ~Scene() {
    box().on = false;
    session().target = std::move(saved);
  }
  struct Shot {
    Image img;
    std::vector<float> data;
  };
  Shot shoot(const ViewPose& p, FrameSettings fs) {
    Session& s = session();
    s.render(p, fs);
    return {s.image(), s.target->readData()};
  }
  std::unique_ptr<Framebuffer> saved;
  std::shared_ptr<ocean_render::OceanRenderer> ocean;
  OceanGuard guard;
};

// The eye altM up, southM south of the box, looking north at it.
ViewPose boxView(double altM = 60.0, double southM = 130.0) {
  ViewPose p;
  p.latDeg = kLat - southM / 110574.0, p.lonDeg = kLon, p.altM = altM;
  p.headingDeg = 0.0, p.pitchDeg = -std::atan2(altM, southM) * 180.0 / kPi;
  p.width = kW, p.height = kH, p.fovYDeg = 50.0;
  return p;
}

struct Masks {
  std::vector<char> drawn, geometric;  // sea pixels in shadow: by the picture, by geometry
  int drawnN = 0, geometricN = 0, both = 0;
  double dx = 0, dy = 0, gx = 0, gy = 0;  // centroids (pixels)
};

Masks shadowMasks(const Scene::Shot& lit, const Scene::Shot& shadowed, const ViewPose& pose, const glm::dvec3& sun,
                  double ratioBelow) {
  Masks m;
  m.drawn.assign(std::size_t(kW) * kH, 0);
  m.geometric = m.drawn;
  const camera::Camera cam = session().renderer->camera(pose);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = std::size_t(y) * kW + x;
      const float* d = &lit.data[4 * i];
      if (d[3] != 1.0f || shadowed.data[4 * i + 3] != 1.0f) continue;  // sea in both
      const glm::dvec3 p = cam.eyeEcef() + glm::dvec3(d[0], d[1], d[2]);
      if (box().shades(p, sun)) m.geometric[i] = 1, ++m.geometricN, m.gx += x, m.gy += y;
      if (grey(shadowed.img, i) < ratioBelow * grey(lit.img, i)) m.drawn[i] = 1, ++m.drawnN, m.dx += x, m.dy += y;
      m.both += m.drawn[i] && m.geometric[i];
    }
  if (m.drawnN) m.dx /= m.drawnN, m.dy /= m.drawnN;
  if (m.geometricN) m.gx /= m.geometricN, m.gy /= m.geometricN;
  return m;
}

// Pixels of the mask whose whole (2r+1)^2 neighbourhood is in it.
std::vector<std::size_t> core(const std::vector<char>& mask, int r) {
  std::vector<std::size_t> out;
  for (int y = r; y < kH - r; ++y)
    for (int x = r; x < kW - r; ++x) {
      bool all = true;
      for (int j = -r; j <= r && all; ++j)
        for (int i = -r; i <= r && all; ++i) all = mask[std::size_t(y + j) * kW + x + i] != 0;
      if (all) out.push_back(std::size_t(y) * kW + x);
    }
  return out;
}

// The shadow map's texel on the sea seen from the eye, in pixels at the box
// (the map covers 2048 texels over the reach's box: GlobeRenderer's
// shadowView), for the tolerances.
double texelPx(const ViewPose& pose, const glm::dvec3& sun) {
  ShadowView sv;
  const camera::Camera cam = session().renderer->camera(pose);
  if (!shadowView(cam, sun, sv)) return 0.0;
  // The rows of the matrix are the light's axes scaled by 2 / the box's sides.
  const double sx = glm::length(glm::dvec3(sv.matrix[0][0], sv.matrix[1][0], sv.matrix[2][0]));
  const double sy = glm::length(glm::dvec3(sv.matrix[0][1], sv.matrix[1][1], sv.matrix[2][1]));
  const double texelM = 2.0 / std::min(sx, sy) / kShadowMapSize;
  const double distM = glm::length(geo::toEcef({kLat, kLon, 0.0}) - cam.eyeEcef());
  return texelM / (distM * 2.0 * std::tan(0.5 * pose.fovYDeg * kPi / 180.0) / kH);
}

TEST(Shadows, ABoxShadowFallsOnTheSeaWhereRaysToTheSunMeetItDarkenedByThePapersHalf) {
  Scene sc;
  const ViewPose pose = boxView(80.0, 60.0);
  // The sun 20 degrees high in the east: the shadow falls west of the box, across the view.
  const glm::dvec3 sun = sunFromLocal(kLat, kLon, 80.0, 20.0);
  FrameSettings fs;
  fs.sunEcef = sun;
  fs.timeS = 3.0;
  fs.shadows = false;
  const Scene::Shot lit = sc.shoot(pose, fs);
  fs.shadows = true;
  fs.shadowModel = ShadowModel::Paper;
  const Scene::Shot paper = sc.shoot(pose, fs);
  dump(lit.img, "shadow_box_none");
  dump(paper.img, "shadow_box_paper");
  // The picture's shadow edge: half the sun seen, 0.75 of the unshadowed in the paper's model.
  const Masks m = shadowMasks(lit, paper, pose, sun, 0.75);
  const double texel = texelPx(pose, sun);
  std::printf("[ measured ] shadow: drawn %d px, geometry %d px, both %d; centroid drawn (%.2f, %.2f), geometry "
              "(%.2f, %.2f); map texel %.2f px\n",
              m.drawnN, m.geometricN, m.both, m.dx, m.dy, m.gx, m.gy, texel);
  ASSERT_GT(m.geometricN, 150) << "the box's shadow is in view";
  // Where geometry says: the centroids agree within a map texel (PCF
  // spreads an edge over a texel, symmetrically) plus a pixel, and the two
  // masks overlap for 80 % of either.
  EXPECT_LT(std::hypot(m.dx - m.gx, m.dy - m.gy), texel + 1.0);
  EXPECT_GT(m.both, 0.8 * m.geometricN);
  EXPECT_GT(m.both, 0.8 * m.drawnN);
  // Paper 001's m = 0.5: the pixels in full shadow (the geometric mask
  // less 2 texels, twice PCF's reach) are half the unshadowed picture's, to the
  // display's rounding (1 of 255 and the half of an odd value).
  const int r = int(std::ceil(2.0 * texel)) + 1;
  int n = 0, off = 0;
  for (std::size_t i : core(m.geometric, r)) {
    ++n;
    for (int c = 0; c < 3; ++c)
      off += std::abs(2 * int(paper.img.rgba[4 * i + c]) - int(lit.img.rgba[4 * i + c])) > 2;
  }
  std::printf("[ measured ] paper darkening: %d core pixels, %d channels off 0.5 by more than a count\n", n, off);
  EXPECT_GT(n, 20);
  EXPECT_EQ(off, 0);
  // Outside the shadow (2 texels clear of it), the picture is unchanged.
  int outside = 0, changed = 0;
  std::vector<char> near(m.geometric.size(), 0);
  for (std::size_t i : core(std::vector<char>(m.geometric.size(), 1), 0)) {
    const int x = int(i % kW), y = int(i / kW);
    for (int j = -r; j <= r && !near[i]; ++j)
      for (int k = -r; k <= r; ++k) {
        const int xx = x + k, yy = y + j;
        if (xx >= 0 && yy >= 0 && xx < kW && yy < kH && m.geometric[std::size_t(yy) * kW + xx]) {
          near[i] = 1;
          break;
        }
      }
    if (near[i] || lit.data[4 * i + 3] != 1.0f) continue;
    ++outside;
    for (int c = 0; c < 3; ++c) changed += lit.img.rgba[4 * i + c] != paper.img.rgba[4 * i + c];
  }
  EXPECT_GT(outside, 10000);
  EXPECT_EQ(changed, 0);
  // Looked at: the box's shadow west of it, a parallelogram on the calm sea.
  expectMatchesGolden(paper.img, "shadow_box_paper", 2.0, 0.005);
}

// Looking towards a low sun: the box's shadow lies on the glitter. By
// default the sun's direct light is removed in shadow: the glitter there is
// gone, down to the level of the same sea with the sun behind the eye (no
// glitter at all; its sky differs only by the sun's aureole, <= 0.07 F).
TEST(Shadows, TheGlitterIsGoneInTheBoxShadowByDefault) {
  Scene sc;
  ViewPose pose = boxView(25.0, 110.0);
  const glm::dvec3 sun = sunFromLocal(kLat, kLon, 0.0, 14.0), behind = sunFromLocal(kLat, kLon, 180.0, 14.0);
  FrameSettings fs;
  fs.sunEcef = sun;
  fs.timeS = 3.0;
  fs.shadows = false;
  const Scene::Shot lit = sc.shoot(pose, fs);
  fs.shadows = true;
  const Scene::Shot shadowed = sc.shoot(pose, fs);
  fs.shadows = false;
  fs.sunEcef = behind;
  const Scene::Shot noGlitter = sc.shoot(pose, fs);
  dump(lit.img, "shadow_glitter_none");
  dump(shadowed.img, "shadow_glitter_physical");
  const Masks m = shadowMasks(lit, shadowed, pose, sun, 0.8);
  const double texel = texelPx(pose, sun);
  const std::vector<std::size_t> c = core(m.geometric, int(std::ceil(2.0 * texel)) + 1);
  double litSum = 0, shadowSum = 0, noneSum = 0;
  for (std::size_t i : c) litSum += grey(lit.img, i), shadowSum += grey(shadowed.img, i), noneSum += grey(noGlitter.img, i);
  const double k = c.empty() ? 1.0 : 1.0 / double(c.size());
  std::printf("[ measured ] %zu core pixels: mean radiance lit %.4f, shadowed %.4f, sun behind %.4f; texel %.2f px; "
              "centroids (%.1f, %.1f) / (%.1f, %.1f)\n",
              c.size(), litSum * k, shadowSum * k, noneSum * k, texel, m.dx, m.dy, m.gx, m.gy);
  ASSERT_GT(c.size(), 20u) << "the shadow is in view";
  EXPECT_GT(litSum, 2.0 * noneSum) << "the glitter is there without shadows";
  EXPECT_LT(shadowSum, 1.3 * noneSum) << "and gone in the shadow";
}

// Phong (paper 001 eq. 19) with exponent n over a calm sea: the highlight's
// excess over the same view with the sun behind, divided by Fresnel, is
// cos^n of the angle between each pixel's mirrored ray (on the flat sea)
// and the sun: its peak is at the mirror direction and ln(excess / F)
// against ln cos(phi) has slope n.
TEST(Shadows, PhongHighlightPeaksAtTheMirrorDirectionWithTheExponentsWidth) {
  Session& s = session();
  OceanGuard guard;
  ocean_render::OceanOptions oo;
  oo.sea.windSpeedMps = 1.5;  // slopes ~0.01: the mirror direction moves by ~1 degree
  useOcean(sessionOceanWith(oo));
  ViewPose p;
  p.latDeg = kLat, p.lonDeg = kLon + 0.2, p.altM = 200.0, p.headingDeg = 180.0, p.pitchDeg = -30.0;
  p.width = p.height = kW, p.fovYDeg = 40.0;
  const camera::Camera cam = s.renderer->camera(p);
  const glm::dvec3 up = geo::surfaceNormal(p.latDeg, p.lonDeg);
  for (double n : {60.0, 240.0}) {
    FrameSettings fs;
    fs.sunModel = SunModel::Phong;
    fs.sunEcef = sunFromLocal(p.latDeg, p.lonDeg, 180.0, 30.0);
    fs.reflections = false;  // the sky BRDF alone, the same both ways
    // The layer's exponent (DirectOceanLayer::phongExponent).
    directLayer().phongExponent = n;
    s.render(p, fs);
    const Image lit = s.image();
    fs.sunEcef = sunFromLocal(p.latDeg, p.lonDeg, 0.0, 30.0);
    s.render(p, fs);
    const Image behind = s.image();
    directLayer().phongExponent = 0.0;
    char name[64];
    std::snprintf(name, sizeof name, "phong_n%03d", int(n));
    dump(lit, name);
    const glm::dvec3 sun = sunFromLocal(p.latDeg, p.lonDeg, 180.0, 30.0);
    double peak = -1.0, peakPhi = 0.0;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int cnt = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const std::size_t i = std::size_t(y) * kW + x;
        const glm::dvec3 v = -cam.pixelRay(x + 0.5, y + 0.5);
        const double cosV = glm::dot(v, up);
        if (cosV <= 0.05) continue;
        const glm::dvec3 r = 2.0 * cosV * up - v;  // the flat sea's mirrored ray
        const double cosPhi = std::min(glm::dot(r, sun), 1.0);
        const double fr = 0.02 + 0.98 * std::pow(1.0 - cosV, 5.0);  // only its variation matters: ~ exact Fresnel
        const double e = (grey(lit, i) - grey(behind, i)) / fr;
        if (e > peak) peak = e, peakPhi = std::acos(cosPhi);
        const std::uint8_t* px = &lit.rgba[4 * i];
        if (std::max({px[0], px[1], px[2]}) >= 250 || cosPhi <= 0.0) continue;
        if (e <= 0.0) continue;
        // The lobe from 10 % of its height (above the sky's difference) to 90 %.
        const double lobe = std::pow(cosPhi, n);
        if (lobe < 0.1 || lobe > 0.9) continue;
        const double X = std::log(cosPhi), Y = std::log(e);
        sx += X, sy += Y, sxx += X * X, sxy += X * Y, ++cnt;
      }
    const double slope = (cnt * sxy - sx * sy) / (cnt * sxx - sx * sx);
    const double halfWidth = std::acos(std::pow(0.5, 1.0 / n)) * 180.0 / kPi;
    std::printf("[ measured ] Phong n = %.0f: peak %.2f deg from the mirror direction (pixel %.2f deg), fitted "
                "exponent %.1f over %d px; half width %.2f deg\n",
                n, peakPhi * 180.0 / kPi, 40.0 / kH, slope, cnt, halfWidth);
    ASSERT_GT(cnt, 200);
    // The peak within a tenth of the half width plus the calm sea's tilt (1 degree).
    EXPECT_LT(peakPhi * 180.0 / kPi, 0.1 * halfWidth + 1.0) << n;
    // The width: the exponent within 5 % (measured 1.2-1.8 % and 0.2-1.2 %: the
    // calm sea's slopes widen the lobe, the 8-bit pixels round the tails).
    EXPECT_NEAR(slope, n, 0.05 * n);
  }
}


// An island's cliffs at a low sun: a 400 x 400 m block standing 150 m out of
// the sea, 3 km north of the box (vertical walls: the shadow's far edge is
// its top edge's, 150 m / tan(6 degrees) = 1.43 km west of it), the sun 6
// degrees high in the east, seen from 150 m, 1 km west and 1.5 km south of
// its south-west corner, looking north (10 degrees east) across the shadow. Truth: rays
// from the drawn sea's points towards the sun meeting the block.
FloatingBox& island() {
  static FloatingBox* b = [] {
    auto p = std::make_shared<FloatingBox>(kLat + 3000.0 / 110574.0, kLon, glm::dvec3(200.0, 200.0, 75.0), 0.0);
    session().renderer->addSceneObject(p);
    return p.get();
  }();
  return *b;
}

TEST(Shadows, AnIslandsCliffShadowAtALowSunFallsWhereGeometrySays) {
  Scene sc;
  box().on = false;
  island().on = true;
  struct Off {
    ~Off() { island().on = false; }
  } off;
  ViewPose pose;
  pose.latDeg = kLat + (3000.0 - 200.0 - 1500.0) / 110574.0, pose.lonDeg = kLon - 1200.0 / 111320.0;
  pose.altM = 150.0, pose.headingDeg = 10.0, pose.pitchDeg = -6.0, pose.fovYDeg = 50.0, pose.width = kW, pose.height = kH;
  const glm::dvec3 sun = sunFromLocal(pose.latDeg, pose.lonDeg, 90.0, 6.0);
  FrameSettings fs;
  fs.sunEcef = sun;
  fs.timeS = 3.0;
  fs.shadows = false;
  const Scene::Shot lit = sc.shoot(pose, fs);
  fs.shadows = true;
  fs.shadowModel = ShadowModel::Paper;
  const Scene::Shot paper = sc.shoot(pose, fs);
  fs.shadowModel = ShadowModel::Physical;
  const Scene::Shot physical = sc.shoot(pose, fs);
  dump(lit.img, "shadow_island_none");
  dump(paper.img, "shadow_island_paper");
  // The same masks with the island as the caster.
  Masks m;
  m.drawn.assign(std::size_t(kW) * kH, 0);
  m.geometric = m.drawn;
  const camera::Camera cam = session().renderer->camera(pose);
  for (std::size_t i = 0; i < std::size_t(kW) * kH; ++i) {
    const float* d = &lit.data[4 * i];
    if (d[3] != 1.0f || paper.data[4 * i + 3] != 1.0f) continue;
    const glm::dvec3 p = cam.eyeEcef() + glm::dvec3(d[0], d[1], d[2]);
    const bool g = island().shades(p, sun), dr = grey(paper.img, i) < 0.75 * grey(lit.img, i);
    m.geometricN += g, m.drawnN += dr, m.both += g && dr;
    m.geometric[i] = g, m.drawn[i] = dr;
  }
  const double texel = texelPx(pose, sun);
  std::printf("[ measured ] island: shadow drawn %d px, by geometry %d, both %d; map texel at the box %.2f px\n",
              m.drawnN, m.geometricN, m.both, texel);
  ASSERT_GT(m.geometricN, 1000) << "the island's shadow is in view";
  // Its edges are where geometry puts them, within PCF's 2 texels: 90 % each way.
  EXPECT_GT(m.both, 0.9 * m.geometricN);
  EXPECT_GT(m.both, 0.9 * m.drawnN);
  // The default model darkens the same pixels (the sun's direct light gone).
  // (The band is a few pixels deep at this grazing view: its core 1 px in.)
  const std::vector<std::size_t> inner = core(m.geometric, 1);
  int darker = 0;
  for (std::size_t i : inner) darker += grey(physical.img, i) < grey(lit.img, i);
  EXPECT_GT(inner.size(), 300u);
  EXPECT_GT(darker, int(0.9 * inner.size()));
  // Looked at: the paper's model shows the band plainly (the default's is faint at
  // this grazing view, where the mirrored sky is most of the water's light).
  expectMatchesGolden(paper.img, "shadow_island_low_sun_paper", 2.0, 0.005);
}

// A cliff at a low sun, drawn by `geocean render` through the plugin (ABI
// 1.8's shadow map and flag): a regional 1' elevation raster (streamed at
// its own cells), a 1 x 1 degree block of 4000 m deep sea around (30 N, 40 W) with a 300 m
// plateau of 15 x 15 cells (0.25 degrees) at its centre, land in a 1' mask
// of the block (without it the 5' default mask calls it sea and the host
// draws the ground under the sea there, casting nothing): its edge falls to
// the deep sea within one cell, crossing the sea level 130 m out (a 66
// degree cliff). The sun 6 degrees high in the east throws the plateau's
// shadow about 2.9 km over the sea west of it. Truth: for each sea pixel
// the ray from its point on the (calm, 1 m/s) sea towards the sun, marched
// over the raster's bilinear surface; the picture's shadow: the pixels the
// paper's model darkens (ratio < 0.8 against --no-shadows).
// A folder of this process's own: the cliff tests run in parallel under
// ctest -j, each writing the rasters and the tile cache.
std::string plateauDir() {
  static const std::string d = [] {
    const std::string p = ::testing::TempDir() + "/shadow_plateau_" + std::to_string(::getpid());
    std::filesystem::create_directories(p);
    return p;
  }();
  return d;
}
double plateauElevation(double lat, double lon) {
  if (std::abs(lat - 30.0) < 0.5 && std::abs(lon + 40.0) < 0.5)
    return std::abs(lat - 30.0) < 7.5 / 60.0 && std::abs(lon + 40.0) < 7.5 / 60.0 ? 300.0 : -4000.0;
  return -32768.0;
}
// The block's 1' cells as a regional GeoTIFF: the relief, or its mask
// (the host's and the ocean's land and sea: land (1) above the sea).
std::string writePlateau(const std::string& name, bool mask) {
  const std::string path = plateauDir() + "/" + name;
  std::vector<float> px(60 * 60);
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 60; ++x) {
      const double e = plateauElevation(30.5 - (y + 0.5) / 60.0, -40.5 + (x + 0.5) / 60.0);
      px[std::size_t(y) * 60 + x] = mask ? (e > 0.0 ? 1.0f : 0.0f) : float(e);
    }
  raster::GeoTiffWriteOptions wo;
  wo.transform = {-40.5, 30.5, 1.0 / 60.0, -1.0 / 60.0, false};
  raster::writeGeoTiff(path, px.data(), 60, 60, 1, raster::SampleType::F32, wo);
  return path;
}
std::string plateauTif() {
  static const std::string p = [] {
    std::filesystem::remove_all(plateauDir() + "/shadow_tile_cache");
    return writePlateau("shadow_plateau.tif", false);
  }();
  return p;
}
std::string plateauMask() {
  static const std::string p = writePlateau("shadow_plateau_mask.tif", true);
  return p;
}
// The raster's bilinear surface (cell centres on the 1' grid).
double bilinear(double lat, double lon) {
  const double fx = (lon + 180.0) * 60.0 - 0.5, fy = (90.0 - lat) * 60.0 - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy), tx = fx - x0, ty = fy - y0;
  const auto at = [](double col, double row) {
    return plateauElevation(90.0 - (row + 0.5) / 60.0, -180.0 + (col + 0.5) / 60.0);
  };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) + ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

Image renderCli(const std::string& args, const std::string& name) {
  std::string out = ::testing::TempDir() + "/" + name + ".png";
  if (const char* dir = std::getenv("GEOCEAN_DUMP_DIR")) out = std::string(dir) + "/" + name + ".png";
  std::filesystem::remove(out);
  const auto r = geocean::test::run(std::string(GEOCEAN_EXE) + " render " + args + " --out " + out);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return readImage(out);
}

// The plateau's shadow over the sea seen from `pose` (sun 90, 6; calm sea),
// drawn without shadows, with the paper's model and (withPhysical) the default; the
// sea pixels within 0.8 of the map's reach counted against the relief.
struct CliffShadow {
  Image none, paper, physical;
  int sea = 0, drawn = 0, geometric = 0, both = 0;
};
CliffShadow cliffShadow(const ViewPose& pose, const std::string& name, bool withPhysical = true) {
  setenv("GEOCEAN_TILE_CACHE", (plateauDir() + "/shadow_tile_cache").c_str(), 1);
  char cam[160];
  std::snprintf(cam, sizeof cam, " --camera %.6f,%.6f,%.1f,%.1f,%.1f --size %dx%d --fov %.1f --sun 90,6 --wind 1",
                pose.latDeg, pose.lonDeg, pose.altM, pose.headingDeg, pose.pitchDeg, kW, kH, pose.fovYDeg);
  const std::string view = std::string(cam) + " --elevation " + plateauTif() + " --mask " + plateauMask();
  CliffShadow r;
  r.none = renderCli(view + " --no-shadows", name + "_none");
  r.paper = renderCli(view + " --shadow-model paper", name + "_paper");
  if (withPhysical) r.physical = renderCli(view, name);
  unsetenv("GEOCEAN_TILE_CACHE");
  if (r.none.width != kW || r.paper.width != kW || (withPhysical && r.physical.width != kW)) {
    ADD_FAILURE() << name << ": a render failed";
    return r;
  }
  const camera::Camera c = camera::Camera::fromView(pose);
  const glm::dvec3 sun = sunForView(pose, 90.0, 6.0);
  const double reach = std::clamp(kShadowReachPerHeight * pose.altM, kShadowReachMinM, kShadowReachMaxM);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::dvec3 ray = c.pixelRay(x + 0.5, y + 0.5);
      const geo::RayHit hit = geo::intersectEllipsoid(c.eyeEcef(), ray);
      if (!hit.hit) continue;
      const glm::dvec3 p = c.eyeEcef() + hit.tFirst() * ray;
      // Sea points within 0.8 of the map's reach, clear of the cliff's cell
      // (deeper than 1000 m: the terrain there is the sea floor or its edge).
      if (hit.tFirst() > 0.8 * reach) continue;
      const geo::Geodetic g = geo::fromEcef(p);
      if (bilinear(g.latDeg, g.lonDeg) > -1000.0) continue;
      // The view of it must not cross the plateau (it does not in either
      // view: the eye is beside it or has it behind).
      bool shaded = false;
      for (double t = 20.0; t < 8000.0 && !shaded; t += 20.0) {
        const geo::Geodetic q = geo::fromEcef(p + t * sun);
        shaded = bilinear(q.latDeg, q.lonDeg) > q.heightM;
      }
      const std::size_t i = std::size_t(y) * kW + x;
      const bool dark = grey(r.paper, i) < 0.8 * grey(r.none, i);
      ++r.sea, r.drawn += dark, r.geometric += shaded, r.both += dark && shaded;
    }
  std::printf("[ measured ] %s: %d sea px within reach, shadow drawn %d, by the relief %d, both %d\n", name.c_str(),
              r.sea, r.drawn, r.geometric, r.both);
  return r;
}

TEST(Shadows, ACliffsShadowAtALowSunFallsWhereItsReliefSays) {
  // 150 m up, 2.5 km west of the plateau's west side, in its shadow, looking north-east at the cliff.
  ViewPose pose;
  pose.latDeg = 29.93, pose.lonDeg = -40.0 - 7.0 / 60.0 - 0.026, pose.altM = 150.0;
  pose.headingDeg = 45.0, pose.pitchDeg = -6.0, pose.fovYDeg = 50.0, pose.width = kW, pose.height = kH;
  const CliffShadow r = cliffShadow(pose, "shadow_cliff");
  ASSERT_GT(r.geometric, 500) << "the cliff's shadow is in view";
  // The terrain's mesh draws the cliff's cell as a ramp over its vertices
  // (cells of ~115 m at its finest level) and the map's texels are ~3 m
  // here: the shadow's edge moves by up to 115 m / tan(6 deg) ~ 1 km only
  // where the ramp's top is cut, so 80 % agreement each way.
  EXPECT_GT(r.both, 0.8 * r.geometric);
  EXPECT_GT(r.both, 0.8 * r.drawn);
  // The default model removes the sun's direct light there: darker too.
  int darker = 0, n = 0;
  for (std::size_t i = 0; i < std::size_t(kW) * kH; ++i)
    if (grey(r.paper, i) < 0.6 * grey(r.none, i)) ++n, darker += grey(r.physical, i) < grey(r.none, i);
  EXPECT_GT(darker, 0.9 * n);
  // Looked at: the cliff's dark face and its shadow band over the sea to
  // the eye (the paper's model; the default's is faint, the sky's
  // reflection being most of the water's light at this grazing view).
  expectMatchesGolden(r.paper, "shadow_cliff_low_sun_paper", 2.0, 0.005);
}

// The same cliff BEHIND the eye: 150 m up, 1 km west of the plateau's top
// edge (its westmost 300 m cell centre, 6.5' west of 40 W), looking west (away from it and from the sun) down at the sea in its
// shadow. The casters are chosen from the map's region, not from the view's
// tiles (which hold none of the plateau): the shadow is drawn all the same.
TEST(Shadows, ACliffBehindTheEyeStillShadowsTheSeaInView) {
  ViewPose pose;
  pose.latDeg = 30.0, pose.lonDeg = -40.0 - 6.5 / 60.0 - 1000.0 / (111320.0 * std::cos(30.0 * 3.14159265358979 / 180.0));
  pose.altM = 150.0, pose.headingDeg = 260.0, pose.pitchDeg = -20.0, pose.fovYDeg = 50.0, pose.width = kW, pose.height = kH;
  const CliffShadow r = cliffShadow(pose, "shadow_cliff_behind", false);
  ASSERT_GT(r.geometric, 5000) << "the cliff's shadow is in view (the near third of the sea within reach)";
  // As above: 80 % agreement each way (the ramp of the cliff's cell).
  EXPECT_GT(r.both, 0.8 * r.geometric);
  EXPECT_GT(r.both, 0.8 * r.drawn);
}

}  // namespace
}  // namespace geocean::render::test
