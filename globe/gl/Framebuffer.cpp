#include "globe/gl/Framebuffer.h"

#include "globe/raster/ImageIo.h"
#include "globe/raster/Raster.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace geocean::gl {

Framebuffer::Framebuffer(int width, int height, bool withDataTarget) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw std::runtime_error("framebuffer size " + std::to_string(width) + "x" + std::to_string(height) +
                             " is out of range (1..16384)");
  glCreateFramebuffers(1, &fbo_);
  glCreateRenderbuffers(1, &color_);
  glNamedRenderbufferStorage(color_, GL_RGBA8, width, height);
  glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  if (withDataTarget) {
    glCreateRenderbuffers(1, &data_);
    glNamedRenderbufferStorage(data_, GL_RGBA32F, width, height);
    glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, data_);
    const GLenum bufs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo_, 2, bufs);
  }
  glCreateRenderbuffers(1, &depth_);
  glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, width, height);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("framebuffer incomplete (status 0x" + std::to_string(status) + ")");
}

Framebuffer::~Framebuffer() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &color_);
  if (data_) glDeleteRenderbuffers(1, &data_);
  glDeleteRenderbuffers(1, &depth_);
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
}

Image Framebuffer::readColor() const {
  Image img;
  img.width = width_;
  img.height = height_;
  std::vector<std::uint8_t> raw(std::size_t(width_) * height_ * 4);
  glNamedFramebufferReadBuffer(fbo_, GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  // GL's first row is the bottom one; images store the top row first.
  img.rgba.resize(raw.size());
  const std::size_t row = std::size_t(width_) * 4;
  for (int y = 0; y < height_; ++y)
    std::memcpy(img.rgba.data() + row * y, raw.data() + row * (height_ - 1 - y), row);
  return img;
}

std::vector<float> Framebuffer::readData() const {
  if (!data_) return {};
  std::vector<float> raw(std::size_t(width_) * height_ * 4), out(raw.size());
  glNamedFramebufferReadBuffer(fbo_, GL_COLOR_ATTACHMENT1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, raw.data());
  glNamedFramebufferReadBuffer(fbo_, GL_COLOR_ATTACHMENT0);
  const std::size_t row = std::size_t(width_) * 4;
  for (int y = 0; y < height_; ++y)
    std::memcpy(out.data() + row * y, raw.data() + row * (height_ - 1 - y), row * sizeof(float));
  return out;
}

void writePng(const std::string& path, const Image& image) {
  try {
    raster::writeImage8(path, image.rgba.data(), image.width, image.height, 4);
  } catch (const raster::RasterError& e) {
    throw std::runtime_error(std::string("cannot write image: ") + e.what());
  }
}

Image readImage(const std::string& path) {
  raster::Image8 in;
  try {
    in = raster::readImage8(path);
  } catch (const raster::RasterError& e) {
    throw std::runtime_error(std::string("cannot read image: ") + e.what());
  }
  Image img;
  img.width = in.width;
  img.height = in.height;
  img.rgba.assign(std::size_t(in.width) * in.height * 4, 255);
  const int nc = std::min(in.channels, 4);
  for (std::size_t i = 0; i < std::size_t(in.width) * in.height; ++i)
    for (int c = 0; c < 4; ++c)
      img.rgba[i * 4 + c] = c < nc ? in.pixels[i * in.channels + c] : (c == 3 ? 255 : in.pixels[i * in.channels]);
  return img;
}

TextureTarget::~TextureTarget() { release(); }

void TextureTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  const GLuint t[] = {color_, depth_};
  glDeleteTextures(2, t);
  fbo_ = color_ = depth_ = 0;
  width_ = height_ = 0;
}

void TextureTarget::ensure(int w, int h) {
  if (fbo_ && w == width_ && h == height_) return;
  release();
  glCreateTextures(GL_TEXTURE_2D, 1, &color_);
  glTextureStorage2D(color_, 1, GL_RGBA8, w, h);
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
  glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, w, h);
  for (GLuint t : {color_, depth_}) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
  glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
  if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("texture target " + std::to_string(w) + "x" + std::to_string(h) + " is incomplete");
  width_ = w;
  height_ = h;
}

}  // namespace geocean::gl
