// The lat/lon kernel's two paths: with FMA (AVX2/AVX-512 CPUs) and without
// (surfaceLatLonBatchPortable, what CPUs without FMA run). They are not
// bit-identical; this pins how far apart they may be, and that the land/sea
// class of the grid's points does not depend on the path.
#include "plugin/grid/RayKernels.h"

#include "globe/camera/Camera.h"
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/World.h"
#include "plugin/landsea/LandSea.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace geocean;

namespace {
// Points of the ellipsoid as the grid passes them (eye-relative), from
// several cameras over coasts and from orbit, plus random surface points.
struct Points {
  double eye[3];
  std::vector<double> rx, ry, rz;
};

std::vector<Points> testPoints() {
  std::vector<Points> out;
  const camera::ViewPose poses[] = {{36.0, -6.5, 2000.0, 90.0, -20.0, 0.0},     // Gibraltar (bench camera)
                                {51.0, 1.5, 30000.0, 200.0, -45.0, 0.0},    // Dover strait
                                {-33.9, 18.4, 5e5, 0.0, -90.0, 0.0},        // Cape Town
                                {64.0, -22.0, 1e6, 0.0, -60.0, 0.0},        // Iceland
                                {0.0, 179.99, 2e7, 0.0, -90.0, 0.0},        // whole Earth at lon 180
                                {89.0, 30.0, 3e6, 180.0, -90.0, 0.0}};      // near the pole
  for (const camera::ViewPose& pose : poses) {
    const camera::Camera cam = camera::Camera::fromGeodetic(pose, 60.0, 1280, 720);
    Points p{{cam.eyeEcef().x, cam.eyeEcef().y, cam.eyeEcef().z}, {}, {}, {}};
    const glm::dvec3 F = cam.forward(), R = cam.right() * cam.tanHalfX(), U = cam.up() * cam.tanHalfY();
    const double Fa[3] = {F.x, F.y, F.z}, Ra[3] = {R.x, R.y, R.z}, Ua[3] = {U.x, U.y, U.z};
    constexpr std::size_t n = 400;
    std::vector<double> t(n), rx(n), ry(n), rz(n);
    for (int j = 0; j < 300; ++j) {
      grid::surfaceHitsRow(p.eye, Fa, Ra, Ua, -1.0, 2.0 / (n - 1), -1.0 + 2.0 * j / 299, n, t.data(), rx.data(),
                           ry.data(), rz.data());
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isnan(t[i])) p.rx.push_back(rx[i]), p.ry.push_back(ry[i]), p.rz.push_back(rz[i]);
    }
    out.push_back(std::move(p));
  }
  Points g{{-0.0, -0.0, -0.0}, {}, {}, {}};  // absolute ECEF points
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 500000; ++i) {
    const glm::dvec3 e = geo::toEcef({std::asin(u(rng)) * 180 / M_PI, 180 * u(rng), 0.0});
    g.rx.push_back(e.x), g.ry.push_back(e.y), g.rz.push_back(e.z);
  }
  out.push_back(std::move(g));
  return out;
}
}  // namespace

// Bound 6e-14 deg (2 ulp at 180 deg, 6 nm): FMA changes 7 roundings per
// vertex, each at most half an ulp of an intermediate below the result's
// magnitude; the measured maximum is printed as a test property.
TEST(LatLonPaths, FmaWithinTwoUlpOfPortable) {
  double worst = 0;
  std::size_t count = 0;
  for (const Points& p : testPoints()) {
    const std::size_t n = p.rx.size();
    std::vector<double> la1(n), lo1(n), la2(n), lo2(n);
    grid::surfaceLatLonBatch(p.eye, p.rx.data(), p.ry.data(), p.rz.data(), n, la1.data(), lo1.data());
    grid::surfaceLatLonBatchPortable(p.eye, p.rx.data(), p.ry.data(), p.rz.data(), n, la2.data(), lo2.data());
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_NEAR(la1[i], la2[i], 6e-14) << i;
      ASSERT_NEAR(lo1[i], lo2[i], 6e-14) << i;
      worst = std::max({worst, std::abs(la1[i] - la2[i]), std::abs(lo1[i] - lo2[i])});
    }
    count += n;
  }
  EXPECT_GT(count, 800000u);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", worst);
  RecordProperty("max_difference_deg", buf);
}

// The class the grid gives each vertex (world mask, 5') is the same on both
// paths for every test point.
TEST(LatLonPaths, SameLandSeaClass) {
  const auto mask = raster::Raster::open(raster::defaultWorld().mask);
  const ocean::LandSea ls(mask, nullptr);
  std::size_t land = 0, count = 0;
  for (const Points& p : testPoints()) {
    const std::size_t n = p.rx.size();
    std::vector<double> la1(n), lo1(n), la2(n), lo2(n);
    grid::surfaceLatLonBatch(p.eye, p.rx.data(), p.ry.data(), p.rz.data(), n, la1.data(), lo1.data());
    grid::surfaceLatLonBatchPortable(p.eye, p.rx.data(), p.ry.data(), p.rz.data(), n, la2.data(), lo2.data());
    std::vector<ocean::Surface> c1(n), c2(n);
    ls.classifyBatch(la1.data(), lo1.data(), n, c1.data());
    ls.classifyBatch(la2.data(), lo2.data(), n, c2.data());
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(c1[i], c2[i]) << la1[i] << " " << lo1[i];
      land += c1[i] == ocean::Surface::Land;
    }
    count += n;
  }
  // Both classes occur (the test is not all sea).
  EXPECT_GT(land, count / 10);
  EXPECT_LT(land, count / 2);
}
