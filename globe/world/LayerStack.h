// A stack of mask and elevation rasters (issue 12): at any point the layer
// that answers first and has data there decides. Answer order: higher
// priority first, then the finer cell, then the order of adding. The
// bundled world sits underneath at kDefaultWorldPriority. Land and sea come
// from masks by their own encoding and from elevation layers by sign (below
// 0 m is ocean), so a user's relief finer than every mask decides where
// its island is. Neutral (no plugin code): the ocean's classifier
// (plugin/landsea) and the host's world textures both go through it, so the
// query and the picture use the same layer at a point.
#pragma once

#include "globe/raster/Raster.h"
#include "globe/world/Surface.h"
#include "globe/world/WorldData.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace geocean::world {

// Imagery layers (RGB or RGBA, 8-bit) are drawn only: they never answer
// a class or an elevation.
enum class LayerKind : std::uint8_t { Mask, Elevation, Imagery };
const char* toString(LayerKind k);  // "mask" | "elevation" | "imagery"

// Below every user layer (whose priorities are the caller's ints).
constexpr int kDefaultWorldPriority = std::numeric_limits<int>::min();

struct RasterLayer {
  LayerKind kind = LayerKind::Mask;
  std::shared_ptr<const raster::Raster> raster;  // non-null; its nodata (NaN) is "no data here"
  MaskEncoding encoding;                         // masks only
  int priority = 0;
  // Geometric mean of the cell's sides, degrees: how fine the layer is.
  double cellDeg() const;
};

class LayerStack {
 public:
  // Throws std::invalid_argument for an empty stack or a null raster.
  explicit LayerStack(std::vector<RasterLayer> layers);

  const std::vector<RasterLayer>& layers() const { return layers_; }  // in answer order
  bool has(LayerKind k) const;

  // Class per point from the first layer with data there; Land where no
  // layer has data or the point is not finite. answeredBy (optional): the
  // index into layers() that answered, -1 for none.
  void classifyBatch(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out,
                     std::int32_t* answeredBy = nullptr) const;
  // Elevation (m, bilinear) from the first elevation layer with data; NaN
  // where none has.
  void elevationBatch(const double* latDeg, const double* lonDeg, std::size_t n, float* out) const;

  // The raster each kind's global drawing grid is built from (the rule the
  // ocean's grids, plugin/render/OceanWorld, and the host's follow: a
  // global in-memory raster is copied pixel for pixel, anything else is
  // resampled through the stack at its step, at most 5'). With several
  // layers of a kind: its finest regional layer, so the grid is resampled
  // and shows every layer. The mask is null when an elevation layer is
  // finer than every mask: the water grid is then resampled at the
  // elevation's step. Null when the stack has no layer of the kind.
  std::shared_ptr<const raster::Raster> drawingMask() const { return drawingMask_; }
  std::shared_ptr<const raster::Raster> drawingElevation() const { return drawingElevation_; }

 private:
  std::vector<RasterLayer> layers_;
  std::shared_ptr<const raster::Raster> drawingMask_, drawingElevation_;
};

// The host's elevation and water layers from the stack, by the drawing rule
// above (the same cells and values as the ocean's own grids). The mask
// encoding of a copied global mask is its layer's.
WorldLayer elevationLayerOf(const LayerStack& stack);
WorldLayer waterLayerOf(const LayerStack& stack);

// A layer by file, as the CLI's --mask/--elevation name it and the C ABI
// takes it (geocean_add_*_layer_file).
struct LayerSource {
  LayerKind kind = LayerKind::Mask;
  std::string path;
  std::string encoding;  // masks: MaskEncoding::parse text, "" for the default
  int priority = 0;
};
// The stack of `layers` (in this order) over the default world's mask and
// relief (unless !defaultWorld), as the ocean façade builds it. Throws
// raster::RasterError naming the file for an imagery layer without 3 or 4
// channels.
LayerStack openLayerStack(const std::vector<LayerSource>& layers, bool defaultWorld,
                          const raster::OpenOptions& options = {});
// An imagery raster as drawn (WorldData::imageryLayers): its own pixels
// when it is in memory and no side exceeds maxSide, else the finest level of
// its tile pyramid (raster::TilePyramid, the on-disk tile cache) that fits.
// Throws raster::RasterError naming the file for a channel count other than
// 3 or 4 or a value outside 0..255.
ImageryLayer imageryLayerOf(std::shared_ptr<const raster::Raster> r, int maxSide = 8192);

// The host's world: the default imagery, elevation and water from
// openLayerStack by the drawing rule (grids at most 5'; the first water
// layers (up to 4, streamedWaterLayers) and elevation layers (up to 4,
// streamedElevationLayers) finer than that, global or regional, streamed
// as tiles: WaterPyramid.h; a fifth of either is drawn from the grid with
// a warning on stderr naming its file), the
// imagery layers over the default
// imagery (at most kMaxImageryLayers). Without layers exactly
// loadDefaultWorld(). Throws raster::RasterError naming the file,
// std::invalid_argument for a bad encoding, an empty stack or too many
// imagery layers.
WorldData loadLayeredWorld(const std::vector<LayerSource>& layers, bool defaultWorld,
                           const raster::OpenOptions& options = {});

}  // namespace geocean::world
