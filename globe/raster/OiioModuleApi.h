// The C function table exported by the geocean_oiio module (the only code
// that links OpenImageIO). Internal; versioned so a stale module is refused.
#pragma once

#include <cstddef>

extern "C" {

#define GEOCEAN_OIIO_MODULE_ABI 1

struct GeoceanOiioInfo {
  int width, height, channels, depth, tileW, tileH;
  int kind;  // detail::SampleKind; 0 = other (read as float)
  char format[32];
};

struct GeoceanOiioApi {
  int abi;
  bool (*info)(const char* path, GeoceanOiioInfo* out, char* err, std::size_t errLen);
  // All channels, interleaved, as float (integers not normalised).
  bool (*readAll)(const char* path, float* out, char* err, std::size_t errLen);
  void* (*cacheCreate)(const char* path, double maxMemoryMB, char* err, std::size_t errLen);
  bool (*cacheRead)(void* cache, int x0, int x1, int y0, int y1, int channel, float* out, char* err,
                    std::size_t errLen);
  void (*cacheDestroy)(void* cache);
  bool (*write8)(const char* path, const unsigned char* data, int w, int h, int channels, char* err,
                 std::size_t errLen);
};

// The module's single exported symbol.
const GeoceanOiioApi* geocean_oiio_api(void);
}
