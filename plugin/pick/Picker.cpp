#include "plugin/pick/Picker.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/geo/Parallel.h"
#include "globe/terrain/TerrainScene.h"

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

namespace geocean::pick {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneDeleter>;

// The sea: the whole ellipsoid as one user primitive, in local coordinates.
struct SeaGeometry {
  glm::dvec3 origin{0.0};
  const ocean::SurfaceClassifier* classify = nullptr;
  unsigned geomID = RTC_INVALID_GEOMETRY_ID;
};

bool seaExistsAt(const ocean::SurfaceClassifier* classify, const glm::dvec3& p) {
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

}  // namespace

struct Picker::Impl {
  std::shared_ptr<const terrain::EmbreeDevice> device;
  std::optional<terrain::TerrainScene> terrain;  // none without elevation or triangles
  ScenePtr scene;                                // sea + an instance of terrain->scene()
  SeaGeometry sea;
  ocean::SurfaceClassifier classifier;
  glm::dvec3 origin{0.0};
  unsigned terrainInstID = RTC_INVALID_GEOMETRY_ID;

  PickResult finish(const PickRay& ray, const glm::dvec3& dUnit, unsigned geomID, unsigned instID, unsigned primID,
                    float tFloat) const;
  void setRay(RTCRayHit16& rh, int lane, const PickRay& ray, glm::dvec3& dUnit, bool& valid) const;
};

Picker::Picker(std::shared_ptr<const raster::Raster> elevation, ocean::SurfaceClassifier classifier,
               const glm::dvec3& localOrigin)
    : Picker(std::move(elevation), std::move(classifier), localOrigin, nullptr) {}

Picker::Picker(std::shared_ptr<const raster::Raster> elevation, ocean::SurfaceClassifier classifier,
               const glm::dvec3& localOrigin, const std::vector<PickRay>& onlyAlong)
    : Picker(std::move(elevation), std::move(classifier), localOrigin, &onlyAlong) {}

Picker::Picker(std::shared_ptr<const raster::Raster> elevation, ocean::SurfaceClassifier classifier,
               const glm::dvec3& localOrigin, const std::vector<PickRay>* onlyAlong)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.origin = localOrigin;
  m.classifier = std::move(classifier);
  m.device = std::make_shared<const terrain::EmbreeDevice>();
  RTCDevice dev = m.device->get();
  if (elevation) {
    std::optional<terrain::CellRegion> sel;
    if (onlyAlong) sel = terrain::cellsAlong(*elevation, *onlyAlong);
    auto mesh = std::make_shared<const terrain::TerrainMesh>(sel ? terrain::TerrainMesh::region(*elevation, *sel, localOrigin)
                                                                 : terrain::TerrainMesh::whole(*elevation, localOrigin));
    if (!mesh->empty()) m.terrain.emplace(m.device, std::move(mesh));
  }
  m.scene.reset(rtcNewScene(dev));
  // ROBUST: rays must not leak through cracks (the terrain scene is robust too).
  rtcSetSceneFlags(m.scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(m.scene.get(), RTC_BUILD_QUALITY_LOW);
  m.sea.origin = localOrigin;
  m.sea.classify = &m.classifier;
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, &m.sea);
  rtcSetGeometryBoundsFunction(g, seaBounds, nullptr);
  rtcSetGeometryIntersectFunction(g, seaIntersect);
  rtcCommitGeometry(g);
  m.sea.geomID = rtcAttachGeometry(m.scene.get(), g);
  rtcReleaseGeometry(g);
  m.device->check("sea geometry");
  if (m.terrain) {
    // Identity transform: float x * 1 + 0 is exact, so the instanced terrain
    // sees the same float rays as the terrain scene alone.
    RTCGeometry inst = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, m.terrain->scene());
    const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
    rtcCommitGeometry(inst);
    m.terrainInstID = rtcAttachGeometry(m.scene.get(), inst);
    rtcReleaseGeometry(inst);
    m.device->check("terrain instance");
  }
  rtcCommitScene(m.scene.get());
  m.device->check("scene build");
}

Picker::~Picker() = default;

std::size_t Picker::terrainTriangles() const { return impl_->terrain ? impl_->terrain->mesh().triangleCount() : 0; }

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

PickResult Picker::Impl::finish(const PickRay& ray, const glm::dvec3& d, unsigned geomID, unsigned instID,
                                unsigned primID, float tFloat) const {
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
  auto keep = [&](double t) {
    if (std::isfinite(t) && t >= 0.0) tTerrain = std::min(tTerrain, t);
  };
  const bool terrainHit = terrain && instID == terrainInstID;
  if (terrainHit) {
    keep(terrain->refine(primID, o, d));
  } else if (terrain && geomID == sea.geomID) {
    // Float error of the local-origin scene: ~1e-7 of the coordinates.
    const double slack = 1.0 + 2e-7 * (glm::length(o - origin) + double(tFloat));
    const terrain::TerrainHit h = terrain->intersect(o, d, std::max(0.0, double(tFloat) - slack), double(tFloat) + slack);
    if (h.hit) keep(h.distanceM);
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
  geo::parallelFor(std::size_t(0), packets, [&](std::size_t p) {
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
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect16(valid, m.scene.get(), &ctx, &rh);
    for (std::size_t k = 0; k < count; ++k) {
      if (!valid[k]) {
        out[base + k] = PickResult{};
        continue;
      }
      // Even if Embree saw nothing (float rounding at a grazing sea hit), the
      // double sea test in finish() still runs.
      out[base + k] = m.finish(rays[base + k], dUnit[k], rh.hit.geomID[k], rh.hit.instID[0][k], rh.hit.primID[k],
                               rh.ray.tfar[k]);
    }
  });
}

}  // namespace geocean::pick
