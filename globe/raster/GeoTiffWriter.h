// Writes tiled, compressed GeoTIFFs (libtiff) in geographic WGS84. Used by
// geocean-import-world to make data/, and by tests to make fixtures,
// including deliberately unsupported ones (projected CRS, rotated transform).
#pragma once

#include "globe/raster/Raster.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace geocean::raster {

enum class SampleType { U8, I16, F32 };
enum class Compression { None, Deflate, Jpeg };

struct GeoTiffWriteOptions {
  GeoTransform transform;        // pixel-area registration
  bool pixelIsPoint = false;     // write the tie point at the centre of pixel (0, 0)
  int tileSize = 256;            // 0: strips instead of tiles
  Compression compression = Compression::Deflate;
  int jpegQuality = 90;
  int deflateLevel = 6;          // 1 (fast) .. 9 (small)
  std::optional<double> nodata;  // GDAL_NODATA
  // Tiles whose every sample is nodata are not written (byte count 0,
  // GDAL's SPARSE_OK convention). Tiled writes with a nodata value only.
  bool sparse = false;
  // Test fixtures only: a projected CRS code (ProjectedCSTypeGeoKey) or a
  // rotation term in ModelTransformation.
  std::optional<int> projectedEpsg;
  double rotationTerm = 0.0;
  bool writeGeoKeys = true;
};

// `data` is row-major, north row first, channels interleaved. Throws
// RasterError naming the file on failure.
void writeGeoTiff(const std::string& path, const void* data, int width, int height, int channels,
                  SampleType type, const GeoTiffWriteOptions& options);

// Streaming form for rasters too big to hold: `fillTile(x0, y0, tile)` fills
// one tileSize x tileSize tile (row-major, channels interleaved) whose top-left
// pixel is (x0, y0). options.tileSize must be > 0.
void writeGeoTiffTiles(const std::string& path, int width, int height, int channels, SampleType type,
                       const GeoTiffWriteOptions& options,
                       const std::function<void(int x0, int y0, void* tile)>& fillTile);

}  // namespace geocean::raster
