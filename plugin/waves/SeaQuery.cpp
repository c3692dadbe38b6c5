#include "plugin/waves/SeaQuery.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

namespace geocean::waves {

SeaQuery::SeaQuery(WaveField field, std::shared_ptr<const ocean::LandSea> landSea)
    : field_(std::move(field)), landSea_(std::move(landSea)) {}

SeaQueryResult SeaQuery::atWater(double latDeg, double lonDeg, double tS, ocean::Surface s, float elevationM) const {
  SeaQueryResult r;
  r.surface = s;
  if (s != ocean::Surface::Ocean) {
    r.seaHeightM = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  if (landSea_ && field_.model() == Model::Gerstner) {
    const float elev = std::isnan(elevationM) ? landSea_->elevationM(latDeg, lonDeg) : elevationM;
    // Where the mask says ocean but the coarser relief says >= 0 m we are in
    // the surf zone: 1 m of water (the waves break there).
    if (std::isfinite(elev)) r.depthM = std::max(-double(elev), 1.0);
  }
  const SurfacePoint p = field_.surfaceAt(latDeg, lonDeg, tS, r.depthM);
  r.seaHeightM = p.heightM;
  r.normalEnu = p.normalEnu;
  r.verticalVelocityMps = p.verticalVelocityMps;
  return r;
}

SeaQueryResult SeaQuery::query(double latDeg, double lonDeg, double tS) const {
  const ocean::Surface s = landSea_ ? landSea_->classify(latDeg, lonDeg) : ocean::Surface::Ocean;
  return atWater(latDeg, lonDeg, tS, s, std::numeric_limits<float>::quiet_NaN());
}

void SeaQuery::queryClassified(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                               std::size_t n, const ocean::Surface* surface, const float* elevationM,
                               SeaQueryResult* out) const {
  const float unknown = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i)
    out[i] = atWater(latDeg[i], lonDeg[i], timesPerPoint ? tS[i] : tS[0], surface[i],
                     elevationM ? elevationM[i] : unknown);
}

void SeaQuery::queryBatch(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                          std::size_t n, SeaQueryResult* out) const {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<ocean::Surface> cls(r.size(), ocean::Surface::Ocean);
    if (landSea_) landSea_->classifyBatch(latDeg + r.begin(), lonDeg + r.begin(), r.size(), cls.data());
    queryClassified(latDeg + r.begin(), lonDeg + r.begin(), timesPerPoint ? tS + r.begin() : tS, timesPerPoint,
                    r.size(), cls.data(), nullptr, out + r.begin());
  });
}

}  // namespace geocean::waves
