// GeoTIFF georeferencing read with libtiff (Debian's OpenImageIO exposes none
// of these tags). Internal to geocean_raster.
#pragma once

#include "globe/raster/Raster.h"

#include <optional>
#include <string>

namespace geocean::raster::detail {

struct TiffGeoref {
  std::optional<GeoTransform> transform;  // empty when the file has no georeferencing
  std::optional<double> nodata;           // GDAL_NODATA
};

// Throws RasterError naming the file, the tag and the value for what we do
// not support: projected or geocentric CRSs, non-WGS84 datums, non-degree
// units, rotated/sheared ModelTransformation.
TiffGeoref readTiffGeoref(const std::string& path, int width, int height);

// Registers the GeoTIFF and GDAL_NODATA tags with libtiff (once per
// process) so that TIFFGetField/TIFFSetField use the signatures below: the
// arrays as (uint32_t count, T* values), GDAL_NODATA as (char*). Without it,
// libtiff treats them as anonymous tags with other signatures.
void registerGeoTiffTags();

// ESRI world file beside an image (.pgw/.jgw/.tfw/.wld/...); empty if none.
std::optional<GeoTransform> readWorldFile(const std::string& imagePath);

}  // namespace geocean::raster::detail
