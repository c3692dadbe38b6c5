// The terrain globe: a quadtree of geographic tiles (8 roots of 90 x 90
// degrees), each a fixed (N+2)^2-vertex grid whose outer ring is a skirt
// hanging below the tile edge, so neighbours of different levels never show
// cracks. Vertices are made in double relative to the tile centre; each draw
// adds (tile centre - eye) computed in double, so nothing absolute reaches
// the GPU. Heights come from the elevation texture in the vertex shader
// (vertical exaggeration is a uniform). Water areas sit below the sea
// surface and are shaded as distant sea (normals + roughness, no geometry).
#pragma once

#include "globe/gl/GlProgram.h"
#include "globe/camera/Camera.h"
#include "globe/render/Layer.h"
#include "globe/render/WorldTextures.h"
#include "globe/world/TileWaterIndex.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <list>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace geocean::render {

struct TerrainOptions {
  double exaggeration = 1.0;
  double pixelErrorPx = 8.0;  // split while a grid cell spans more pixels than this
  // Deepest level; also no finer than 1/16 of the finest elevation or water
  // texel per cell (WorldTextures::finestShapeTexelDeg): finer cells cost
  // vertices and triangles but show nothing new (level 10, 305 m cells, for
  // the 5' mask; at 2 m above the Strait 63 tiles instead of 316).
  int maxLevel = 16;
  int poolTiles = 768;        // GPU tile slots: memory stays flat
  double seaDropM = 30.0;     // water areas of the terrain sit this far below the sea
  // Horizon culling: the lowest opaque surface (terrain water areas, wave
  // troughs) lies no deeper than this under the ellipsoid.
  double occluderDepthM = 100.0;
  // With an ocean layer, a depth-only pass first (sea_proxy.frag) so the
  // colour pass skips water the ocean covers. Off: on llvmpipe the extra pass
  // cost more than it saved (flight medians, terrain CPU ms, bench_render
  // --sea-proxy on a quiet machine: 188/192 without, 223/230 with); a GPU
  // with cheap vertex and depth passes may gain.
  bool seaProxy = false;
  // With an ocean layer, tiles that the ocean covers opaquely (open water
  // with a margin, world::WaterIndex) are not drawn at all.
  bool skipOpenWater = true;
  // Streamed water (WorldTextures::waterTiles): a frame waits for the tiles
  // it asks for, for single pictures (geocean render). Off: the coarser
  // resident tile is drawn until a finer one arrives (views, flights).
  bool waitForTiles = false;
};

// How the terrain shades its water areas.
enum class SeaShading {
  None,        // land colour only
  DistantSea,  // flat sea with Fresnel sky, depth colour and glint (no ocean layer)
  UnderOcean,  // as DistantSea; with TerrainOptions::seaProxy, water the ocean
               // layer will cover gets only depth (not shaded twice)
};

struct TerrainStats {
  int tilesDrawn = 0;
  int tilesBuilt = 0;
  int tilesFlat = 0;  // of tilesDrawn, drawn with the coarse grid (water throughout)
  int maxLevel = 0;
};

class TerrainRenderer {
 public:
  static constexpr int kGrid = 33;  // vertices per tile edge (without skirt)

  explicit TerrainRenderer(const WorldTextures& world, TerrainOptions options = {});
  ~TerrainRenderer();
  TerrainRenderer(const TerrainRenderer&) = delete;
  TerrainRenderer& operator=(const TerrainRenderer&) = delete;

  // Chooses tiles for the view, builds missing ones, draws. `bare` uses
  // trivial shaders (the reference for frame-time ratios).
  // waterLayer: a layer whose info().opaqueWater lets the terrain leave out
  // the tiles it covers (TerrainOptions::skipOpenWater), or nullptr.
  TerrainStats draw(const camera::Camera& cam, const camera::Lighting& light, bool bare = false,
                    SeaShading sea = SeaShading::DistantSea, const Layer* waterLayer = nullptr);

  // The terrain above the sea, mirrored: drawn with the mirrored camera,
  // its tiles chosen from the real one (a reflection pass).
  TerrainStats drawMirrored(const camera::Camera& mirrored, const camera::Camera& selectFrom,
                            const camera::Lighting& light);

  // Depth only into the sun's shadow map: the terrain above the sea drawn
  // with viewProj (positions relative to selectFrom's eye). Its tiles are
  // chosen over `region` (lat0, lat1, lon0, lon1; the sea in view widened
  // towards the sun: ShadowView::region), not the view's frustum, so a
  // caster behind the eye or beside the view still shades the sea in it;
  // their level follows selectFrom's distance as the view's would. Tiles of
  // open water (nothing above the sea) are left out.
  TerrainStats drawDepth(const glm::mat4& viewProj, const camera::Camera& selectFrom, const Layer* waterLayer,
                         const double region[4]);

  const TerrainOptions& options() const { return options_; }
  void setSkipOpenWater(bool on) { options_.skipOpenWater = on; }
  // A global streamed mask's tiles flat at the sea's drop when the vertex
  // bilinear's texels are water throughout (on, the default); off: the
  // B-spline's 2-texel reach as before (for tests: the same picture).
  void setFlatWaterFromBilinear(bool on) { flatWaterFromBilinear_ = on; }
  // Tiles of water throughout at level >= 9 drawn with 8 x 8 cells (on, the
  // default) or the full grid (off; for tests).
  void setCoarseFlatTiles(bool on) { coarseFlat_ = on; }

 private:
  struct Key {
    int level, x, y;
    // Drawn with the coarse grid (Terrain.cpp's kFlatStep): water
    // throughout at level >= kFlatLevel (select). Not the tile's identity.
    bool flat = false;
    bool operator==(const Key& o) const { return level == o.level && x == o.x && y == o.y; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::uint64_t>()((std::uint64_t(k.level) << 48) ^ (std::uint64_t(k.x) << 24) ^ std::uint64_t(k.y));
    }
  };
  struct Slot {
    int index;
    glm::dvec3 centerEcef;
    std::list<Key>::iterator lru;
  };
  struct Bounds {
    glm::dvec3 center;
    double radius;
    glm::dvec3 samples[9];  // 3 x 3 points at the highest height
    double bulgeM = 0.0;    // how far the surface rises between them
    // Water throughout (WaterIndex; a global streamed mask's own cells under
    // the vertex bilinear): flat at -seaDrop, no relief to refine.
    bool allWater = false;
  };

  void select(const Key& k, const camera::Camera& cam, std::vector<Key>& out, int depth);
  // The shadow pass's casters: tiles over `region` with land, at the level
  // the view's screen-space error gives them, without the frustum.
  void selectCasters(const Key& k, const camera::Camera& cam, const double region[4], std::vector<Key>& out,
                     int depth);
  // The level-of-detail rule select and selectCasters share: true if k's
  // cells are coarser on screen than the pixel error allows.
  bool refines(const Key& k, const Bounds& b, const camera::Camera& cam, double dist) const;
  // With options_.waitForTiles (a picture): load the streamed mask's
  // (water) and relief's (elevation) blocks these tiles ask for first.
  void waitForBlocks(const std::vector<Key>& tiles, bool water, bool elevation);
  Bounds bounds(const Key& k) const;
  const Slot& acquire(const Key& k, TerrainStats& stats);
  void selectTiles(const camera::Camera& cam, std::vector<Key>& tiles, std::vector<const Slot*>& slots,
                   TerrainStats& stats);
  void drawTiles(const gl::GlProgram& prog, const camera::Camera& cam, const camera::Lighting& light, SeaShading sea,
                 double oceanCellPx, const std::vector<Key>& tiles, const std::vector<const Slot*>& slots,
                 const glm::mat4* viewProj = nullptr);  // instead of cam's (the shadow pass)
  // pxPerM: pixels per metre at 1 m distance.
  bool underOpenWater(double lat0, double lat1, double lon0, double lon1, const Bounds& b, double dist,
                      const camera::Camera& cam, double pxPerM) const;
  void tileRange(const Key& k, double& lat0, double& lat1, double& lon0, double& lon1) const;
  // terrain.frag's GEOCEAN_IMAGERY_LAYERS: the world's imagery layers, compiled in.
  std::string imageryDefine() const;
  // Streamed water: the pool tiles this terrain tile samples, as uniforms
  // (none with a null prog: only the requests). True when they are of the
  // level the tile wants.
  bool bindWaterBlock(const gl::GlProgram* prog, const Key& k);
  // The same for any pool: uniforms prefix + Slots, Block, Level, LevelGeo
  // (each + index: an array's element, e.g. "[0]").
  bool bindBlock(const gl::GlProgram* prog, gl::TilePool& pool, const Key& k, const char* prefix,
                 const char* index = "");

  const WorldTextures& world_;
  TerrainOptions options_;
  gl::GlProgram program_, underOcean_, bare_, seaProxy_, mirrored_, depth_;
  std::vector<std::string> depthDefines_;  // depth_'s (made on first use)
  const Layer* waterLayer_ = nullptr;  // this draw: leave out tiles it covers opaquely
  int maxLevel_ = 16;           // options_.maxLevel capped by the data's resolution
  // One global streamed mask's own cells (bounds: water throughout at them).
  mutable std::unique_ptr<world::TileWaterIndex> fineWater_;
  bool flatWaterFromBilinear_ = true;
  bool coarseFlat_ = true;
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  GLsizei indexCount_ = 0, flatIndexCount_ = 0;  // the flat tiles' indices follow the full grid's
  std::unordered_map<Key, Slot, KeyHash> cache_;
  std::list<Key> lru_;
  std::vector<int> freeSlots_;
};

// The sun direction in ECEF for a subsolar point.
glm::dvec3 sunFromSubsolar(double latDeg, double lonDeg);
// The sun for a given elevation/azimuth (degrees) seen from a place.
glm::dvec3 sunFromLocal(double latDeg, double lonDeg, double azimuthDeg, double elevationDeg);

}  // namespace geocean::render
