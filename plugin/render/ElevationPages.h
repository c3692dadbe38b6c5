// The ocean's water depth from the streamed reliefs (issues 12 and 15):
// the elevation layers the host terrain draws from tiles
// (world::streamedElevationLayers, up to world::kMaxStreamedLayers, in
// answer order; raster::TilePyramid::open of each, so the host's pyramid
// and disk cache) in the ocean's own R32F tile pools (NaN where a layer
// has no data) with a page table each, read per vertex by ocean.vert
// (shaders/elev_pages.glsl, GEOCEAN_ELEV_PAGES n) for the Gerstner depth,
// refraction's bottom and the shore foam (vDepthM), by the query's rule.
// Per frame each drawn vertex asks for the tiles of the level whose texel
// is about its cell (|eye-relative| x cellRadians, as the shader's
// footprint); until they arrive their nearest resident ancestor is read;
// complete() frames (single pictures) wait. The texel positions are
// eye-relative: setReference splits the eye's position in each layer into
// an integer texel and a fraction in double. GL calls on the context's
// thread only.
#pragma once

#include "plugin/render/WaterPages.h"

namespace geocean::ocean_render {

class ElevationPages {
 public:
  // Needs a current GL context; loads the top tiles. `layers` in answer
  // order, 1 to world::kMaxStreamedLayers (else std::invalid_argument
  // naming the first file).
  explicit ElevationPages(std::vector<std::shared_ptr<const raster::TilePyramid>> layers);
  ElevationPages(const ElevationPages&) = delete;
  ElevationPages& operator=(const ElevationPages&) = delete;
  void abandonGl();

  // Asks for the tiles the frame's drawn vertices read (cellRadians:
  // ocean.vert's uCellRadians); returns how many are not resident.
  std::size_t request(const grid::GridFrame& frame, double cellRadians);
  // Waits (bounded) until they are: single pictures.
  void complete(const grid::GridFrame& frame, double cellRadians);
  // Units 25 + k (pools), 29 + k (tables) and the uniforms; refLatDeg,
  // refLonDeg: exactly the floats the program's uRefLatDeg/uRefLonDeg hold.
  void bind(const gl::GlProgram& p, float refLatDeg, float refLonDeg);
  void endFrame();
  // GEOCEAN_ELEV_PAGES n.
  std::vector<std::string> defines() const;

  int layers() const { return int(layers_.size()); }
  const gl::TilePool& pool(int layer = 0) const { return *layers_[std::size_t(layer)].pool; }

  // The level a cell of footprintM reads in a layer of level-0 latitude
  // step latStepDeg (elev_pages.glsl epWant, in the shader's float).
  static int wantLevel(double footprintM, double latStepDeg, int top);

 private:
  std::size_t request(PagedPool& l, const grid::GridFrame& frame, double cellRadians);
  std::vector<PagedPool> layers_;
};

}  // namespace geocean::ocean_render
