#include "globe/terrain/TerrainScene.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace geocean::terrain {

EmbreeDevice::EmbreeDevice() : device_(rtcNewDevice(nullptr)) {
  if (!device_) throw std::runtime_error("embree: cannot create a device");
  rtcSetDeviceErrorFunction(
      device_,
      [](void* user, RTCError, const char* str) {
        static_cast<EmbreeDevice*>(user)->error_ = str ? str : "unknown error";
      },
      this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::check(const char* what) const {
  if (!error_.empty()) throw std::runtime_error(std::string("embree: ") + what + ": " + error_);
}

TerrainScene::TerrainScene(std::shared_ptr<const EmbreeDevice> device, std::shared_ptr<const TerrainMesh> mesh)
    : device_(std::move(device)), mesh_(std::move(mesh)) {
  scene_.reset(rtcNewScene(device_->get()));
  device_->check("terrain scene");
  rtcSetSceneFlags(scene(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene(), RTC_BUILD_QUALITY_LOW);
  const std::vector<glm::dvec3>& ecef = mesh_->verticesEcef();
  const std::vector<std::uint32_t>& indices = mesh_->indices();
  if (!indices.empty()) {
    RTCGeometry g = rtcNewGeometry(device_->get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), ecef.size()));
    auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                    3 * sizeof(std::uint32_t), indices.size() / 3));
    if (!v || !idx) {
      rtcReleaseGeometry(g);
      device_->check("terrain buffers");
      throw std::runtime_error("embree: terrain buffers: no memory");
    }
    for (std::size_t k = 0; k < ecef.size(); ++k) {
      const glm::dvec3 p = mesh_->localVertex(k);  // rounded to float last
      v[3 * k] = float(p.x), v[3 * k + 1] = float(p.y), v[3 * k + 2] = float(p.z);
    }
    std::copy(indices.begin(), indices.end(), idx);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene(), g);
    rtcReleaseGeometry(g);
    device_->check("terrain geometry");
  }
  rtcCommitScene(scene());
  device_->check("terrain scene build");
}

TerrainScene::~TerrainScene() = default;

void TerrainScene::SceneRelease::operator()(RTCScene s) const { rtcReleaseScene(s); }

double TerrainScene::refine(unsigned triangle, const glm::dvec3& originEcef, const glm::dvec3& d) const {
  const std::uint32_t* t3 = &mesh_->indices()[std::size_t(triangle) * 3];
  const std::vector<glm::dvec3>& ecef = mesh_->verticesEcef();
  const glm::dvec3& v0 = ecef[t3[0]];
  const glm::dvec3 e1 = ecef[t3[1]] - v0, e2 = ecef[t3[2]] - v0, s = originEcef - v0;
  // Moller-Trumbore's t, without the barycentric bounds: Embree chose the triangle.
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return std::numeric_limits<double>::quiet_NaN();
  const glm::dvec3 q = glm::cross(s, e1);
  return glm::dot(e2, q) / det;
}

TerrainHit TerrainScene::intersect(const glm::dvec3& originEcef, const glm::dvec3& d, double tMinM,
                                   double tMaxM) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  const glm::dvec3 lo = originEcef - mesh_->originEcef();
  rh.ray.org_x = float(lo.x), rh.ray.org_y = float(lo.y), rh.ray.org_z = float(lo.z);
  rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
  rh.ray.tnear = float(tMinM);
  rh.ray.tfar = float(tMaxM);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene(), &ctx, &rh);
  TerrainHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.triangle = rh.hit.primID;
  h.distanceM = refine(h.triangle, originEcef, d);
  return h;
}

}  // namespace geocean::terrain
