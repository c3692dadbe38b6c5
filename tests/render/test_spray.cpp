// Issue 15 item 4: the near band's breaking spray (paper 003; Spray.h,
// shaders/spray.vert). The 1:50 spilling beach of test_coast_bands.cpp
// (U10 10 m/s onto the shore), seen from 30 m looking at the shore across
// the break line. The spray's pixels are those that differ between the
// frame with it and without it (the same time: everything else is equal).
// Each such pixel's ray meets the sea level at a point; the cluster drawn
// there flies at most v0^2 / 2g = 1.23 m above a surface within the waves'
// reach, so its ground point is within (1.23 + reach) / tan(depression)
// + its own size of that point: the test asks that point to be at most that
// far from where the CPU's breaking field (WaveField::breakingFoamMean, the
// phase average of the kernel's wv_breakingFoam) is non-zero. Over deep
// water (the lattice 2 km off the break line) no pixel may differ, and with
// the bands off (OceanOptions::coastBands false) there is no spray at all.
#include "CoastScene.h"
#include "RenderFixture.h"

#include "globe/gl/Framebuffer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace geocean::render::test {
namespace {

constexpr double kShoreLon = kSpillingShoreLon, kSlope = kSpillingSlope, kMPerDeg = 111320.0;

double depthAt(double lonDeg) { return std::max(1.0, std::min(200.0, -kSlope * (lonDeg - kShoreLon) * kMPerDeg)); }

// The frame with the spray and without it, at the spray's sun.
std::pair<Image, Image> withAndWithoutSpray(GlobeRenderer& renderer, ocean_render::OceanRenderer& ocean,
                                            const ViewPose& p, double timeS) {
  Framebuffer fb(p.width, p.height, true);
  fb.bind();
  FrameSettings fs;
  fs.sunEcef = sunForView(p, 150.0, 40.0);
  fs.timeS = timeS;
  ocean.setSpray(true);
  renderer.render(p, fs);
  Image with = fb.readColor();
  ocean.setSpray(false);
  renderer.render(p, fs);
  return {std::move(with), fb.readColor()};
}

// The spray's pixels in views from poses (those that differ between the
// frame with it and without it), written as <name>_<i>.png for looking at.
std::vector<std::vector<bool>> sprayPixels(const CoastScene& scene, const std::vector<ViewPose>& poses, double timeS,
                                           const std::string& name) {
  const auto ocean = std::make_shared<ocean_render::OceanRenderer>(scene.grids, scene.snap->landSea, scene.options());
  GlobeRenderer renderer(scene.world);
  renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
  std::vector<std::vector<bool>> out;
  for (const ViewPose& p : poses) {
    const auto [with, without] = withAndWithoutSpray(renderer, *ocean, p, timeS);
    gl::writePng(::testing::TempDir() + "/" + name + "_" + std::to_string(out.size()) + ".png", with);
    std::vector<bool> px(std::size_t(p.width) * p.height);
    Image mask = with;  // the spray's pixels red (looked at)
    for (std::size_t i = 0; i < px.size(); ++i)
      if ((px[i] = std::memcmp(&with.rgba[i * 4], &without.rgba[i * 4], 3) != 0))
        mask.rgba[i * 4] = 255, mask.rgba[i * 4 + 1] = mask.rgba[i * 4 + 2] = 0;
    gl::writePng(::testing::TempDir() + "/" + name + "_" + std::to_string(out.size()) + "_mask.png", mask);
    out.push_back(std::move(px));
  }
  return out;
}

}  // namespace

TEST(Spray, OnlyWhereTheWavesBreakNearTheEye) {
  session();
  const auto beach = spillingBeach();
  const auto& snap = beach->snap;
  ASSERT_NE(snap->waves->coastField(), nullptr);
  // The breaking zone across the beach at the view's latitude: the CPU's
  // phase-averaged breaking foam, every 2 m from 1.5 km off the shore.
  constexpr double kLat = 0.3;
  double breakWestLon = 1e9;
  for (double m = 1500.0; m >= 0.0; m -= 2.0) {
    const double lon = kShoreLon - m / kMPerDeg;
    if (snap->waves->breakingFoamMean(kLat, lon, 30.0, depthAt(lon)).foam > 0.0) {
      breakWestLon = lon;
      break;
    }
  }
  ASSERT_LT(breakWestLon, kShoreLon) << "the coast field breaks no wave on the beach";
  const double breakWidthM = (kShoreLon - breakWestLon) * kMPerDeg;
  std::printf("breaking from %.0f m off the shore (depth %.2f m)\n", breakWidthM, depthAt(breakWestLon));

  auto render = [&](bool bands, double offBreakM, double timeS, const std::string& name, int& sprayPx, int& outsidePx) {
    ocean_render::OceanOptions oo = beach->options();
    oo.coastBands = bands;
    const auto ocean = std::make_shared<ocean_render::OceanRenderer>(beach->grids, snap->landSea, oo);
    // 30 m up, offBreakM seaward of the break line, looking east at the shore.
    ViewPose p;
    p.latDeg = kLat, p.lonDeg = breakWestLon - offBreakM / kMPerDeg, p.altM = 30.0, p.headingDeg = 90.0,
    p.pitchDeg = -40.0;
    p.width = p.height = 384;
    GlobeRenderer renderer(beach->world);
    renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
    const auto [with, without] = withAndWithoutSpray(renderer, *ocean, p, timeS);
    gl::writePng(::testing::TempDir() + "/spray_" + name + ".png", with);
    const camera::Camera cam = camera::Camera::fromView(p);
    sprayPx = outsidePx = 0;
    double worstM = -1e9;
    Image mask = with;  // the spray's pixels red over the frame without it (looked at)
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const std::size_t i = (std::size_t(y) * p.width + x) * 4;
        if (std::memcmp(&with.rgba[i], &without.rgba[i], 3) == 0) continue;
        ++sprayPx;
        mask.rgba[i] = 255, mask.rgba[i + 1] = mask.rgba[i + 2] = 0;
        geo::Geodetic g;
        if (!seaPoint(cam, x, y, g)) {
          ++outsidePx;
          continue;
        }
        // The ray's slope there: a height h above the sea moves the ground
        // point by h / tan(depression) along the view.
        const glm::dvec3 ray = cam.pixelRay(x + 0.5, y + 0.5);
        const double sinDep = -glm::dot(ray, geo::surfaceNormal(g.latDeg, g.lonDeg));
        const double tanDep = sinDep / std::sqrt(std::max(1e-9, 1.0 - sinDep * sinDep));
        // 1.23 m of flight + 3 m for the surface there (spray is drawn only
        // where waves break, whose crests the cap keeps under 0.39 h, h <= 6 m
        // at the break line: 2.3 m) + a 0.6 m cluster. Measured: every spray
        // pixel 34 m or more inside this bound.
        const double slackM = (1.23 + 3.0) / tanDep + 0.6;
        const double seawardM = (breakWestLon - g.lonDeg) * kMPerDeg;  // > 0: beyond the break line
        worstM = std::max(worstM, seawardM - slackM);
        if (seawardM > slackM) ++outsidePx;
      }
    gl::writePng(::testing::TempDir() + "/spray_" + name + "_mask.png", mask);
    std::printf("%s: %d spray pixels, %d beyond the break line (worst %.1f m past its slack)\n", name.c_str(), sprayPx,
                outsidePx, worstM);
  };
  int spray = 0, outside = 0;
  // The surf zone 10 .. 110 m ahead, open water nearer.
  render(true, 40.0, 30.0, "break", spray, outside);
  EXPECT_GT(spray, 200) << "no spray over the breaking waves";
  EXPECT_EQ(outside, 0) << "spray seaward of the breaking";
  int spray2 = 0, outside2 = 0;
  render(true, 40.0, 31.7, "break2", spray2, outside2);
  EXPECT_GT(spray2, 200);
  EXPECT_EQ(outside2, 0);
  // Deep water: 2 km off the break line (40 m deep), the lattice all sea.
  int deep = 0, deepOut = 0;
  render(true, 2000.0, 30.0, "deep", deep, deepOut);
  EXPECT_EQ(deep, 0) << "spray over deep water";
  // The bands off: no spray drawn (the toggle changes nothing).
  int off = 0, offOut = 0;
  render(false, 40.0, 30.0, "bands_off", off, offOut);
  EXPECT_EQ(off, 0) << "spray with the coast bands off";
}

// The spray's seed is continuous across 180 degrees: the 1:50 beach with
// its surf zone 40 .. 340 m ahead of an eye on the meridian, at 0 and at
// 180 degrees (the same rasters and coast region shifted), each seen from
// 1 cm west and 1 cm east of its meridian. At 180 the nadir's longitude
// wraps from +180 to -180 between the two frames (at 0 nothing wraps):
// the same sites must throw the same clusters, so the two frames' spray
// pixels are nearly one set (overlap: shared over either's), as at 0.
TEST(Spray, SeedIsContinuousAcrossTheAntimeridian) {
  session();
  const double aheadDeg = 340.0 / kMPerDeg;  // the shore east of the eye
  auto overlapAt = [&](double meridian, const std::string& name) {
    waves::CoastField::Region r;
    r.latDeg = 0.3, r.lonDeg = meridian, r.cellM = 8.0, r.nodes = 501, r.islandRadiusM = 50.0;
    const auto scene = makeCoastScene(
        straightBeach(400, 800, {meridian - 0.02, 0.34, 0.0001, -0.0001, false}, meridian + aheadDeg, kSlope), r);
    std::vector<ViewPose> poses;
    for (double side : {-1.0, 1.0}) {
      ViewPose p;
      const double lon = meridian + side * 1e-7;  // 1.1 cm
      p.latDeg = 0.3, p.lonDeg = lon > 180.0 ? lon - 360.0 : lon, p.altM = 30.0, p.headingDeg = 90.0, p.pitchDeg = -40.0;
      p.width = p.height = 256;
      poses.push_back(p);
    }
    const auto px = sprayPixels(*scene, poses, 30.0, "spray_meridian_" + name);
    int both = 0, either = 0;
    for (std::size_t i = 0; i < px[0].size(); ++i) both += px[0][i] && px[1][i], either += px[0][i] || px[1][i];
    std::printf("%s: %d and %d spray pixels, %d in either frame, %d in both (overlap %.3f)\n", name.c_str(),
                int(std::count(px[0].begin(), px[0].end(), true)), int(std::count(px[1].begin(), px[1].end(), true)),
                either, both, double(both) / std::max(either, 1));
    EXPECT_GT(either, 100) << name << ": no spray in view";
    return double(both) / std::max(either, 1);
  };
  const double at0 = overlapAt(0.0, "0"), at180 = overlapAt(180.0, "180");
  EXPECT_GT(at0, 0.8);
  EXPECT_GT(at180, at0 - 0.1) << "the spray changes where the nadir's longitude wraps";
}

}  // namespace geocean::render::test
