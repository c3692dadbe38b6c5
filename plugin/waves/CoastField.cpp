#include "plugin/waves/CoastField.h"

#include "globe/geo/Parallel.h"
#include "plugin/waves/WaveField.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace geocean::waves {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kA = 6378137.0;
constexpr double kF = 1.0 / 298.257223563;
constexpr double kE2 = kF * (2.0 - kF);
// Kernel's minimum depth (wv_gerstner): land and the swash zone are this shallow.
constexpr double kMinDepthM = 0.05;
// Below these a node does not feel the bottom: stored as exact 0 so the
// kernel reproduces deep water bit for bit. The eikonal's rounding reaches
// ~5e-7 rad over 400 nodes; 1e-5 rad is 0.01 mm on a 1 m wave. A turning
// below 1e-7 rad moves a 1 m wave by 0.1 um (deep water stored 1.7e-9 rad
// for a component 72 degrees off the wind, above the former 1e-9 cutoff).
constexpr double kPhaseEps = 1e-5, kAngleEps = 1e-7, kKrEps = 1e-7;
// Kr bounds: where rays cross (caustics) or diverge at the shoreline the
// ray-tube width has no meaning; the breaking cap limits heights anyway.
constexpr double kKrMin = CoastField::kMinKr, kKrMax = CoastField::kMaxKr;
constexpr double kMaxIslandRadiusNodes = 64.0;

double smooth01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// The inflow edges as one path (the edge normal to x, then the one normal
// to y, through their shared corner); along it, from each fixed node both
// ways, S steps by the local wave vector's component along the edge. The
// wave vector by Snell's law over the local contours: the depth gradient g
// (central differences over +-3 nodes; where the bottom is flat, the edge's
// normal: contours along the edge), the component along the contour
// k_c = k_ref s0 . c conserved from deep water, the rest k_g =
// sqrt(k^2 - k_c^2) along g with the sign of s0 . g. Contours across the
// edge (a region moved along a straight shore) and along it (an offshore
// edge: then the plane wave's own k_ref s0 . t) are both exact; k is taken
// as the sweeps take it over a step (at b, moved toward a by half the
// step's weight), so their straight-contour state continues it. Each node
// takes the value from its nearest fixed node on the path; runs stop at
// land. qEdge (NaN elsewhere): the ray-tube spreading of the same model,
// ln(cos(theta) / cos(theta0)), theta from g: Kr = sqrt(cos theta0 / cos theta).
void inflowEdgePhase(int n, double cellM, double s0x, double s0y, double k0, const std::vector<double>& kLoc,
                     const std::vector<double>& depth, const std::vector<char>& fixedNode, std::vector<double>& s,
                     std::vector<double>& qEdge) {
  struct Node {
    int i, j;
    bool alongY;  // on the x-normal edge (the path runs along y there)
  };
  std::vector<Node> path;
  const int ie = s0x > 0 ? 0 : n - 1, je = s0y > 0 ? 0 : n - 1;
  if (s0x != 0.0)  // the x-normal edge, from its far end to the corner
    for (int m = 0; m < n; ++m) path.push_back({ie, je == 0 ? n - 1 - m : m, true});
  if (s0y != 0.0)  // the y-normal edge, from the corner on (the corner once)
    for (int m = s0x != 0.0 ? 1 : 0; m < n; ++m) path.push_back({ie == 0 ? m : n - 1 - m, je, false});
  if (path.size() < 2) return;
  auto at = [n](const Node& a) { return std::size_t(a.j) * n + a.i; };
  const double inf = std::numeric_limits<double>::infinity();
  const std::size_t len = path.size();
  // Per path node: the unit depth gradient g (or the edge normal).
  std::vector<glm::dvec2> grad(len);
  for (std::size_t c = 0; c < len; ++c) {
    const int i = path[c].i, j = path[c].j;
    const int i0 = std::max(i - 3, 0), i1 = std::min(i + 3, n - 1), j0 = std::max(j - 3, 0), j1 = std::min(j + 3, n - 1);
    const glm::dvec2 g((depth[std::size_t(j) * n + i1] - depth[std::size_t(j) * n + i0]) / ((i1 - i0) * cellM),
                       (depth[std::size_t(j1) * n + i] - depth[std::size_t(j0) * n + i]) / ((j1 - j0) * cellM));
    // Flatter than 1:10000: no contour to refract over; the edge's normal.
    grad[c] = glm::length(g) > 1e-4 ? glm::normalize(g) : (path[c].alongY ? glm::dvec2(1.0, 0.0) : glm::dvec2(0.0, 1.0));
  }
  const glm::dvec2 s0(s0x, s0y);
  // The wave vector at path node c with wave number k.
  auto wave = [&](std::size_t c, double k) {
    const glm::dvec2 g = grad[c], cn(-g.y, g.x);
    const double kc = k0 * glm::dot(s0, cn), sg = glm::dot(s0, g) >= 0.0 ? 1.0 : -1.0;
    return kc * cn + sg * std::sqrt(std::max(k * k - kc * kc, 0.0)) * g;
  };
  std::vector<double> val[2] = {std::vector<double>(len, inf), std::vector<double>(len, inf)};
  std::vector<std::size_t> dist[2] = {std::vector<std::size_t>(len, len), std::vector<std::size_t>(len, len)};
  auto step = [&](std::size_t ca, std::size_t cb) {
    const Node &a = path[ca], &b = path[cb];
    const glm::dvec2 d(double(b.i - a.i) * cellM, double(b.j - a.j) * cellM);
    const double ka = kLoc[at(a)], kb = kLoc[at(b)];
    const glm::dvec2 t = glm::normalize(d);
    const double along0 = glm::dot(wave(cb, kb), t);
    const double w = kb > 0.0 ? along0 * along0 / (kb * kb) : 0.0, km = kb + 0.5 * w * (ka - kb);
    return glm::dot(wave(cb, km), d);
  };
  auto wet = [&](const Node& a) { return depth[at(a)] > 2.0 * kMinDepthM; };
  for (int dir = 0; dir < 2; ++dir)
    for (std::size_t m = 0; m < len; ++m) {
      const std::size_t c = dir == 0 ? m : len - 1 - m;
      if (fixedNode[at(path[c])]) {
        val[dir][c] = s[at(path[c])], dist[dir][c] = 0;
        continue;
      }
      if (m == 0 || !wet(path[c])) continue;
      const std::size_t pr = dir == 0 ? c - 1 : c + 1;
      if (!wet(path[pr]) || dist[dir][pr] >= len) continue;
      val[dir][c] = val[dir][pr] + step(pr, c);
      dist[dir][c] = dist[dir][pr] + 1;
    }
  for (std::size_t c = 0; c < len; ++c) {
    if (fixedNode[at(path[c])]) continue;
    const int d = dist[0][c] <= dist[1][c] ? 0 : 1;
    if (dist[d][c] >= len) continue;
    s[at(path[c])] = val[d][c];
    const double k = kLoc[at(path[c])], cos0 = std::abs(glm::dot(s0, grad[c]));
    const double kg = std::abs(glm::dot(wave(c, k), grad[c]));
    if (cos0 > 1e-3 && kg > 0.0) qEdge[at(path[c])] = std::log(kg / (k * cos0));
  }
}

// The grid one component is solved on: CoastField's region or an OuterPhase.
struct Grid {
  int n;
  double cellM;
  const std::vector<double>* depth;      // >= kMinDepthM
  const std::vector<double>* elevation;  // < 0: water (land counts as no deep water)
  // Land is no path (OuterPhase: coarse cells, waves go round the land);
  // CoastField's fine grid keeps crossing it slowly (its island table shades the lee).
  bool blockLand = false;
};

struct Solved {
  double sgn = 1.0;          // -1: the time-reversed wave, from the outflow edges
  double s0x = 0.0, s0y = 0.0;  // the solved wave's travel (sgn times the component's)
  bool fromOuter = false;    // the inflow edges were fixed by the outer phase
  std::vector<double> s, sx, sy, q;  // phase (inf: not reached), direction, ray-tube spreading
};

// The phase deep enough at the fixed inflow nodes: the plane wave there
// differs from the deep-water one by (k - k_deep) over the grid's diagonal,
// at most this (rad); else the phase's constant depends on where the edges lie.
constexpr double kDeepInflowRad = 0.01;

// One component with travel (tx, ty) (unit, x east, y north) on a grid
// centred on node (n - 1) / 2: its inflow edges, the fast-sweeping eikonal,
// directions and ray-tube spreading. If the deepest inflow node is not
// deep (kDeepInflowRad) and outerAt is given, every node at least
// OuterPhase::kMinDepthM deep where outerAt(i, j) = (phase offset, ray-tube
// spreading) is finite is fixed to it (the region then only solves the
// rest); otherwise (or where none is) the deepest inflow nodes carry the
// plane wave k_ref s0 . x and the rest of the edges is carried from them by
// Snell's law (inflowEdgePhase).
using OuterAt = std::function<glm::dvec2(int i, int j)>;
Solved solveComponent(const Grid& g, double k0, double omega, double tx, double ty, const OuterAt& outerAt) {
  const int n = g.n;
  const double cellM = g.cellM;
  const std::vector<double>& depth = *g.depth;
  const std::vector<double>& elevation = *g.elevation;
  const double inf = std::numeric_limits<double>::infinity();
  auto at = [n](int i, int j) { return std::size_t(j) * n + i; };
  const double half = 0.5 * (n - 1);
  auto x = [&](int i) { return (i - half) * cellM; };
  kd::Kernel kernel{};
  Solved out;
  std::vector<double> kLoc(depth.size()), div(depth.size()), qEdge(depth.size());
  std::vector<double>&s = out.s, &sx = out.sx, &sy = out.sy, &q = out.q;
  s.resize(depth.size()), sx.resize(depth.size()), sy.resize(depth.size()), q.resize(depth.size());
  std::vector<char> fixedNode(depth.size());
  // The kernel's own dispersion solve (Guo + 2 Newton steps, ~1e-9) and
  // its deep-water cut-off: deep nodes get exactly k_deep, as the kernel.
  const double kDeep = omega * omega / WV_G;
  for (std::size_t p = 0; p < depth.size(); ++p)
    kLoc[p] = kDeep * depth[p] < WV_DEEP_KH ? kernel.wv_waveNumber(omega, depth[p]) : kDeep;
  // How much deep water the inflow edges of travel (dx, dy) have: per node
  // kEdge / k (1: as deep as the deepest wet edge node; land 0: no wave
  // comes from land), the mean over each edge weighted by the flux through it.
  auto edgeDeepness = [&](double dx, double dy, double kEdge) {
    double num = 0.0, den = 0.0;
    auto side = [&](double flux, bool xNormal, int fixed) {
      if (flux <= 0.0) return;
      double sum = 0.0;
      for (int m = 0; m < n; ++m) {
        const std::size_t p = xNormal ? at(fixed, m) : at(m, fixed);
        if (elevation[p] < 0.0) sum += kEdge / kLoc[p];
      }
      num += flux * sum / n, den += flux;
    };
    side(std::abs(dx), true, dx > 0.0 ? 0 : n - 1);
    side(std::abs(dy), false, dy > 0.0 ? 0 : n - 1);
    return den > 0.0 ? num / den : 0.0;
  };
  // Carried from its deeper side: a component travelling toward deeper
  // water (offshore) has no deep inflow edge; its rays, traced back, end on
  // the shore, so a forward solve's phase there would be whatever arrives
  // first from the region's (moving) edges. Rays are reversible: solve the
  // time-reversed wave (-s0) from the deep outflow edges, where the phase
  // is the deep-water phase, and negate its phase (same turning and Kr:
  // the same rays and tubes). So two regions over one shelf agree
  // (Ocean::followCoastRegion). Reversed when the outflow edges' deep
  // water (edgeDeepness) exceeds the inflow's by 5 % of the flux: land
  // or an island blocking less of the inflow, and ties (deep all round),
  // keep the forward solve (its island shadows on the lee side).
  double kEdge = inf;
  for (int m = 0; m < n; ++m)
    for (const std::size_t p : {at(0, m), at(n - 1, m), at(m, 0), at(m, n - 1)})
      if (elevation[p] < 0.0) kEdge = std::min(kEdge, kLoc[p]);
  const double dIn = edgeDeepness(tx, ty, kEdge);
  const double dOut = edgeDeepness(-tx, -ty, kEdge);
  const double sgn = std::isfinite(kEdge) && dOut > dIn + 0.05 ? -1.0 : 1.0;
  out.sgn = sgn;
  const double s0x = sgn * tx, s0y = sgn * ty;
  out.s0x = s0x, out.s0y = s0y;
  // Inflow edges: the plane wave of the reference depth (outside the
  // region the kernel has no offset, so none here either). Only the
  // deepest inflow nodes carry it (deep water, or for long waves the
  // deepest the edge has): a shallower one would inject an early arrival;
  // there the sweeps continue the interior.
  std::fill(s.begin(), s.end(), inf);
  std::fill(fixedNode.begin(), fixedNode.end(), 0);
  auto inflow = [&](int i, int j) {
    return (i == 0 && s0x > 0) || (i == n - 1 && s0x < 0) || (j == 0 && s0y > 0) || (j == n - 1 && s0y < 0);
  };
  auto open = [&](std::size_t p) { return !g.blockLand || elevation[p] < 0.0; };
  double kIn = inf;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (inflow(i, j) && open(at(i, j))) kIn = std::min(kIn, kLoc[at(i, j)]);
  const double kFix = std::max(kIn, k0) * (1.0 + 1e-3);
  std::fill(qEdge.begin(), qEdge.end(), std::numeric_limits<double>::quiet_NaN());
  // No deep inflow node: the outer phase (same for every region) fixes the edges.
  const double diag = std::sqrt(2.0) * (n - 1) * cellM;
  if (outerAt && (kIn - kDeep) * diag > kDeepInflowRad)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (elevation[at(i, j)] >= 0.0 || depth[at(i, j)] < OuterPhase::kMinDepthM) continue;
        const glm::dvec2 o = outerAt(i, j);
        if (!std::isfinite(o.x) || !std::isfinite(o.y)) continue;
        s[at(i, j)] = k0 * (s0x * x(i) + s0y * x(j)) + sgn * o.x;
        qEdge[at(i, j)] = o.y;
        fixedNode[at(i, j)] = 1;
        out.fromOuter = true;
      }
  if (!out.fromOuter)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (!inflow(i, j) || kLoc[at(i, j)] > kFix || !open(at(i, j))) continue;
        s[at(i, j)] = k0 * (s0x * x(i) + s0y * x(j));
        fixedNode[at(i, j)] = 1;
      }
  // The other inflow nodes: the phase carried along the inflow edges from
  // the nearest deep node by Snell's law across the edge (the wave number
  // normal to the edge, k_ref s0 . n, conserved; the one along it
  // sqrt(k^2 - k_n^2)), exact where the contours cross the edge at right
  // angles, as a straight shore does for a region moved along it. So the
  // phase no longer depends on where the edge lies (issue 15 item 1: a
  // re-centred region agrees with the old one). Not fixed: the sweeps may
  // still lower them (an earlier arrival through the interior); land ends a run.
  inflowEdgePhase(n, cellM, s0x, s0y, k0, kLoc, depth, fixedNode, s, qEdge);
  // Fast sweeping, four orderings, until nothing changes.
  for (int iter = 0; iter < 12; ++iter) {
    double change = 0.0;
    for (int sweep = 0; sweep < 4; ++sweep) {
      const bool fx = sweep & 1, fy = sweep & 2;
      for (int jj = 0; jj < n; ++jj)
        for (int ii = 0; ii < n; ++ii) {
          const int i = fx ? n - 1 - ii : ii, j = fy ? n - 1 - jj : jj;
          const std::size_t p = at(i, j);
          if (fixedNode[p] || !open(p)) continue;
          const double a = std::min(i > 0 ? s[at(i - 1, j)] : inf, i < n - 1 ? s[at(i + 1, j)] : inf);
          const double b = std::min(j > 0 ? s[at(i, j - 1)] : inf, j < n - 1 ? s[at(i, j + 1)] : inf);
          if (a == inf && b == inf) continue;
          // Godunov update, then once more with k at the middle of the step
          // (weights: the step's share along each axis, cos^2 / sin^2), so
          // the phase gradient between nodes is second order where depth
          // changes along the ray (first order otherwise).
          const int ia = i > 0 && (i == n - 1 || s[at(i - 1, j)] <= s[at(i + 1, j)]) ? i - 1 : i + 1;
          const int jb = j > 0 && (j == n - 1 || s[at(i, j - 1)] <= s[at(i, j + 1)]) ? j - 1 : j + 1;
          auto update = [&](double k) {
            const double f = k * cellM;
            if (std::abs(a - b) >= f) return std::min(a, b) + f;
            return 0.5 * (a + b + std::sqrt(2.0 * f * f - (a - b) * (a - b)));
          };
          double v = update(kLoc[p]);
          {
            const double da = a < inf ? std::max(v - a, 0.0) : 0.0, db = b < inf ? std::max(v - b, 0.0) : 0.0;
            const double wsum = da * da + db * db;
            if (wsum > 0.0) {
              const double wa = da * da / wsum, wb = db * db / wsum;
              const double km = kLoc[p] + 0.5 * (wa * (kLoc[at(ia, j)] - kLoc[p]) + wb * (kLoc[at(i, jb)] - kLoc[p]));
              v = update(km);
            }
          }
          if (v < s[p]) {
            if (s[p] < inf) change = std::max(change, s[p] - v);
            s[p] = v;
          }
        }
    }
    if (iter > 0 && change < 1e-12) break;
  }
  // Direction (central differences, one-sided at edges) and its divergence.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, n - 1);
      int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, n - 1);
      if (g.blockLand) {  // one-sided beside land (not reached: inf)
        if (!std::isfinite(s[at(i0, j)])) i0 = i;
        if (!std::isfinite(s[at(i1, j)])) i1 = i;
        if (!std::isfinite(s[at(i, j0)])) j0 = j;
        if (!std::isfinite(s[at(i, j1)])) j1 = j;
        if (i0 == i1 || j0 == j1 || !std::isfinite(s[at(i, j)])) {
          sx[at(i, j)] = s0x, sy[at(i, j)] = s0y;
          continue;
        }
      }
      const double gx = (s[at(i1, j)] - s[at(i0, j)]) / ((i1 - i0) * cellM);
      const double gy = (s[at(i, j1)] - s[at(i, j0)]) / ((j1 - j0) * cellM);
      const double len = std::hypot(gx, gy);
      sx[at(i, j)] = len > 0 && std::isfinite(len) ? gx / len : s0x;
      sy[at(i, j)] = len > 0 && std::isfinite(len) ? gy / len : s0y;
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, n - 1);
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, n - 1);
      div[at(i, j)] = (sx[at(i1, j)] - sx[at(i0, j)]) / ((i1 - i0) * cellM) +
                      (sy[at(i, j1)] - sy[at(i, j0)]) / ((j1 - j0) * cellM);
    }
  // Ray-tube spreading: s . grad q = div s, q = 0 on the inflow edges
  // (upwind Gauss-Seidel in the same four orderings).
  for (std::size_t p = 0; p < q.size(); ++p) q[p] = std::isnan(qEdge[p]) ? 0.0 : qEdge[p];
  for (int iter = 0; iter < 4; ++iter)
    for (int sweep = 0; sweep < 4; ++sweep) {
      const bool fx = sweep & 1, fy = sweep & 2;
      for (int jj = 0; jj < n; ++jj)
        for (int ii = 0; ii < n; ++ii) {
          const int i = fx ? n - 1 - ii : ii, j = fy ? n - 1 - jj : jj;
          const std::size_t p = at(i, j);
          if (fixedNode[p] || !std::isnan(qEdge[p])) continue;
          const double ax = std::abs(sx[p]), ay = std::abs(sy[p]);
          const int iu = i - (sx[p] > 0 ? 1 : -1), ju = j - (sy[p] > 0 ? 1 : -1);
          const double qx = iu >= 0 && iu < n ? q[at(iu, j)] : 0.0;
          const double qy = ju >= 0 && ju < n ? q[at(i, ju)] : 0.0;
          q[p] = (div[p] * cellM + ax * qx + ay * qy) / std::max(ax + ay, 1e-30);
        }
    }
  return out;
}
}  // namespace

CoastField CoastField::build(const WaveField& field, const Region& r,
                             const std::function<double(double, double)>& depthAt, std::string& error,
                             const std::function<const OuterPhase*()>& outer) {
  CoastField cf;
  auto bad = [&](const char* name, double v, const char* want) {
    std::ostringstream os;
    os << "coast field: " << name << " = " << v << " is invalid (" << want << ")";
    error = os.str();
    return CoastField{};
  };
  if (field.model() != Model::Gerstner) {
    error = std::string("coast field: model ") + toString(field.model()) + " has no phase field (gerstner only)";
    return cf;
  }
  if (!(r.latDeg >= -90.0 && r.latDeg <= 90.0)) return bad("latDeg", r.latDeg, "expected -90 .. 90");
  if (!std::isfinite(r.lonDeg)) return bad("lonDeg", r.lonDeg, "expected finite");
  if (!(r.cellM > 0.0 && r.cellM <= 1e4)) return bad("cellM", r.cellM, "expected 0 < cellM <= 10 km");
  if (r.nodes < 5 || r.nodes > 2049) return bad("nodes", r.nodes, "expected 5 .. 2049");
  if (r.margin < 1 || 2 * r.margin >= r.nodes) return bad("margin", r.margin, "expected 1 .. nodes / 2");
  if (r.cellM * (r.nodes - 1) > 40e3) return bad("cellM * (nodes - 1)", r.cellM * (r.nodes - 1), "expected <= 40 km");
  if (!(r.islandRadiusM >= 0.0 && r.islandRadiusM <= 40e3))
    return bad("islandRadiusM", r.islandRadiusM, "expected 0 (automatic) .. 40 km");

  const int n = r.nodes;
  cf.region_ = r;
  cf.n_ = n;
  const double phi = r.latDeg * kPi / 180.0, lam = r.lonDeg * kPi / 180.0;
  const double sp = std::sin(phi), cp = std::cos(phi), sl = std::sin(lam), cl = std::cos(lam);
  const double nr = kA / std::sqrt(1.0 - kE2 * sp * sp);
  cf.centre_ = {nr * cp * cl, nr * cp * sl, nr * (1.0 - kE2) * sp};
  cf.east_ = {-sl, cl, 0.0};
  cf.north_ = {-sp * cl, -sp * sl, cp};
  // Axes rounded to float: CPU and GPU locate points with the same numbers.
  cf.eAxis_ = glm::dvec3(glm::vec3(cf.east_ / r.cellM));
  cf.nAxis_ = glm::dvec3(glm::vec3(cf.north_ / r.cellM));
  const glm::dvec3 radial = glm::normalize(cf.centre_);

  const double half = 0.5 * (n - 1);
  auto x = [&](int i) { return (i - half) * r.cellM; };
  std::vector<double> depth(std::size_t(n) * n);
  IslandInputs& isl = cf.islandInputs_;
  isl.elevation.resize(depth.size());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double h = depthAt(x(i), x(j));
      depth[std::size_t(j) * n + i] = std::isfinite(h) ? std::max(h, kMinDepthM) : kMinDepthM;
      isl.elevation[std::size_t(j) * n + i] = std::isfinite(h) ? -h : -kMinDepthM;
    }

  const auto& comps = field.components();
  cf.components_ = int(comps.size());
  cf.texels_.assign((comps.size() + 1) * std::size_t(n) * n, glm::dvec4(0.0));
  // NaN: the component does not reach the node (or has no travel here); its texel stays 0.
  cf.eikonal_.assign(comps.size() * std::size_t(n) * n, glm::dvec3(std::numeric_limits<double>::quiet_NaN()));
  auto at = [n](int i, int j) { return std::size_t(j) * n + i; };
  // Travel directions at the centre (as the kernel's great circles there).
  isl.nodes = n;
  isl.components = int(comps.size());
  isl.cellM = r.cellM;
  isl.travel.assign(comps.size(), glm::dvec4(0.0));
  std::vector<char> atSource(comps.size(), 0);
  double longest = 0.0;
  for (std::size_t c = 0; c < comps.size(); ++c) {
    const WaveField::Component& w = comps[c];
    glm::dvec3 g = radial * glm::dot(w.source, radial) - w.source;
    atSource[c] = glm::length(g) < 1e-12;  // at its source: the taper is 0 here
    g = atSource[c] ? cf.east_ : glm::normalize(g);
    isl.travel[c] = glm::dvec4(glm::dot(g, cf.east_), glm::dot(g, cf.north_), w.omega, 0.0);
    longest = std::max(longest, 2.0 * kPi * WV_G / (w.omega * w.omega));
  }
  // Occlusion radius: a few wavelengths (the shadow's Fresnel zone), at most
  // half the region and 64 nodes (the build's cost grows with its square).
  isl.radiusCells = std::min({(r.islandRadiusM > 0.0 ? r.islandRadiusM : 6.0 * longest) / r.cellM, 0.5 * (n - 1),
                              kMaxIslandRadiusNodes});
  isl.radiusCells = std::max(isl.radiusCells, 1.0);
  isl.landSat.assign(std::size_t(n + 1) * (n + 1), 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      isl.landSat[std::size_t(j + 1) * (n + 1) + i + 1] = int(isl.elevation[at(i, j)] > 0.0) +
          isl.landSat[std::size_t(j) * (n + 1) + i + 1] + isl.landSat[std::size_t(j + 1) * (n + 1) + i] -
          isl.landSat[std::size_t(j) * (n + 1) + i];
  cf.islands_ = islandTable(isl, &cf.shadow_);
  cf.reversed_.assign(comps.size(), 0);
  // Per component: the eikonal (solveComponent), the outer phase on the
  // inflow edges where the region has no deep node (OuterPhase).
  const OuterPhase* outerPhase = nullptr;
  bool outerAsked = false;
  const Grid grid{n, r.cellM, &depth, &isl.elevation};
  for (std::size_t c = 0; c < comps.size(); ++c) {
    const WaveField::Component& w = comps[c];
    if (atSource[c]) continue;
    const double k0 = w.kRef;
    // The outer phase at inflow node (i, j), asked for once (the first component without deep inflow).
    double turns = std::numeric_limits<double>::quiet_NaN();
    auto outerAt = [&](int i, int j) {
      if (!outerAsked) outerPhase = outer ? outer() : nullptr, outerAsked = true;
      if (!outerPhase || outerPhase->empty() || outerPhase->components() != int(comps.size()))
        return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
      glm::dvec2 o = outerPhase->sample(int(c), cf.centre_ + cf.east_ * x(i) + cf.north_ * x(j));
      // Less whole turns (the waves are the same): the outer offset is the
      // excess phase from deep water 100 km away (hundreds of rad), which
      // the margin's blend to 0 would squeeze into 400 m; so the first node
      // read sets the turns taken off (then a few tens of rad, as the fine
      // field's own).
      if (std::isfinite(o.x)) {
        if (std::isnan(turns)) turns = 2.0 * kPi * std::round(o.x / (2.0 * kPi));
        o.x -= turns;
      }
      return o;
    };
    const Solved sol = solveComponent(grid, k0, w.omega, isl.travel[c].x, isl.travel[c].y, outer ? OuterAt(outerAt) : OuterAt());
    cf.reversed_[c] = sol.sgn < 0.0;
    cf.outerComponents_ += sol.fromOuter;
    const double sgn = sol.sgn, s0x = sol.s0x, s0y = sol.s0y;
    // The eikonal's phase offset, turning and Kr per node, before the island table is folded in.
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t p = at(i, j);
        if (!std::isfinite(sol.s[p]) || !std::isfinite(sol.q[p])) continue;  // not reached from the inflow edges
        cf.eikonal_[c * std::size_t(n) * n + p] =
            glm::dvec3(sgn * (sol.s[p] - k0 * (s0x * x(i) + s0y * x(j))),
                       std::atan2(s0x * sol.sy[p] - s0y * sol.sx[p], s0x * sol.sx[p] + s0y * sol.sy[p]),
                       std::clamp(std::exp(-0.5 * sol.q[p]), kKrMin, kKrMax));
      }
  }
  cf.fold(cf.islands_, cf.shadow_, cf.texels_);
  // The beach slab (wv_gerstnerCoast's curl and collapse): slope over +-L0/4.
  const double l0 = field.peakWavelengthM(), h0 = field.spectrumHsM();
  const int m = std::clamp(int(std::lround(0.25 * l0 / r.cellM)), 1, 8);
  const double steep = h0 > 0.0 && l0 > 0.0 ? std::sqrt(h0 / l0) : 0.0;
  glm::dvec4* slab = &cf.texels_[comps.size() * std::size_t(n) * n];
  // Water nodes only (land is not the beach's slope): the span shrinks toward the node.
  auto wet = [&](int i, int j) { return isl.elevation[at(i, j)] < 0.0; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int i0 = std::max(i - m, 0), i1 = std::min(i + m, n - 1);
      int j0 = std::max(j - m, 0), j1 = std::min(j + m, n - 1);
      while (i0 < i && !wet(i0, j)) ++i0;
      while (i1 > i && !wet(i1, j)) --i1;
      while (j0 < j && !wet(i, j0)) ++j0;
      while (j1 > j && !wet(i, j1)) --j1;
      const double gx = i1 > i0 ? (depth[at(i1, j)] - depth[at(i0, j)]) / ((i1 - i0) * r.cellM) : 0.0;
      const double gy = j1 > j0 ? (depth[at(i, j1)] - depth[at(i, j0)]) / ((j1 - j0) * r.cellM) : 0.0;
      const double tanBeta = std::hypot(gx, gy);
      const double xi = steep > 0.0 ? tanBeta / steep : 0.0;
      const int edge = std::min(std::min(i, j), std::min(n - 1 - i, n - 1 - j));
      const double wgt = smooth01(double(edge) / r.margin);
      const double notSurging = 1.0 - glm::smoothstep(1.8, 2.2, xi);
      const double curl = glm::smoothstep(0.3, 0.5, xi) * notSurging;
      const double on = r.breaking ? wgt : 0.0;
      slab[at(i, j)] = glm::dvec4(xi, on * curl, on * notSurging, tanBeta);
    }
  return cf;
}

CoastField::Breaker CoastField::breakerType(double xi) {
  return xi < 0.4 ? Breaker::Spilling : (xi <= 2.0 ? Breaker::Plunging : Breaker::Surging);
}

const char* CoastField::breakerName(Breaker b) {
  switch (b) {
    case Breaker::Spilling: return "spilling";
    case Breaker::Plunging: return "plunging";
    case Breaker::Surging: return "surging";
  }
  return "?";
}

CoastField::Beach CoastField::beachAt(double eastM, double northM) const {
  Beach b;
  if (n_ == 0) return b;
  const double half = 0.5 * (n_ - 1);
  const long i = std::lround(eastM / region_.cellM + half), j = std::lround(northM / region_.cellM + half);
  if (i < 0 || j < 0 || i >= n_ || j >= n_) return b;
  const glm::dvec4 t = texels_[(std::size_t(components_) * n_ + std::size_t(j)) * n_ + std::size_t(i)];
  b.iribarren = t.x;
  b.curlWeight = t.y;
  b.breakWeight = t.z;
  b.tanBeta = t.w;
  b.type = breakerType(t.x);
  return b;
}

std::vector<glm::dvec4> CoastField::islandTable(const IslandInputs& in, std::vector<double>* shadowOut) {
  const int n = in.nodes;
  std::vector<glm::dvec4> out(std::size_t(in.components) * n * n, glm::dvec4(1.0, 0.0, 1.0, 0.0));
  std::vector<double> shadowLocal;
  std::vector<double>& shadow = shadowOut ? *shadowOut : shadowLocal;
  shadow.assign(out.size(), 0.0);
  if (n == 0 || in.components == 0) return out;
  geo::parallelFor(0, n, [&](int j) {
    kd::Kernel k{};
    k.wvIslandElev = in.elevation.data();
    k.wvIslandLandSat = in.landSat.data();
    k.wvIslandComps = in.travel.data();
    k.wvIslandTable = out.data();
    k.wvIslandShadow = shadow.data();
    for (int i = 0; i < n; ++i) k.wv_islandNode(n, i, j, in.components, in.cellM, in.radiusCells);
  });
  return out;
}

void CoastField::fold(const std::vector<glm::dvec4>& islands, const std::vector<double>& shadow,
                      std::vector<glm::dvec4>& texels) const {
  const int n = n_;
  const Region& r = region_;
  for (int c = 0; c < components_; ++c)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t e = (std::size_t(c) * n + std::size_t(j)) * n + std::size_t(i);
        glm::dvec4& out = texels[e];
        out = glm::dvec4(0.0);
        const glm::dvec3 eik = eikonal_[e];
        if (std::isnan(eik.x)) continue;
        const double delta = eik.x;
        // The island table: D_obs on the height, theta_def on the direction.
        const glm::dvec4 isle = islands[e];
        const double lit = 1.0 - shadow[e];
        const double beta = lit * eik.y + isle.w;
        const double kr = (1.0 + lit * (eik.z - 1.0)) * isle.z;
        if (std::abs(delta) < kPhaseEps && std::abs(beta) < kAngleEps && std::abs(kr - 1.0) < kKrEps) continue;
        const int edge = std::min(std::min(i, j), std::min(n - 1 - i, n - 1 - j));
        const double wgt = smooth01(double(edge) / r.margin);
        if (wgt == 0.0) continue;
        const double b = wgt * beta;
        out = glm::dvec4(wgt * delta, std::sin(b), 1.0 - std::cos(b), wgt * (kr - 1.0));
      }
}

std::vector<glm::vec4> CoastField::gpuTexelsWith(const std::vector<glm::vec4>& islands,
                                                 const std::vector<float>& shadow) const {
  const std::size_t m = std::size_t(components_) * n_ * n_;
  if (islands.size() != m || shadow.size() != m) return {};
  std::vector<glm::dvec4> t(texels_.size()), isl(m);
  std::vector<double> sh(m);
  for (std::size_t i = 0; i < m; ++i) isl[i] = glm::dvec4(islands[i]), sh[i] = shadow[i];
  fold(isl, sh, t);
  std::copy(texels_.begin() + std::ptrdiff_t(m), texels_.end(), t.begin() + std::ptrdiff_t(m));  // the beach slab
  std::vector<glm::vec4> v;
  v.reserve(t.size());
  for (const auto& x : t) v.push_back(glm::vec4(x));
  return v;
}

kd::WvCoast CoastField::at(const glm::dvec3& o) const {
  kd::WvCoast c{};
  if (n_ == 0) return c;
  const double half = 0.5 * (n_ - 1);
  const double tx = glm::dot(eAxis_, o - centre_) + half, ty = glm::dot(nAxis_, o - centre_) + half;
  const double fx = std::floor(tx), fy = std::floor(ty);
  // Far outside the grid: any cell outside (the kernel returns 0 there).
  const double lim = 1e9;
  c.eAxis = glm::dvec4(eAxis_, tx - fx);
  c.nAxis = glm::dvec4(nAxis_, ty - fy);
  c.cell = glm::ivec4(int(std::clamp(fx, -lim, lim)), int(std::clamp(fy, -lim, lim)), n_, 0);
  return c;
}

kf::WvCoast CoastField::gpuAt(const glm::dvec3& o) const {
  const kd::WvCoast c = at(o);
  return {glm::vec4(c.eAxis), glm::vec4(c.nAxis), c.cell};
}

std::vector<glm::vec4> CoastField::gpuTexels() const {
  std::vector<glm::vec4> v;
  v.reserve(texels_.size());
  for (const auto& t : texels_) v.push_back(glm::vec4(t));
  return v;
}

}  // namespace geocean::waves

namespace geocean::waves {

void OuterPhase::latticePoint(double latDeg, double lonDeg, double& latOut, double& lonOut) {
  latOut = std::clamp(std::round(latDeg / kLatticeDeg) * kLatticeDeg, -89.0, 89.0);
  lonOut = std::round(lonDeg / kLatticeDeg) * kLatticeDeg;
}

OuterPhase OuterPhase::build(const WaveField& field, double latDeg, double lonDeg,
                             const std::function<double(double, double)>& depthAt, std::string& error) {
  OuterPhase op;
  if (field.model() != Model::Gerstner) {
    error = std::string("outer phase: model ") + toString(field.model()) + " has no phase field (gerstner only)";
    return op;
  }
  if (!(latDeg >= -89.0 && latDeg <= 89.0) || !std::isfinite(lonDeg)) {
    std::ostringstream os;
    os << "outer phase: centre " << latDeg << ", " << lonDeg << " is invalid (expected latitude -89 .. 89, finite longitude)";
    error = os.str();
    return op;
  }
  const int n = kNodes;
  op.latDeg_ = latDeg, op.lonDeg_ = lonDeg;
  const double phi = latDeg * kPi / 180.0, lam = lonDeg * kPi / 180.0;
  const double sp = std::sin(phi), cp = std::cos(phi), sl = std::sin(lam), cl = std::cos(lam);
  const double nr = kA / std::sqrt(1.0 - kE2 * sp * sp);
  op.centre_ = {nr * cp * cl, nr * cp * sl, nr * (1.0 - kE2) * sp};
  op.east_ = {-sl, cl, 0.0};
  op.north_ = {-sp * cl, -sp * sl, cp};
  const glm::dvec3 radial = glm::normalize(op.centre_);
  const double half = 0.5 * (n - 1);
  auto x = [&](int i) { return (i - half) * kCellM; };
  std::vector<double> depth(std::size_t(n) * n), elevation(depth.size());
  // Rows on all cores: depthAt is the façade's query (thread-safe).
  geo::parallelFor(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const double h = depthAt(x(i), x(j));
      depth[std::size_t(j) * n + i] = std::isfinite(h) ? std::max(h, kMinDepthM) : kMinDepthM;
      elevation[std::size_t(j) * n + i] = std::isfinite(h) ? -h : -kMinDepthM;
    }
  });
  const auto& comps = field.components();
  op.n_ = n;
  op.components_ = int(comps.size());
  op.nodes_.assign(comps.size() * std::size_t(n) * n, glm::dvec2(std::numeric_limits<double>::quiet_NaN()));
  const Grid grid{n, kCellM, &depth, &elevation, true};
  op.reversed_.assign(comps.size(), 0);
  // Components in parallel: each solve is independent (its own buffers).
  geo::parallelFor(std::size_t(0), comps.size(), [&](std::size_t c) {
    const WaveField::Component& w = comps[c];
    glm::dvec3 g = radial * glm::dot(w.source, radial) - w.source;
    if (glm::length(g) < 1e-12) return;  // at its source: no travel (the fine field skips it too)
    g = glm::normalize(g);
    const Solved sol = solveComponent(grid, w.kRef, w.omega, glm::dot(g, op.east_), glm::dot(g, op.north_), {});
    op.reversed_[c] = sol.sgn < 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t p = std::size_t(j) * n + i;
        if (!std::isfinite(sol.s[p]) || !std::isfinite(sol.q[p]) || elevation[p] >= 0.0) continue;
        op.nodes_[c * std::size_t(n) * n + p] =
            glm::dvec2(sol.sgn * (sol.s[p] - w.kRef * (sol.s0x * x(i) + sol.s0y * x(j))), sol.q[p]);
      }
  });
  return op;
}

bool OuterPhase::covers(const glm::dvec3& centreEcef, double halfM) const {
  if (n_ == 0) return false;
  const glm::dvec3 d = centreEcef - centre_;
  const double lim = 0.5 * (n_ - 1) * kCellM - kReachM - halfM;
  return std::abs(glm::dot(d, east_)) <= lim && std::abs(glm::dot(d, north_)) <= lim;
}

glm::dvec2 OuterPhase::sample(int c, const glm::dvec3& p) const {
  const glm::dvec2 none(std::numeric_limits<double>::quiet_NaN());
  if (n_ == 0 || c < 0 || c >= components_) return none;
  const double half = 0.5 * (n_ - 1);
  const glm::dvec3 d = p - centre_;
  const double tx = glm::dot(d, east_) / kCellM + half, ty = glm::dot(d, north_) / kCellM + half;
  const double fx = std::floor(tx), fy = std::floor(ty);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < n_ - 1 && fy < n_ - 1)) return none;
  const int i = int(fx), j = int(fy);
  const double ax = tx - fx, ay = ty - fy;
  glm::dvec2 sum(0.0);
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const glm::dvec2 v = nodes_[(std::size_t(c) * n_ + std::size_t(j + dj)) * n_ + std::size_t(i + di)];
      if (std::isnan(v.x)) return none;
      sum += (di ? ax : 1.0 - ax) * (dj ? ay : 1.0 - ay) * v;
    }
  return sum;
}

}  // namespace geocean::waves
