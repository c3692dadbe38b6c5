// Land/sea/lake classification from a mask raster and/or an elevation
// raster. A mask alone is enough; an elevation alone gives ocean where the
// elevation is below 0.
#pragma once

#include "globe/raster/Raster.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace geocean::ocean {

enum class Surface : std::uint8_t { Ocean = 0, Land = 1, Lake = 2 };
const char* toString(Surface s);  // "ocean" | "land" | "lake"

// How mask values map to classes (default: 0 ocean, 1 land, 2 lake;
// values >= 256 or unmapped count as land).
struct MaskEncoding {
  std::array<Surface, 256> classOf{};
  MaskEncoding();
  static MaskEncoding parse(const std::string& spec);  // "0=ocean,1=land,2=lake,3=land"
};

class LandSea {
 public:
  LandSea(std::shared_ptr<const raster::Raster> mask, std::shared_ptr<const raster::Raster> elevation,
          MaskEncoding encoding = {});

  Surface classify(double latDeg, double lonDeg) const;
  void classifyBatch(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const;

  // Fraction of water (ocean or lake) around the point, in [0, 1]: the
  // bilinear blend of the four nearest mask cells. 0.5 is the coastline;
  // the renderer anti-aliases the shore with it.
  float waterCoverage(double latDeg, double lonDeg) const;
  // Terrain elevation (ocean depth negative) in metres, bilinear; NaN when
  // there is no elevation raster or no data there.
  float elevationM(double latDeg, double lonDeg) const;
  void elevationBatch(const double* latDeg, const double* lonDeg, std::size_t n, float* out) const;

  const raster::Raster* mask() const { return mask_.get(); }
  const raster::Raster* elevation() const { return elevation_.get(); }

 private:
  std::shared_ptr<const raster::Raster> mask_, elevation_;
  MaskEncoding encoding_;
  // In-memory mask as class bytes: the fast path (no float conversion).
  std::vector<std::uint8_t> classes_;
};

}  // namespace geocean::ocean
