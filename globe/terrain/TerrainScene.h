// A TerrainMesh in an Embree 3 scene, with every hit refined in double.
// Embree traces in float, in the mesh's local coordinates (rounded from
// double last); the caller's double ray is then intersected with the plane
// of the triangle Embree found, on the mesh's double vertices (exact at
// vertices). Embree may report the neighbour across an edge: its plane
// meets the ray at the same point to rounding.
// Thread-safety: const members may run concurrently.
#pragma once

#include "globe/terrain/TerrainMesh.h"

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include <memory>
#include <string>

namespace geocean::terrain {

// An Embree device that remembers Embree's last error message.
class EmbreeDevice {
 public:
  // Throws std::runtime_error if Embree cannot create a device.
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }
  // Throws std::runtime_error("embree: <what>: <message>") if Embree has
  // reported an error on this device.
  void check(const char* what) const;

 private:
  RTCDevice device_ = nullptr;
  std::string error_;
};

struct TerrainHit {
  bool hit = false;
  unsigned triangle = 0;  // index into mesh().indices() / 3
  // Along the caller's unit direction, from the double ray and the
  // triangle's double plane; NaN when the ray is parallel to the plane.
  double distanceM = 0.0;
};

class TerrainScene {
 public:
  // A committed scene holding the mesh (none if it is empty), robust
  // traversal (rays do not leak through cracks of huge meshes) and low build
  // quality (the world's 1.2 M triangles build once per process, in a
  // fraction of MEDIUM's time). Throws std::runtime_error with Embree's message.
  TerrainScene(std::shared_ptr<const EmbreeDevice> device, std::shared_ptr<const TerrainMesh> mesh);
  ~TerrainScene();
  TerrainScene(const TerrainScene&) = delete;
  TerrainScene& operator=(const TerrainScene&) = delete;

  // For instancing into a caller's scene on the same device (identity
  // transform: local coordinates of the mesh's origin).
  RTCScene scene() const { return scene_.get(); }
  const TerrainMesh& mesh() const { return *mesh_; }
  const glm::dvec3& originEcef() const { return mesh_->originEcef(); }

  // t along dirUnit where the double ray meets the plane of `triangle`.
  double refine(unsigned triangle, const glm::dvec3& originEcef, const glm::dvec3& dirUnit) const;
  // The triangle Embree reports first on the float ray within [tMinM, tMaxM]
  // (dirUnit of length 1), refined by refine().
  TerrainHit intersect(const glm::dvec3& originEcef, const glm::dvec3& dirUnit, double tMinM, double tMaxM) const;

 private:
  std::shared_ptr<const EmbreeDevice> device_;
  std::shared_ptr<const TerrainMesh> mesh_;
  struct SceneRelease {
    void operator()(RTCScene s) const;
  };
  // After device_: released before the device.
  std::unique_ptr<RTCSceneTy, SceneRelease> scene_;
};

}  // namespace geocean::terrain
