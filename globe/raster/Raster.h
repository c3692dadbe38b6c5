// A georeferenced raster on WGS84 geographic coordinates. Pixels of TIFF
// files are decoded with libtiff, every other format through OpenImageIO
// (loaded on demand, see PixelSource.h; its types never appear here);
// georeferencing comes from GeoTIFF tags (libtiff), an ESRI world file, or
// the caller's "global equirectangular". Small rasters are held in memory;
// big ones stream through a bounded cache of decoded blocks (libtiff's for
// TIFFs, OpenImageIO's ImageCache otherwise).
//
// Thread safety: a Raster is immutable after open(); all const methods may
// be called from any number of threads.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace geocean::raster {

// Every failure to open or read a raster: the message names the file, the
// field and the offending value.
class RasterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// lonDeg + 360 k nearest centreDeg (lonDeg itself, bit for bit, within 180
// degrees of it): a regional layer's own longitudes.
inline double lonNear(double lonDeg, double centreDeg) {
  return lonDeg + 360.0 * __builtin_nearbyint((centreDeg - lonDeg) / 360.0);
}

// Maps pixel (column, row) <-> (lonDeg, latDeg). Pixel (i, j) covers
// [i, i+1) x [j, j+1) in pixel space; (i + 0.5, j + 0.5) is its centre.
struct GeoTransform {
  double originLonDeg = -180.0;  // longitude of pixel-space x = 0 (left edge of column 0)
  double originLatDeg = 90.0;    // latitude of pixel-space y = 0 (top edge of row 0)
  double lonStepDeg = 1.0;       // degrees per pixel along x (> 0)
  double latStepDeg = -1.0;      // degrees per pixel along y (< 0: north up; > 0: south up)
  bool global = false;           // columns span 360 degrees: longitude wraps
  // Columns x lonStepDeg, set by Raster (0: unknown). A regional raster
  // reads each longitude as the lon + 360 k nearest its centre, so one
  // across the antimeridian (179.5 .. 180.5) answers at -179.9 too.
  double lonSpanDeg = 0.0;

  double pixelX(double lonDeg) const;  // continuous pixel-space x, wrapping if global
  // The longitude as this raster reads it: a regional one's nearest its
  // centre, anything else unchanged.
  double nearLon(double lonDeg) const;
  double pixelY(double latDeg) const;
  // Rows 0 .. height span [south, north]; false when that reaches beyond a
  // pole by more than a pixel (GMT's pixel-is-point global grids put
  // centres on the poles): not geographic degrees. The file reader's and
  // the C ABI's rule.
  bool rowsWithinPoles(int height, double& south, double& north) const {
    const double edge = latOf(double(height));
    north = std::max(originLatDeg, edge), south = std::min(originLatDeg, edge);
    const double slack = std::abs(latStepDeg) * 1.01;
    return !std::isnan(edge) && north <= 90.0 + slack && south >= -90.0 - slack;
  }
  double lonOf(double px) const { return originLonDeg + px * lonStepDeg; }
  double latOf(double py) const { return originLatDeg + py * latStepDeg; }
};

enum class Georef {
  FromFile,           // GeoTIFF tags, or a world file beside PNG/JPEG
  GlobalEquirect,     // the caller says: whole Earth, north up, column 0 at -180
};

// The largest tile (width x height x channels) a file may declare.
inline constexpr std::int64_t kMaxTileSamples = std::int64_t(8192) * 8192;

struct OpenOptions {
  Georef georef = Georef::FromFile;
  // Rasters whose decoded pixels need more than this are streamed instead of
  // being loaded; their memory is bounded by cacheBytes.
  std::size_t inMemoryLimitBytes = std::size_t(256) << 20;
  // A regional raster (less than 360 degrees wide) over this many bytes as
  // floats streams even under inMemoryLimitBytes (0: no such rule). A
  // drawing host sets it for the masks and reliefs the ocean plugin holds
  // too; a whole-globe raster keeps one rule on both sides, where it may be
  // drawn on its own cells (world::globalInMemory).
  std::size_t regionalInMemoryLimitBytes = 0;
  // 16 MB: 128 int16 tiles of 256^2. A drawn layer is read mostly in single
  // passes by tile (the 5' grids' resampling), which more does not speed up.
  std::size_t cacheBytes = std::size_t(16) << 20;
  std::optional<double> nodata;  // overrides GDAL_NODATA from the file
  // A handful of lookups (one-point queries): read only the tiles they
  // touch with libtiff, no ImageCache. Tiled TIFFs only; ignored otherwise.
  bool fewLookups = false;
  // Absurd dimensions are rejected before any allocation.
  std::int64_t maxPixels = std::int64_t(1) << 34;
};

class Raster {
 public:
  static std::shared_ptr<const Raster> open(const std::string& path, const OpenOptions& options = {});
  // An in-memory raster from values (row-major, channels interleaved).
  static std::shared_ptr<const Raster> fromPixels(std::vector<float> pixels, int width, int height,
                                                  int channels, const GeoTransform& transform,
                                                  std::optional<double> nodata = std::nullopt,
                                                  std::string name = "<memory>");
  virtual ~Raster();

  const std::string& path() const { return path_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  const GeoTransform& transform() const { return transform_; }
  std::optional<double> nodata() const { return nodata_; }
  bool inMemory() const { return !pixels_.empty() || !narrow_.empty(); }
  // Global, north up and pole to pole: its rows are the whole globe's.
  bool wholeGlobeNorthUp() const {
    return transform_.global && transform_.latStepDeg < 0 && std::abs(transform_.latStepDeg * height_ + 180.0) < 1e-6;
  }
  // In-memory pixels as float (a copy; NaN where nodata), row-major,
  // channels interleaved (empty if cached).
  std::vector<float> pixels() const;

  // Value of pixel (x, y) clamped to the raster; NaN for nodata.
  float pixel(int x, int y, int channel = 0) const;
  // Nearest-pixel and bilinear samples at (lat, lon); NaN outside a
  // non-global raster or where nodata. Bilinear ignores nodata neighbours.
  // Longitudes wrap for global rasters; latitudes clamp at the poles. A
  // pole is one point: for a global raster whose first or last row ends
  // there, nearest at the pole gives the row's median and bilinear blends
  // into it over the half row next to the pole.
  float sampleNearest(double latDeg, double lonDeg, int channel = 0) const;
  float sampleBilinear(double latDeg, double lonDeg, int channel = 0) const;
  // Batches: sorted by tile internally when cached (coherent ImageCache access).
  void sampleNearestBatch(const double* latDeg, const double* lonDeg, std::size_t n, float* out,
                          int channel = 0) const;
  void sampleBilinearBatch(const double* latDeg, const double* lonDeg, std::size_t n, float* out,
                           int channel = 0) const;

  // Bytes this raster holds (pixels, or the cache bound).
  std::size_t memoryBytes() const;

 protected:
  Raster() = default;
  // The value at the pole a polar row touches: the row's upper median; NaN
  // if the row is all nodata.
  float poleValue(int row, int channel) const;
  struct CacheImpl;
  std::string path_;
  int width_ = 0, height_ = 0, channels_ = 1;
  GeoTransform transform_;
  std::optional<double> nodata_;
  // In memory: floats (nodata already NaN), or a TIFF's own 8- or 16-bit
  // integer samples (exact as floats; a 16-bit relief is half its floats, an
  // 8-bit mask a quarter: issue 12 item 6), nodata compared on reading.
  std::vector<float> pixels_;
  std::vector<std::uint8_t> narrow_;
  int narrowKind_ = 0;  // detail::SampleKind of narrow_
  float narrowAt(std::size_t i) const;
  std::unique_ptr<CacheImpl> cache_;
  std::size_t cacheBytes_ = 0;
};

}  // namespace geocean::raster
