// A fixed-size GPU pool of pyramid tiles (issue 12 item 2): one
// GL_TEXTURE_2D_ARRAY of `slots` layers of (tileSize+2)^2 texels (the
// pyramid's bordered tiles), filled from a raster::TilePyramid on worker
// threads. Per frame the drawer asks for the tiles the view needs
// (slotOf); a missing tile is queued and its nearest resident ancestor is
// drawn meanwhile: the top tile (the whole raster) is loaded at construction
// and pinned, so there is never a hole, and nothing waits for a load (never
// a stall). endFrame uploads at most maxUploadsPerFrame finished tiles into
// free slots or those least recently used before this frame.
//
// Bounds, independent of the raster's size: GPU memory gpuBytes() =
// slots x (tileSize+2)^2 x texel bytes; CPU memory of the pool
// cpuBoundBytes() = (queue bound + ready bound + workers) tile buffers,
// plus the pyramid's own residentBoundBytes().
//
// GL calls (constructor, endFrame, destructor) on the context's thread only;
// slotOf also on that thread.
#pragma once

#include "globe/raster/TilePyramid.h"

#include <epoxy/gl.h>

#include <cmath>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <vector>

namespace geocean::gl {

struct TilePoolOptions {
  int slots = 192;  // at most: a pyramid of fewer tiles gets one per tile (TilePool::slots())
  int workers = 2;
  int maxUploadsPerFrame = 16;
  int maxQueued = 256;  // requests beyond this are dropped (asked again next frame)
  int maxReady = 32;    // loaded tiles waiting for upload; workers wait beyond it
  // GL_R8 (values clamped to [0, 1], e.g. water coverage) or GL_R32F. First channel only.
  GLenum internalFormat = GL_R8;
  float nodataValue = 0.0f;  // what NaN texels become
};

// A streamed water layer's pool (the host's terrain and the ocean alike):
// a layer whose raster declares nodata keeps it (NaN) in an R32F pool, so
// the next layer (or, for a lone regional layer, the grid below) answers
// there, as the query's (R8 would make it land); past a layer's edge the
// shader knows by position, so a layer without nodata, or a lone global
// one (its pyramid's nodata is land, world::waterPyramid), stays R8.
inline TilePoolOptions chainedWaterPool(TilePoolOptions o, const raster::Raster& source, bool several) {
  if (source.nodata() && (several || !source.transform().global)) o.internalFormat = GL_R32F, o.nodataValue = NAN;
  return o;
}

class TilePool {
 public:
  // Needs a current GL context. Loads the top tile synchronously.
  TilePool(std::shared_ptr<const raster::TilePyramid> pyramid, TilePoolOptions options = {});
  ~TilePool();
  TilePool(const TilePool&) = delete;
  TilePool& operator=(const TilePool&) = delete;
  // Without the context of its texture: the destructor then makes no GL
  // call (the context owns the name) and only stops the workers.
  void abandonGl() { texture_ = 0; }

  // The layer holding `want` or, until it arrives, its nearest resident
  // ancestor (`drawn` says which). Queues `want` when it is missing. Never
  // blocks on a load.
  int slotOf(raster::TileId want, raster::TileId* drawn = nullptr);
  // The layer of `id` if it is resident (marks it used this frame), else -1.
  int residentSlot(raster::TileId id);
  // Queues `id` if it is neither resident nor queued.
  void request(raster::TileId id);
  // Uploads finished loads, forgets requests older than two frames, starts the next frame.
  void endFrame();
  // Blocks until every queued tile is loaded or the ready list is full
  // (TerrainOptions::waitForTiles: single pictures, never views).
  void waitIdle();

  GLuint texture() const { return texture_; }
  // Every resident tile and its layer (a drawer's page table), and a count
  // that changes whenever that set does.
  std::vector<std::pair<raster::TileId, int>> residentTiles() const;
  std::uint64_t residencyVersion() const { return residency_; }
  const raster::TilePyramid& pyramid() const { return *pyramid_; }
  const std::shared_ptr<const raster::TilePyramid>& sharedPyramid() const { return pyramid_; }
  // The texture array's layers: the options' slots, or the pyramid's tile
  // count where that is smaller. gpuBytes() is bounded by the options'
  // slots whatever the raster's size.
  int slots() const { return options_.slots; }
  std::size_t gpuBytes() const;
  std::size_t cpuBoundBytes() const;

  struct Stats {
    int resident = 0, queued = 0, ready = 0;
    std::uint64_t uploads = 0, requests = 0, dropped = 0;
  };
  Stats stats() const;

 private:
  static std::uint64_t keyOf(raster::TileId id);
  void upload(int slot, const std::vector<float>& bordered);
  void work();

  std::shared_ptr<const raster::TilePyramid> pyramid_;
  TilePoolOptions options_;
  GLuint texture_ = 0;
  int border_ = 0;  // tileSize + 2
  std::uint64_t frame_ = 1;
  struct SlotInfo {
    raster::TileId id{-1, 0, 0};
    std::uint64_t lastUsed = 0;
    bool pinned = false;
  };
  std::vector<SlotInfo> slotInfo_;
  std::unordered_map<std::uint64_t, int> resident_;  // key -> slot
  Stats stats_;
  std::uint64_t residency_ = 0;

  // Shared with the workers.
  mutable std::mutex mutex_;
  std::condition_variable wake_, space_;
  struct Request {
    raster::TileId id;
    std::uint64_t frame;
  };
  std::deque<Request> queue_;                             // newest at the back
  std::unordered_map<std::uint64_t, std::uint64_t> wanted_;  // queued or loading -> frame asked
  std::vector<std::pair<raster::TileId, std::vector<float>>> ready_;
  int loading_ = 0;  // taken by a worker, not yet ready
  std::condition_variable idle_;
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace geocean::gl
