// The screen-subdivision ocean grid (paper 002 sec. 3, on WGS84): an N x M
// grid of screen points, each unprojected to a ray and intersected with the
// ellipsoid (near root); rays that miss are put on the horizon, so the mesh
// has no holes and no triangles stretched into the sky. Clamp spheres (002
// sec. 3.2) enlarge the gridded screen rectangle so the wave-displaced mesh
// still covers the screen edges. The ISPG mode (paper 000 sec. 3.3) is the
// alternative projector, kept for comparison (see docs/ARCHITECTURE.md).
//
// This header is the contract with the renderer: GridVertex and GridFrame
// are stable; new fields go at the end.
#pragma once

#include "globe/camera/Camera.h"
#include "plugin/landsea/LandSea.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace geocean::grid {

enum class GridMode : std::uint8_t {
  Direct,  // ray/ellipsoid per vertex (default: exact, screen-uniform)
  Ispg,    // improved spherical projected grid: plane hit, then radial map
};

// Per-vertex flags.
enum VertexFlag : std::uint8_t {
  kVertexHorizon = 1,    // the ray missed: vertex placed on the horizon
  kVertexOffscreen = 2,  // outside the visible screen (clamp-sphere margin)
};

// One grid vertex, 32 bytes, std430-compatible as
// { vec3 eyeRel; uint classAndFlags; dvec2 latLon; } (uint = surface | flags << 8).
struct GridVertex {
  // ECEF position minus the eye, metres. Computed in double as t * ray, so
  // it carries no cancellation; rounded to float last.
  float eyeRelM[3];
  std::uint8_t surface;  // ocean::Surface (Ocean, Land, Lake)
  std::uint8_t flags;    // VertexFlag bits
  std::uint16_t reserved;
  // Geodetic position in double (the float pair hi/lo split is the GPU's job:
  // float hi = float(latDeg), lo = float(latDeg - hi)).
  double latDeg;
  double lonDeg;
};
static_assert(sizeof(GridVertex) == 32, "GridVertex is a GPU layout");

// The classifier (plugin/landsea/LandSea.h) is called once per grid row on
// its span of ray hits, and on the limb points (two per grid column or row)
// whose lat/lon and class the horizon vertices copy. Header-only, so the grid
// library itself does not link the raster stack.

struct GridOptions {
  // Grid size in vertices; 0 means "from cellPx": one vertex every cellPx
  // pixels across the clamp rectangle, plus one, plus one cell beyond each
  // side (so where the horizon leaves the screen through a corner, the
  // corner cell's sliver falls off screen).
  int cols = 0;
  int rows = 0;
  double cellPx = 8.0;
  // Upper bound of the wave displacement in any direction, metres (from
  // the wave library; 0 = flat sea, no clamp-sphere enlargement).
  double maxDisplacementM = 0.0;
  GridMode mode = GridMode::Direct;
  // Worker threads (0: TBB's default, all cores).
  int threads = 0;
};

// Screen rectangle in NDC that the grid spans: [-1, 1]^2 enlarged by the
// clamp spheres, then by one cell per side. Grid row 0 is at minY (bottom),
// column 0 at minX (left); vertex (i, j) is at minX + i (maxX - minX) / (cols - 1).
struct NdcRect {
  double minX = -1.0, minY = -1.0, maxX = 1.0, maxY = 1.0;
};

struct GridFrame {
  int cols = 0, rows = 0;
  NdcRect rect;
  glm::dvec3 eyeEcef{0.0};
  // cols * rows vertices, row-major.
  std::vector<GridVertex> vertices;
  // (cols - 1) * (rows - 1) flags, row-major: 1 when all four corners are land
  // (the renderer skips the cell), else 0.
  std::vector<std::uint8_t> cellSkip;
  // Two counter-clockwise (seen from the eye) triangles per cell, all cells:
  // the topology only depends on cols x rows and is rebuilt when that changes.
  std::vector<std::uint32_t> indices;
  std::size_t landCells = 0;  // number of skipped cells
};

// Triangles of the non-skipped cells only (for renderers without a per-cell discard).
std::vector<std::uint32_t> compactIndices(const GridFrame& frame);

// compactIndices with a coarser mesh where `coarse` says (issue 15 item 4,
// paper 003's middle band): the cells in blocks of `block` x `block`
// (block 2, 4 or 8; blocks start at cell (0, 0), a partial block at the far
// edges stays fine) are drawn as one cell where every vertex of the block
// has coarse[v] != 0 (coarse: one flag per vertex), none is on the horizon
// and none of its cells is skipped. A coarse block's side that borders
// cells of any other kind keeps that side's vertices (a fan from the
// block's centre vertex), so the fine cells' vertices on it are vertices of
// both: no T-junction, no crack; a side between two coarse blocks, or on
// the grid's edge, is one edge. Writes `out` in groups of 6 indices (a
// pair of counter-clockwise triangles; a fan's odd count padded with a
// degenerate one), as compactIndices' cells; returns the coarse blocks.
std::size_t coarseIndices(const GridFrame& frame, const std::vector<std::uint8_t>& coarse, int block,
                          std::vector<std::uint32_t>& out);

// Clamp-sphere rectangle (002 sec. 3.2, generalised): the base-ellipsoid
// points seen along the screen border, displaced by maxDisplacementM in every
// direction, projected back to the screen; the rectangle grows by the largest
// inward motion so the displaced border still lies outside the screen.
// Grows at most to [-4, 4]^2 (a camera below the wave crests cannot be covered).
// Rays that miss are placed on the limb of the ellipsoid inflated by the
// displacement (capped at half the eye height) where their grid column or
// row crosses it.
NdcRect clampRectangle(const camera::Camera& cam, double maxDisplacementM);

class ScreenGrid {
 public:
  // Throws std::invalid_argument naming the option for a bad size, cellPx or displacement.
  explicit ScreenGrid(GridOptions options, ocean::SurfaceClassifier classifier = {});
  ~ScreenGrid();
  ScreenGrid(const ScreenGrid&) = delete;
  ScreenGrid& operator=(const ScreenGrid&) = delete;

  // Rebuilds `frame` for this camera, reusing its buffers. Without a
  // classifier every vertex is ocean. Thread-safe for distinct frames.
  void build(const camera::Camera& cam, GridFrame& frame) const;

  const GridOptions& options() const { return options_; }
  // The projector for the next builds (not during one).
  void setMode(GridMode mode) { options_.mode = mode; }

 private:
  struct Impl;
  GridOptions options_;
  ocean::SurfaceClassifier classifier_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace geocean::grid
