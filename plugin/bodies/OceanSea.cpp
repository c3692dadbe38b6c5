#include "plugin/bodies/OceanSea.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace geocean::bodies {

OceanSea::OceanSea(std::shared_ptr<const ocean::Snapshot> snapshot) : snap_(std::move(snapshot)) {
  if (!snap_) throw std::invalid_argument("geocean::bodies: OceanSea snapshot is null");
  if (snap_->waves) k_ = 2.0 * std::numbers::pi / snap_->waves->peakWavelengthM();
  if (snap_->waves && snap_->waves->model() == waves::Model::Gerstner && !snap_->waves->coastField()) {
    double kMax = 0.0;
    for (const auto& c : snap_->waves->components()) kMax = std::max(kMax, c.kRef);
    if (kMax > 0.0) shortest_ = 2.0 * std::numbers::pi / kMax;
  }
}

void OceanSea::sampleSlopes(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n,
                            SeaSample* out) const {
  if (n == 0) return;
  if (!snap_->waves) {  // flat: heights (0 or NaN) from sample()
    sample(latDeg, lonDeg, tS, n, false, out);
    return;
  }
  thread_local std::vector<double> h, vz, nrm;
  h.resize(n), vz.resize(n), nrm.resize(3 * n);
  ocean::SurfaceOutputs o;
  o.heightM = h.data();
  o.verticalVelocityMps = vz.data();
  o.normalEnu = nrm.data();
  snap_->querySurfaceOnThisThread(ocean::Points{latDeg, lonDeg, n, tS, true}, o);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = SeaSample{h[i], 0.0, {0.0, 0.0}, {0.0, 0.0}};
    if (std::isnan(h[i])) continue;
    out[i].verticalVelocityMps = vz[i];
    // The surface z = eta(e, n) has the normal (-eta_e, -eta_n, 1) / |.|.
    out[i].slopeEn = {-nrm[3 * i] / nrm[3 * i + 2], -nrm[3 * i + 1] / nrm[3 * i + 2]};
  }
}

void OceanSea::sample(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n, bool velocities,
                      SeaSample* out) const {
  if (n == 0) return;
  thread_local std::vector<double> h, vz, vh;
  thread_local std::vector<ocean::Surface> cls;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (!snap_->waves) {
    cls.resize(n);
    if (snap_->landSea) {
      snap_->classify(latDeg, lonDeg, n, cls.data());
    } else {
      std::fill(cls.begin(), cls.end(), ocean::Surface::Ocean);
    }
    for (std::size_t i = 0; i < n; ++i)
      out[i] = SeaSample{cls[i] == ocean::Surface::Ocean ? 0.0 : kNaN, 0.0, {0.0, 0.0}};
    return;
  }
  h.resize(n);
  ocean::SurfaceOutputs o;
  o.heightM = h.data();
  if (velocities) {
    vz.resize(n), vh.resize(2 * n);
    o.verticalVelocityMps = vz.data();
    o.horizontalVelocityEnMps = vh.data();
  }
  snap_->querySurfaceOnThisThread(ocean::Points{latDeg, lonDeg, n, tS, true}, o);
  for (std::size_t i = 0; i < n; ++i) {
    out[i].heightM = h[i];
    if (velocities && !std::isnan(h[i])) {
      out[i].verticalVelocityMps = vz[i];
      out[i].horizontalVelocityEnMps = {vh[2 * i], vh[2 * i + 1]};
    } else {
      out[i].verticalVelocityMps = 0.0;
      out[i].horizontalVelocityEnMps = {0.0, 0.0};
    }
  }
}

}  // namespace geocean::bodies

namespace geocean::bodies {

std::shared_ptr<HeightField> terrainPatch(const ocean::Snapshot& snap, const geo::Geodetic& southWest, int n,
                                          double spacingM) {
  if (!snap.landSea && !snap.elevation)
    throw std::invalid_argument("geocean::bodies: terrainPatch: the snapshot has no elevation");
  if (n < 2 || !(spacingM > 0.0)) throw std::invalid_argument("geocean::bodies: terrainPatch: n < 2 or spacing <= 0");
  const geo::EnuFrame f = geo::enuFrame(geo::Geodetic{southWest.latDeg, southWest.lonDeg, 0.0});
  const std::size_t m = std::size_t(n) * std::size_t(n);
  std::vector<double> lat(m), lon(m);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const geo::Geodetic g = geo::fromEcef(f.originEcef + f.toEcef(glm::dvec3(i * spacingM, j * spacingM, 0.0)));
      lat[std::size_t(j) * n + i] = g.latDeg, lon[std::size_t(j) * n + i] = g.lonDeg;
    }
  std::vector<float> z(m);
  snap.elevationAt(lat.data(), lon.data(), m, z.data());
  std::vector<double> h(m);
  for (std::size_t k = 0; k < m; ++k) {
    if (!std::isfinite(z[k]))
      throw std::invalid_argument("geocean::bodies: terrainPatch: no elevation at " + std::to_string(lat[k]) + ", " +
                                  std::to_string(lon[k]));
    h[k] = f.toLocal(geo::toEcef(geo::Geodetic{lat[k], lon[k], double(z[k])}) - f.originEcef).z;
  }
  return std::make_shared<HeightField>(geo::Geodetic{southWest.latDeg, southWest.lonDeg, 0.0}, n, n, spacingM,
                                       std::move(h));
}

namespace {
constexpr int kPatchN = 201;
constexpr double kPatchCellM = 2.0, kPatchHalfM = 200.0, kPatchMarginM = 100.0;
}  // namespace

std::shared_ptr<TerrainContact> terrainContactAround(const ocean::Snapshot& snap, const BodyState& s,
                                                     std::vector<glm::dvec3> points, double friction) {
  const geo::EnuFrame f = geo::enuFrame(geo::fromEcef(s.positionEcef));
  geo::Geodetic sw = geo::fromEcef(f.originEcef + f.toEcef(glm::dvec3(-kPatchHalfM, -kPatchHalfM, 0.0)));
  sw.heightM = 0.0;
  return std::make_shared<TerrainContact>(terrainPatch(snap, sw, kPatchN, kPatchCellM), std::move(points), friction);
}

bool nearPatchEdge(const TerrainContact& c, const BodyState& s) {
  const glm::dvec3 p = c.terrain().toPatch(s.positionEcef);
  const double size = (kPatchN - 1) * kPatchCellM;
  return !(p.x > kPatchMarginM && p.y > kPatchMarginM && p.x < size - kPatchMarginM && p.y < size - kPatchMarginM);
}

}  // namespace geocean::bodies
