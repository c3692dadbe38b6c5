#include "globe/raster/ImageIo.h"

#include "globe/raster/PixelSource.h"
#include "globe/raster/Raster.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

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

void writeImage8(const std::string& path, const unsigned char* pixels, int width, int height, int channels) {
  detail::oiioWrite8(path, pixels, width, height, channels);
}

}  // namespace geocean::raster
