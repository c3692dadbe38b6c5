// Boats in the picture (issue 14 item 5): boats simulated by the plugin
// through ABI 1.4 and drawn by the host are drawn at their poses (the
// depth of a boat's pixels is a point of that boat's hull at the pose the
// ABI gives) and float on the queried sea (keel under, deck over the
// surface geocean_query_sea_surface gives there). Golden, looked at:
// tests/render/golden/boats_chase.png (the chased boat, blue, from behind
// and above, its hull under the waterline hidden by the sea; the other
// boats further off, white, green, blue, on a 12 m/s Gerstner sea with
// its Jacobian whitecaps and their decaying trails, shaders/foam.glsl).
#include "globe/geo/Ellipsoid.h"
#include "globe/gl/Framebuffer.h"
#include "globe/host/Boats.h"
#include "globe/render/Session.h"
#include "globe/world/WorldData.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace geocean;

struct Scene {
  render::Session s;
  std::shared_ptr<host::PluginOceanLayer> ocean;
  std::shared_ptr<host::PluginBoats> boats;
};

// The boats as the renderer sees them, with a switch that leaves them out
// of the mirrored pass only (the reflection test draws both ways).
class MirrorSwitch final : public render::SceneObject {
 public:
  explicit MirrorSwitch(std::shared_ptr<render::SceneObject> inner) : inner_(std::move(inner)) {}
  void update(double timeS) override { inner_->update(timeS); }
  void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
            const camera::Camera* mirroredFrom) override {
    if (mirroredFrom && !inMirror) return;
    inner_->draw(cam, light, bare, mirroredFrom);
  }
  bool inMirror = true;

 private:
  std::shared_ptr<render::SceneObject> inner_;
};
MirrorSwitch* gMirror = nullptr;

// Mid-Atlantic, 8 boats, a 12 m/s Gerstner sea, 320 x 200 with the data
// attachment (the boats write their eye-relative position there, w = 2).
Scene& scene() {
  static Scene* sc = [] {
    setenv("GEOCEAN_PLUGIN", GEOCEAN_PLUGIN_BUILD_PATH, 0);  // the build's plugin, as the CLI finds it beside itself
    auto* x = new Scene;
    x->s = render::Session::headless(world::loadDefaultWorld(), 320, 200);
    x->s.target = std::make_unique<gl::Framebuffer>(320, 200, true);
    const std::string err = host::addPluginOcean(*x->s.renderer, "gerstner", 12.0, 270.0, &x->ocean);
    EXPECT_EQ(err, "");
    std::string e2;
    x->boats = host::PluginBoats::spawn(x->ocean, 8, 30.0, -40.0, 1u, e2);
    EXPECT_NE(x->boats, nullptr) << e2;
    if (x->boats) {
      auto sw = std::make_shared<MirrorSwitch>(x->boats);
      gMirror = sw.get();
      x->s.renderer->addSceneObject(sw);
    }
    return x;
  }();
  return *sc;
}

glm::dvec3 vec(const double* v) { return {v[0], v[1], v[2]}; }
glm::dquat quat(const double* q) { return {q[0], q[1], q[2], q[3]}; }

TEST(RenderBoats, ABoatsPixelsAreItsHullAtThePoseAndItFloatsOnTheQueriedSea) {
  Scene& sc = scene();
  ASSERT_NE(sc.boats, nullptr);
  ASSERT_EQ(sc.boats->count(), 8u);
  const double t = 12.0;
  sc.boats->update(t);
  camera::ViewPose base;
  base.width = 320, base.height = 200, base.fovYDeg = 50.0;
  const camera::ViewPose pose = sc.boats->chase(0, base);
  render::FrameSettings fs;
  fs.timeS = t;
  fs.sunEcef = render::sunForView(pose, 120.0, 40.0);
  sc.s.render(pose, fs);
  const std::vector<float> data = sc.s.target->readData();
  const gl::Image img = sc.s.image();
  const camera::Camera cam = sc.s.renderer->camera(pose);
  const geocean_body_pose p = sc.boats->poses()[0];
  const glm::dvec3 com = vec(p.position_ecef_m);
  const glm::dquat q = quat(p.orientation_wxyz);

  // The hull's bounds in body axes, through the ABI.
  const auto& api = sc.ocean->plugin().api();
  size_t nv = 0, ni = 0;
  ASSERT_EQ(api.bodiesGetHull(sc.boats->bodies(), p.id, nullptr, 0, nullptr, 0, &nv, &ni), GEOCEAN_OK);
  std::vector<double> v(3 * nv);
  std::vector<uint32_t> idx(ni);
  ASSERT_EQ(api.bodiesGetHull(sc.boats->bodies(), p.id, v.data(), nv, idx.data(), ni, &nv, &ni), GEOCEAN_OK);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (size_t i = 0; i < nv; ++i) lo = glm::min(lo, vec(&v[3 * i])), hi = glm::max(hi, vec(&v[3 * i]));
  EXPECT_NEAR(hi.x - lo.x, sc.boats->lengthM(0), 1e-9);

  // Every boat-marked pixel within 40 px of the boat's centre is a point of
  // its hull at the ABI's pose: inside the bounds to 2 cm (float
  // eye-relative positions at ~60 m keep ~10 um; rasterisation puts a
  // pixel's sample on the triangle's plane, so the margin is rounding only).
  const glm::dvec4 c = cam.gpu().viewProjD * glm::dvec4(com - cam.eyeEcef(), 1.0);
  ASSERT_GT(c.w, 0.0);
  const int cx = int((c.x / c.w * 0.5 + 0.5) * 320), cy = int((c.y / c.w * 0.5 + 0.5) * 200);  // bottom-up
  int boatPx = 0, outside = 0;
  for (int y = std::max(0, cy - 40); y < std::min(200, cy + 40); ++y)
    for (int x = std::max(0, cx - 40); x < std::min(320, cx + 40); ++x) {
      const float* d = &data[(std::size_t(199 - y) * 320 + x) * 4];  // readData: top row first
      if (d[3] != 2.0f) continue;
      ++boatPx;
      const glm::dvec3 world = cam.eyeEcef() + glm::dvec3(d[0], d[1], d[2]);
      const glm::dvec3 b = glm::conjugate(q) * (world - com);
      const bool in = glm::all(glm::greaterThanEqual(b, lo - 0.02)) && glm::all(glm::lessThanEqual(b, hi + 0.02));
      if (!in) ++outside;
    }
  EXPECT_GT(boatPx, 200) << "the chased boat covers a good part of the view's centre";
  EXPECT_EQ(outside, 0) << "of " << boatPx << " boat pixels";

  // It floats on the surface the plugin gives at that place and time:
  // the keel is under it and the deck above it (upright: |roll|, |pitch|
  // small, so the hull's z bounds bracket the sea at the centre).
  double sea = 0;
  uint8_t cls = 0;
  ASSERT_EQ(api.querySeaSurface(sc.ocean->ocean(), 1, &p.lat_deg, &p.lon_deg, t, &sea, nullptr, &cls), GEOCEAN_OK);
  EXPECT_EQ(cls, GEOCEAN_SURFACE_OCEAN);
  EXPECT_LT(p.height_m + lo.z, sea);
  EXPECT_GT(p.height_m + hi.z, sea);
  // And so does every boat.
  for (const auto& o : sc.boats->poses()) {
    double h = 0;
    ASSERT_EQ(api.querySeaSurface(sc.ocean->ocean(), 1, &o.lat_deg, &o.lon_deg, t, &h, nullptr, nullptr), GEOCEAN_OK);
    EXPECT_LT(std::abs(o.height_m - h), 3.0) << o.id;  // within a draft of 30 m boats' depth L/8
  }

  // The picture, looked at.
  const std::string golden = std::string(GEOCEAN_GOLDEN_DIR) + "/boats_chase.png";
  const std::string actual = ::testing::TempDir() + "/boats_chase.actual.png";
  gl::writePng(actual, img);
  if (std::getenv("GEOCEAN_UPDATE_GOLDEN")) {
    gl::writePng(golden, img);
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden;
  const gl::Image g = gl::readImage(golden);
  ASSERT_EQ(g.rgba.size(), img.rgba.size());
  // The margins of the other goldens (test_render.cpp: another Mesa build
  // rounds shading differently): mean under 2 of 255, 0.5 % of pixels > 16 off.
  double sum = 0;
  std::size_t over = 0;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4) {
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
      const int dlt = std::abs(int(img.rgba[i + k]) - int(g.rgba[i + k]));
      sum += dlt;
      worst = std::max(worst, dlt);
    }
    if (worst > 16) ++over;
  }
  const double n = double(img.rgba.size() / 4);
  EXPECT_LE(sum / (3 * n), 2.0) << actual;
  EXPECT_LE(over / n, 0.005) << actual;
}

// The sea reflects the boats (issue 14 item 5: "meshes that the ocean's
// foam and reflections see"): the host draws them again in the mirrored
// pass. From 3 L astern of boat 1 and 0.25 L above the sea, looking at it
// (looked at: the dark streaks under the hull, flecks on near wave faces),
// the picture is drawn with the boats in the mirrored pass and without
// them there: the main pass (so the hulls and the refraction's scene copy)
// is the same, so every pixel that differs is the reflection. They are sea
// pixels, and they lie under the hull in the picture, in its columns.
TEST(RenderBoats, TheSeaReflectsTheBoatsUnderTheirHulls) {
  Scene& sc = scene();
  ASSERT_NE(sc.boats, nullptr);
  ASSERT_NE(gMirror, nullptr);
  const double t = 12.0;
  sc.boats->update(t);
  const geocean_body_pose p = sc.boats->poses()[0];
  const double L = sc.boats->lengthM(0);
  camera::ViewPose base;
  base.width = 320, base.height = 200, base.fovYDeg = 40.0;
  camera::ViewPose pose = sc.boats->chase(0, base);  // astern, looking along the bow
  const geo::EnuFrame f = geo::enuFrame({p.lat_deg, p.lon_deg, 0.0});
  const double h = std::sin(pose.headingDeg * std::numbers::pi / 180.0),
               c = std::cos(pose.headingDeg * std::numbers::pi / 180.0);
  const geo::Geodetic eye =
      geo::fromEcef(vec(p.position_ecef_m) + f.toEcef(glm::dvec3(-3.0 * L * h, -3.0 * L * c, 0.0)) + 0.25 * L * f.up);
  pose.latDeg = eye.latDeg, pose.lonDeg = eye.lonDeg, pose.altM = eye.heightM;
  pose.pitchDeg = -std::atan2(0.25 * L, 3.0 * L) * 180.0 / std::numbers::pi;
  render::FrameSettings fs;
  fs.timeS = t;
  fs.sunEcef = render::sunForView(pose, 120.0, 40.0);
  ASSERT_TRUE(fs.reflections);
  gMirror->inMirror = true;
  sc.s.render(pose, fs);
  const gl::Image with = sc.s.image();
  const std::vector<float> data = sc.s.target->readData();
  gMirror->inMirror = false;
  sc.s.render(pose, fs);
  const gl::Image without = sc.s.image();
  gMirror->inMirror = true;
  if (const char* dir = std::getenv("GEOCEAN_DUMP_DIR")) {
    gl::writePng(std::string(dir) + "/boats_reflected.png", with);
    gl::writePng(std::string(dir) + "/boats_not_reflected.png", without);
  }
  // The boat's pixels (data w = 2) and the pixels that differ (top row first).
  int hull = 0, hx0 = 320, hx1 = -1;
  double hy = 0.0;
  int changed = 0, onHull = 0, under = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 320; ++x) {
      if (data[(std::size_t(y) * 320 + x) * 4 + 3] == 2.0f && std::abs(x - 160) < 40 && std::abs(y - 100) < 30)
        ++hull, hx0 = std::min(hx0, x), hx1 = std::max(hx1, x), hy += y;
    }
  ASSERT_GT(hull, 50) << "boat 1 in the middle of the picture";
  hy /= hull;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 320; ++x) {
      const std::size_t i = std::size_t(y) * 320 + x;
      int d = 0;
      for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(with.rgba[4 * i + k]) - int(without.rgba[4 * i + k])));
      if (d == 0) continue;
      ++changed;
      onHull += data[4 * i + 3] == 2.0f;
      under += x >= hx0 - 10 && x <= hx1 + 10 && y > hy;
    }
  std::printf("[ measured ] hull %d px (columns %d-%d), reflection %d px, %d of them under it, %d on a hull\n",
              hull, hx0, hx1, changed, under, onHull);
  EXPECT_GT(changed, hull / 10) << "the sea reflects the boat";
  EXPECT_EQ(onHull, 0) << "the reflection is on the water, never on a hull";
  // The rest: the other boats' reflections, and the stern's in the wave
  // face behind it (above its centre in the picture).
  EXPECT_GE(under, changed * 7 / 10) << "under the hull, in its columns (10 px margin)";
}

TEST(RenderBoats, TheCliRefusesAFollowBeyondTheBoatsAndBoatsWithoutTheOcean) {
  const std::string exe = GEOCEAN_EXE;
  const std::string out = ::testing::TempDir() + "/boats_bad.png";
  auto run = [&](const std::string& args) {
    const std::string cmd = exe + " render --size 64x64 --out " + out + " " + args + " 2>&1";
    FILE* f = popen(cmd.c_str(), "r");
    std::string text;
    char buf[512];
    while (f && fgets(buf, sizeof buf, f)) text += buf;
    const int rc = f ? pclose(f) : -1;
    return std::make_pair(WEXITSTATUS(rc), text);
  };
  auto [rc1, t1] = run("--boats 3 --follow 4");
  EXPECT_EQ(rc1, 2);
  EXPECT_NE(t1.find("--follow 4 is not a boat of --boats 3 (1..3)"), std::string::npos) << t1;
  auto [rc2, t2] = run("--boats 3 --no-ocean");
  EXPECT_EQ(rc2, 2);
  EXPECT_NE(t2.find("--boats needs the ocean"), std::string::npos) << t2;
  auto [rc3, t3] = run("--boats -1");
  EXPECT_EQ(rc3, 2);
  EXPECT_NE(t3.find("--boats -1 is not in 0..10000"), std::string::npos) << t3;
}


// The chased boat's pixels in a picture: boat 3 of the viewer's spawn
// (seed 1) is the yellow one (palette {0.90, 0.70, 0.10}: red and green
// well above blue; sea, foam and sky are grey to blue). Returns the count
// and the centroid (x right, y down, pixels).
struct Blob {
  int n = 0;
  double x = 0, y = 0;
};
Blob yellowPixels(const gl::Image& img) {
  Blob b;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = &img.rgba[(std::size_t(y) * img.width + x) * 4];
      if (int(p[0]) > int(p[2]) + 60 && int(p[1]) > int(p[2]) + 40) ++b.n, b.x += x, b.y += y;
    }
  if (b.n) b.x /= b.n, b.y /= b.n;
  return b;
}

// `fly --follow I`, `render --follow I` and `view --follow I` (issue 14 item 5): the camera
// chases boat I, 3 L behind and 1.2 L above its centre of mass, looking at
// it, so the boat stays at the picture's centre while it moves (its engine
// drives it some metres over the flight) and the camera keeps its height
// above the boat. Without the chase the flight looks at the target from
// orbit and no boat is near the centre (the test can fail).
TEST(RenderBoats, FlyAndViewFollowKeepTheChasedBoatAtThePictureCentre) {
  Scene& sc = scene();  // the same spawn (seed 1, around 30, -40): boat 3's length
  ASSERT_NE(sc.boats, nullptr);
  const double L = sc.boats->lengthM(2);
  const std::string dir = ::testing::TempDir() + "/boats_follow";
  std::filesystem::remove_all(dir);
  const auto r = geocean::test::run(std::string(GEOCEAN_EXE) +
                                    " fly --to 30,-40 --boats 3 --follow 3 --frames 4 --fps 0.1 --size 200x120"
                                    " --waves gerstner --out " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream csv(dir + "/timings.csv");
  std::string line;
  std::getline(csv, line);  // header: frame,time_s,lat,lon,alt_m,...
  std::vector<std::array<double, 3>> cam;
  while (std::getline(csv, line)) {
    std::stringstream ss(line);
    std::string f[5];
    for (auto& x : f) std::getline(ss, x, ',');
    cam.push_back({std::stod(f[2]), std::stod(f[3]), std::stod(f[4])});
  }
  ASSERT_EQ(cam.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/frame_%05d.png", i);
    const gl::Image img = gl::readImage(dir + name);
    const Blob b = yellowPixels(img);
    // About 190 pixels (0.8 % of the picture) at 3 L; its centroid near the centre (the
    // deck above the centre of mass, the hull under the waterline hidden:
    // a few pixels up), within a tenth of the width and height.
    EXPECT_GT(b.n, 80) << name;
    EXPECT_NEAR(b.x, 100.0, 20.0) << name;
    EXPECT_NEAR(b.y, 60.0, 12.0) << name;
    // The camera 1.2 L above the centre of mass, which floats within a
    // metre of the sea (a draft of L/8 at most, waves of ~1 m).
    EXPECT_NEAR(cam[i][2], 1.2 * L, 2.0) << name;
  }
  // And the boat went somewhere: the camera moved with it (metres, locally).
  const double dn = (cam[3][0] - cam[0][0]) * 111'000.0;
  const double de = (cam[3][1] - cam[0][1]) * 111'000.0 * std::cos(30.0 * M_PI / 180.0);
  EXPECT_GT(std::hypot(dn, de), 5.0);

  // `render --follow 3`: one frame, the camera given by --camera (3 km up)
  // replaced by the chase; without --follow no boat is in sight.
  for (const bool follow : {true, false}) {
    const std::string png = dir + (follow ? "/render_follow.png" : "/render_nofollow.png");
    const auto rr = geocean::test::run(std::string(GEOCEAN_EXE) + " render --camera 30,-40,3000,0,-60 --boats 3" +
                                       (follow ? " --follow 3" : "") +
                                       " --time 10 --waves gerstner --size 200x120 --out " + png);
    ASSERT_EQ(rr.exitCode, 0) << rr.err;
    const Blob b = yellowPixels(gl::readImage(png));
    if (!follow) {
      EXPECT_LT(b.n, 5) << "from 3 km the boats are specks";
      continue;
    }
    EXPECT_GT(b.n, 80);
    EXPECT_NEAR(b.x, 100.0, 20.0);
    EXPECT_NEAR(b.y, 60.0, 12.0);
  }

  // `view --follow 3` in a window (GLFW under Xvfb), its last frame.
  if (!geocean::test::haveTool("xvfb-run")) {
    std::printf("view --follow not checked: xvfb-run is not installed (Debian xvfb, xauth)\n");
    return;
  }
  const std::string shot = dir + "/view.png";
  const auto v = geocean::test::run("xvfb-run -a -s '-screen 0 640x480x24' " + std::string(GEOCEAN_EXE) +
                                    " view --fly-to 30,-40 --boats 3 --follow 3 --frames 30 --size 200x120 --no-hud"
                                    " --screenshot " + shot);
  ASSERT_EQ(v.exitCode, 0) << v.err;
  const Blob b = yellowPixels(gl::readImage(shot));
  EXPECT_GT(b.n, 80);
  EXPECT_NEAR(b.x, 100.0, 20.0);
  EXPECT_NEAR(b.y, 60.0, 12.0);
}

// The F key (issue 14 item 5: "key and option"): a user in the window taps
// F once (xdotool, as a user would) and the camera chases boat 1 (F cycles
// off, 1, 2, 3; one tap, since taps closer than a frame count once and an
// ASan build draws a frame in about half a second). The view flies down from
// orbit over 100,000 frames, so without the key the camera is still
// 20,000 km up when Escape ends the run; with it, the last frame sits 1.2 L
// above boat 1.
TEST(RenderBoats, TheFKeyInTheWindowStartsTheChase) {
  if (!geocean::test::haveTool("xvfb-run") || !geocean::test::haveTool("xdotool")) {
    std::printf("F key not checked: needs xvfb-run and xdotool (Debian xvfb, xauth, xdotool)\n");
    return;
  }
  Scene& sc = scene();  // the same spawn as the view: boat 1's length
  ASSERT_NE(sc.boats, nullptr);
  const double L = sc.boats->lengthM(0);
  const std::string dir = ::testing::TempDir() + "/boats_fkey";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // Keys after the window is up and drawing (search --sync waits for it, at
  // most 2 minutes: a view that fails to open must not hang the test);
  // sticky keys keep each tap for the next poll. Escape once the window's
  // title (the HUD on one line) shows an altitude in metres: the flight is
  // still above 10 km, so that frame is the chase's (a fixed 3 s wait was
  // too short for one frame on a loaded machine).
  const std::string script =
      std::string(GEOCEAN_EXE) + " view --fly-to 30,-40 --boats 3 --frames 100000 --size 200x120 --no-hud --stats " +
      dir + "/stats.csv & v=$!; "
      "timeout 120 xdotool search --sync --onlyvisible --name Geocean >/dev/null; sleep 2; "
      "xdotool key f; timeout 120 xdotool search --sync --name \"alt +[0-9.]+ m \" >/dev/null; sleep 1; "
      "xdotool key Escape; wait $v";
  const auto r = geocean::test::run("xvfb-run -a -s '-screen 0 640x480x24' sh -c '" + script + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream csv(dir + "/stats.csv");
  std::string line;
  std::getline(csv, line);  // frame,wall_s,lat,lon,alt_m,...
  std::vector<double> alt;
  while (std::getline(csv, line)) {
    std::stringstream ss(line);
    std::string f[5];
    for (auto& x : f) std::getline(ss, x, ',');
    alt.push_back(std::stod(f[4]));
  }
  ASSERT_GT(alt.size(), 10u);
  EXPECT_GT(alt.front(), 1e5) << "the flight starts in orbit";
  // The last frame chases boat 1 as --follow 1 would (the test above: 3).
  EXPECT_NEAR(alt.back(), 1.2 * L, 2.0) << alt.size() << " frames";
}

}  // namespace

// The ocean's foam sees the boats (issue 14 item 5, shaders/wake.glsl): the
// plugin's draw takes the bodies of every body set on the ocean, so a boat
// driven through the ABI (a set of its own, 5 km from the scene's boats)
// leaves foam behind it along its track and none ahead. Straight down from
// 150 m over it (0.59 m a pixel), foam pixels (red over 170, as SeaOptics
// counts whitecaps) are counted in the wedge of half angle 25 degrees from
// 5 to 60 m behind its stern, and in the same wedge mirrored ahead of its
// bow: the 12 m/s sea's whitecaps (1.8 % cover, Monahan) fall in both alike.
TEST(RenderBoats, TheSeaFoamsInTheWakeOfABoatUnderWayAndNotAheadOfIt) {
  Scene& sc = scene();
  ASSERT_NE(sc.boats, nullptr);
  const auto& api = sc.ocean->plugin().api();
  geocean_bodies* set = nullptr;
  ASSERT_EQ(api.bodiesCreate(sc.ocean->ocean(), nullptr, &set), GEOCEAN_OK) << api.lastError();
  geocean_body_desc d;
  api.bodyDescInit(&d);
  d.hull = GEOCEAN_HULL_BOAT;
  d.size_m[0] = 20.0;
  d.density_kg_m3 = 450.0;
  d.lat_deg = 30.05, d.lon_deg = -40.0, d.heading_deg = 40.0;
  d.thrust_n = 6.0e4;
  geocean_body_id id = 0;
  ASSERT_EQ(api.bodiesAdd(set, &d, &id), GEOCEAN_OK) << api.lastError();
  const double t = 60.0;
  ASSERT_EQ(api.bodiesAdvanceTo(set, t, nullptr), GEOCEAN_OK);
  sc.boats->update(t);
  geocean_body_pose b{};
  size_t n = 0;
  ASSERT_EQ(api.bodiesGetPoses(set, 1, &b, 1, &n), GEOCEAN_OK);
  const geo::EnuFrame f = geo::enuFrame({b.lat_deg, b.lon_deg, 0.0});
  const glm::dvec3 vEnu = f.toLocal(vec(b.velocity_ecef_mps));
  const double speed = glm::length(glm::dvec2(vEnu)), L = d.size_m[0];
  ASSERT_GT(speed, 4.0) << "under way: Froude number over 0.28, its bow wave breaking";
  camera::ViewPose pose;
  pose.latDeg = b.lat_deg, pose.lonDeg = b.lon_deg, pose.altM = 150.0;
  pose.headingDeg = 0.0, pose.pitchDeg = -90.0, pose.width = pose.height = 256, pose.fovYDeg = 60.0;
  render::FrameSettings fs;
  fs.timeS = t;
  fs.sunEcef = render::sunForView(pose, 200.0, 15.0);
  sc.s.render(pose, fs);
  const gl::Image img = sc.s.image();
  api.bodiesDestroy(set);
  if (const char* dir = std::getenv("GEOCEAN_DUMP_DIR")) gl::writePng(std::string(dir) + "/boat_wake.png", img);
  const camera::Camera cam = sc.s.renderer->camera(pose);
  const glm::dvec2 track = glm::normalize(glm::dvec2(vEnu));
  const double tanY = std::tan(0.5 * pose.fovYDeg * std::numbers::pi / 180.0);
  const double tanWedge = std::tan(25.0 * std::numbers::pi / 180.0);
  int behind = 0, ahead = 0, area = 0;
  for (int y = 0; y < pose.height; ++y)
    for (int x = 0; x < pose.width; ++x) {
      const double nx = (2.0 * (x + 0.5) / pose.width - 1.0) * tanY, ny = (1.0 - 2.0 * (y + 0.5) / pose.height) * tanY;
      const glm::dvec3 ray = glm::normalize(cam.forward() + cam.right() * nx + cam.up() * ny);
      const double s = glm::dot(f.originEcef - cam.eyeEcef(), f.up) / glm::dot(ray, f.up);
      const glm::dvec3 g = f.toLocal(cam.eyeEcef() + s * ray - f.originEcef);
      const double along = glm::dot(glm::dvec2(g), track), across = std::abs(glm::dot(glm::dvec2(g), {track.y, -track.x}));
      const double back = -along - 0.5 * L, front = along - 0.5 * L;  // beyond the stern / the bow
      const bool foam = img.rgba[(std::size_t(y) * pose.width + x) * 4] > 170;
      if (back > 5.0 && back < 60.0 && across < back * tanWedge) behind += foam, ++area;
      if (front > 5.0 && front < 60.0 && across < front * tanWedge) ahead += foam;
    }
  std::printf("boat L %.0f m at %.1f m/s: foam pixels %d behind, %d ahead, of %d in each wedge\n", L, speed, behind,
              ahead, area);
  EXPECT_GT(behind, area / 10) << "foam on over 10 % of the wedge behind";
  EXPECT_LT(ahead, behind / 5);
}
