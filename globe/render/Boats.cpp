#include "globe/render/Boats.h"

#include "globe/geo/Ellipsoid.h"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <stdexcept>

namespace geocean::render {

BoatRenderer::BoatRenderer() { program_ = gl::GlProgram::graphics("boat.vert", "boat.frag"); }

BoatRenderer::~BoatRenderer() {
  for (Mesh& m : meshes_) {
    glDeleteVertexArrays(1, &m.vao);
    glDeleteBuffers(1, &m.vbo);
    glDeleteBuffers(1, &m.ibo);
  }
}

int BoatRenderer::addMesh(const std::vector<double>& xyz, const std::vector<std::uint32_t>& indices) {
  if (xyz.empty() || xyz.size() % 3 != 0 || indices.empty() || indices.size() % 3 != 0)
    throw std::invalid_argument("BoatRenderer::addMesh: " + std::to_string(xyz.size()) + " coordinates and " +
                                std::to_string(indices.size()) + " indices are not whole vertices and triangles");
  for (std::uint32_t i : indices)
    if (i >= xyz.size() / 3) throw std::invalid_argument("BoatRenderer::addMesh: index " + std::to_string(i) + " out of range");
  // Body-axis coordinates are metres about the centre of mass: float is exact to ~1 um.
  const std::vector<float> v(xyz.begin(), xyz.end());
  Mesh m;
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.vbo);
  glCreateBuffers(1, &m.ibo);
  glNamedBufferStorage(m.vbo, GLsizeiptr(v.size() * sizeof(float)), v.data(), 0);
  glNamedBufferStorage(m.ibo, GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
  glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, 3 * sizeof(float));
  glVertexArrayElementBuffer(m.vao, m.ibo);
  glEnableVertexArrayAttrib(m.vao, 0);
  glVertexArrayAttribFormat(m.vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(m.vao, 0, 0);
  m.indexCount = int(indices.size());
  meshes_.push_back(m);
  return int(meshes_.size()) - 1;
}

void BoatRenderer::draw(const camera::Camera& cam, const camera::Lighting& light,
                        const camera::Camera* mirroredFrom) const {
  glm::vec4 plane(0.0f, 0.0f, 0.0f, 1.0f);
  if (mirroredFrom) {
    // The sea-level plane under the real eye, in the mirrored eye's frame:
    // a point p (relative to the mirrored eye) is above it when dot(p, n) > h.
    const glm::dvec3 n = geo::surfaceNormal(mirroredFrom->latDeg(), mirroredFrom->lonDeg());
    plane = glm::vec4(glm::vec3(n), float(-mirroredFrom->heightM()));
  }
  drawWith(cam.gpu().viewProj, cam.eyeEcef(), glm::vec3(light.sunEcef), plane);
}

void BoatRenderer::drawDepth(const glm::mat4& viewProj, const glm::dvec3& originEcef) const {
  // The whole hull: what is under the water is farther from the sun than
  // the water above it, so it shades nothing there.
  drawWith(viewProj, originEcef, glm::vec3(0.0f, 0.0f, 1.0f), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

void BoatRenderer::drawWith(const glm::mat4& viewProj, const glm::dvec3& originEcef, const glm::vec3& sun,
                            const glm::vec4& plane) const {
  if (instances_.empty()) return;
  program_.use();
  glUniformMatrix4fv(program_.uniform("uViewProj"), 1, GL_FALSE, glm::value_ptr(viewProj));
  glUniform3fv(program_.uniform("uSunDir"), 1, &sun[0]);
  glUniform4fv(program_.uniform("uClipPlane"), 1, &plane[0]);
  glEnable(GL_CLIP_DISTANCE0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  for (const BoatInstance& b : instances_) {
    if (b.mesh < 0 || b.mesh >= int(meshes_.size())) continue;
    const glm::vec3 offset(b.positionEcef - originEcef);  // difference in double, then float
    const glm::mat3 rot(glm::mat3_cast(b.orientation));
    const geo::Geodetic g = geo::fromEcef(b.positionEcef);
    const glm::vec3 up(geo::surfaceNormal(g.latDeg, g.lonDeg));
    glUniform3fv(program_.uniform("uOffset"), 1, &offset[0]);
    glUniformMatrix3fv(program_.uniform("uRot"), 1, GL_FALSE, glm::value_ptr(rot));
    glUniform3fv(program_.uniform("uColor"), 1, &b.color[0]);
    glUniform3fv(program_.uniform("uUp"), 1, &up[0]);
    glBindVertexArray(meshes_[b.mesh].vao);
    glDrawElements(GL_TRIANGLES, meshes_[b.mesh].indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_CLIP_DISTANCE0);
  glBindVertexArray(0);
}

}  // namespace geocean::render
