#include "plugin/grid/ScreenGrid.h"

#include "globe/geo/Parallel.h"
#include "plugin/grid/RayKernels.h"

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <iterator>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace geocean::grid {

namespace {
constexpr double kMaxRectNdc = 4.0;

// Row arrays of one kernel pass in ONE allocation, each array padded so that
// array k starts k cache lines further in the 4 KB page than array 0. As
// separate 512-double (4 KB) allocations they began 16 bytes apart in their
// pages: element i of every array fell into the same L1 set (horizonRow reads
// and writes 26 such arrays, packRow 7). 512^2 build 5% faster (A/B of 8
// alternating runs, 2026-11-30). Uninitialised unless zeroed: every kernel
// writes before it reads.
class PaddedArrays {
 public:
  void resize(std::size_t count, std::size_t n) {
    stride_ = (n + 7) / 8 * 8 + 8;  // whole cache lines, plus one
    block_ = std::make_unique_for_overwrite<double[]>(count * stride_ + 8);
    // 64-byte alignment: the block comes from operator new (16-byte aligned).
    const auto addr = reinterpret_cast<std::uintptr_t>(block_.get());
    base_ = block_.get() + ((64 - addr % 64) % 64) / sizeof(double);
  }
  double* operator[](std::size_t k) const { return base_ + k * stride_; }

 private:
  std::unique_ptr<double[]> block_;
  double* base_ = nullptr;
  std::size_t stride_ = 0;
};

template <class T>
struct RowBuf {
  std::unique_ptr<T[]> p;
  void resize(std::size_t n) { p = std::make_unique_for_overwrite<T[]>(n); }
  T* data() { return p.get(); }
  T* begin() { return p.get(); }
  T& operator[](std::size_t i) { return p[i]; }
  const T& operator[](std::size_t i) const { return p[i]; }
};

// A view of one array of a PaddedArrays block.
struct RowArray {
  double* p = nullptr;
  double* data() const { return p; }
  double& operator[](std::size_t i) const { return p[i]; }
};

struct RowScratch {
  PaddedArrays block;
  RowArray dx, dy, dz, t, rx, ry, rz, lat, lon;
  RowBuf<ocean::Surface> surf;
  RowBuf<std::uint8_t> unresolved;
  void resize(std::size_t n) {
    block.resize(9, n);
    std::size_t k = 0;
    for (auto* v : {&dx, &dy, &dz, &t, &rx, &ry, &rz, &lat, &lon}) v->p = block[k++];
    surf.resize(n);
    unresolved.resize(n);
    // horizonRow blends these for every lane (keeping the non-miss ones):
    // defined values once per task.
    std::fill_n(lat.data(), n, 0.0);
    std::fill_n(lon.data(), n, 0.0);
    std::fill_n(surf.data(), n, ocean::Surface::Ocean);
  }
};

// The limb candidates of every grid column in SoA form, for horizonRow.
struct ColumnLimbs {
  PaddedArrays block;
  RowArray dir[2][3], rel[2][3], lat[2], lon[2];
  std::vector<std::uint8_t> surface[2];
  void resize(std::size_t n) {
    block.resize(16, n);
    std::size_t b = 0;
    for (int k = 0; k < 2; ++k) {
      for (int a = 0; a < 3; ++a) dir[k][a].p = block[b++], rel[k][a].p = block[b++];
      lat[k].p = block[b++], lon[k].p = block[b++];
      surface[k].assign(n, 0);
    }
    for (std::size_t i = 0; i < b; ++i) std::fill_n(block[i], n, 0.0);
  }
};

// Horizon offset for rays that miss: the outer clamp ellipsoid, so a mesh
// lowered by the waves still reaches the true horizon; never above half the
// eye height (horizonPoint needs the eye outside that surface).
double horizonOffsetM(const camera::Camera& cam, double maxDisplacementM) {
  return std::min(maxDisplacementM, 0.5 * std::max(cam.heightM(), 0.0));
}

// Where a grid point whose ray misses goes: onto the limb (horizon) of the
// ellipsoid inflated by offsetM, where the grid's own column or row crosses
// it (whichever crossing is closer in direction to the ray; border columns
// and rows use their own line first). Columns stay straight up to the
// horizon and the screen edges keep their horizon corner:
// geo::horizonPoint (the limb point closest in direction) would pull edge
// columns towards the nadir and open slits at the screen border. Falls back
// to horizonPoint when neither line meets the limb.
enum class Along { Nearest, Column, Row };

// Up to two limb points on one grid line (a plane through the eye), eye-relative.
struct LimbLine {
  int n = 0;
  glm::dvec3 rel[2];
  glm::dvec3 dir[2];  // unit directions from the eye
  // surfaceLatLonBatch of each point, so horizon vertices copy them: the
  // same kernel on the same input, bit-identical to computing them per vertex.
  double latDeg[2], lonDeg[2];
  ocean::Surface surface[2];  // filled by the grid build (the classifier is not ours)
};

// A horizon vertex: eye-relative position and its lat/lon.
struct LimbPick {
  glm::dvec3 rel;
  double latDeg, lonDeg;
  const ocean::Surface* surface;  // the line's class, or null (horizonPoint fallback)
};

class LimbSolver {
 public:
  LimbSolver(const camera::Camera& cam, double offsetM) : cam_(cam), offsetM_(offsetM) {
    const double a = geo::kWgs84A + offsetM, b = geo::kWgs84B + offsetM;
    toScaled_ = {1.0 / a, 1.0 / a, 1.0 / b};
    fromScaled_ = {a, a, b};
    e_ = cam.eyeEcef() * toScaled_;
    const double r = glm::length(e_);
    valid_ = r > 1.0;
    if (!valid_) return;
    // Limb in scaled space: the circle |p| = 1, p.u = 1/r.
    const glm::dvec3 u = e_ / r;
    c0_ = u / r;
    rho_ = std::sqrt(std::max(0.0, 1.0 - 1.0 / (r * r)));
    v1_ = glm::normalize(glm::cross(u, std::abs(u.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
    v2_ = glm::cross(u, v1_);
    R_ = cam.right() * cam.tanHalfX();
    U_ = cam.up() * cam.tanHalfY();
  }
  LimbLine column(double x) const { return line(glm::cross(cam_.forward() + x * R_, U_)); }
  LimbLine row(double y) const { return line(glm::cross(cam_.forward() + y * U_, R_)); }

  // The chosen limb point for a missed ray of direction d (any length:
  // the choice compares dot products with d, which scale together).
  LimbPick choose(const LimbLine& col, const LimbLine& row, const glm::dvec3& d, Along along) const {
    double best = 0.0;
    int which = -1;
    auto consider = [&](const LimbLine& l, int base) {
      for (int k = 0; k < l.n; ++k) {
        const double dot = glm::dot(l.dir[k], d);
        if (dot > best) best = dot, which = base + k;
      }
    };
    if (along != Along::Row) consider(col, 0);
    if (along != Along::Column || which < 0) consider(row, 2);
    if (along == Along::Row && which < 0) consider(col, 0);
    if (which >= 0) {
      const LimbLine& l = which < 2 ? col : row;
      return {l.rel[which % 2], l.latDeg[which % 2], l.lonDeg[which % 2], &l.surface[which % 2]};
    }
    return fallback(d);
  }
  // No line crossing in front of the ray: the limb point closest in direction.
  LimbPick fallback(const glm::dvec3& d) const {
    LimbPick p{geo::horizonPoint(cam_.eyeEcef(), glm::normalize(d), offsetM_) - cam_.eyeEcef(), 0.0, 0.0, nullptr};
    surfaceLatLonBatch(eye_, &p.rel.x, &p.rel.y, &p.rel.z, 1, &p.latDeg, &p.lonDeg);
    return p;
  }

 private:
  LimbLine line(const glm::dvec3& normalWorld) const {
    LimbLine l;
    if (!valid_) return l;
    // A world plane normal n maps to n * fromScaled in scaled space.
    const glm::dvec3 n = normalWorld * fromScaled_;
    const double A = glm::dot(n, v1_), B = glm::dot(n, v2_), M = std::sqrt(A * A + B * B);
    const double k = (glm::dot(n, e_) - glm::dot(n, c0_)) / rho_;
    if (!(M > 0.0) || std::abs(k) > M) return l;
    // The circle's angles phi +- delta, phi = atan2(B, A), delta = acos(k / M),
    // as cosines and sines without trigonometric calls (cos phi = A / M,
    // cos delta = k / M, sin delta = sqrt((M - k)(M + k)) / M >= 0).
    const double sd = std::sqrt((M - k) * (M + k)), iM2 = 1.0 / (M * M);
    const double cs[2][2] = {{(A * k - B * sd) * iM2, (B * k + A * sd) * iM2},
                             {(A * k + B * sd) * iM2, (B * k - A * sd) * iM2}};
    for (const auto& c : cs) {
      const glm::dvec3 p = (c0_ + rho_ * (c[0] * v1_ + c[1] * v2_)) * fromScaled_;
      l.rel[l.n] = p - cam_.eyeEcef();
      l.dir[l.n] = glm::normalize(l.rel[l.n]);
      ++l.n;
    }
    const double rx[2] = {l.rel[0].x, l.rel[1].x}, ry[2] = {l.rel[0].y, l.rel[1].y}, rz[2] = {l.rel[0].z, l.rel[1].z};
    surfaceLatLonBatch(eye_, rx, ry, rz, std::size_t(l.n), l.latDeg, l.lonDeg);
    return l;
  }

  const camera::Camera& cam_;
  double offsetM_;
  double eye_[3] = {cam_.eyeEcef().x, cam_.eyeEcef().y, cam_.eyeEcef().z};
  bool valid_ = false;
  glm::dvec3 toScaled_{1.0}, fromScaled_{1.0}, e_{0.0}, c0_{0.0}, v1_{0.0}, v2_{0.0}, R_{0.0}, U_{0.0};
  double rho_ = 0.0;
};

glm::dvec3 missPointRel(const camera::Camera& cam, double x, double y, double offsetM, Along along) {
  const LimbSolver limb(cam, offsetM);
  return limb.choose(limb.column(x), limb.row(y), cam.rayThroughNdc(x, y), along).rel;
}

// Eye-relative point seen through NDC (x, y) on the base ellipsoid, or on the
// limb when the ray misses.
glm::dvec3 basePointRel(const camera::Camera& cam, double x, double y, double horizonOffset, Along along) {
  const glm::dvec3 d = cam.rayThroughNdc(x, y);
  const geo::RayHit h = geo::intersectEllipsoid(cam.eyeEcef(), d);
  if (h.hit) return d * h.tFirst();
  return missPointRel(cam, x, y, horizonOffset, along);
}

glm::dvec3 ellipsoidNormal(const glm::dvec3& p) {
  const double a2 = geo::kWgs84A * geo::kWgs84A, b2 = geo::kWgs84B * geo::kWgs84B;
  return glm::normalize(glm::dvec3(p.x / a2, p.y / a2, p.z / b2));
}
}  // namespace

NdcRect clampRectangle(const camera::Camera& cam, double h) {
  NdcRect r;
  if (!(h > 0.0)) return r;
  const double hOff = horizonOffsetM(cam, h);
  constexpr int kSamples = 17;
  // margin[e]: how far (NDC) a displaced border point can move inwards, for
  // edges left, right, bottom, top.
  double margin[4] = {0, 0, 0, 0};
  for (int iter = 0; iter < 2; ++iter) {
    const NdcRect at = r;
    for (int e = 0; e < 4; ++e) {
      const bool vertical = e < 2;  // left/right edges move in x
      for (int k = 0; k < kSamples; ++k) {
        const double s = double(k) / (kSamples - 1);
        const double x = vertical ? (e == 0 ? at.minX : at.maxX) : at.minX + s * (at.maxX - at.minX);
        const double y = vertical ? at.minY + s * (at.maxY - at.minY) : (e == 2 ? at.minY : at.maxY);
        const glm::dvec3 p = basePointRel(cam, x, y, hOff, vertical ? Along::Column : Along::Row);
        const auto q0 = cam.projectEyeRelative(p);
        if (!q0) continue;
        const glm::dvec3 n = ellipsoidNormal(cam.eyeEcef() + p);
        const glm::dvec3 t1 = glm::normalize(glm::cross(n, std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
        const glm::dvec3 t2 = glm::cross(n, t1);
        // First-order bound for a displacement of length h in any direction:
        // the norm of the three per-axis motions.
        double sum2 = 0.0;
        for (const glm::dvec3& u : {n, t1, t2}) {
          double m = 0.0;
          for (double sign : {-1.0, 1.0}) {
            const auto q = cam.projectEyeRelative(p + sign * h * u);
            const double move = !q ? kMaxRectNdc : vertical ? std::abs(q->x - q0->x) : std::abs(q->y - q0->y);
            m = std::max(m, move);
          }
          sum2 += m * m;
        }
        margin[e] = std::max(margin[e], std::sqrt(sum2));
      }
    }
    // 10 % over the first-order bound for the curvature of the projection.
    r.minX = std::max(-kMaxRectNdc, -1.0 - 1.1 * margin[0]);
    r.maxX = std::min(kMaxRectNdc, 1.0 + 1.1 * margin[1]);
    r.minY = std::max(-kMaxRectNdc, -1.0 - 1.1 * margin[2]);
    r.maxY = std::min(kMaxRectNdc, 1.0 + 1.1 * margin[3]);
  }
  return r;
}

std::vector<std::uint32_t> compactIndices(const GridFrame& f) {
  std::vector<std::uint32_t> out;
  out.reserve(f.indices.size());
  for (std::size_t c = 0; c < f.cellSkip.size(); ++c)
    if (!f.cellSkip[c]) out.insert(out.end(), f.indices.begin() + 6 * c, f.indices.begin() + 6 * c + 6);
  return out;
}

std::size_t coarseIndices(const GridFrame& f, const std::vector<std::uint8_t>& coarse, int block,
                          std::vector<std::uint32_t>& out) {
  if (block != 2 && block != 4 && block != 8) throw std::invalid_argument("grid: coarse block must be 2, 4 or 8");
  if (coarse.size() != f.vertices.size()) throw std::invalid_argument("grid: one coarse flag per vertex");
  out.clear();
  out.reserve(f.indices.size());
  const int cols = f.cols, rows = f.rows, B = block;
  const int bc = std::max(0, (cols - 1) / B), br = std::max(0, (rows - 1) / B);
  const auto vid = [&](int i, int j) { return std::uint32_t(j * cols + i); };
  std::vector<std::uint8_t> isCoarse(std::size_t(bc) * br, 0);
  for (int bj = 0; bj < br; ++bj)
    for (int bi = 0; bi < bc; ++bi) {
      bool ok = true;
      for (int j = bj * B; j <= bj * B + B && ok; ++j)
        for (int i = bi * B; i <= bi * B + B && ok; ++i) {
          const std::uint32_t v = vid(i, j);
          ok = coarse[v] != 0 && !(f.vertices[v].flags & kVertexHorizon);
          if (ok && i < bi * B + B && j < bj * B + B) ok = !f.cellSkip[std::size_t(j) * (cols - 1) + i];
        }
      isCoarse[std::size_t(bj) * bc + bi] = ok;
    }
  const auto coarseAt = [&](int bi, int bj) {
    return bi >= 0 && bj >= 0 && bi < bc && bj < br && isCoarse[std::size_t(bj) * bc + bi];
  };
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      const std::size_t c = std::size_t(j) * (cols - 1) + i;
      if (f.cellSkip[c] || coarseAt(i / B, j / B)) continue;
      out.insert(out.end(), f.indices.begin() + std::ptrdiff_t(6 * c), f.indices.begin() + std::ptrdiff_t(6 * c + 6));
    }
  std::size_t blocks = 0;
  std::vector<std::uint32_t> loop;
  for (int bj = 0; bj < br; ++bj)
    for (int bi = 0; bi < bc; ++bi) {
      if (!isCoarse[std::size_t(bj) * bc + bi]) continue;
      ++blocks;
      const int i0 = bi * B, j0 = bj * B, i1 = i0 + B, j1 = j0 + B;
      // A side keeps its vertices where cells lie beyond it that are not a coarse block.
      const bool fineS = j0 > 0 && !coarseAt(bi, bj - 1), fineE = i1 < cols - 1 && !coarseAt(bi + 1, bj);
      const bool fineN = j1 < rows - 1 && !coarseAt(bi, bj + 1), fineW = i0 > 0 && !coarseAt(bi - 1, bj);
      if (!(fineS || fineE || fineN || fineW)) {
        // The fine cells' diagonal (v00, v11), their winding.
        for (std::uint32_t v : {vid(i0, j0), vid(i1, j0), vid(i1, j1), vid(i0, j0), vid(i1, j1), vid(i0, j1)})
          out.push_back(v);
        continue;
      }
      // The boundary counter-clockwise (i right, j up, as the cells' own
      // winding), then a fan from the centre: the block is convex, so every
      // fan triangle keeps the cells' orientation.
      loop.clear();
      for (int i = i0; i < i1; i += fineS ? 1 : B) loop.push_back(vid(i, j0));
      for (int j = j0; j < j1; j += fineE ? 1 : B) loop.push_back(vid(i1, j));
      for (int i = i1; i > i0; i -= fineN ? 1 : B) loop.push_back(vid(i, j1));
      for (int j = j1; j > j0; j -= fineW ? 1 : B) loop.push_back(vid(i0, j));
      const std::uint32_t m = vid(i0 + B / 2, j0 + B / 2);
      for (std::size_t k = 0; k < loop.size(); ++k)
        for (std::uint32_t v : {m, loop[k], loop[(k + 1) % loop.size()]}) out.push_back(v);
      if (loop.size() % 2) out.insert(out.end(), {m, m, m});
    }
  return blocks;
}

struct ScreenGrid::Impl {
  std::optional<tbb::task_arena> arena;
};

ScreenGrid::ScreenGrid(GridOptions o, ocean::SurfaceClassifier classifier)
    : options_(o), classifier_(std::move(classifier)), impl_(std::make_unique<Impl>()) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("grid: " + what); };
  if (o.cols < 0 || o.cols == 1 || o.rows < 0 || o.rows == 1 || o.cols > 16384 || o.rows > 16384)
    bad("cols/rows " + std::to_string(o.cols) + "x" + std::to_string(o.rows) + " must be 0 or in [2, 16384]");
  if (!(o.cellPx >= 1.0 && o.cellPx <= 4096.0)) bad("cellPx " + std::to_string(o.cellPx) + " must be in [1, 4096]");
  if (!(o.maxDisplacementM >= 0.0 && o.maxDisplacementM < 1e5))
    bad("maxDisplacementM " + std::to_string(o.maxDisplacementM) + " must be in [0, 1e5)");
  if (o.threads < 0) bad("threads " + std::to_string(o.threads) + " must be >= 0");
  if (o.threads > 0) impl_->arena.emplace(o.threads);
}

ScreenGrid::~ScreenGrid() = default;

void ScreenGrid::build(const camera::Camera& cam, GridFrame& f) const {
  const GridOptions& o = options_;
  NdcRect rect = clampRectangle(cam, o.maxDisplacementM);
  // One extra cell beyond the rectangle on every side: where the limb leaves
  // the screen through a corner, the grid's corner vertex can follow only
  // one border line, and the sliver it leaves must fall off screen.
  int cols, rows;
  if (o.cols > 0) {
    cols = o.cols;
    const double ext = cols >= 4 ? (rect.maxX - rect.minX) / (cols - 3) : 0.0;
    rect.minX -= ext, rect.maxX += ext;
  } else {
    cols = std::max(2, int(std::ceil(0.5 * (rect.maxX - rect.minX) * cam.widthPx() / o.cellPx)) + 3);
    const double ext = 2.0 * o.cellPx / cam.widthPx();
    rect.minX -= ext, rect.maxX += ext;
  }
  if (o.rows > 0) {
    rows = o.rows;
    const double ext = rows >= 4 ? (rect.maxY - rect.minY) / (rows - 3) : 0.0;
    rect.minY -= ext, rect.maxY += ext;
  } else {
    rows = std::max(2, int(std::ceil(0.5 * (rect.maxY - rect.minY) * cam.heightPx() / o.cellPx)) + 3);
    const double ext = 2.0 * o.cellPx / cam.heightPx();
    rect.minY -= ext, rect.maxY += ext;
  }
  if (f.cols != cols || f.rows != rows || f.indices.size() != std::size_t(cols - 1) * (rows - 1) * 6) {
    f.indices.resize(std::size_t(cols - 1) * (rows - 1) * 6);
    std::size_t k = 0;
    for (int j = 0; j + 1 < rows; ++j)
      for (int i = 0; i + 1 < cols; ++i) {
        const std::uint32_t v00 = std::uint32_t(j * cols + i), v10 = v00 + 1, v01 = v00 + cols, v11 = v01 + 1;
        for (std::uint32_t v : {v00, v10, v11, v00, v11, v01}) f.indices[k++] = v;
      }
  }
  f.cols = cols;
  f.rows = rows;
  f.rect = rect;
  f.eyeEcef = cam.eyeEcef();
  f.vertices.resize(std::size_t(cols) * rows);
  f.cellSkip.resize(std::size_t(cols - 1) * (rows - 1));

  const double eye[3] = {cam.eyeEcef().x, cam.eyeEcef().y, cam.eyeEcef().z};
  const double hOff = horizonOffsetM(cam, o.maxDisplacementM);
  const glm::dvec3 F = cam.forward(), R = cam.right() * cam.tanHalfX(), U = cam.up() * cam.tanHalfY();
  const double dxNdc = (rect.maxX - rect.minX) / (cols - 1), dyNdc = (rect.maxY - rect.minY) / (rows - 1);
  // ISPG: the plane tangent to the ellipsoid below the eye (paper 000, eq. 5).
  const geo::Geodetic eyeGeo{0.0, 0.0, cam.heightM()};
  const geo::Geodetic nadirGeo = o.mode == GridMode::Ispg ? geo::fromEcef(cam.eyeEcef()) : eyeGeo;
  const glm::dvec3 planeN = geo::surfaceNormal(nadirGeo.latDeg, nadirGeo.lonDeg);
  const double planeH = nadirGeo.heightM;  // eye height above the plane
  const double ispgFar = cam.farM();
  const double Fa[3] = {F.x, F.y, F.z}, Ra[3] = {R.x, R.y, R.z}, Ua[3] = {U.x, U.y, U.z};
  const double Na[3] = {planeN.x, planeN.y, planeN.z};

  // Limb crossings of every grid column, needed only if some ray misses: the
  // rays that hit form a convex cone, so if the four corners hit, all do.
  const LimbSolver limb(cam, hOff);
  std::vector<LimbLine> colLines;
  bool cornersHit = o.mode == GridMode::Ispg;
  if (!cornersHit) {
    cornersHit = true;
    for (double cx : {rect.minX, rect.maxX})
      for (double cy : {rect.minY, rect.maxY})
        cornersHit = cornersHit && geo::intersectEllipsoid(cam.eyeEcef(), cam.rayThroughNdc(cx, cy)).hit;
  }
  if (!cornersHit) colLines.resize(std::size_t(cols));
  ColumnLimbs colLimbs;  // zero directions (no candidate) unless some corner misses
  colLimbs.resize(std::size_t(cols));

  auto classifyLine = [&](LimbLine& l) {
    if (classifier_ && l.n > 0) {
      classifier_(l.latDeg, l.lonDeg, std::size_t(l.n), l.surface);
    } else {
      std::fill(std::begin(l.surface), std::end(l.surface), ocean::Surface::Ocean);
    }
  };
  // Cell row j of cellSkip from the classes of vertex rows j and j + 1.
  auto skipRow = [&](int j, const std::uint8_t* below, const std::uint8_t* above) {
    return landCellRow(below, above, std::uint8_t(ocean::Surface::Land), std::size_t(cols),
                       f.cellSkip.data() + std::size_t(j) * (cols - 1));
  };

  // Rows in chunks, each touched once: rays, hits, horizon, lat/lon, class,
  // vertices, and the cell flags between the chunk's rows. A chunk is one
  // task (sky rows are cheaper than sea rows, so several chunks per thread
  // balance the load; fewer, larger tasks than TBB's auto partitioner).
  const int rowsPerChunk = std::max(4, rows / 64);
  const int chunks = (rows + rowsPerChunk - 1) / rowsPerChunk;
  // Stream the vertices out only when the buffer cannot stay in the cache.
  const bool streamOut = f.vertices.size() * sizeof(GridVertex) > (std::size_t(16) << 20);
  std::vector<std::size_t> chunkLandCells(static_cast<std::size_t>(chunks), 0);
  // The classes of each chunk's first and last row, for the cell rows
  // between chunks (read back from the vertex buffer they were 16 KB-strided
  // reads of memory, serial after the parallel part).
  std::vector<std::uint8_t> edgeSurf(std::size_t(chunks) * 2 * cols);
  auto buildChunk = [&](int c) {
    const int j0 = c * rowsPerChunk, j1 = std::min(rows, j0 + rowsPerChunk);
    // Per task, not thread-local: a classifier that itself runs TBB work
    // could make this thread pick up another row task while it waits.
    RowScratch s;
    s.resize(std::size_t(cols));
    std::vector<std::uint8_t> prevSurf(static_cast<std::size_t>(cols));
    for (int j = j0; j < j1; ++j) {
      const double y = rect.minY + j * dyNdc;
      // The row's vertex lines are requested now, so their transfer from L3
      // overlaps the row's arithmetic instead of stalling packRow.
      prefetchPackRow(f.vertices.data() + std::size_t(j) * cols, std::size_t(cols), streamOut);
      if (o.mode == GridMode::Direct) {
        surfaceHitsRow(eye, Fa, Ra, Ua, rect.minX, dxNdc, y, std::size_t(cols), s.t.data(), s.rx.data(), s.ry.data(),
                       s.rz.data());
      } else {
        rayRow(Fa, Ra, Ua, rect.minX, dxNdc, y, std::size_t(cols), s.dx.data(), s.dy.data(), s.dz.data());
        ispgBatch(eye, Na, planeH, ispgFar, s.dx.data(), s.dy.data(), s.dz.data(), std::size_t(cols), s.t.data(),
                  s.rx.data(), s.ry.data(), s.rz.data());
      }
      // The hits of a row are one span (the rays lie in a plane through the
      // eye); misses get their limb point with its lat/lon and class.
      // Count first (vectorised): sky rows then skip the scalar scans.
      const std::size_t misses = countNan(s.t.data(), std::size_t(cols));
      int first = misses == std::size_t(cols) ? cols : 0, last = cols - 1;
      if (misses > 0 && first < cols) {
        while (first < cols && std::isnan(s.t[first])) ++first;
        while (last >= first && std::isnan(s.t[last])) --last;
      }
      const bool anyMiss = misses > 0;
      if (anyMiss) {
        LimbLine rowLine = limb.row(y);
        classifyLine(rowLine);
        LimbCandidates cand;
        for (int k = 0; k < 2; ++k) {
          for (int a = 0; a < 3; ++a) {
            cand.colDir[k][a] = colLimbs.dir[k][a].data();
            cand.colRel[k][a] = colLimbs.rel[k][a].data();
            cand.rowDir[k][a] = k < rowLine.n ? rowLine.dir[k][a] : 0.0;
            cand.rowRel[k][a] = k < rowLine.n ? rowLine.rel[k][a] : 0.0;
          }
          cand.colLat[k] = colLimbs.lat[k].data();
          cand.colLon[k] = colLimbs.lon[k].data();
          cand.colSurface[k] = colLimbs.surface[k].data();
          cand.rowLat[k] = k < rowLine.n ? rowLine.latDeg[k] : 0.0;
          cand.rowLon[k] = k < rowLine.n ? rowLine.lonDeg[k] : 0.0;
          cand.rowSurface[k] = k < rowLine.n ? std::uint8_t(rowLine.surface[k]) : 0;
        }
        auto* surfBytes = reinterpret_cast<std::uint8_t*>(s.surf.data());
        const std::size_t left =
            horizonRow(Fa, Ra, Ua, rect.minX, dxNdc, y, std::size_t(cols), j == 0 || j == rows - 1, cand, s.t.data(),
                       s.rx.data(), s.ry.data(), s.rz.data(), s.lat.data(), s.lon.data(), surfBytes,
                       s.unresolved.data());
        for (int i = 0; left > 0 && i < cols; ++i) {
          if (!s.unresolved[std::size_t(i)]) continue;
          // No crossing in front of the ray (rare): the nearest limb point.
          const double x = rect.minX + double(i) * dxNdc;
          const glm::dvec3 d(F.x + y * U.x + x * R.x, F.y + y * U.y + x * R.y, F.z + y * U.z + x * R.z);
          const LimbPick pick = limb.fallback(d);
          s.rx[i] = pick.rel.x;
          s.ry[i] = pick.rel.y;
          s.rz[i] = pick.rel.z;
          s.lat[i] = pick.latDeg;
          s.lon[i] = pick.lonDeg;
          if (classifier_) {
            classifier_(&s.lat[i], &s.lon[i], 1, &s.surf[i]);
          } else {
            s.surf[i] = ocean::Surface::Ocean;
          }
        }
      }
      // Horizon vertices lie on the limb of the ellipsoid inflated by hOff:
      // the closed form is exact on the surface and off by at most
      // hOff e^2 / R there (3 cm for 5 m waves), irrelevant at the horizon.
      // Only the hit span needs the kernel (a miss inside it, if rounding
      // ever made one, is recomputed from the same input: same bits).
      if (last >= first) {
        const std::size_t n = std::size_t(last - first + 1), i0 = std::size_t(first);
        surfaceLatLonBatch(eye, s.rx.data() + i0, s.ry.data() + i0, s.rz.data() + i0, n, s.lat.data() + i0,
                           s.lon.data() + i0);
        if (classifier_) {
          classifier_(s.lat.data() + i0, s.lon.data() + i0, n, s.surf.data() + i0);
        } else {
          std::fill_n(s.surf.begin() + first, n, ocean::Surface::Ocean);
        }
      }
      const auto* surf = reinterpret_cast<const std::uint8_t*>(s.surf.data());
      packRow(s.t.data(), s.rx.data(), s.ry.data(), s.rz.data(), s.lat.data(), s.lon.data(), surf, rect.minX,
              dxNdc, std::abs(y) > 1.0, std::size_t(cols), f.vertices.data() + std::size_t(j) * cols, streamOut);
      if (j > j0) chunkLandCells[std::size_t(c)] += skipRow(j - 1, prevSurf.data(), surf);
      if (j == j0) std::copy_n(surf, cols, edgeSurf.data() + std::size_t(2 * c) * cols);
      std::copy_n(surf, cols, prevSurf.data());
    }
    std::copy_n(prevSurf.data(), cols, edgeSurf.data() + std::size_t(2 * c + 1) * cols);
  };
  auto run = [&] {
    if (!colLines.empty()) {
      geo::parallelFor(tbb::blocked_range<int>(0, cols, 32), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i < r.end(); ++i) {
          LimbLine& l = colLines[std::size_t(i)];
          l = limb.column(rect.minX + i * dxNdc);
          classifyLine(l);
          for (int k = 0; k < l.n; ++k) {
            for (int a = 0; a < 3; ++a) {
              colLimbs.dir[k][a][std::size_t(i)] = l.dir[k][a];
              colLimbs.rel[k][a][std::size_t(i)] = l.rel[k][a];
            }
            colLimbs.lat[k][std::size_t(i)] = l.latDeg[k];
            colLimbs.lon[k][std::size_t(i)] = l.lonDeg[k];
            colLimbs.surface[k][std::size_t(i)] = std::uint8_t(l.surface[k]);
          }
        }
      });
    }
    geo::parallelFor(tbb::blocked_range<int>(0, chunks, 1), [&](const tbb::blocked_range<int>& r) {
      for (int c = r.begin(); c < r.end(); ++c) buildChunk(c);
    }, tbb::simple_partitioner());
  };
  if (impl_->arena) {
    impl_->arena->execute(run);
  } else {
    run();
  }
  // The cell rows between chunks.
  std::size_t landCells = 0;
  for (std::size_t n : chunkLandCells) landCells += n;
  for (int c = 1; c < chunks; ++c) {
    landCells += skipRow(c * rowsPerChunk - 1, edgeSurf.data() + std::size_t(2 * c - 1) * cols,
                         edgeSurf.data() + std::size_t(2 * c) * cols);
  }
  f.landCells = landCells;
}

}  // namespace geocean::grid
