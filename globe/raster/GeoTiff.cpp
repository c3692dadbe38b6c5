#include "globe/raster/GeoTiff.h"

#include <tiffio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

namespace geocean::raster::detail {

namespace {
constexpr ttag_t kModelPixelScale = 33550;
constexpr ttag_t kModelTiepoint = 33922;
constexpr ttag_t kModelTransformation = 34264;
constexpr ttag_t kGeoKeyDirectory = 34735;
constexpr ttag_t kGdalNodata = 42113;

// GeoKey ids (GeoTIFF 1.1, OGC 19-008r4).
constexpr int kGTModelType = 1024;       // 1 projected, 2 geographic, 3 geocentric
constexpr int kGTRasterType = 1025;      // 1 PixelIsArea, 2 PixelIsPoint
constexpr int kGeographicType = 2048;    // EPSG geographic CRS code
constexpr int kGeogGeodeticDatum = 2050; // EPSG datum code
constexpr int kGeogAngularUnits = 2054;  // 9102 = degree
constexpr int kProjectedCSType = 3072;
constexpr int kUserDefined = 32767;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// libtiff reports through global handlers; keep them quiet, errors are ours.
void silenceLibtiff() {
  static std::once_flag once;
  std::call_once(once, [] {
    TIFFSetWarningHandler(nullptr);
    TIFFSetErrorHandler(nullptr);
  });
}

TIFFExtendProc gParentExtender = nullptr;

void extendWithGeoTags(TIFF* tif) {
  // TIFF_VARIABLE2: counts are passed as uint32_t.
  static const TIFFFieldInfo info[] = {
      {kModelPixelScale, TIFF_VARIABLE2, TIFF_VARIABLE2, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, const_cast<char*>("ModelPixelScaleTag")},
      {kModelTiepoint, TIFF_VARIABLE2, TIFF_VARIABLE2, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, const_cast<char*>("ModelTiepointTag")},
      {kModelTransformation, TIFF_VARIABLE2, TIFF_VARIABLE2, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, const_cast<char*>("ModelTransformationTag")},
      {kGeoKeyDirectory, TIFF_VARIABLE2, TIFF_VARIABLE2, TIFF_SHORT, FIELD_CUSTOM, 1, 1, const_cast<char*>("GeoKeyDirectoryTag")},
      {kGdalNodata, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, const_cast<char*>("GDAL_NODATA")},
  };
  TIFFMergeFieldInfo(tif, info, sizeof(info) / sizeof(info[0]));
  if (gParentExtender) gParentExtender(tif);
}
}  // namespace

void registerGeoTiffTags() {
  static std::once_flag once;
  std::call_once(once, [] { gParentExtender = TIFFSetTagExtender(extendWithGeoTags); });
}

TiffGeoref readTiffGeoref(const std::string& path, int width, int height) {
  silenceLibtiff();
  registerGeoTiffTags();
  TIFF* tif = TIFFOpen(path.c_str(), "r");
  if (!tif) throw RasterError(path + ": not a readable TIFF file (libtiff could not parse the header)");
  struct Closer {
    TIFF* t;
    ~Closer() { TIFFClose(t); }
  } closer{tif};

  TiffGeoref out;
  // GeoKeys: validate the CRS before using any transform.
  uint16_t rasterType = 1;
  {
    uint32_t count = 0;
    uint16_t* keys = nullptr;
    if (TIFFGetField(tif, kGeoKeyDirectory, &count, &keys) && keys && count >= 4) {
      const int n = keys[3];
      if (4 + 4 * n > static_cast<int>(count))
        throw RasterError(path + ": GeoKeyDirectory is truncated (" + std::to_string(n) + " keys declared, " +
                          std::to_string(count) + " values present)");
      for (int i = 0; i < n; ++i) {
        const int id = keys[4 + 4 * i], loc = keys[5 + 4 * i], value = keys[7 + 4 * i];
        if (loc != 0) continue;  // value stored in another tag: only ascii/double params, not needed
        switch (id) {
          case kGTModelType:
            if (value == 1) throw RasterError(path + ": GeoKey GTModelTypeGeoKey = 1 (projected CRS) is not supported; reproject to geographic WGS84 (EPSG:4326)");
            if (value == 3) throw RasterError(path + ": GeoKey GTModelTypeGeoKey = 3 (geocentric) is not supported; use geographic WGS84 (EPSG:4326)");
            break;
          case kProjectedCSType:
            throw RasterError(path + ": GeoKey ProjectedCSTypeGeoKey = " + std::to_string(value) +
                              " (projected CRS, e.g. UTM) is not supported; reproject to geographic WGS84 (EPSG:4326)");
          case kGTRasterType:
            if (value != 1 && value != 2)
              throw RasterError(path + ": GeoKey GTRasterTypeGeoKey = " + std::to_string(value) + " is not PixelIsArea (1) or PixelIsPoint (2)");
            rasterType = static_cast<uint16_t>(value);
            break;
          case kGeographicType:
            if (value != 4326 && value != kUserDefined)
              throw RasterError(path + ": GeoKey GeographicTypeGeoKey = EPSG:" + std::to_string(value) +
                                " is not supported; only WGS84 (EPSG:4326)");
            break;
          case kGeogGeodeticDatum:
            if (value != 6326 && value != kUserDefined)
              throw RasterError(path + ": GeoKey GeogGeodeticDatumGeoKey = " + std::to_string(value) + " is not WGS84 (6326)");
            break;
          case kGeogAngularUnits:
            if (value != 9102)
              throw RasterError(path + ": GeoKey GeogAngularUnitsGeoKey = " + std::to_string(value) + " is not degrees (9102)");
            break;
          default:
            break;
        }
      }
    }
  }

  uint32_t nScale = 0, nTie = 0, nXform = 0;
  double *scale = nullptr, *tie = nullptr, *xform = nullptr;
  const bool haveScale = TIFFGetField(tif, kModelPixelScale, &nScale, &scale) && scale && nScale >= 2;
  const bool haveTie = TIFFGetField(tif, kModelTiepoint, &nTie, &tie) && tie && nTie >= 6;
  const bool haveXform = TIFFGetField(tif, kModelTransformation, &nXform, &xform) && xform && nXform >= 16;

  double sx = 0, sy = 0, i0 = 0, j0 = 0, x0 = 0, y0 = 0;
  if (haveXform) {
    if (xform[1] != 0.0 || xform[4] != 0.0)
      throw RasterError(path + ": ModelTransformation is rotated or sheared (terms " + fmt("%g", xform[1]) + ", " +
                        fmt("%g", xform[4]) + "); only north-up rasters are supported");
    sx = xform[0];
    sy = -xform[5];
    x0 = xform[3];
    y0 = xform[7];
  } else if (haveScale && haveTie) {
    if (nTie > 6) throw RasterError(path + ": ModelTiepoint has " + std::to_string(nTie / 6) + " tie points (warped rasters are not supported)");
    sx = scale[0];
    sy = scale[1];
    i0 = tie[0];
    j0 = tie[1];
    x0 = tie[3];
    y0 = tie[4];
  } else {
    // Plain TIFF: nodata may still be there; georeferencing is the caller's.
  }

  if (haveXform || (haveScale && haveTie)) {
    if (!(std::isfinite(sx) && sx > 0.0))
      throw RasterError(path + ": ModelPixelScale x = " + fmt("%g", sx) + " is not a positive pixel size");
    if (!(std::isfinite(sy) && sy != 0.0))
      throw RasterError(path + ": ModelPixelScale y = " + fmt("%g", sy) + " is not a valid pixel size");
    if (!std::isfinite(x0) || !std::isfinite(y0))
      throw RasterError(path + ": ModelTiepoint is not finite");
    // PixelIsPoint: raster coordinate (i, j) is a pixel centre, so the
    // pixel-space point (i + 0.5, j + 0.5) maps to (x0, y0).
    const double shift = rasterType == 2 ? 0.5 : 0.0;
    GeoTransform t;
    t.lonStepDeg = sx;
    t.latStepDeg = -sy;
    t.originLonDeg = x0 - (i0 + shift) * sx;
    t.originLatDeg = y0 + (j0 + shift) * sy;
    double south = 0.0, north = 0.0;
    if (!t.rowsWithinPoles(height, south, north))
      throw RasterError(path + ": latitude range [" + fmt("%g", south) + ", " + fmt("%g", north) +
                        "] is outside [-90, 90]: the raster is not in geographic degrees (projected CRS without GeoKeys?)");
    t.global = std::abs(width * sx - 360.0) < 1e-6 * 360.0;
    out.transform = t;
  }

  char* nod = nullptr;
  if (TIFFGetField(tif, kGdalNodata, &nod) && nod) {
    char* end = nullptr;
    const double v = std::strtod(nod, &end);
    if (end == nod) throw RasterError(path + ": GDAL_NODATA = '" + std::string(nod) + "' is not a number");
    out.nodata = v;
  }
  return out;
}

std::optional<GeoTransform> readWorldFile(const std::string& imagePath) {
  namespace fs = std::filesystem;
  const fs::path p(imagePath);
  std::string ext = p.extension().string();
  std::vector<std::string> candidates;
  if (ext.size() >= 3) {
    // .jpg -> .jgw, .png -> .pgw, .tif -> .tfw; also .jpgw and .wld.
    candidates.push_back(std::string(".") + ext[1] + ext.back() + "w");
    candidates.push_back(ext + "w");
  }
  candidates.push_back(".wld");
  for (const auto& c : candidates) {
    fs::path w = p;
    w.replace_extension(c);
    std::ifstream f(w);
    if (!f) continue;
    double v[6];
    for (int i = 0; i < 6; ++i)
      if (!(f >> v[i])) throw RasterError(w.string() + ": world file line " + std::to_string(i + 1) + " is not a number");
    if (v[1] != 0.0 || v[2] != 0.0)
      throw RasterError(w.string() + ": world file rotation terms (" + fmt("%g", v[1]) + ", " + fmt("%g", v[2]) +
                        ") are not zero; only north-up rasters are supported");
    if (!(v[0] > 0.0) || !(v[3] != 0.0) || !std::isfinite(v[0]) || !std::isfinite(v[3]) || !std::isfinite(v[4]) ||
        !std::isfinite(v[5]))
      throw RasterError(w.string() + ": world file pixel size (" + fmt("%g", v[0]) + ", " + fmt("%g", v[3]) + ") is invalid");
    GeoTransform t;
    t.lonStepDeg = v[0];
    t.latStepDeg = v[3];
    // World files give the centre of the upper-left pixel.
    t.originLonDeg = v[4] - 0.5 * v[0];
    t.originLatDeg = v[5] - 0.5 * v[3];
    return t;
  }
  return std::nullopt;
}

}  // namespace geocean::raster::detail
