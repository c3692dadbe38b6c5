#include "globe/gl/Texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace geocean::gl {

GLuint createGeoTexture(GLenum internal, int w, int h, bool mip) {
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

GLuint redGeoTexture(const float* values, int channels, int w, int h, GLenum internal, bool mip) {
  std::vector<float> v(std::size_t(w) * h);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = values[i * channels];
  GLuint t = createGeoTexture(internal, w, h, mip);
  glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RED, GL_FLOAT, v.data());
  if (mip) glGenerateTextureMipmap(t);
  return t;
}

GLuint srgbGeoTexture(const float* values, int channels, int w, int h) {
  std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4);
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    for (int c = 0; c < 3; ++c)
      rgba[i * 4 + c] = std::uint8_t(std::clamp(values[i * channels + c], 0.0f, 255.0f) + 0.5f);
    rgba[i * 4 + 3] = 255;
  }
  // sRGB storage: the GPU filters in linear light.
  GLuint t = createGeoTexture(GL_SRGB8_ALPHA8, w, h, true);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glGenerateTextureMipmap(t);
  // No anisotropic filtering: llvmpipe's software path took 40 s for a
  // 64x64 frame looking at the horizon (trilinear costs ~0).
  return t;
}

}  // namespace geocean::gl
