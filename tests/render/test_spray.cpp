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
#include "RenderFixture.h"

#include "globe/camera/Camera.h"
#include "globe/geo/Ellipsoid.h"
#include "globe/gl/Framebuffer.h"
#include "globe/raster/Raster.h"
#include "globe/world/WorldData.h"
#include "plugin/ocean/Ocean.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace geocean::render::test {
namespace {

constexpr int kW = 400, kH = 800;
const raster::GeoTransform kPlace{-0.02, 0.34, 0.0001, -0.0001, false};
constexpr double kShoreLon = 0.005, kSlope = 0.02, kMPerDeg = 111320.0;

double depthAt(double lonDeg) { return std::max(1.0, std::min(200.0, -kSlope * (lonDeg - kShoreLon) * kMPerDeg)); }

struct Beach {
  std::shared_ptr<const world::WorldGrids> grids;
  std::shared_ptr<const WorldTextures> world;
  ocean::Ocean o;
  std::shared_ptr<const ocean::Snapshot> snap;
};

std::unique_ptr<Beach> makeBeach() {
  auto b = std::make_unique<Beach>();
  std::vector<float> elev(std::size_t(kW) * kH), land(std::size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const double eastOfShoreM = (-0.02 + (x + 0.5) * 0.0001 - kShoreLon) * kMPerDeg;
      elev[std::size_t(y) * kW + x] = float(std::max(-200.0, kSlope * eastOfShoreM));
      land[std::size_t(y) * kW + x] = eastOfShoreM > 0.0 ? 1.0f : 0.0f;
    }
  const auto elevation = raster::Raster::fromPixels(elev, kW, kH, 1, kPlace, std::nullopt, "beach");
  const auto mask = raster::Raster::fromPixels(land, kW, kH, 1, kPlace, std::nullopt, "beach_mask");
  b->o.setRasters(mask, elevation);
  waves::SeaState sea;
  sea.windSpeedMps = 10.0;
  sea.windFromDeg = 270.0;
  sea.anchorLatDeg = 0.3;
  b->o.setSeaState(waves::Model::Gerstner, sea);
  waves::CoastField::Region r;
  r.latDeg = 0.3, r.lonDeg = 0.0, r.cellM = 8.0, r.nodes = 501, r.islandRadiusM = 50.0;
  b->o.setCoastRegion(r);
  b->snap = b->o.current();
  b->grids = std::make_shared<const world::WorldGrids>(world::layerOf(*elevation, 0), world::waterLayerOf(*mask));
  std::vector<float> sand(std::size_t(kW) * kH * 3);
  for (std::size_t i = 0; i < sand.size(); i += 3) sand[i] = 194.0f, sand[i + 1] = 178.0f, sand[i + 2] = 128.0f;
  world::WorldData wd = world::loadDefaultWorld();
  wd.imagery = world::layerOf(*raster::Raster::fromPixels(sand, kW, kH, 3, kPlace, std::nullopt, "sand"));
  wd.elevation = world::layerOf(*elevation, 0);
  wd.water = world::waterLayerOf(*mask);
  b->world = std::make_shared<const WorldTextures>(wd);
  return b;
}

// Where the ray through a pixel's centre meets the ellipsoid (bisection on
// the geodetic height); false if it does not within 5 km.
bool seaPoint(const camera::Camera& cam, int x, int y, geo::Geodetic& out) {
  const glm::dvec3 eye = cam.eyeEcef(), ray = cam.pixelRay(x + 0.5, y + 0.5);
  double lo = 0.0, hi = 5000.0;
  if (geo::fromEcef(eye + hi * ray).heightM > 0.0) return false;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (geo::fromEcef(eye + mid * ray).heightM > 0.0 ? lo : hi) = mid;
  }
  out = geo::fromEcef(eye + hi * ray);
  return true;
}

}  // namespace

TEST(Spray, OnlyWhereTheWavesBreakNearTheEye) {
  session();
  const auto beach = makeBeach();
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
    ocean_render::OceanOptions oo;
    oo.model = waves::Model::Gerstner;
    oo.sea = snap->seaState;
    oo.coast = snap->waves->coastFieldShared();
    oo.coastBands = bands;
    const auto ocean = std::make_shared<ocean_render::OceanRenderer>(beach->grids, snap->landSea, oo);
    // 30 m up, offBreakM seaward of the break line, looking east at the shore.
    ViewPose p;
    p.latDeg = kLat, p.lonDeg = breakWestLon - offBreakM / kMPerDeg, p.altM = 30.0, p.headingDeg = 90.0,
    p.pitchDeg = -40.0;
    p.width = p.height = 384;
    GlobeRenderer renderer(beach->world);
    renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
    Framebuffer fb(p.width, p.height, true);
    fb.bind();
    FrameSettings fs;
    fs.sunEcef = sunForView(p, 150.0, 40.0);
    fs.timeS = timeS;
    ocean->setSpray(true);
    renderer.render(p, fs);
    const Image with = fb.readColor();
    ocean->setSpray(false);
    renderer.render(p, fs);
    const Image without = fb.readColor();
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

}  // namespace geocean::render::test
