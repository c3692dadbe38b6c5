// One headless session with the default world for all renderer tests (the
// world upload costs about a second; GL tests must stay fast).
#pragma once

#include "globe/render/Session.h"
#include "tests/render/DirectOcean.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace geocean::render {
using camera::ViewPose;
using gl::Framebuffer;
using gl::Image;
using gl::GlProgram;
using gl::ShaderError;
using gl::readImage;
using world::loadDefaultWorld;
}  // namespace geocean::render

namespace geocean::render::test {

// The default world with the default ocean (noise waves, 10 m/s wind).
Session& session();
// The ocean layer of session().
ocean_render::OceanRenderer& sessionOcean();

// The session's ocean layer (its phongExponent).
DirectOceanLayer& directLayer();
// Draws `ocean` instead of the session's own until the guard goes (null:
// back to the default ocean).
void useOcean(std::shared_ptr<ocean_render::OceanRenderer> ocean);
// An ocean on the session's world and default land/sea with other options
// (a sea state, a model), for useOcean.
std::shared_ptr<ocean_render::OceanRenderer> sessionOceanWith(const ocean_render::OceanOptions& options);
// Puts the session's own ocean back when it goes.
struct OceanGuard {
  ~OceanGuard() { useOcean(nullptr); }
};

// Image difference in 8-bit units over RGB.
struct ImageDiff {
  double mean = 0.0;
  int max = 0;
  double fractionOver16 = 0.0;  // share of pixels with any channel off by > 16
};
ImageDiff compare(const Image& a, const Image& b);

// Compares with tests/render/golden/<name>.png; GEOCEAN_UPDATE_GOLDEN=1
// rewrites the golden instead (look at it before committing).
void expectMatchesGolden(const Image& img, const std::string& name, double maxMean, double maxFractionOver16);

// Pixel (x, y) of the image projected from an ECEF point, or false if behind.
bool projectToPixel(const camera::Camera& cam, const ViewPose& pose, const glm::dvec3& ecef, double& x, double& y);

}  // namespace geocean::render::test
