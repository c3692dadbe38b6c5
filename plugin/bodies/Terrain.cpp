#include "plugin/bodies/Terrain.h"

#include "plugin/bodies/Validate.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace geocean::bodies {

using detail::fail;

HeightField::HeightField(const geo::Geodetic& origin, int nx, int ny, double spacingM, std::vector<double> heightsM)
    : frame_(geo::enuFrame(origin)), nx_(nx), ny_(ny), s_(spacingM), h_(std::move(heightsM)) {
  if (nx < 2 || ny < 2) fail("height field size", std::min(nx, ny), "vertices", "must be >= 2 each way");
  detail::requirePositive("height field spacing", spacingM, "m");
  if (h_.size() != std::size_t(nx) * ny)
    fail("height field sample count", double(h_.size()), "", "must be nx * ny = " + std::to_string(std::size_t(nx) * ny));
  for (std::size_t k = 0; k < h_.size(); ++k)
    if (!std::isfinite(h_[k])) fail("height field sample " + std::to_string(k), h_[k], "m", "must be finite");
  cellMax_.resize(std::size_t(nx - 1) * (ny - 1));
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const double m = std::max({h_[std::size_t(j) * nx + i], h_[std::size_t(j) * nx + i + 1],
                                 h_[std::size_t(j + 1) * nx + i], h_[std::size_t(j + 1) * nx + i + 1]});
      // Rounded up so the float bound never cuts below the true maximum.
      cellMax_[std::size_t(j) * (nx - 1) + i] = std::nextafter(static_cast<float>(m), std::numeric_limits<float>::max());
    }
  levelMax_.push_back(cellMax_);
  levelW_.push_back(nx - 1), levelH_.push_back(ny - 1);
  while (levelW_.back() > 1 || levelH_.back() > 1) {
    const int w = levelW_.back(), h = levelH_.back(), W = (w + 1) / 2, H = (h + 1) / 2;
    const std::vector<float>& c = levelMax_.back();
    std::vector<float> up(std::size_t(W) * H, -std::numeric_limits<float>::max());
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        float& u = up[std::size_t(j / 2) * W + i / 2];
        u = std::max(u, c[std::size_t(j) * w + i]);
      }
    levelMax_.push_back(std::move(up));
    levelW_.push_back(W), levelH_.push_back(H);
  }
}

void HeightField::testCell(int i, int j, const glm::dvec3& a, const glm::dvec3& b, std::optional<Hit>& best) const {
  const glm::dvec3 v00 = vertex(i, j), v10 = vertex(i + 1, j), v01 = vertex(i, j + 1), v11 = vertex(i + 1, j + 1);
  const glm::dvec3 tris[2][3] = {{v00, v10, v11}, {v00, v11, v01}};
  const glm::dvec3 d = b - a;
  for (const auto& tr : tris) {
    const glm::dvec3 e1 = tr[1] - tr[0], e2 = tr[2] - tr[0];
    const glm::dvec3 pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);  // = -d . (e1 x e2): > 0 going down through the upward face
    if (!(det > 0.0)) continue;
    const glm::dvec3 tv = a - tr[0];
    const double u = glm::dot(tv, pv) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 qv = glm::cross(tv, e1);
    const double v = glm::dot(d, qv) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = glm::dot(e2, qv) / det;
    if (t < 0.0 || t > 1.0) continue;
    if (!best || t < best->t) best = Hit{t, a + t * d, glm::normalize(glm::cross(e1, e2))};
  }
}

bool HeightField::clipToGrid(const glm::dvec3& a, const glm::dvec3& d, double& t0, double& t1) const {
  t0 = 0.0, t1 = 1.0;
  const double lo[2] = {0.0, 0.0}, hi[2] = {(nx_ - 1) * s_, (ny_ - 1) * s_};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

std::optional<HeightField::Hit> HeightField::sweep(const glm::dvec3& a, const glm::dvec3& b) const {
  const glm::dvec3 d = b - a;
  double t0, t1;
  if (!clipToGrid(a, d, t0, t1)) return std::nullopt;
  // Cells crossed ~ the ground length over the spacing: few, walk them.
  const double cells = (t1 - t0) * (std::abs(d.x) + std::abs(d.y)) / s_;
  return cells <= 16.0 ? walk(a, b, t0, t1) : sweepQuadtree(a, b);
}

std::optional<HeightField::Hit> HeightField::sweepCellWalk(const glm::dvec3& a, const glm::dvec3& b) const {
  double t0, t1;
  if (!clipToGrid(a, b - a, t0, t1)) return std::nullopt;
  return walk(a, b, t0, t1);
}

std::optional<HeightField::Hit> HeightField::sweepQuadtree(const glm::dvec3& a, const glm::dvec3& b) const {
  double t0, t1;
  if (!clipToGrid(a, b - a, t0, t1)) return std::nullopt;
  // Start at the smallest node holding the clipped segment's ground box.
  const glm::dvec3 d = b - a, p0 = a + t0 * d, p1 = a + t1 * d;
  auto cellOf = [&](double v, int n) { return std::clamp(int(std::floor(v / s_)), 0, n - 2); };
  int i0 = cellOf(std::min(p0.x, p1.x), nx_), i1 = cellOf(std::max(p0.x, p1.x), nx_);
  int j0 = cellOf(std::min(p0.y, p1.y), ny_), j1 = cellOf(std::max(p0.y, p1.y), ny_);
  int level = 0;
  while (level + 1 < int(levelMax_.size()) && (i0 != i1 || j0 != j1)) i0 >>= 1, i1 >>= 1, j0 >>= 1, j1 >>= 1, ++level;
  std::optional<Hit> best;
  descend(level, i0, j0, a, b, t0, t1, best);
  return best;
}

void HeightField::descend(int level, int bi, int bj, const glm::dvec3& a, const glm::dvec3& b, double ta, double tb,
                          std::optional<Hit>& best) const {
  const glm::dvec3 d = b - a;
  // Coarse: the segment's lowest point over the node against its highest vertex.
  if (std::min(a.z + ta * d.z, a.z + tb * d.z) > levelMax_[level][std::size_t(bj) * levelW_[level] + bi]) return;
  if (level == 0) {
    testCell(bi, bj, a, b, best);
    return;
  }
  // The children the segment meets, by where it enters them. Their
  // intervals are padded by a rounding's width, so a segment along a
  // boundary opens both sides (a hit is exact whichever cell finds it).
  struct Child {
    double ta, tb;
    int i, j;
  };
  std::array<Child, 4> kids;
  int n = 0;
  const int cw = 1 << (level - 1);
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const int i = 2 * bi + di, j = 2 * bj + dj;
      if (i >= levelW_[level - 1] || j >= levelH_[level - 1]) continue;
      const double lo[2] = {double(i) * cw * s_, double(j) * cw * s_};
      const double hi[2] = {std::min(double(i + 1) * cw, double(nx_ - 1)) * s_,
                            std::min(double(j + 1) * cw, double(ny_ - 1)) * s_};
      double c0 = ta, c1 = tb;
      bool in = true;
      for (int k = 0; k < 2 && in; ++k) {
        const double pad = 1e-9 * (hi[k] - lo[k]);
        if (d[k] == 0.0) {
          in = a[k] >= lo[k] - pad && a[k] <= hi[k] + pad;
          continue;
        }
        double x0 = (lo[k] - pad - a[k]) / d[k], x1 = (hi[k] + pad - a[k]) / d[k];
        if (x0 > x1) std::swap(x0, x1);
        c0 = std::max(c0, x0), c1 = std::min(c1, x1);
        in = c0 <= c1;
      }
      if (in) kids[n++] = {c0, c1, i, j};
    }
  for (int k = 1; k < n; ++k)  // insertion sort of at most 4
    for (int m = k; m > 0 && kids[m].ta < kids[m - 1].ta; --m) std::swap(kids[m], kids[m - 1]);
  for (int k = 0; k < n; ++k) {
    if (best && kids[k].ta > best->t) return;  // every later cell is further along
    descend(level - 1, kids[k].i, kids[k].j, a, b, kids[k].ta, kids[k].tb, best);
  }
}

std::optional<HeightField::Hit> HeightField::walk(const glm::dvec3& a, const glm::dvec3& b, double t0, double t1) const {
  const glm::dvec3 d = b - a;
  // Amanatides-Woo over the cells, in order along the segment.
  const glm::dvec3 p = a + t0 * d;
  int i = std::clamp(int(std::floor(p.x / s_)), 0, nx_ - 2), j = std::clamp(int(std::floor(p.y / s_)), 0, ny_ - 2);
  const int si = d.x > 0 ? 1 : (d.x < 0 ? -1 : 0), sj = d.y > 0 ? 1 : (d.y < 0 ? -1 : 0);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  auto nextBoundary = [&](int cell, int step, double origin, double dir) {
    if (step == 0) return kInf;
    const double edge = (cell + (step > 0 ? 1 : 0)) * s_;
    return (edge - origin) / dir;
  };
  double tMaxX = nextBoundary(i, si, a.x, d.x), tMaxY = nextBoundary(j, sj, a.y, d.y);
  const double tDx = si ? s_ / std::abs(d.x) : kInf, tDy = sj ? s_ / std::abs(d.y) : kInf;
  double tEnter = t0;
  for (;;) {
    const double tExit = std::min({tMaxX, tMaxY, t1});
    // Coarse: the segment's lowest point over this cell against the cell's highest vertex.
    const double zLow = std::min(a.z + tEnter * d.z, a.z + tExit * d.z);
    if (zLow <= cellMax_[std::size_t(j) * (nx_ - 1) + i]) {
      std::optional<Hit> hit;
      testCell(i, j, a, b, hit);
      if (hit) return hit;
    }
    if (tExit >= t1) return std::nullopt;
    if (tMaxX < tMaxY) {
      i += si, tEnter = tMaxX, tMaxX += tDx;
    } else {
      j += sj, tEnter = tMaxY, tMaxY += tDy;
    }
    if (i < 0 || j < 0 || i > nx_ - 2 || j > ny_ - 2) return std::nullopt;
  }
}

std::optional<HeightField::Hit> HeightField::sweepBruteForce(const glm::dvec3& a, const glm::dvec3& b) const {
  std::optional<Hit> best;
  for (int j = 0; j + 1 < ny_; ++j)
    for (int i = 0; i + 1 < nx_; ++i) testCell(i, j, a, b, best);
  return best;
}

double HeightField::heightAt(double x, double y) const {
  if (!(x >= 0.0 && y >= 0.0 && x <= (nx_ - 1) * s_ && y <= (ny_ - 1) * s_))
    return std::numeric_limits<double>::quiet_NaN();
  const int i = std::min(int(x / s_), nx_ - 2), j = std::min(int(y / s_), ny_ - 2);
  const double fx = x / s_ - i, fy = y / s_ - j;
  const double h00 = h_[std::size_t(j) * nx_ + i], h10 = h_[std::size_t(j) * nx_ + i + 1];
  const double h01 = h_[std::size_t(j + 1) * nx_ + i], h11 = h_[std::size_t(j + 1) * nx_ + i + 1];
  return fx >= fy ? h00 + fx * (h10 - h00) + fy * (h11 - h10) : h00 + fy * (h01 - h00) + fx * (h11 - h01);
}

TerrainContact::TerrainContact(std::shared_ptr<const HeightField> terrain, std::vector<glm::dvec3> points,
                               double frictionCoefficient)
    : terrain_(std::move(terrain)), points_(std::move(points)), mu_(frictionCoefficient) {
  if (!terrain_) throw std::invalid_argument("geocean::bodies: TerrainContact terrain is null");
  if (!(mu_ >= 0.0) || !std::isfinite(mu_)) fail("terrain contact friction coefficient", mu_, "", "must be finite and >= 0");
  if (points_.empty()) fail("terrain contact point count", 0.0, "", "must be > 0");
}

// Coulomb: the tangential velocity loses up to mu times the normal velocity removed.
void TerrainContact::friction(glm::dvec3& v, const glm::dvec3& n, double removedNormal) const {
  if (mu_ <= 0.0) return;
  const glm::dvec3 vt = v - glm::dot(v, n) * n;
  const double speed = glm::length(vt);
  if (speed <= 0.0) return;
  v -= vt * (std::min(speed, mu_ * removedNormal) / speed);
}

void TerrainContact::afterStep(Body& body, const BodyState& before) const {
  BodyState& s = body.state;
  const HeightField& T = *terrain_;
  // Swept test: the earliest hit of any point between the two poses.
  std::optional<HeightField::Hit> first;
  for (const auto& p : points_) {
    const glm::dvec3 a = T.toPatch(before.positionEcef + before.bodyToEcef(p));
    const glm::dvec3 b = T.toPatch(s.positionEcef + s.bodyToEcef(p));
    if (auto h = bruteForce_ ? T.sweepBruteForce(a, b) : T.sweep(a, b); h && (!first || h->t < first->t)) first = h;
  }
  if (first) {
    s.positionEcef = before.positionEcef + first->t * (s.positionEcef - before.positionEcef);
    const glm::dvec3 n = T.frame().toEcef(first->normalEnu);
    const double vn = glm::dot(s.velocityEcef, n);
    if (vn < 0.0) {
      s.velocityEcef -= vn * n;
      friction(s.velocityEcef, n, -vn);
    }
  }
  // Static pass: lift by the deepest point (vertical lifts keep every point's
  // ground position, so after it none is below the surface).
  double deepest = 0.0;
  for (const auto& p : points_) {
    const glm::dvec3 q = T.toPatch(s.positionEcef + s.bodyToEcef(p));
    const double h = T.heightAt(q.x, q.y);
    if (!std::isnan(h)) deepest = std::max(deepest, h - q.z);
  }
  if (deepest > 0.0) {
    s.positionEcef += (deepest + 1e-9) * T.frame().up;
    const double vu = glm::dot(s.velocityEcef, T.frame().up);
    if (vu < 0.0) {
      s.velocityEcef -= vu * T.frame().up;
      friction(s.velocityEcef, T.frame().up, -vu);
    }
  }
}

double TerrainContact::clearanceM(const BodyState& s) const {
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (const auto& p : points_) {
    const glm::dvec3 q = terrain_->toPatch(s.positionEcef + s.bodyToEcef(p));
    const double h = terrain_->heightAt(q.x, q.y);
    if (!std::isnan(h) && !(q.z - h >= lowest)) lowest = q.z - h;
  }
  return lowest;
}

}  // namespace geocean::bodies
