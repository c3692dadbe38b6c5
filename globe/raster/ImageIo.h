// Plain 8-bit images (PNG output of the renderer, golden images, imagery
// import) without georeferencing. TIFF is read with libtiff and PNG written
// with libpng; other formats, and reading PNG, go through OpenImageIO, loaded
// on demand.
#pragma once

#include <string>
#include <vector>

namespace geocean::raster {

struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> pixels;  // row-major, top row first, channels interleaved
};

// Reads any supported image; samples are clamped to [0, 255] (no scaling).
// Throws RasterError naming the file.
Image8 readImage8(const std::string& path);

// Writes by extension (.png, .jpg, .tif, ...). Throws RasterError naming the file.
void writeImage8(const std::string& path, const unsigned char* pixels, int width, int height, int channels);

}  // namespace geocean::raster
