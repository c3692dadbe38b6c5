// Terrain collision (paper 000 sec. 2.2, first part): a terrain patch as a
// regular height grid in the east-north-up frame of its origin, the swept
// contact points of t and t + dt walked over the grid's cells, a coarse
// height test per cell, and exact segment/triangle tests at the end.
//
// Cells are walked with the exact grid traversal of Amanatides & Woo (A Fast
// Voxel Traversal Algorithm, Eurographics 1987): every cell the segment's
// ground projection touches, in order; the paper's Bresenham line can step
// past a cell the segment clips at a corner. Each cell is split along the
// (i, j)-(i+1, j+1) diagonal; segment/triangle by Moller & Trumbore (1997) in
// double. The first hit along the segment is the contact.
//
// Over the cells a quadtree of maximum heights (paper 000's quadtree): a
// node whose highest vertex is below the segment's lowest point over the
// node is skipped whole, the others are opened child by child in the order
// the segment meets them. sweep() walks the cells directly when the
// segment crosses few of them (a body's step: 1-2 cells) and descends the
// quadtree for long ones (a fast body, a long step), where it skips the
// open sky above the terrain.
#pragma once

#include "plugin/bodies/Simulation.h"

#include <glm/vec3.hpp>

#include <optional>
#include <vector>

namespace geocean::bodies {

class HeightField {
 public:
  // nx x ny heights (row-major, j * nx + i), vertex (i, j) at east i * spacing,
  // north j * spacing, up height, in the ENU frame at `origin`.
  HeightField(const geo::Geodetic& origin, int nx, int ny, double spacingM, std::vector<double> heightsM);

  struct Hit {
    double t = 0.0;             // along the segment, 0..1
    glm::dvec3 pointEnu{0.0};   // in the patch frame
    glm::dvec3 normalEnu{0.0};  // unit, pointing up out of the terrain
  };
  // First crossing of the segment a -> b (patch frame) from above the
  // surface to below it, by the cell walk.
  std::optional<Hit> sweep(const glm::dvec3& a, const glm::dvec3& b) const;
  // The two ways sweep() chooses between (the same hits; tests, benchmark).
  std::optional<Hit> sweepCellWalk(const glm::dvec3& a, const glm::dvec3& b) const;
  std::optional<Hit> sweepQuadtree(const glm::dvec3& a, const glm::dvec3& b) const;
  // The same by testing every triangle of the grid: the reference.
  std::optional<Hit> sweepBruteForce(const glm::dvec3& a, const glm::dvec3& b) const;
  // Height of the triangulated surface at (east, north); NaN outside.
  double heightAt(double eastM, double northM) const;

  const geo::EnuFrame& frame() const { return frame_; }
  glm::dvec3 toPatch(const glm::dvec3& ecef) const { return frame_.toLocal(ecef - frame_.originEcef); }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double spacingM() const { return s_; }

 private:
  glm::dvec3 vertex(int i, int j) const { return {i * s_, j * s_, h_[std::size_t(j) * nx_ + i]}; }
  // Segment against cell (i, j)'s two triangles; keeps the nearest t.
  void testCell(int i, int j, const glm::dvec3& a, const glm::dvec3& b, std::optional<Hit>& best) const;

  // The segment's parameter interval over the grid (Liang-Barsky); false if none.
  bool clipToGrid(const glm::dvec3& a, const glm::dvec3& d, double& t0, double& t1) const;
  std::optional<Hit> walk(const glm::dvec3& a, const glm::dvec3& b, double t0, double t1) const;
  void descend(int level, int bi, int bj, const glm::dvec3& a, const glm::dvec3& b, double ta, double tb,
               std::optional<Hit>& best) const;

  geo::EnuFrame frame_;
  int nx_, ny_;
  double s_;
  std::vector<double> h_;
  std::vector<float> cellMax_;  // per cell, for the coarse test
  // Quadtree of maxima: level 0 is cellMax_, level k nodes of 2^k x 2^k
  // cells (dims levelW_[k] x levelH_[k]); the last level is one node.
  std::vector<std::vector<float>> levelMax_;
  std::vector<int> levelW_, levelH_;
};

// After each step, for every contact point (body axes) swept from the
// step's start pose to its end pose: at the first hit the body is moved back
// along its step to the hit, lifted out of the terrain along the normal, and
// its velocity into the terrain removed (inelastic contact, no friction).
// Then every point still below the surface (a rotation can sink another one)
// lifts the body by its depth. Nothing tunnels: a point that ends below the
// surface crossed it along its sweep.
//
// frictionCoefficient mu > 0 adds Coulomb friction at the centre of mass:
// the velocity along the ground loses up to mu times the velocity the
// contact removed into it (the impulse bound |J_t| <= mu |J_n|), so a body
// resting on a slope, or pushed along the ground with less than mu times
// its weight on it, stops. Wet sand on a hull: about 0.5 (Engineering
// ToolBox tables, wood or steel on wet sand 0.4-0.6). 0: none (the default).
class TerrainContact final : public StepConstraint {
 public:
  TerrainContact(std::shared_ptr<const HeightField> terrain, std::vector<glm::dvec3> contactPointsBody,
                 double frictionCoefficient = 0.0);
  void afterStep(Body& body, const BodyState& before) const override;
  // Height of the lowest contact point above the terrain in `state` (m; the
  // contact leaves a touching point at +1e-9); NaN when every point is
  // outside the patch. `geocean float` reports grounded when <= 1 cm.
  double clearanceM(const BodyState& state) const;
  const HeightField& terrain() const { return *terrain_; }
  // The reference (benchmark): every sweep tests every triangle of the
  // field (HeightField::sweepBruteForce); the same hits, far slower.
  void setBruteForce(bool on) { bruteForce_ = on; }

 private:
  std::shared_ptr<const HeightField> terrain_;
  bool bruteForce_ = false;
  void friction(glm::dvec3& velocityEcef, const glm::dvec3& normalEcef, double removedNormalMps) const;
  std::vector<glm::dvec3> points_;
  double mu_ = 0.0;
};

}  // namespace geocean::bodies
