// Drawing floating bodies: closed hull meshes (body axes, metres) at poses
// given in double (ECEF centre of mass, body -> ECEF quaternion), lit by the
// sun, flat-shaded. Knows nothing of the simulation: the host fills the
// meshes and poses (from the plugin's ABI, globe/host/Boats) and calls
// draw from a SceneObject, in the main and the mirrored pass. GL objects
// belong to the context current at construction.
#pragma once

#include "globe/camera/Camera.h"
#include "globe/gl/GlProgram.h"

#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <vector>

namespace geocean::render {

struct BoatInstance {
  int mesh = 0;                               // from addMesh
  glm::dvec3 positionEcef{0.0};               // centre of mass
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // body -> ECEF
  glm::vec3 color{0.8f};                      // linear RGB
};

class BoatRenderer {
 public:
  BoatRenderer();
  ~BoatRenderer();
  BoatRenderer(const BoatRenderer&) = delete;
  BoatRenderer& operator=(const BoatRenderer&) = delete;

  // xyz per vertex (body axes about the centre of mass), triangle indices.
  // Returns the mesh's index for BoatInstance::mesh.
  int addMesh(const std::vector<double>& verticesXyz, const std::vector<std::uint32_t>& indices);
  void setInstances(std::vector<BoatInstance> instances) { instances_ = std::move(instances); }
  const std::vector<BoatInstance>& instances() const { return instances_; }

  // See SceneObject::draw.
  void draw(const camera::Camera& cam, const camera::Lighting& light, const camera::Camera* mirroredFrom) const;
  // See SceneObject::drawDepth (the sun's shadow map).
  void drawDepth(const glm::mat4& viewProj, const glm::dvec3& originEcef) const;

 private:
  struct Mesh {
    unsigned vao = 0, vbo = 0, ibo = 0;
    int indexCount = 0;
  };
  void drawWith(const glm::mat4& viewProj, const glm::dvec3& originEcef, const glm::vec3& sun,
                const glm::vec4& clipPlane) const;
  gl::GlProgram program_;
  std::vector<Mesh> meshes_;
  std::vector<BoatInstance> instances_;
};

}  // namespace geocean::render
