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
// Several streamed masks (world::streamedWaterLayers, up to
// world::kMaxStreamedLayers): each its own pyramid, pool and page table;
// the shader falls through them in answer order, the first with data at a
// point answers (GEOCEAN_WATER_PAGES_LAYERS), the grid past the last.
// GL calls on the context's thread only.
#pragma once

#include "globe/gl/GlProgram.h"
#include "globe/gl/TilePool.h"
#include "plugin/grid/ScreenGrid.h"

#include <epoxy/gl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

namespace geocean::ocean_render {

// One streamed layer of pages: its pyramid's pool and the page table
// (per level, per tile: its pool layer, -1 when not resident; levels'
// rows one under another). Shared by WaterPages and ElevationPages. Owns
// the table's GL name (deleted with it unless abandoned): a layer made
// before a later one throws is not leaked.
struct PagedPool {
  PagedPool() = default;
  PagedPool(PagedPool&& o) noexcept;
  PagedPool& operator=(PagedPool&& o) noexcept;
  ~PagedPool();
  std::unique_ptr<gl::TilePool> pool;
  GLuint table = 0;
  int tableW = 0, tableH = 0;
  std::vector<int> rowOf;  // first table row of each level
  std::vector<std::int32_t> cpu;
  std::uint64_t version = ~std::uint64_t(0);
  // Needs a current GL context; throws std::invalid_argument (naming the
  // file and `what`) for more than 24 levels or a table over GL_MAX_TEXTURE_SIZE.
  static PagedPool make(std::shared_ptr<const raster::TilePyramid> pyramid, gl::TilePoolOptions pool, const char* what);
  // Uploads the table when residency changed.
  void refresh();
  // Per level: width, height, tiles across, first table row (uPageLevel's layout).
  std::vector<GLint> levelsUniform() const;
  // The GL names are left to their context (OceanRenderer::abandonGl).
  void abandonGl();
  // The tiles a frame's request has asked about. Neighbouring vertices
  // mostly fall in the tile just asked: `last` skips the set (and the
  // pool's lookup) for them.
  struct Asked {
    std::unordered_set<std::uint64_t> seen;
    std::uint64_t last = ~std::uint64_t(0);
  };
  // A frame's tile, once per frame: asks for it when it is not resident;
  // returns 1 then, else 0.
  std::size_t ask(const raster::TileId& id, Asked& asked);
  // Single pictures: while request() (a frame's asking over all layers)
  // finds tiles missing, waits for the loads and puts them up. Bounded: a
  // view needing more tiles than a pool holds uses what fits.
  template <class Request>
  static void completeAll(std::vector<PagedPool>& layers, Request&& request) {
    for (int round = 0; round < 64 && request() > 0; ++round) {
      for (PagedPool& l : layers) l.pool->waitIdle();
      for (PagedPool& l : layers) l.pool->endFrame();
    }
  }
};

class WaterPages {
 public:
  // Needs a current GL context; loads the top tile. below: the streamed
  // layers under `pyramid`, in answer order (each a pool of belowPool's
  // slots); throws std::invalid_argument for more than
  // world::kMaxStreamedLayers layers in all.
  explicit WaterPages(std::shared_ptr<const raster::TilePyramid> pyramid, gl::TilePoolOptions pool = {},
                      std::vector<std::shared_ptr<const raster::TilePyramid>> below = {},
                      gl::TilePoolOptions belowPool = defaultBelowPool());
  static gl::TilePoolOptions defaultBelowPool();
  WaterPages(const WaterPages&) = delete;
  WaterPages& operator=(const WaterPages&) = delete;
  // The GL names are left to their context (OceanRenderer::abandonGl).
  void abandonGl();

  // Asks for what the frame's drawn vertices need; returns how many of
  // those tiles are not resident.
  std::size_t request(const grid::GridFrame& frame, double cellPx);
  // Waits (bounded) until the frame's tiles are resident: single pictures.
  void complete(const grid::GridFrame& frame, double cellPx);
  // Units 6 (pool) and 7 (page table) and the uniforms; refreshes the
  // table. Layers below: pools on units 9.., tables on 22.. (uPageB*).
  void bind(const gl::GlProgram& p);
  // After the frame's draws: finished loads go up.
  void endFrame();
  // The program's defines for these pages (GEOCEAN_WATER_PAGES, _REGIONAL
  // for a regional first layer, _LAYERS n for n > 1 layers).
  std::vector<std::string> defines() const;

  const raster::TilePyramid& pyramid() const { return layers_[0].pool->pyramid(); }
  const gl::TilePool& pool(int layer = 0) const { return *layers_[std::size_t(layer)].pool; }
  int layers() const { return int(layers_.size()); }

 private:
  using Layer = PagedPool;
  std::size_t request(Layer& l, const grid::GridFrame& frame, double cellPx);
  std::vector<Layer> layers_;
  std::vector<double> texelX_, texelY_;  // request's per-vertex scratch
};

}  // namespace geocean::ocean_render
