#include "plugin/grid/Picker.h"

#include "globe/geo/Ellipsoid.h"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <stdexcept>
#include <string>
#include <vector>

namespace geocean::grid {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

struct DeviceDeleter {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using DevicePtr = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneDeleter>;

// Intersection context extended with our own flag (Embree's documented
// pattern): the refinement query looks at the terrain only.
struct PickContext {
  RTCIntersectContext base;
  bool terrainOnly = false;
};

// The sea: the whole ellipsoid as one user primitive, in local coordinates.
struct SeaGeometry {
  glm::dvec3 origin{0.0};
  const SurfaceClassifier* classify = nullptr;
  unsigned geomID = RTC_INVALID_GEOMETRY_ID;
};

bool seaExistsAt(const SurfaceClassifier* classify, const glm::dvec3& p) {
  if (!classify || !*classify) return true;
  const geo::Geodetic g = geo::fromEcef(p);
  ocean::Surface s = ocean::Surface::Land;
  (*classify)(&g.latDeg, &g.lonDeg, 1, &s);
  return s == ocean::Surface::Ocean;
}

void seaBounds(const RTCBoundsFunctionArguments* args) {
  const auto* sea = static_cast<const SeaGeometry*>(args->geometryUserPtr);
  const double pad = 1.0;  // metres, covers float rounding of the box
  args->bounds_o->lower_x = float(-geo::kWgs84A - sea->origin.x - pad);
  args->bounds_o->lower_y = float(-geo::kWgs84A - sea->origin.y - pad);
  args->bounds_o->lower_z = float(-geo::kWgs84B - sea->origin.z - pad);
  args->bounds_o->upper_x = float(geo::kWgs84A - sea->origin.x + pad);
  args->bounds_o->upper_y = float(geo::kWgs84A - sea->origin.y + pad);
  args->bounds_o->upper_z = float(geo::kWgs84B - sea->origin.z + pad);
}

// Double-precision intersection from Embree's float ray (the refinement with
// the caller's double ray happens afterwards).
void seaIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto* sea = static_cast<const SeaGeometry*>(args->geometryUserPtr);
  if (reinterpret_cast<const PickContext*>(args->context)->terrainOnly) return;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const glm::dvec3 o = sea->origin + glm::dvec3(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                                                  RTCRayN_org_z(ray, args->N, i));
    const glm::dvec3 d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
    const geo::RayHit h = geo::intersectEllipsoid(o, d);
    if (!h.hit) continue;
    const double tnear = RTCRayN_tnear(ray, args->N, i);
    float& tfar = RTCRayN_tfar(ray, args->N, i);
    for (double t : {h.tNear, h.tFar}) {
      if (t < tnear || t > double(tfar)) continue;
      const glm::dvec3 p = o + d * t;
      if (!seaExistsAt(sea->classify, p)) continue;
      const glm::dvec3 n = glm::normalize(glm::dvec3(p.x / (geo::kWgs84A * geo::kWgs84A), p.y / (geo::kWgs84A * geo::kWgs84A),
                                                     p.z / (geo::kWgs84B * geo::kWgs84B)));
      tfar = float(t);
      RTCHitN_Ng_x(hit, args->N, i) = float(n.x);
      RTCHitN_Ng_y(hit, args->N, i) = float(n.y);
      RTCHitN_Ng_z(hit, args->N, i) = float(n.z);
      RTCHitN_u(hit, args->N, i) = 0.0f;
      RTCHitN_v(hit, args->N, i) = 0.0f;
      RTCHitN_primID(hit, args->N, i) = args->primID;
      RTCHitN_geomID(hit, args->N, i) = args->geomID;
      RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
      break;
    }
  }
}

// t of a double ray/triangle plane hit (Moller-Trumbore); NaN if parallel.
double refineTriangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& v0, const glm::dvec3& v1,
                      const glm::dvec3& v2) {
  const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0, s = o - v0;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return std::numeric_limits<double>::quiet_NaN();
  const glm::dvec3 q = glm::cross(s, e1);
  return glm::dot(e2, q) / det;
}

// The cells of the raster's vertex grid (vertex (i, j) at pixel centre
// (i + 0.5, j + 0.5); cell (i, j) spans vertices i..i+1, j..j+1) that some
// ray can meet, and the polar fans (global rasters) it can meet.
struct CellSelection {
  std::vector<std::uint64_t> cells;  // j * cellCols + i, sorted, unique
  bool fan[2] = {false, false};      // fan on vertex row 0 / row H - 1
};

// Walks each ray through the shell of heights the terrain mesh can reach
// (raster min/max, widened by the chord sag of a cell) in steps of a
// quarter cell, and marks every cell within one cell of the lat/lon box
// each step can reach. nullopt when that would take too many steps.
std::optional<CellSelection> cellsAlong(const raster::Raster& r, const std::vector<PickRay>& rays) {
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
  CellSelection s;
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
  for (const PickRay& ray : rays) {
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

}  // namespace

struct Picker::Impl {
  DevicePtr device;
  ScenePtr scene;
  SeaGeometry sea;
  SurfaceClassifier classifier;
  glm::dvec3 origin{0.0};
  std::vector<glm::dvec3> terrainEcef;  // double vertices for refinement
  std::vector<std::uint32_t> terrainIdx;
  unsigned terrainID = RTC_INVALID_GEOMETRY_ID;
  std::string error;

  void check(const char* what) const {
    if (!error.empty()) throw std::runtime_error(std::string("embree: ") + what + ": " + error);
  }
  void buildTerrain(const raster::Raster& r);
  void buildTerrainCells(const raster::Raster& r, const CellSelection& sel);
  void uploadTerrain();
  PickResult finish(const PickRay& ray, const glm::dvec3& dUnit, unsigned geomID, unsigned primID, float tFloat) const;
  void setRay(RTCRayHit16& rh, int lane, const PickRay& ray, glm::dvec3& dUnit, bool& valid) const;
};

void Picker::Impl::buildTerrain(const raster::Raster& r) {
  const int W = r.width(), H = r.height();
  const raster::GeoTransform& gt = r.transform();
  const bool wrap = gt.global;
  terrainEcef.resize(std::size_t(W) * H);
  std::vector<std::uint8_t> ok(terrainEcef.size());
  tbb::parallel_for(0, H, [&](int j) {
    const double lat = gt.latOf(j + 0.5);
    for (int i = 0; i < W; ++i) {
      const float e = r.pixel(i, j);
      ok[std::size_t(j) * W + i] = std::isfinite(e);
      terrainEcef[std::size_t(j) * W + i] = geo::toEcef({std::clamp(lat, -90.0, 90.0), gt.lonOf(i + 0.5), std::isfinite(e) ? e : 0.0});
    }
  });
  const int cellCols = wrap ? W : W - 1;
  terrainIdx.clear();
  terrainIdx.reserve(std::size_t(cellCols) * (H - 1) * 6 + std::size_t(W) * 6);
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (ok[a] && ok[b] && ok[c]) terrainIdx.insert(terrainIdx.end(), {a, b, c});
  };
  for (int j = 0; j + 1 < H; ++j)
    for (int i = 0; i < cellCols; ++i) {
      const int i1 = (i + 1) % W;
      const auto a = std::uint32_t(j * W + i), b = std::uint32_t(j * W + i1), c = std::uint32_t((j + 1) * W + i),
                 d = std::uint32_t((j + 1) * W + i1);
      tri(a, b, d);
      tri(a, d, c);
    }
  // Global rasters: close the polar holes with a fan to a pole vertex at
  // the mean height of the edge row.
  if (wrap) {
    for (int edge = 0; edge < 2; ++edge) {
      const int j = edge == 0 ? 0 : H - 1;
      const auto pole = std::uint32_t(terrainEcef.size());
      terrainEcef.push_back(poleVertexEcef(r, j));
      ok.push_back(1);
      for (int i = 0; i < W; ++i) tri(pole, std::uint32_t(j * W + i), std::uint32_t(j * W + (i + 1) % W));
    }
  }
  uploadTerrain();
}


// The same vertices and triangles as buildTerrain, for the selected cells only.
void Picker::Impl::buildTerrainCells(const raster::Raster& r, const CellSelection& sel) {
  const int W = r.width(), H = r.height();
  const raster::GeoTransform& gt = r.transform();
  const long long cellCols = gt.global ? W : W - 1;
  std::unordered_map<std::uint32_t, std::uint32_t> local;  // raster vertex -> terrainEcef index
  std::vector<std::uint8_t> ok;
  terrainEcef.clear();
  terrainIdx.clear();
  auto vertex = [&](std::uint32_t id) {
    auto [it, fresh] = local.try_emplace(id, std::uint32_t(terrainEcef.size()));
    if (fresh) {
      const int i = int(id % std::uint32_t(W)), j = int(id / std::uint32_t(W));
      const double lat = gt.latOf(j + 0.5);
      const float e = r.pixel(i, j);
      ok.push_back(std::isfinite(e));
      terrainEcef.push_back(geo::toEcef({std::clamp(lat, -90.0, 90.0), gt.lonOf(i + 0.5), std::isfinite(e) ? e : 0.0}));
    }
    return it->second;
  };
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const std::uint32_t la = vertex(a), lb = vertex(b), lc = vertex(c);
    if (ok[la] && ok[lb] && ok[lc]) terrainIdx.insert(terrainIdx.end(), {la, lb, lc});
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
    const auto pole = std::uint32_t(terrainEcef.size());
    terrainEcef.push_back(poleVertexEcef(r, j));
    ok.push_back(1);
    for (int i = 0; i < W; ++i) {
      const std::uint32_t la = vertex(std::uint32_t(j * W + i)), lb = vertex(std::uint32_t(j * W + (i + 1) % W));
      if (ok[la] && ok[lb]) terrainIdx.insert(terrainIdx.end(), {pole, la, lb});
    }
  }
  if (!terrainIdx.empty()) uploadTerrain();  // no cell on the rays: no terrain geometry
}

void Picker::Impl::uploadTerrain() {
  RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), terrainEcef.size()));
  auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(std::uint32_t), terrainIdx.size() / 3));
  check("terrain buffers");
  for (std::size_t k = 0; k < terrainEcef.size(); ++k) {
    const glm::dvec3 p = terrainEcef[k] - origin;  // local coordinates, rounded last
    v[3 * k] = float(p.x), v[3 * k + 1] = float(p.y), v[3 * k + 2] = float(p.z);
  }
  std::copy(terrainIdx.begin(), terrainIdx.end(), idx);
  rtcCommitGeometry(g);
  terrainID = rtcAttachGeometry(scene.get(), g);
  rtcReleaseGeometry(g);
  check("terrain geometry");
}

Picker::Picker(std::shared_ptr<const raster::Raster> elevation, SurfaceClassifier classifier,
               const glm::dvec3& localOrigin)
    : Picker(std::move(elevation), std::move(classifier), localOrigin, nullptr) {}

Picker::Picker(std::shared_ptr<const raster::Raster> elevation, SurfaceClassifier classifier,
               const glm::dvec3& localOrigin, const std::vector<PickRay>& onlyAlong)
    : Picker(std::move(elevation), std::move(classifier), localOrigin, &onlyAlong) {}

Picker::Picker(std::shared_ptr<const raster::Raster> elevation, SurfaceClassifier classifier,
               const glm::dvec3& localOrigin, const std::vector<PickRay>* onlyAlong)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.origin = localOrigin;
  m.classifier = std::move(classifier);
  m.device.reset(rtcNewDevice(nullptr));
  if (!m.device) throw std::runtime_error("embree: cannot create a device");
  rtcSetDeviceErrorFunction(
      m.device.get(),
      [](void* user, RTCError, const char* str) { static_cast<Impl*>(user)->error = str ? str : "unknown error"; },
      &m);
  m.scene.reset(rtcNewScene(m.device.get()));
  // ROBUST: rays must not leak through cracks between huge triangles. LOW
  // build quality: the world's 1.2 M triangles build in a fraction of the
  // time of MEDIUM, and a CLI pick traces only a few rays per build.
  rtcSetSceneFlags(m.scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(m.scene.get(), RTC_BUILD_QUALITY_LOW);
  m.sea.origin = localOrigin;
  m.sea.classify = &m.classifier;
  RTCGeometry g = rtcNewGeometry(m.device.get(), RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, &m.sea);
  rtcSetGeometryBoundsFunction(g, seaBounds, nullptr);
  rtcSetGeometryIntersectFunction(g, seaIntersect);
  rtcCommitGeometry(g);
  m.sea.geomID = rtcAttachGeometry(m.scene.get(), g);
  rtcReleaseGeometry(g);
  m.check("sea geometry");
  if (elevation) {
    std::optional<CellSelection> sel;
    if (onlyAlong) sel = cellsAlong(*elevation, *onlyAlong);
    if (sel) {
      m.buildTerrainCells(*elevation, *sel);
    } else {
      m.buildTerrain(*elevation);
    }
  }
  rtcCommitScene(m.scene.get());
  m.check("scene build");
}

Picker::~Picker() = default;

std::size_t Picker::terrainTriangles() const { return impl_->terrainIdx.size() / 3; }

void Picker::Impl::setRay(RTCRayHit16& rh, int k, const PickRay& ray, glm::dvec3& dUnit, bool& valid) const {
  const double len = glm::length(ray.dir);
  const glm::dvec3& o = ray.originEcef;
  valid = len > 0.0 && std::isfinite(len) && std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z);
  dUnit = valid ? ray.dir / len : glm::dvec3(0, 0, 1);
  const glm::dvec3 lo = valid ? o - origin : glm::dvec3(0.0);
  rh.ray.org_x[k] = float(lo.x), rh.ray.org_y[k] = float(lo.y), rh.ray.org_z[k] = float(lo.z);
  rh.ray.dir_x[k] = float(dUnit.x), rh.ray.dir_y[k] = float(dUnit.y), rh.ray.dir_z[k] = float(dUnit.z);
  rh.ray.tnear[k] = 0.0f;
  rh.ray.tfar[k] = kInf;
  rh.ray.mask[k] = 0xFFFFFFFFu;
  rh.ray.time[k] = 0.0f;
  rh.ray.flags[k] = 0;
  rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
}

PickResult Picker::Impl::finish(const PickRay& ray, const glm::dvec3& d, unsigned geomID, unsigned primID,
                                float tFloat) const {
  const glm::dvec3& o = ray.originEcef;
  // Double sea candidate: exact root, where the sea exists.
  double tSea = std::numeric_limits<double>::infinity();
  const geo::RayHit sh = geo::intersectEllipsoid(o, d);
  if (sh.hit) {
    for (double t : {sh.tNear, sh.tFar}) {
      if (t >= 0.0 && seaExistsAt(&classifier, o + d * t)) {
        tSea = t;
        break;
      }
    }
  }
  // Double terrain candidate: the triangle Embree found, or, when Embree
  // reported the sea, any terrain triangle within its float error of it.
  double tTerrain = std::numeric_limits<double>::infinity();
  auto refine = [&](unsigned prim) {
    const std::uint32_t* t3 = &terrainIdx[std::size_t(prim) * 3];
    const double t = refineTriangle(o, d, terrainEcef[t3[0]], terrainEcef[t3[1]], terrainEcef[t3[2]]);
    if (std::isfinite(t) && t >= 0.0) tTerrain = std::min(tTerrain, t);
  };
  if (geomID == terrainID && terrainID != RTC_INVALID_GEOMETRY_ID) {
    refine(primID);
  } else if (geomID == sea.geomID && terrainID != RTC_INVALID_GEOMETRY_ID) {
    // Float error of the local-origin scene: ~1e-7 of the coordinates.
    const double slack = 1.0 + 2e-7 * (glm::length(o - origin) + double(tFloat));
    PickContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.terrainOnly = true;
    RTCRayHit rh{};
    const glm::dvec3 lo = o - origin;
    rh.ray.org_x = float(lo.x), rh.ray.org_y = float(lo.y), rh.ray.org_z = float(lo.z);
    rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
    rh.ray.tnear = float(std::max(0.0, double(tFloat) - slack));
    rh.ray.tfar = float(double(tFloat) + slack);
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.get(), &ctx.base, &rh);
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) refine(rh.hit.primID);
  }
  PickResult r;
  const double t = std::min(tSea, tTerrain);
  if (!std::isfinite(t)) return r;
  r.hit = true;
  r.kind = tSea <= tTerrain ? HitKind::Sea : HitKind::Terrain;
  r.distanceM = t;
  r.pointEcef = o + d * t;
  const geo::Geodetic g = geo::fromEcef(r.pointEcef);
  r.latDeg = g.latDeg, r.lonDeg = g.lonDeg, r.heightM = g.heightM;
  if (r.kind == HitKind::Sea) {
    r.surface = ocean::Surface::Ocean;
  } else {
    ocean::Surface s = ocean::Surface::Land;
    if (classifier) classifier(&r.latDeg, &r.lonDeg, 1, &s);
    r.surface = s == ocean::Surface::Lake ? ocean::Surface::Lake : ocean::Surface::Land;
  }
  return r;
}

PickResult Picker::pick(const PickRay& ray) const {
  PickResult r;
  pickBatch(&ray, 1, &r);
  return r;
}

void Picker::pickBatch(const PickRay* rays, std::size_t n, PickResult* out) const {
  const Impl& m = *impl_;
  const std::size_t packets = (n + 15) / 16;
  tbb::parallel_for(std::size_t(0), packets, [&](std::size_t p) {
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    glm::dvec3 dUnit[16];
    const std::size_t base = p * 16, count = std::min<std::size_t>(16, n - base);
    for (int k = 0; k < 16; ++k) {
      bool ok = false;
      if (std::size_t(k) < count) {
        m.setRay(rh, k, rays[base + k], dUnit[k], ok);
      } else {
        m.setRay(rh, k, PickRay{}, dUnit[k], ok);
      }
      valid[k] = ok ? -1 : 0;
    }
    PickContext ctx;
    rtcInitIntersectContext(&ctx.base);
    rtcIntersect16(valid, m.scene.get(), &ctx.base, &rh);
    for (std::size_t k = 0; k < count; ++k) {
      if (!valid[k]) {
        out[base + k] = PickResult{};
        continue;
      }
      // Even if Embree saw nothing (float rounding at a grazing sea hit), the
      // double sea test in finish() still runs.
      out[base + k] = m.finish(rays[base + k], dUnit[k], rh.hit.geomID[k], rh.hit.primID[k], rh.ray.tfar[k]);
    }
  });
}

}  // namespace geocean::grid
