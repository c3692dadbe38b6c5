// Internal to geocean_raster: where pixels come from. Raster keeps
// OpenImageIO out of every process that only reads GeoTIFFs: TIFF files are
// decoded with libtiff (already needed for the GeoTIFF tags); OpenImageIO,
// whose Debian build pulls in ~260 libraries and costs ~0.25 s at process
// start, is loaded on demand (dlopen of the geocean_oiio module) for
// other formats (and big TIFFs whose layout or blocks libtiff's path does
// not take).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace geocean::raster::detail {

enum class SampleKind : int { U8 = 1, I8, U16, I16, U32, I32, F32, F64 };

inline std::size_t sampleBytes(SampleKind k) {
  switch (k) {
    case SampleKind::U8: case SampleKind::I8: return 1;
    case SampleKind::U16: case SampleKind::I16: return 2;
    case SampleKind::F64: return 8;
    default: return 4;
  }
}

template <class T>
void widenSamples(const void* src, std::size_t n, float* dst) {
  const T* s = static_cast<const T*>(src);
  for (std::size_t i = 0; i < n; ++i) dst[i] = static_cast<float>(s[i]);
}

// Widens native samples to float without normalisation (uint8 255 -> 255.0;
// OpenImageIO's own conversion would give 1.0).
inline void toFloat(SampleKind k, const void* src, std::size_t n, float* dst) {
  switch (k) {
    case SampleKind::U8: widenSamples<std::uint8_t>(src, n, dst); break;
    case SampleKind::I8: widenSamples<std::int8_t>(src, n, dst); break;
    case SampleKind::U16: widenSamples<std::uint16_t>(src, n, dst); break;
    case SampleKind::I16: widenSamples<std::int16_t>(src, n, dst); break;
    case SampleKind::U32: widenSamples<std::uint32_t>(src, n, dst); break;
    case SampleKind::I32: widenSamples<std::int32_t>(src, n, dst); break;
    case SampleKind::F32: widenSamples<float>(src, n, dst); break;
    case SampleKind::F64: widenSamples<double>(src, n, dst); break;
  }
}

struct ImageInfo {
  int width = 0, height = 0, channels = 0, depth = 1;
  int tileW = 0, tileH = 0;  // 0: not tiled
  int stripRows = 0;         // rows per strip of a TIFF that is not tiled
  SampleKind kind = SampleKind::F32;
  std::string format;        // "tiff", "png", ...
};

// Reads a rectangle [x0, x1) x [y0, y1) of one channel as float.
class TileSource {
 public:
  virtual ~TileSource() = default;
  virtual bool read(int x0, int x1, int y0, int y1, int channel, float* out) = 0;
  virtual std::string error() = 0;
  int tileW = 256, tileH = 256;
};

// ---- libtiff (in process) ----
bool isTiff(const std::string& path);
// Throws RasterError naming the file for corrupt headers.
ImageInfo tiffInfo(const std::string& path);
// True if libtiff can decode this layout here (contiguous planes, 8..64-bit
// samples, no palette); otherwise OpenImageIO is used.
bool tiffSupported(const std::string& path);
// Whole image, all channels interleaved, as float. Throws RasterError.
std::vector<float> tiffReadAll(const std::string& path, const ImageInfo& info);
// Whole image as the file's own samples (info.kind), all channels
// interleaved, row-major. Throws RasterError.
std::vector<std::uint8_t> tiffReadAllNative(const std::string& path, const ImageInfo& info);
// Direct block (tile or strip) reads through an LRU of decoded blocks in the
// file's sample type, bounded by cacheBytes (at least two blocks);
// thread-safe. Serves big TIFFs without OpenImageIO.
std::unique_ptr<TileSource> tiffTiles(const std::string& path, const ImageInfo& info, std::size_t cacheBytes);

// ---- OpenImageIO (loaded on demand) ----
ImageInfo oiioInfo(const std::string& path);  // throws RasterError
std::vector<float> oiioReadAll(const std::string& path, const ImageInfo& info);
std::unique_ptr<TileSource> oiioCache(const std::string& path, const ImageInfo& info, std::size_t cacheBytes);
// The same, made (and OpenImageIO loaded) on the first read; an error then
// is the read's (false, error()).
std::unique_ptr<TileSource> oiioCacheOnFirstRead(const std::string& path, const ImageInfo& info,
                                                 std::size_t cacheBytes);
void oiioWrite8(const std::string& path, const unsigned char* data, int width, int height, int channels);

}  // namespace geocean::raster::detail
