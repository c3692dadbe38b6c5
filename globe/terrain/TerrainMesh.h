// The terrain surface of an elevation raster as a triangle mesh on WGS84:
// vertices in ECEF double, and a local origin for float consumers (float at
// Earth scale is metres off, so they take localVertex(), computed in double
// and rounded to float last). Shared by picking (TerrainScene), and meant
// for the renderer and body collision. No OpenGL, no Embree.
//
// Vertex grid: vertex (i, j) is pixel (i, j)'s centre (i + 0.5, j + 0.5) at
// its height (nodata: no triangle uses it). Cell (i, j) spans vertices
// i..i+1, j..j+1 (a global raster wraps in longitude: cell W-1 joins column
// W-1 to column 0) and is split along the a-d diagonal into (a, b, d) and
// (a, d, c), a = (i, j), b = (i+1, j), c = (i, j+1), d = (i+1, j+1). A
// global raster's polar holes are closed by fans to a pole vertex at the
// mean height of the edge row.
#pragma once

#include "globe/raster/Raster.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace geocean::terrain {

struct Ray {
  glm::dvec3 originEcef{0.0};
  glm::dvec3 dir{0.0};  // any length > 0
};

// Some cells of a raster's vertex grid, and which polar fans (global rasters).
struct CellRegion {
  std::vector<std::uint64_t> cells;  // j * cellCols + i, sorted, unique
  bool fan[2] = {false, false};      // fan on vertex row 0 / row H - 1
};

// The cells some of these rays can meet: each ray is walked through the
// shell of heights the mesh can reach (raster min/max, widened by the chord
// sag of a cell) in quarter-cell steps, and every cell within one cell of
// the lat/lon box of each step is kept. Rays with a zero or non-finite
// origin or direction are ignored. nullopt when that takes more than 2^20
// steps (use the whole mesh). Reads every pixel once (the height range).
std::optional<CellRegion> cellsAlong(const raster::Raster& elevation, std::span<const Ray> rays);

class TerrainMesh {
 public:
  // The whole raster. Vertex j * W + i is pixel (i, j), for every pixel;
  // a global raster's two pole vertices follow (north row 0's, then row H-1's).
  static TerrainMesh whole(const raster::Raster& elevation, const glm::dvec3& localOriginEcef);
  // Only the cells of `region`: the same vertex positions and triangles, in
  // the same order per cell, as whole() (vertices are those the cells use).
  static TerrainMesh region(const raster::Raster& elevation, const CellRegion& region,
                            const glm::dvec3& localOriginEcef);

  const glm::dvec3& originEcef() const { return origin_; }
  // ECEF, metres, from GeographicLib (pixel centre, height).
  const std::vector<glm::dvec3>& verticesEcef() const { return ecef_; }
  // Vertex k minus originEcef(), in double.
  glm::dvec3 localVertex(std::size_t k) const { return ecef_[k] - origin_; }
  // Three vertex indices per triangle (winding not consistent: the polar
  // fans turn the other way from the cells).
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  std::size_t triangleCount() const { return indices_.size() / 3; }
  bool empty() const { return indices_.empty(); }

 private:
  glm::dvec3 origin_{0.0};
  std::vector<glm::dvec3> ecef_;
  std::vector<std::uint32_t> indices_;
};

}  // namespace geocean::terrain
