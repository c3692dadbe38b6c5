#include "globe/raster/ImageIo.h"

#include "globe/raster/PixelSource.h"
#include "globe/raster/Raster.h"

#include <zlib.h>

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

// A PNG our writer makes as OpenImageIO would: no alpha, or an opaque one
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

void put32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<unsigned char>(v >> s));
}

void chunk(std::vector<unsigned char>& out, const char* type, const unsigned char* data, std::size_t n) {
  put32(out, std::uint32_t(n));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + n);
  put32(out, std::uint32_t(crc32(0L, out.data() + start, uInt(out.size() - start))));
}

// The Paeth predictor (PNG spec, section 9.4).
unsigned char paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return static_cast<unsigned char>(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// 8-bit PNG (ISO/IEC 15948) with zlib alone (the renderer's frames): each row takes the filter
// whose output has the least sum of absolute values (the spec's
// recommended heuristic, as libpng's), deflate at zlib's default level.
// OpenImageIO is not loaded for it: its Debian build maps ~260 libraries,
// ~110 MB of a flight's resident memory (docs/PERFORMANCE.md).
void writePng(const std::string& path, const unsigned char* pixels, int width, int height, int channels) {
  static const unsigned char kColourType[5] = {0, 0, 4, 2, 6};  // grey, grey + alpha, RGB, RGBA
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
    throw RasterError(path + ": cannot write image (PNG needs 1-4 channels and a positive size, got " +
                      std::to_string(width) + " x " + std::to_string(height) + " x " + std::to_string(channels) + ")");
  const std::size_t row = std::size_t(width) * std::size_t(channels);
  std::vector<unsigned char> filtered((row + 1) * std::size_t(height));
  std::vector<unsigned char> trial[5];
  for (auto& t : trial) t.resize(row);
  const std::vector<unsigned char> zero(row, 0);
  for (int y = 0; y < height; ++y) {
    const unsigned char* cur = pixels + std::size_t(y) * row;
    const unsigned char* up = y > 0 ? cur - row : zero.data();
    for (std::size_t i = 0; i < row; ++i) {
      const int a = i >= std::size_t(channels) ? cur[i - channels] : 0, b = up[i];
      const int c = i >= std::size_t(channels) ? up[i - channels] : 0;
      trial[0][i] = cur[i];
      trial[1][i] = static_cast<unsigned char>(cur[i] - a);
      trial[2][i] = static_cast<unsigned char>(cur[i] - b);
      trial[3][i] = static_cast<unsigned char>(cur[i] - ((a + b) >> 1));
      trial[4][i] = static_cast<unsigned char>(cur[i] - paeth(a, b, c));
    }
    int best = 0;
    std::uint64_t bestSum = ~std::uint64_t(0);
    for (int f = 0; f < 5; ++f) {
      std::uint64_t sum = 0;
      for (const unsigned char v : trial[f]) sum += std::uint64_t(std::abs(int(static_cast<signed char>(v))));
      if (sum < bestSum) bestSum = sum, best = f;
    }
    unsigned char* out = filtered.data() + std::size_t(y) * (row + 1);
    out[0] = static_cast<unsigned char>(best);
    std::memcpy(out + 1, trial[best].data(), row);
  }
  uLongf zn = compressBound(uLong(filtered.size()));
  std::vector<unsigned char> z(zn);
  if (compress2(z.data(), &zn, filtered.data(), uLong(filtered.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
    throw RasterError(path + ": cannot write image (deflate failed)");
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> ihdr;
  put32(ihdr, std::uint32_t(width));
  put32(ihdr, std::uint32_t(height));
  ihdr.insert(ihdr.end(), {8, kColourType[channels], 0, 0, 0});  // depth, colour type, deflate, adaptive filters, no interlace
  chunk(png, "IHDR", ihdr.data(), ihdr.size());
  chunk(png, "IDAT", z.data(), zn);
  chunk(png, "IEND", nullptr, 0);
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw RasterError(path + ": cannot write image (" + std::strerror(errno) + ")");
  if (std::fwrite(png.data(), 1, png.size(), f.get()) != png.size() || std::fflush(f.get()) != 0)
    throw RasterError(path + ": cannot write image (" + std::strerror(errno) + ")");
}

}  // namespace

void writeImage8(const std::string& path, const unsigned char* pixels, int width, int height, int channels) {
  if (ownPng(path, pixels, width, height, channels)) return writePng(path, pixels, width, height, channels);
  detail::oiioWrite8(path, pixels, width, height, channels);
}

}  // namespace geocean::raster
