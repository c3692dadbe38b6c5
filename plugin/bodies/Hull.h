// Closed triangle meshes of hulls in body axes (x bow, y port, z up; origin
// at the centre of volume, which is the centre of mass of a homogeneous
// body), their volume and inertia by exact polyhedral integration.
#pragma once

#include "plugin/bodies/RigidBody.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace geocean::bodies {

class HullMesh {
 public:
  // A closed, consistently wound (outward, counter-clockwise seen from
  // outside) triangle mesh; the vertices are shifted so the origin is the
  // centre of volume (the shift is designCentroid()). Throws
  // std::invalid_argument when an index is out of range, a coordinate is not
  // finite, an edge is not shared by exactly two triangles in opposite
  // directions, or the enclosed volume is not > 0 (inward winding).
  static HullMesh fromTriangles(std::vector<glm::dvec3> vertices, std::vector<std::uint32_t> indices,
                                std::string kind = "mesh");

  // Box of full edge lengths size (x, y, z), each face cut into n x n
  // squares (two triangles each), so a wave's pressure, interpolated
  // linearly between vertices, follows the surface.
  static HullMesh box(const glm::dvec3& sizeM, int facetsPerEdge = 4);
  // Vertical-axis cylinder (a buoy or spar) of radius r and height h with
  // `segments` sides. The polygon's radius is enlarged so its area is pi r^2:
  // volume, waterplane area and displacement are those of the true cylinder;
  // the inertia differs by O(1/segments^4) (4e-4 at 24; tests/bodies).
  static HullMesh cylinder(double radiusM, double heightM, int segments = 24);
  // A simple displacement boat of length L: beam L/3.5, depth L/8, elliptic
  // sections narrowing to a stem at the bow and a transom at the stern, a
  // flat deck; 11 stations x 11 points per section (242 triangles).
  static HullMesh boat(double lengthM);

  const std::vector<glm::dvec3>& vertices() const { return vertices_; }
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  std::size_t triangleCount() const { return indices_.size() / 3; }
  const std::string& kind() const { return kind_; }

  double volumeM3() const { return volume_; }
  // Where the centre of volume was in the caller's coordinates.
  const glm::dvec3& designCentroid() const { return designCentroid_; }
  // Bounding box (body axes, about the centre of volume).
  const glm::dvec3& minCorner() const { return min_; }
  const glm::dvec3& maxCorner() const { return max_; }

  // Homogeneous solid of this density: mass rho V and the inertia tensor
  // about the centre of volume, from the covariance of the tetrahedra
  // (origin, a, b, c): C = sum det/120 (sum_v v v^T + s s^T), s = a + b + c,
  // I = trace(C) 1 - C (Tonon, J. Math. Stat. 1(1), 2004; Blow & Binstock,
  // "How to find the inertia tensor of a 3D solid body represented by a
  // triangle mesh", 2004). Exact for the polyhedron.
  MassProperties massProperties(double densityKgM3) const;

  // Volume below the body-axis plane z = zBody (exact: the clipped polyhedron).
  double volumeBelow(double zBody) const;
  // The z of the plane under which volumeBelow = densityRatio * volume, by
  // bisection to 1e-12 of the height: an upright body of density
  // densityRatio * rho_water floats with its centre of mass -restingWaterlineZ
  // above the still water (densityRatio in (0, 1)).
  double restingWaterlineZ(double densityRatio) const;

 private:
  std::vector<glm::dvec3> vertices_;
  std::vector<std::uint32_t> indices_;
  std::string kind_;
  double volume_ = 0.0;
  glm::dvec3 designCentroid_{0.0}, min_{0.0}, max_{0.0};
  glm::dmat3 unitInertia_{0.0};  // inertia at density 1
};

}  // namespace geocean::bodies
