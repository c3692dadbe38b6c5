#include "globe/raster/GeoTiffWriter.h"

#include "globe/raster/GeoTiff.h"

#include <tiffio.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace geocean::raster {


namespace {
using TileFill = std::function<void(int, int, void*)>;

void write(const std::string& path, const void* data, const TileFill& fill, int width, int height, int channels,
           SampleType type, const GeoTiffWriteOptions& o) {
  detail::registerGeoTiffTags();
  TIFFSetWarningHandler(nullptr);
  TIFF* tif = TIFFOpen(path.c_str(), (std::size_t(width) * height * channels > (std::size_t(1) << 31)) ? "w8" : "w");
  if (!tif) throw RasterError(path + ": cannot create file");
  // Closed on every path: a tile callback may throw (geocean mask: GMT
  // failing mid-band), and the handle leaked (LeakSanitizer, MaskCli).
  struct Closer {
    TIFF*& t;
    ~Closer() {
      if (t) TIFFClose(t);
    }
  } closer{tif};
  const int bytesPerSample = type == SampleType::U8 ? 1 : type == SampleType::I16 ? 2 : 4;
  TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, uint32_t(width));
  TIFFSetField(tif, TIFFTAG_IMAGELENGTH, uint32_t(height));
  TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, uint16_t(channels));
  TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, uint16_t(8 * bytesPerSample));
  TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT,
               uint16_t(type == SampleType::F32 ? SAMPLEFORMAT_IEEEFP : type == SampleType::I16 ? SAMPLEFORMAT_INT : SAMPLEFORMAT_UINT));
  TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  const bool jpeg = o.compression == Compression::Jpeg;
  if (jpeg) {
    TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_JPEG);
    TIFFSetField(tif, TIFFTAG_JPEGQUALITY, o.jpegQuality);
    if (channels == 3) {
      TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_YCBCR);
      TIFFSetField(tif, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB);
    } else {
      TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    }
  } else {
    TIFFSetField(tif, TIFFTAG_COMPRESSION, o.compression == Compression::Deflate ? COMPRESSION_ADOBE_DEFLATE : COMPRESSION_NONE);
    if (o.compression == Compression::Deflate) {
      TIFFSetField(tif, TIFFTAG_PREDICTOR, type == SampleType::F32 ? 1 : 2);
      TIFFSetField(tif, TIFFTAG_ZIPQUALITY, o.deflateLevel);
    }
    TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, channels >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
  }

  // Georeferencing.
  const GeoTransform& t = o.transform;
  const double sx = t.lonStepDeg, sy = -t.latStepDeg;
  if (o.rotationTerm != 0.0) {
    const double m[16] = {sx, o.rotationTerm, 0, t.originLonDeg, 0, -sy, 0, t.originLatDeg, 0, 0, 0, 0, 0, 0, 0, 1};
    TIFFSetField(tif, 34264, 16, m);
  } else {
    const double scale[3] = {sx, sy, 0.0};
    const double shift = o.pixelIsPoint ? 0.5 : 0.0;
    const double tie[6] = {0, 0, 0, t.originLonDeg + shift * sx, t.originLatDeg - shift * sy, 0};
    TIFFSetField(tif, 33550, 3, scale);
    TIFFSetField(tif, 33922, 6, tie);
  }
  if (o.writeGeoKeys) {
    std::vector<uint16_t> keys = {1, 1, 0, 0};
    auto add = [&](uint16_t id, uint16_t v) { keys.insert(keys.end(), {id, 0, 1, v}); };
    if (o.projectedEpsg) {
      add(1024, 1);
      add(1025, uint16_t(o.pixelIsPoint ? 2 : 1));
      add(3072, uint16_t(*o.projectedEpsg));
    } else {
      add(1024, 2);
      add(1025, uint16_t(o.pixelIsPoint ? 2 : 1));
      add(2048, 4326);
      add(2054, 9102);
    }
    keys[3] = uint16_t((keys.size() - 4) / 4);
    TIFFSetField(tif, 34735, uint32_t(keys.size()), keys.data());
  }
  if (o.nodata) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", *o.nodata);
    TIFFSetField(tif, 42113, buf);
  }

  const auto* src = static_cast<const unsigned char*>(data);
  const std::size_t pixelBytes = std::size_t(bytesPerSample) * channels;
  bool ok = true;
  if (o.tileSize > 0) {
    const int ts = o.tileSize;
    TIFFSetField(tif, TIFFTAG_TILEWIDTH, uint32_t(ts));
    TIFFSetField(tif, TIFFTAG_TILELENGTH, uint32_t(ts));
    std::vector<unsigned char> tile(std::size_t(ts) * ts * pixelBytes), empty;
    if (o.sparse && o.nodata) {
      // One tile of nodata in the file's sample type: tiles equal to it are not written.
      empty.resize(tile.size());
      for (std::size_t i = 0; i < empty.size(); i += bytesPerSample) {
        if (type == SampleType::U8) empty[i] = static_cast<unsigned char>(*o.nodata);
        else if (type == SampleType::I16) { const auto v = static_cast<std::int16_t>(*o.nodata); std::memcpy(&empty[i], &v, 2); }
        else { const auto v = static_cast<float>(*o.nodata); std::memcpy(&empty[i], &v, 4); }
      }
    }
    for (int ty = 0; ty < height && ok; ty += ts)
      for (int tx = 0; tx < width && ok; tx += ts) {
        std::fill(tile.begin(), tile.end(), 0);
        if (fill) {
          fill(tx, ty, tile.data());
        } else {
          const int w = std::min(ts, width - tx), h = std::min(ts, height - ty);
          for (int y = 0; y < h; ++y)
            std::memcpy(&tile[std::size_t(y) * ts * pixelBytes], src + (std::size_t(ty + y) * width + tx) * pixelBytes,
                        std::size_t(w) * pixelBytes);
        }
        if (!empty.empty() && tile == empty) continue;
        ok = TIFFWriteTile(tif, tile.data(), uint32_t(tx), uint32_t(ty), 0, 0) >= 0;
      }
  } else {
    TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, uint32_t(jpeg ? 16 : 64));
    std::vector<unsigned char> row(std::size_t(width) * pixelBytes);
    for (int y = 0; y < height && ok; ++y) {
      std::memcpy(row.data(), src + std::size_t(y) * width * pixelBytes, row.size());
      ok = TIFFWriteScanline(tif, row.data(), uint32_t(y), 0) >= 0;
    }
  }
  TIFFClose(tif);
  tif = nullptr;
  if (!ok) throw RasterError(path + ": writing pixel data failed (disk full?)");
}
}  // namespace

void writeGeoTiff(const std::string& path, const void* data, int width, int height, int channels, SampleType type,
                  const GeoTiffWriteOptions& o) {
  write(path, data, {}, width, height, channels, type, o);
}

void writeGeoTiffTiles(const std::string& path, int width, int height, int channels, SampleType type,
                       const GeoTiffWriteOptions& o, const std::function<void(int, int, void*)>& fillTile) {
  if (o.tileSize <= 0) throw RasterError(path + ": streaming write needs tileSize > 0");
  write(path, nullptr, fillTile, width, height, channels, type, o);
}

}  // namespace geocean::raster
