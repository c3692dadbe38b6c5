#include "plugin/bodies/Hull.h"

#include "plugin/bodies/Validate.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

namespace geocean::bodies {

using detail::fail;
using detail::requirePositive;

namespace {

glm::dmat3 outer(const glm::dvec3& a, const glm::dvec3& b) {
  glm::dmat3 m;
  for (int c = 0; c < 3; ++c) m[c] = a * b[c];
  return m;
}

}  // namespace

HullMesh HullMesh::fromTriangles(std::vector<glm::dvec3> vertices, std::vector<std::uint32_t> indices,
                                 std::string kind) {
  if (indices.empty() || indices.size() % 3 != 0)
    fail("hull index count", static_cast<double>(indices.size()), "", "must be a positive multiple of 3");
  for (std::size_t i = 0; i < vertices.size(); ++i)
    detail::requireFinite("hull vertex " + std::to_string(i), vertices[i], "m");
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= vertices.size())
      fail("hull index " + std::to_string(i), indices[i], "", "must be below the vertex count " +
                                                                 std::to_string(vertices.size()));
  // Closed and consistently wound: every directed edge once, its reverse once.
  std::unordered_map<std::uint64_t, int> edges;
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  for (std::size_t t = 0; t < indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) ++edges[key(indices[t + e], indices[t + (e + 1) % 3])];
  for (const auto& [k, n] : edges) {
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k & 0xffffffffu);
    auto rev = edges.find(key(b, a));
    if (n != 1 || rev == edges.end() || rev->second != 1)
      fail("hull edge " + std::to_string(a) + "-" + std::to_string(b) + " use count", n, "",
           "a closed, consistently wound mesh uses each directed edge once and its reverse once");
  }

  // Volume, centroid and covariance of the tetrahedra (0, a, b, c).
  double vol = 0.0;
  glm::dvec3 firstMoment(0.0);
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    const glm::dvec3 &a = vertices[indices[t]], &b = vertices[indices[t + 1]], &c = vertices[indices[t + 2]];
    const double det = glm::dot(a, glm::cross(b, c));
    vol += det / 6.0;
    firstMoment += det / 24.0 * (a + b + c);
  }
  if (!(vol > 0.0)) fail("hull volume", vol, "m^3", "must be > 0 (outward, counter-clockwise winding)");
  HullMesh h;
  h.kind_ = std::move(kind);
  h.volume_ = vol;
  h.designCentroid_ = firstMoment / vol;
  for (auto& v : vertices) v -= h.designCentroid_;
  glm::dmat3 C(0.0);
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    const glm::dvec3 &a = vertices[indices[t]], &b = vertices[indices[t + 1]], &c = vertices[indices[t + 2]];
    const double det = glm::dot(a, glm::cross(b, c));
    const glm::dvec3 s = a + b + c;
    C += (det / 120.0) * (outer(a, a) + outer(b, b) + outer(c, c) + outer(s, s));
  }
  const double tr = C[0][0] + C[1][1] + C[2][2];
  h.unitInertia_ = glm::dmat3(tr) - C;
  // Symmetrise the rounding.
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) h.unitInertia_[i][j] = h.unitInertia_[j][i] = 0.5 * (h.unitInertia_[i][j] + h.unitInertia_[j][i]);
  h.min_ = h.max_ = vertices.front();
  for (const auto& v : vertices) h.min_ = glm::min(h.min_, v), h.max_ = glm::max(h.max_, v);
  h.vertices_ = std::move(vertices);
  h.indices_ = std::move(indices);
  return h;
}

MassProperties HullMesh::massProperties(double densityKgM3) const {
  requirePositive("body density", densityKgM3, "kg/m^3");
  return MassProperties(densityKgM3 * volume_, densityKgM3 * unitInertia_);
}

double HullMesh::volumeBelow(double zc) const {
  // Divergence theorem with the field (0, 0, z - zc): the plane's lid adds 0.
  double v = 0.0;
  for (std::size_t t = 0; t < indices_.size(); t += 3) {
    glm::dvec3 p[3] = {vertices_[indices_[t]], vertices_[indices_[t + 1]], vertices_[indices_[t + 2]]};
    glm::dvec3 poly[4];
    int m = 0;
    for (int e = 0; e < 3; ++e) {
      const glm::dvec3 &a = p[e], &b = p[(e + 1) % 3];
      const bool ia = a.z < zc, ib = b.z < zc;
      if (ia) poly[m++] = a;
      if (ia != ib) poly[m++] = a + (zc - a.z) / (b.z - a.z) * (b - a);
    }
    for (int j = 1; j + 1 < m; ++j) {
      const glm::dvec3 S = 0.5 * glm::cross(poly[j] - poly[0], poly[j + 1] - poly[0]);
      v += S.z * ((poly[0].z + poly[j].z + poly[j + 1].z) / 3.0 - zc);
    }
  }
  return v;
}

double HullMesh::restingWaterlineZ(double densityRatio) const {
  if (!(densityRatio > 0.0 && densityRatio < 1.0))
    fail("density ratio body / water", densityRatio, "", "must be in (0, 1) for the body to float");
  double lo = min_.z, hi = max_.z;
  const double target = densityRatio * volume_;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * (max_.z - min_.z); ++i) {
    const double mid = 0.5 * (lo + hi);
    (volumeBelow(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

HullMesh HullMesh::box(const glm::dvec3& sizeM, int facetsPerEdge) {
  requirePositive("box length", sizeM.x, "m");
  requirePositive("box beam", sizeM.y, "m");
  requirePositive("box height", sizeM.z, "m");
  if (facetsPerEdge < 1 || facetsPerEdge > 64) fail("box facets per edge", facetsPerEdge, "", "must be 1..64");
  const int n = facetsPerEdge;
  std::map<std::array<int, 3>, std::uint32_t> index;
  std::vector<glm::dvec3> verts;
  std::vector<std::uint32_t> tris;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, fresh] = index.try_emplace(p, static_cast<std::uint32_t>(verts.size()));
    if (fresh)
      verts.emplace_back((p[0] / double(n) - 0.5) * sizeM.x, (p[1] / double(n) - 0.5) * sizeM.y,
                         (p[2] / double(n) - 0.5) * sizeM.z);
    return it->second;
  };
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;  // u x v = +a
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<int, 3> p00{}, p10{}, p01{}, p11{};
          for (auto* p : {&p00, &p10, &p01, &p11}) (*p)[a] = side * n;
          p00[u] = i, p00[v] = j;
          p10[u] = i + 1, p10[v] = j;
          p01[u] = i, p01[v] = j + 1;
          p11[u] = i + 1, p11[v] = j + 1;
          const std::uint32_t q00 = vertex(p00), q10 = vertex(p10), q01 = vertex(p01), q11 = vertex(p11);
          if (side == 1) {
            tris.insert(tris.end(), {q00, q10, q11, q00, q11, q01});
          } else {
            tris.insert(tris.end(), {q00, q11, q10, q00, q01, q11});
          }
        }
    }
  }
  return fromTriangles(std::move(verts), std::move(tris), "box");
}

HullMesh HullMesh::cylinder(double radiusM, double heightM, int segments) {
  requirePositive("cylinder radius", radiusM, "m");
  requirePositive("cylinder height", heightM, "m");
  if (segments < 3 || segments > 1024) fail("cylinder segments", segments, "", "must be 3..1024");
  constexpr int kRows = 4;  // side rows, so wave pressure is sampled up the side
  const double pi = std::numbers::pi;
  // Polygon of area pi r^2: (N/2) R^2 sin(2 pi / N) = pi r^2.
  const double R = radiusM * std::sqrt(2.0 * pi / (segments * std::sin(2.0 * pi / segments)));
  std::vector<glm::dvec3> v;
  std::vector<std::uint32_t> t;
  for (int row = 0; row <= kRows; ++row)
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * pi * s / segments;
      v.emplace_back(R * std::cos(a), R * std::sin(a), heightM * (row / double(kRows) - 0.5));
    }
  const auto bottom = static_cast<std::uint32_t>(v.size());
  v.emplace_back(0.0, 0.0, -0.5 * heightM);
  const auto top = static_cast<std::uint32_t>(v.size());
  v.emplace_back(0.0, 0.0, 0.5 * heightM);
  auto at = [&](int row, int s) { return static_cast<std::uint32_t>(row * segments + (s % segments)); };
  for (int row = 0; row < kRows; ++row)
    for (int s = 0; s < segments; ++s) {
      const auto a = at(row, s), b = at(row, s + 1), c = at(row + 1, s), d = at(row + 1, s + 1);
      t.insert(t.end(), {a, b, d, a, d, c});
    }
  for (int s = 0; s < segments; ++s) {
    t.insert(t.end(), {bottom, at(0, s + 1), at(0, s)});
    t.insert(t.end(), {top, at(kRows, s), at(kRows, s + 1)});
  }
  return fromTriangles(std::move(v), std::move(t), "cylinder");
}

HullMesh HullMesh::boat(double lengthM) {
  requirePositive("boat length", lengthM, "m");
  constexpr int kStations = 11, kK = 5, kRing = 2 * kK + 1;
  const double L = lengthM, halfB = 0.5 * L / 3.5, D = L / 8.0;
  const double pi = std::numbers::pi;
  std::vector<glm::dvec3> v;
  std::vector<std::uint32_t> t;
  for (int i = 0; i < kStations; ++i) {
    const double xi = i / double(kStations - 1);  // 0 stern .. 1 bow
    const double x = (xi - 0.5) * L;
    // Half-beam: widest at 40 % from the stern, 85 % at the transom, 0 at the stem.
    const double f = xi < 0.4 ? 1.0 - 0.15 * std::pow((0.4 - xi) / 0.4, 2) : 1.0 - std::pow((xi - 0.4) / 0.6, 2);
    const double b = halfB * std::max(f, 0.0);
    // The keel rises towards the raked stem over the last 20 %.
    const double zKeel = xi > 0.8 ? 0.5 * D * std::pow((xi - 0.8) / 0.2, 2) : 0.0;
    auto point = [&](int k, double side) {
      const double th = 0.5 * pi * k / kK;
      v.emplace_back(x, side * b * std::sin(th), zKeel + (D - zKeel) * (1.0 - std::cos(th)));
    };
    point(0, 0.0);
    for (int k = 1; k <= kK; ++k) point(k, 1.0);
    for (int k = kK; k >= 1; --k) point(k, -1.0);
  }
  auto at = [](int station, int r) { return static_cast<std::uint32_t>(station * kRing + (r % kRing)); };
  for (int i = 0; i + 1 < kStations; ++i)
    for (int r = 0; r < kRing; ++r) {
      const auto a = at(i, r), b = at(i, r + 1), c = at(i + 1, r), d = at(i + 1, r + 1);
      t.insert(t.end(), {a, b, d, a, d, c});
    }
  for (int end = 0; end < 2; ++end) {
    const int s = end == 0 ? 0 : kStations - 1;
    glm::dvec3 centre(0.0);
    for (int r = 0; r < kRing; ++r) centre += v[at(s, r)];
    const auto c = static_cast<std::uint32_t>(v.size());
    v.push_back(centre / double(kRing));
    for (int r = 0; r < kRing; ++r) {
      if (end == 0) {
        t.insert(t.end(), {c, at(s, r + 1), at(s, r)});
      } else {
        t.insert(t.end(), {c, at(s, r), at(s, r + 1)});
      }
    }
  }
  // The ring runs keel -> port -> deck -> starboard; if that turned the mesh
  // inside out, flip every triangle.
  double vol = 0.0;
  for (std::size_t k = 0; k < t.size(); k += 3) vol += glm::dot(v[t[k]], glm::cross(v[t[k + 1]], v[t[k + 2]]));
  if (vol < 0.0)
    for (std::size_t k = 0; k < t.size(); k += 3) std::swap(t[k + 1], t[k + 2]);
  return fromTriangles(std::move(v), std::move(t), "boat");
}

}  // namespace geocean::bodies
