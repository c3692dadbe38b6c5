#include "globe/render/WorldTextures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace geocean::render {

namespace {
glm::vec4 geoOf(const WorldLayer& l) {
  return {float(l.originLonDeg), float(l.originLatDeg), float(l.lonStepDeg * l.width),
          float(l.latStepDeg * l.height)};
}

void check(const WorldLayer& l, const char* what, int channels) {
  if (l.width <= 0 || l.height <= 0 || l.channels < channels ||
      l.values.size() != std::size_t(l.width) * l.height * l.channels)
    throw std::runtime_error(std::string("world layer '") + what + "' is empty or inconsistent (" +
                             std::to_string(l.width) + "x" + std::to_string(l.height) + "x" +
                             std::to_string(l.channels) + ")");
}

GLuint makeTexture(GLenum internal, int w, int h, bool mip) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  const int levels = mip ? 1 + int(std::floor(std::log2(std::max(w, h)))) : 1;
  glTextureStorage2D(t, levels, internal, w, h);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);  // longitude wraps
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, mip ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  return t;
}

float bilinear(const WorldLayer& l, double latDeg, double lonDeg) {
  double x = (lonDeg - l.originLonDeg) / l.lonStepDeg - 0.5;
  double y = (latDeg - l.originLatDeg) / l.latStepDeg - 0.5;
  x = std::fmod(x, double(l.width));
  if (x < 0) x += l.width;
  y = std::clamp(y, 0.0, double(l.height - 1));
  const int x0 = int(x), y0 = int(y);
  const int x1 = (x0 + 1) % l.width, y1 = std::min(y0 + 1, l.height - 1);
  const double fx = x - x0, fy = y - y0;
  auto v = [&](int xi, int yi) { return double(l.values[(std::size_t(yi) * l.width + xi) * l.channels]); };
  return float((v(x0, y0) * (1 - fx) + v(x1, y0) * fx) * (1 - fy) + (v(x0, y1) * (1 - fx) + v(x1, y1) * fx) * fy);
}
}  // namespace

WorldTextures::WorldTextures(const WorldData& data) {
  check(data.imagery, "imagery", 3);
  check(data.elevation, "elevation", 1);
  check(data.water, "water", 1);
  {
    const auto& l = data.imagery;
    std::vector<std::uint8_t> rgba(std::size_t(l.width) * l.height * 4);
    for (std::size_t i = 0; i < std::size_t(l.width) * l.height; ++i) {
      for (int c = 0; c < 3; ++c)
        rgba[i * 4 + c] = std::uint8_t(std::clamp(l.values[i * l.channels + c], 0.0f, 255.0f) + 0.5f);
      rgba[i * 4 + 3] = 255;
    }
    // sRGB storage: the GPU filters in linear light.
    imagery_ = makeTexture(GL_SRGB8_ALPHA8, l.width, l.height, true);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(imagery_, 0, 0, 0, l.width, l.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glGenerateTextureMipmap(imagery_);
    // No anisotropic filtering: llvmpipe's software path took 40 s for a
    // 64x64 frame looking at the horizon (trilinear costs ~0).
    imageryGeo_ = geoOf(l);
  }
  auto single = [](const WorldLayer& l, GLenum internal, bool mip) {
    std::vector<float> v(std::size_t(l.width) * l.height);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = l.values[i * l.channels];
    GLuint t = makeTexture(internal, l.width, l.height, mip);
    glTextureSubImage2D(t, 0, 0, 0, l.width, l.height, GL_RED, GL_FLOAT, v.data());
    if (mip) glGenerateTextureMipmap(t);
    return t;
  };
  elevation_ = single(data.elevation, GL_R32F, false);
  elevationGeo_ = geoOf(data.elevation);
  // Mipmapped so that far coasts average to partial coverage instead of aliasing.
  water_ = single(data.water, GL_R8, true);
  waterGeo_ = geoOf(data.water);
  elev_ = data.elevation;
  waterHost_ = data.water;
  waterIndex_ = WaterIndex(waterHost_);
  for (const WorldLayer* l : {&data.elevation, &data.water})
    for (const double step : {std::abs(l->lonStepDeg), std::abs(l->latStepDeg)})
      if (step > 0.0 && (finestShapeTexelDeg_ == 0.0 || step < finestShapeTexelDeg_)) finestShapeTexelDeg_ = step;
}

WorldTextures::~WorldTextures() {
  const GLuint t[] = {imagery_, elevation_, water_};
  glDeleteTextures(3, t);
}

void WorldTextures::bind() const {
  glBindTextureUnit(0, imagery_);
  glBindTextureUnit(1, elevation_);
  glBindTextureUnit(2, water_);
}

float WorldTextures::elevationAt(double latDeg, double lonDeg) const { return bilinear(elev_, latDeg, lonDeg); }
float WorldTextures::waterAt(double latDeg, double lonDeg) const { return bilinear(waterHost_, latDeg, lonDeg); }

}  // namespace geocean::render
