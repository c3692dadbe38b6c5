// Camera pose, rays and matrices, checked against geometry that does not go
// through the camera code: ENU frames from GeographicLib, the ellipsoid
// intersection, and the horizon distance sqrt(2 R h) of a sphere.
#include "globe/camera/Camera.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace geocean;
using camera::Camera;
using camera::ViewPose;

namespace {
void expectVecNear(const glm::dvec3& a, const glm::dvec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(Camera, PitchMinus90LooksStraightDownWithNorthUp) {
  const Camera c = Camera::fromGeodetic({45.0, 10.0, 500.0, 0.0, -90.0, 0.0}, 60.0, 800, 600);
  const geo::EnuFrame f = geo::enuFrame({45.0, 10.0, 500.0});
  expectVecNear(c.forward(), -f.up, 1e-15);  // rounding of unit vectors
  expectVecNear(c.up(), f.north, 1e-15);
  expectVecNear(c.right(), f.east, 1e-15);
  expectVecNear(c.eyeEcef(), f.originEcef, 1e-9);
  // The centre ray hits the sea 500 m below.
  const geo::RayHit h = geo::intersectEllipsoid(c.eyeEcef(), c.pixelRay(400.0, 300.0));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.tNear, 500.0, 1e-6);  // GeographicLib's 7 nm plus rounding
}

TEST(Camera, HeadingAndRoll) {
  const geo::EnuFrame f = geo::enuFrame({-30.0, 170.0, 10.0});
  const Camera east = Camera::fromGeodetic({-30.0, 170.0, 10.0, 90.0, 0.0, 0.0}, 60.0, 100, 100);
  expectVecNear(east.forward(), f.east, 1e-15);
  expectVecNear(east.up(), f.up, 1e-15);
  // Rolling 90 deg clockwise (right wing down): screen right points down.
  const Camera rolled = Camera::fromGeodetic({-30.0, 170.0, 10.0, 90.0, 0.0, 90.0}, 60.0, 100, 100);
  expectVecNear(rolled.forward(), f.east, 1e-15);
  expectVecNear(rolled.right(), -f.up, 1e-15);
  expectVecNear(rolled.up(), -f.north, 1e-15);  // screen up turns to the south
  // Pitch up 30 deg towards the north.
  const Camera north = Camera::fromGeodetic({-30.0, 170.0, 10.0, 0.0, 30.0, 0.0}, 60.0, 100, 100);
  expectVecNear(north.forward(), std::cos(M_PI / 6) * f.north + 0.5 * f.up, 1e-15);
}

TEST(Camera, PixelRaysAndProjectionAreInverse) {
  const Camera c = Camera::fromGeodetic({12.0, -45.0, 2000.0, 33.0, -20.0, 5.0}, 47.0, 1280, 720);
  for (double x : {0.0, 0.5, 640.0, 1279.5, 1280.0}) {
    for (double y : {0.0, 360.0, 719.5}) {
      const glm::dvec3 d = c.pixelRay(x, y);
      EXPECT_NEAR(glm::length(d), 1.0, 1e-15);
      const auto ndc = c.projectEyeRelative(d * 1234.5);
      ASSERT_TRUE(ndc.has_value());
      const glm::dvec2 want = c.pixelToNdc(x, y);
      EXPECT_NEAR(ndc->x, want.x, 1e-13);
      EXPECT_NEAR(ndc->y, want.y, 1e-13);
    }
  }
  // The corner rays span the field of view: angle between top and bottom
  // centre rays equals the vertical fov.
  const double ang = std::acos(glm::dot(c.pixelRay(640, 0), c.pixelRay(640, 720))) * 180.0 / M_PI;
  EXPECT_NEAR(ang, 47.0, 1e-9);
  EXPECT_FALSE(c.projectEyeRelative(-c.forward()).has_value());  // behind the eye
}

TEST(Camera, GpuMatricesMatchDoubleProjection) {
  const Camera c = Camera::fromGeodetic({60.0, 179.9, 300.0, 200.0, -10.0, 0.0}, 60.0, 640, 480);
  const glm::mat4 vp = c.projectionReversedZ() * c.viewRotation();
  for (double t : {1.0, 50.0, 3000.0}) {
    const glm::dvec3 rel = c.pixelRay(100, 400) * t;
    const glm::vec4 clip = vp * glm::vec4(glm::vec3(rel), 1.0f);
    const auto ndc = c.projectEyeRelative(rel);
    ASSERT_TRUE(ndc.has_value());
    // float matrices: relative error a few ulp of 1.
    EXPECT_NEAR(clip.x / clip.w, ndc->x, 1e-5);
    EXPECT_NEAR(clip.y / clip.w, ndc->y, 1e-5);
  }
  // Reversed Z: depth 1 at the near plane, 0 at the far plane, along the axis.
  const glm::mat4 p = c.projectionReversedZ();
  const glm::vec4 nearClip = p * glm::vec4(0, 0, -float(c.nearM()), 1);
  const glm::vec4 farClip = p * glm::vec4(0, 0, -float(c.farM()), 1);
  EXPECT_NEAR(nearClip.z / nearClip.w, 1.0, 1e-6);
  EXPECT_NEAR(farClip.z / farClip.w, 0.0, 1e-6);
}

TEST(Camera, ClipPlanesFromAltitude) {
  // Horizon distance of a sphere of radius a: sqrt(2 a h + h^2) (textbook).
  for (double h : {1.0, 100.0, 1e4, 1e6, 2e7}) {
    const Camera c = Camera::fromGeodetic({0.0, 0.0, h, 0.0, 0.0, 0.0}, 60.0, 100, 100);
    const double horizon = std::sqrt(2.0 * geo::kWgs84A * h + h * h);
    EXPECT_LT(c.nearM(), 0.5 * h) << h;  // the sea below is never clipped
    EXPECT_GT(c.farM(), horizon) << h;   // nor the sea at the horizon
    // Far/near stays within what reversed-Z float depth resolves (2^23 per octave).
    EXPECT_LT(c.farM() / c.nearM(), 1e9) << h;
  }
  const Camera low = Camera::fromGeodetic({0.0, 0.0, 1.0, 0.0, 0.0, 0.0}, 60.0, 100, 100);
  EXPECT_LE(low.nearM(), 0.1);
}

TEST(Camera, FromEcefMatchesGeodetic) {
  const Camera g = Camera::fromGeodetic({-70.0, 45.0, 1e5, 0.0, -90.0, 0.0}, 30.0, 64, 64);
  const Camera e = Camera::fromEcef(g.eyeEcef(), g.forward(), g.up(), 30.0, 64, 64);
  expectVecNear(e.right(), g.right(), 1e-15);
  expectVecNear(e.up(), g.up(), 1e-15);
  EXPECT_NEAR(e.heightM(), 1e5, 1e-6);  // GeographicLib inverse, 7 nm
}

TEST(Camera, BadInputNamesTheField) {
  try {
    Camera::fromGeodetic({}, 180.0, 10, 10);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field of view"), std::string::npos);
  }
  EXPECT_THROW(Camera::fromGeodetic({91.0, 0, 1, 0, 0, 0}, 60.0, 10, 10), std::invalid_argument);
  EXPECT_THROW(Camera::fromGeodetic({0, 0, NAN, 0, 0, 0}, 60.0, 10, 10), std::invalid_argument);
  EXPECT_THROW(Camera::fromGeodetic({}, 60.0, 0, 10), std::invalid_argument);
  EXPECT_THROW(Camera::fromEcef(glm::dvec3(7e6, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(2, 0, 0), 60, 10, 10),
               std::invalid_argument);
}
