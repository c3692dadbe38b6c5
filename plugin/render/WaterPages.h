// The ocean's water coverage from a streamed mask (issue 12): the mask's
// tile pyramid (world::waterPyramid, the host terrain's own cache and
// texels) in the ocean's own GPU tile pool (gl::TilePool), with a page
// table so one draw over the whole view can take any resident tile
// (shaders/geo_uv.glsl, GEOCEAN_WATER_PAGES). Per frame the grid's
// vertices ask for the tile at the level whose texel is about their pixel;
// until it arrives its nearest resident ancestor is drawn (never a hole,
// never a wait), except in complete() frames (single pictures), which
// wait until what the view asked for is resident. A regional mask's
// pyramid (not global) is drawn over the ocean's water grid: past its edge
// and at its nodata the grid's coverage answers (the layers below).
// GL calls on the context's thread only.
#pragma once

#include "globe/gl/GlProgram.h"
#include "globe/gl/TilePool.h"
#include "plugin/grid/ScreenGrid.h"

#include <epoxy/gl.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace geocean::ocean_render {

class WaterPages {
 public:
  // Needs a current GL context; loads the top tile.
  explicit WaterPages(std::shared_ptr<const raster::TilePyramid> pyramid, gl::TilePoolOptions pool = {});
  ~WaterPages();
  WaterPages(const WaterPages&) = delete;
  WaterPages& operator=(const WaterPages&) = delete;
  // The GL names are left to their context (OceanRenderer::abandonGl).
  void abandonGl();

  // Asks for what the frame's drawn vertices need; returns how many of
  // those tiles are not resident.
  std::size_t request(const grid::GridFrame& frame, double cellPx);
  // Waits (bounded) until the frame's tiles are resident: single pictures.
  void complete(const grid::GridFrame& frame, double cellPx);
  // Units 6 (pool) and 7 (page table) and the uniforms; refreshes the table.
  void bind(const gl::GlProgram& p);
  // After the frame's draws: finished loads go up.
  void endFrame() { pool_->endFrame(); }

  const raster::TilePyramid& pyramid() const { return pool_->pyramid(); }
  const gl::TilePool& pool() const { return *pool_; }

 private:
  void refreshTable();
  std::unique_ptr<gl::TilePool> pool_;
  GLuint table_ = 0;
  int tableW_ = 0, tableH_ = 0;
  std::vector<int> rowOf_;  // first table row of each level
  std::vector<std::int32_t> cpu_;
  std::uint64_t version_ = ~std::uint64_t(0);
  bool abandoned_ = false;
};

}  // namespace geocean::ocean_render
