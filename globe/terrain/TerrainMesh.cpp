#include "globe/terrain/TerrainMesh.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/geo/Parallel.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace geocean::terrain {

namespace {
// The fan vertex closing a global raster's polar hole: at the pole, at the
// mean finite height of edge row j.
glm::dvec3 poleVertexEcef(const raster::Raster& r, int j) {
  const double lat = r.transform().latOf(j + 0.5);
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < r.width(); ++i) {
    const float e = r.pixel(i, j);
    if (std::isfinite(e)) sum += e, ++n;
  }
  return geo::toEcef({lat > 0 ? 90.0 : -90.0, 0.0, n ? sum / n : 0.0});
}

// Vertex (i, j) in ECEF: the pixel centre at its height (0 for nodata, unused).
glm::dvec3 vertexEcef(const raster::Raster& r, int i, int j, bool& finite) {
  const raster::GeoTransform& gt = r.transform();
  const double lat = gt.latOf(j + 0.5);
  const float e = r.pixel(i, j);
  finite = std::isfinite(e);
  return geo::toEcef({std::clamp(lat, -90.0, 90.0), gt.lonOf(i + 0.5), finite ? e : 0.0});
}

}  // namespace

std::optional<CellRegion> cellsAlong(const raster::Raster& r, std::span<const Ray> rays) {
  const int W = r.width(), H = r.height();
  const raster::GeoTransform& gt = r.transform();
  const bool wrap = gt.global;
  const long long cellCols = wrap ? W : W - 1, cellRows = H - 1;
  if (cellCols <= 0 || cellRows <= 0) return std::nullopt;
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const float e = r.pixel(i, j);
      if (std::isfinite(e)) lo = std::min(lo, e), hi = std::max(hi, e);
    }
  CellRegion s;
  if (!(lo <= hi)) return s;  // no finite height: the whole-raster mesh is empty too
  constexpr double kDegM = 111320.0;  // longest degree (equator), metres
  const double latStepM = std::abs(gt.latStepDeg) * kDegM, lonStepM = std::abs(gt.lonStepDeg) * kDegM;
  // A flat triangle dips below its vertices by at most diag^2 / 8R (the
  // sag of its longest chord); the inflated ellipsoid a + h differs from
  // geodetic height h by h e^2 < 1 % of h; 100 m for the rest.
  const double sag = (latStepM * latStepM + lonStepM * lonStepM) / (8.0 * 6.3e6);
  const double pad = 100.0 + 0.01 * std::max(std::abs(double(lo)), std::abs(double(hi))) + sag;
  // Sea level included: a sea hit asks for terrain within float slack of it.
  const double hLo = std::min(double(lo), 0.0) - pad, hHi = std::max(double(hi), 0.0) + pad;
  const double step = 0.25 * std::min(latStepM, lonStepM);
  constexpr std::size_t kMaxSteps = 1u << 20;
  std::size_t steps = 0;
  auto markBox = [&](long long rowLo, long long rowHi, long long colLo, long long colHi, bool allCols) {
    if (allCols || colHi - colLo + 1 >= cellCols) colLo = 0, colHi = cellCols - 1;
    for (long long j = rowLo; j <= rowHi; ++j) {
      if (j < 0 || j >= cellRows) {
        if (wrap) s.fan[j < 0 ? 0 : 1] = true;
        continue;
      }
      for (long long c = colLo; c <= colHi; ++c) {
        long long i = c;
        if (wrap) {
          i = ((c % cellCols) + cellCols) % cellCols;
        } else if (c < 0 || c >= cellCols) {
          continue;
        }
        s.cells.push_back(std::uint64_t(j * cellCols + i));
      }
    }
  };
  constexpr double kToDeg = 180.0 / 3.14159265358979323846;
  for (const Ray& ray : rays) {
    const double len = glm::length(ray.dir);
    const glm::dvec3& o = ray.originEcef;
    if (!(len > 0.0 && std::isfinite(len) && std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z))) continue;
    const glm::dvec3 d = ray.dir / len;
    const geo::RayHit outer = geo::intersectEllipsoid(o, d, hHi);
    if (!outer.hit) continue;
    // Inside the outer surface and outside the inner one: up to two spans.
    double spans[2][2];
    int nSpans = 0;
    const double a0 = std::max(0.0, outer.tNear), a1 = outer.tFar;
    const geo::RayHit inner = geo::intersectEllipsoid(o, d, hLo);
    if (!inner.hit) {
      spans[nSpans][0] = a0, spans[nSpans][1] = a1, ++nSpans;
    } else {
      const double b0 = std::max(0.0, inner.tNear), b1 = inner.tFar;
      if (b0 > a0) spans[nSpans][0] = a0, spans[nSpans][1] = std::min(a1, b0), ++nSpans;
      if (b1 < a1) spans[nSpans][0] = std::max(a0, b1), spans[nSpans][1] = a1, ++nSpans;
    }
    for (int k = 0; k < nSpans; ++k) {
      const double t0 = std::max(0.0, spans[k][0] - step), t1 = spans[k][1] + step;
      if (!(t1 >= t0)) continue;
      const double n = std::ceil((t1 - t0) / step);
      if (!(n < double(kMaxSteps)) || (steps += std::size_t(n) + 1) > kMaxSteps) return std::nullopt;
      const double ds = (t1 - t0) / std::max(n, 1.0), radius = ds + 1.0;
      for (std::size_t q = 0; q <= std::size_t(n); ++q) {
        const glm::dvec3 p = o + d * (t0 + double(q) * ds);
        const geo::Geodetic g = geo::fromEcef(p);
        // Within `radius` of p: geodetic latitude moves by at most
        // radius / (M + h) (M >= a (1 - e^2) = 6335 km), longitude by
        // asin(radius / rho) <= radius / (rho - radius).
        const double dLat = 1.01 * radius / 6.3e6 * kToDeg;
        const double rho = std::hypot(p.x, p.y);
        const bool allLon = rho <= 2.0 * radius;
        const double dLon = allLon ? 0.0 : radius / (rho - radius) * kToDeg;
        const double vA = (g.latDeg - dLat - gt.originLatDeg) / gt.latStepDeg - 0.5,
                     vB = (g.latDeg + dLat - gt.originLatDeg) / gt.latStepDeg - 0.5;
        const long long rowLo = (long long)std::floor(std::min(vA, vB)) - 1,
                        rowHi = (long long)std::floor(std::max(vA, vB)) + 1;
        // A regional raster may use longitudes beyond +-180.
        constexpr double kShifts[3] = {0.0, -360.0, 360.0};
        for (int sh = 0; sh < (wrap ? 1 : 3); ++sh) {
          const double shift = kShifts[sh];
          const double uA = (g.lonDeg + shift - dLon - gt.originLonDeg) / gt.lonStepDeg - 0.5,
                       uB = (g.lonDeg + shift + dLon - gt.originLonDeg) / gt.lonStepDeg - 0.5;
          const double uMin = std::max(std::min(uA, uB), -4.0 * cellCols), uMax = std::min(std::max(uA, uB), 4.0 * cellCols);
          markBox(rowLo, rowHi, (long long)std::floor(uMin) - 1, (long long)std::floor(uMax) + 1, allLon);
        }
      }
    }
  }
  std::sort(s.cells.begin(), s.cells.end());
  s.cells.erase(std::unique(s.cells.begin(), s.cells.end()), s.cells.end());
  return s;
}

TerrainMesh TerrainMesh::whole(const raster::Raster& r, const glm::dvec3& localOrigin) {
  const int W = r.width(), H = r.height();
  const bool wrap = r.transform().global;
  TerrainMesh m;
  m.origin_ = localOrigin;
  m.ecef_.resize(std::size_t(W) * H);
  std::vector<std::uint8_t> ok(m.ecef_.size());
  geo::parallelFor(0, H, [&](int j) {
    for (int i = 0; i < W; ++i) {
      bool finite = false;
      m.ecef_[std::size_t(j) * W + i] = vertexEcef(r, i, j, finite);
      ok[std::size_t(j) * W + i] = finite;
    }
  });
  const int cellCols = wrap ? W : W - 1;
  m.indices_.reserve(std::size_t(std::max(cellCols, 0)) * std::max(H - 1, 0) * 6 + std::size_t(W) * 6);
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (ok[a] && ok[b] && ok[c]) m.indices_.insert(m.indices_.end(), {a, b, c});
  };
  for (int j = 0; j + 1 < H; ++j)
    for (int i = 0; i < cellCols; ++i) {
      const int i1 = (i + 1) % W;
      const auto a = std::uint32_t(j * W + i), b = std::uint32_t(j * W + i1), c = std::uint32_t((j + 1) * W + i),
                 d = std::uint32_t((j + 1) * W + i1);
      tri(a, b, d);
      tri(a, d, c);
    }
  if (wrap) {
    for (int edge = 0; edge < 2; ++edge) {
      const int j = edge == 0 ? 0 : H - 1;
      const auto pole = std::uint32_t(m.ecef_.size());
      m.ecef_.push_back(poleVertexEcef(r, j));
      ok.push_back(1);
      for (int i = 0; i < W; ++i) tri(pole, std::uint32_t(j * W + i), std::uint32_t(j * W + (i + 1) % W));
    }
  }
  return m;
}

TerrainMesh TerrainMesh::region(const raster::Raster& r, const CellRegion& sel, const glm::dvec3& localOrigin) {
  const int W = r.width(), H = r.height();
  const long long cellCols = r.transform().global ? W : W - 1;
  TerrainMesh m;
  m.origin_ = localOrigin;
  std::unordered_map<std::uint32_t, std::uint32_t> local;  // raster vertex -> mesh vertex
  std::vector<std::uint8_t> ok;
  auto vertex = [&](std::uint32_t id) {
    auto [it, fresh] = local.try_emplace(id, std::uint32_t(m.ecef_.size()));
    if (fresh) {
      bool finite = false;
      m.ecef_.push_back(vertexEcef(r, int(id % std::uint32_t(W)), int(id / std::uint32_t(W)), finite));
      ok.push_back(finite);
    }
    return it->second;
  };
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const std::uint32_t la = vertex(a), lb = vertex(b), lc = vertex(c);
    if (ok[la] && ok[lb] && ok[lc]) m.indices_.insert(m.indices_.end(), {la, lb, lc});
  };
  for (const std::uint64_t cell : sel.cells) {
    const int j = int(cell / std::uint64_t(cellCols)), i = int(cell % std::uint64_t(cellCols));
    const int i1 = (i + 1) % W;
    const auto a = std::uint32_t(j * W + i), b = std::uint32_t(j * W + i1), c = std::uint32_t((j + 1) * W + i),
               d = std::uint32_t((j + 1) * W + i1);
    tri(a, b, d);
    tri(a, d, c);
  }
  for (int edge = 0; edge < 2; ++edge) {
    if (!sel.fan[edge]) continue;
    const int j = edge == 0 ? 0 : H - 1;
    const auto pole = std::uint32_t(m.ecef_.size());
    m.ecef_.push_back(poleVertexEcef(r, j));
    ok.push_back(1);
    for (int i = 0; i < W; ++i) {
      const std::uint32_t la = vertex(std::uint32_t(j * W + i)), lb = vertex(std::uint32_t(j * W + (i + 1) % W));
      if (ok[la] && ok[lb]) m.indices_.insert(m.indices_.end(), {pole, la, lb});
    }
  }
  return m;
}

}  // namespace geocean::terrain
