#include "plugin/waves/SeaQuery.h"

#include "globe/geo/Parallel.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace geocean::waves {

SeaQuery::SeaQuery(WaveField field, std::shared_ptr<const ocean::LandSea> landSea)
    : field_(std::move(field)), landSea_(std::move(landSea)) {}

double SeaQuery::depthAt(double latDeg, double lonDeg, float elevationM) const {
  if (!landSea_ || field_.model() != Model::Gerstner) return kDeepWaterM;
  const float elev = std::isnan(elevationM) ? landSea_->elevationM(latDeg, lonDeg) : elevationM;
  // Where the mask says ocean but the coarser relief says >= 0 m we are in
  // the surf zone: 1 m of water (the waves break there).
  return std::isfinite(elev) ? std::max(-double(elev), 1.0) : kDeepWaterM;
}

SeaQueryResult SeaQuery::atWater(double latDeg, double lonDeg, double tS, ocean::Surface s, float elevationM) const {
  SeaQueryResult r;
  r.surface = s;
  if (s != ocean::Surface::Ocean) {
    r.seaHeightM = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  r.depthM = depthAt(latDeg, lonDeg, elevationM);
  const SurfacePoint p = field_.surfaceAt(latDeg, lonDeg, tS, r.depthM);
  r.seaHeightM = p.heightM;
  r.normalEnu = p.normalEnu;
  r.verticalVelocityMps = p.verticalVelocityMps;
  r.restOffsetEnuM = p.restOffsetEnuM;
  return r;
}

SeaQueryResult SeaQuery::query(double latDeg, double lonDeg, double tS) const {
  const ocean::Surface s = landSea_ ? landSea_->classify(latDeg, lonDeg) : ocean::Surface::Ocean;
  return atWater(latDeg, lonDeg, tS, s, std::numeric_limits<float>::quiet_NaN());
}

void SeaQuery::queryClassified(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                               std::size_t n, const ocean::Surface* surface, const float* elevationM,
                               SeaQueryResult* out) const {
  // The ocean points of each chunk go through the field's batch form (SIMD
  // for the noise, Gerstner and FFT models).
  constexpr std::size_t kChunk = 256;
  std::array<double, kChunk> la, lo, ts, dep;
  std::array<std::size_t, kChunk> idx;
  std::array<SurfacePoint, kChunk> sp;
  for (std::size_t i0 = 0; i0 < n; i0 += kChunk) {
    const std::size_t i1 = std::min(n, i0 + kChunk);
    std::size_t m = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      SeaQueryResult& r = out[i];
      r = SeaQueryResult{};
      r.surface = surface[i];
      if (surface[i] != ocean::Surface::Ocean) {
        r.seaHeightM = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      r.depthM = depthAt(latDeg[i], lonDeg[i], elevationM ? elevationM[i] : std::numeric_limits<float>::quiet_NaN());
      la[m] = latDeg[i], lo[m] = lonDeg[i], ts[m] = timesPerPoint ? tS[i] : tS[0], dep[m] = r.depthM, idx[m] = i;
      ++m;
    }
    field_.surfaceBatch(la.data(), lo.data(), ts.data(), true, dep.data(), m, sp.data());
    for (std::size_t k = 0; k < m; ++k) {
      SeaQueryResult& r = out[idx[k]];
      r.seaHeightM = sp[k].heightM;
      r.normalEnu = sp[k].normalEnu;
      r.verticalVelocityMps = sp[k].verticalVelocityMps;
      r.restOffsetEnuM = sp[k].restOffsetEnuM;
    }
  }
}

void SeaQuery::queryBatch(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                          std::size_t n, SeaQueryResult* out) const {
  geo::parallelFor(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<ocean::Surface> cls(r.size(), ocean::Surface::Ocean);
    if (landSea_) landSea_->classifyBatch(latDeg + r.begin(), lonDeg + r.begin(), r.size(), cls.data());
    queryClassified(latDeg + r.begin(), lonDeg + r.begin(), timesPerPoint ? tS + r.begin() : tS, timesPerPoint,
                    r.size(), cls.data(), nullptr, out + r.begin());
  });
}

}  // namespace geocean::waves
