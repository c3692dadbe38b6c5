// An offscreen render target: RGBA8 colour (sRGB-encoded values written by
// the shaders) and a 32-bit float depth buffer for reversed Z, optionally
// with a second RGBA32F attachment for data passes (picking, parity tests).
#pragma once

#include <epoxy/gl.h>

#include <cstdint>
#include <string>
#include <vector>

namespace geocean::gl {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // top row first
};

class Framebuffer {
 public:
  Framebuffer(int width, int height, bool withDataTarget = false);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  void bind() const;
  int width() const { return width_; }
  int height() const { return height_; }
  GLuint id() const { return fbo_; }

  // Colour as RGBA8, top row first.
  Image readColor() const;
  // The data attachment (RGBA32F), top row first; empty without one.
  std::vector<float> readData() const;

 private:
  int width_, height_;
  GLuint fbo_ = 0, color_ = 0, data_ = 0, depth_ = 0;
};

// A colour (RGBA8) + depth (DEPTH32F) target whose attachments are textures,
// so a later pass can sample them (reflections, scene copies).
class TextureTarget {
 public:
  TextureTarget() = default;
  ~TextureTarget();
  TextureTarget(const TextureTarget&) = delete;
  TextureTarget& operator=(const TextureTarget&) = delete;
  // (Re)allocates when the size changes.
  void ensure(int width, int height);
  GLuint fbo() const { return fbo_; }
  GLuint color() const { return color_; }
  GLuint depth() const { return depth_; }

 private:
  void release();
  GLuint fbo_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0;
};

// Writes an image as PNG through OpenImageIO; throws std::runtime_error
// naming the file when it cannot be written.
void writePng(const std::string& path, const Image& image);
// Reads a PNG/any OIIO format into RGBA8; throws naming the file.
Image readImage(const std::string& path);

}  // namespace geocean::gl
