#include "globe/raster/ImageIo.h"

#include "globe/raster/PixelSource.h"
#include "globe/raster/Raster.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace geocean::raster {

Image8 readImage8(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw RasterError(path + ": no such file");
  const bool tiff = detail::isTiff(path);
  const detail::ImageInfo info = tiff ? detail::tiffInfo(path) : detail::oiioInfo(path);
  if (info.width <= 0 || info.height <= 0 || info.channels <= 0 ||
      std::int64_t(info.width) * info.height * info.channels > (std::int64_t(1) << 32))
    throw RasterError(path + ": dimensions " + std::to_string(info.width) + " x " + std::to_string(info.height) +
                      " are not a valid image");
  const std::vector<float> f = (tiff && detail::tiffSupported(path)) ? detail::tiffReadAll(path, info)
                                                                     : detail::oiioReadAll(path, info);
  Image8 img{info.width, info.height, info.channels, std::vector<unsigned char>(f.size())};
  for (std::size_t i = 0; i < f.size(); ++i)
    img.pixels[i] = static_cast<unsigned char>(std::isnan(f[i]) ? 0.0f : std::clamp(std::round(f[i]), 0.0f, 255.0f));
  return img;
}

namespace {

// A PNG libpng writes as OpenImageIO would: no alpha, or an opaque one
// (OpenImageIO takes RGBA as premultiplied and divides the colour by a
// partial alpha; such images still go through it).
bool ownPng(const std::string& path, const unsigned char* pixels, int width, int height, int channels) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (e != ".png") return false;
  if (channels != 2 && channels != 4) return true;
  const std::size_t n = std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0));
  for (std::size_t i = 0; i < n; ++i)
    if (pixels[i * std::size_t(channels) + std::size_t(channels - 1)] != 255) return false;
  return true;
}

// libpng's part, with nothing but plain locals: its errors longjmp back
// here (no C++ destructor may be skipped), and the caller throws.
bool pngWrite(std::FILE* f, png_bytepp rows, int width, int height, int channels) {
  static const int kColourType[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                     PNG_COLOR_TYPE_RGB_ALPHA};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, kColourType[channels], PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);  // per row the one libpng's heuristic picks
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// 8-bit PNG through libpng (the renderer's frames). OpenImageIO is not
// loaded for it: its Debian build maps ~260 libraries, ~110 MB of a
// flight's resident memory (docs/PERFORMANCE.md).
void writePng(const std::string& path, const unsigned char* pixels, int width, int height, int channels) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
    throw RasterError(path + ": cannot write image (PNG needs 1-4 channels and a positive size, got " +
                      std::to_string(width) + " x " + std::to_string(height) + " x " + std::to_string(channels) + ")");
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[std::size_t(y)] = const_cast<png_bytep>(pixels + std::size_t(y) * std::size_t(width) * std::size_t(channels));
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw RasterError(path + ": cannot write image (" + std::strerror(errno) + ")");
  errno = 0;
  if (!pngWrite(f.get(), rows.data(), width, height, channels) || std::fflush(f.get()) != 0)
    throw RasterError(path + ": cannot write image (libpng or the disk failed" +
                      (errno ? std::string(": ") + std::strerror(errno) : std::string()) + ")");
}

}  // namespace

void writeImage8(const std::string& path, const unsigned char* pixels, int width, int height, int channels) {
  if (ownPng(path, pixels, width, height, channels)) return writePng(path, pixels, width, height, channels);
  detail::oiioWrite8(path, pixels, width, height, channels);
}

}  // namespace geocean::raster
