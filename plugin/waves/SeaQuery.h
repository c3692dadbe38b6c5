// The sea-height query: the displaced sea surface exactly above a geographic
// point, with its normal and the surface class; land says land instead of
// inventing sea. Heights are relative to the WGS84 ellipsoid (mean sea level
// = ellipsoid: no geoid grid is applied).
//
// Thread safety: const methods may be called from any number of threads.
#pragma once

#include "plugin/landsea/LandSea.h"
#include "plugin/waves/WaveField.h"

#include <cstddef>
#include <memory>

namespace geocean::waves {

struct SeaQueryResult {
  ocean::Surface surface = ocean::Surface::Ocean;
  // Height of the sea surface above the ellipsoid (m); NaN on land and on
  // lakes (the ocean's wave field does not cover lakes).
  double seaHeightM = 0.0;
  glm::dvec3 normalEnu{0.0, 0.0, 1.0};  // (0,0,1) where there is no sea
  double verticalVelocityMps = 0.0;
  double depthM = kDeepWaterM;          // water depth used (m)
  // Rest point of the particle now at the surface above (ENU offset from
  // the point, the inversion's answer): where its velocity is evaluated.
  glm::dvec3 restOffsetEnuM{0.0};
};

class SeaQuery {
 public:
  // landSea may be null: then everything is deep ocean.
  SeaQuery(WaveField field, std::shared_ptr<const ocean::LandSea> landSea);

  SeaQueryResult query(double latDeg, double lonDeg, double tS) const;
  // The batch form: runs on all cores (TBB); out[i] for (latDeg[i], lonDeg[i])
  // at time tS[i] (or tS[0] for every point when timesPerPoint is false).
  void queryBatch(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint, std::size_t n,
                  SeaQueryResult* out) const;
  // The same for points whose surface class (and, if elevationM is not null,
  // terrain elevation in m) the caller already looked up, e.g. to print them
  // too; runs on the calling thread only (callers parallelise by blocks).
  // Both batch forms use WaveField::surfaceBatch (SIMD); query() the scalar
  // surfaceAt. They agree to rounding (tests/waves/test_batch.cpp).
  void queryClassified(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                       std::size_t n, const ocean::Surface* surface, const float* elevationM,
                       SeaQueryResult* out) const;

  const WaveField& field() const { return field_; }

 private:
  double depthAt(double latDeg, double lonDeg, float elevationM) const;  // elevationM NaN: look it up
  SeaQueryResult atWater(double latDeg, double lonDeg, double tS, ocean::Surface s, float elevationM) const;
  WaveField field_;
  std::shared_ptr<const ocean::LandSea> landSea_;
};

}  // namespace geocean::waves
