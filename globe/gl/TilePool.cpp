#include "globe/gl/TilePool.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace geocean::gl {

std::uint64_t TilePool::keyOf(raster::TileId id) {
  return (std::uint64_t(id.level) << 56) | (std::uint64_t(std::uint32_t(id.y)) << 28) | std::uint32_t(id.x);
}

TilePool::TilePool(std::shared_ptr<const raster::TilePyramid> pyramid, TilePoolOptions options)
    : pyramid_(std::move(pyramid)), options_(options) {
  if (!pyramid_) throw std::invalid_argument("tile pool: no pyramid");
  if (options_.slots < 2) throw std::invalid_argument("tile pool: at least 2 slots");
  if (options_.internalFormat != GL_R8 && options_.internalFormat != GL_R32F)
    throw std::invalid_argument("tile pool: internal format must be GL_R8 or GL_R32F");
  // A pyramid of fewer tiles than slots (a small regional raster) gets a
  // slot per tile: all of it fits, nothing is evicted, the slots taken are
  // the same, and its GPU (and, llvmpipe, CPU) memory is that much less.
  int tiles = 0;
  for (int l = 0; l < pyramid_->levels() && tiles < options_.slots; ++l)
    tiles += pyramid_->tilesX(l) * pyramid_->tilesY(l);
  options_.slots = std::max(2, std::min(options_.slots, tiles));
  border_ = pyramid_->tileSize() + 2;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_);
  glTextureStorage3D(texture_, 1, options_.internalFormat, border_, border_, options_.slots);
  // Shaders read texels (texelFetch) and filter themselves; no sampler state matters.
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  slotInfo_.resize(std::size_t(options_.slots));
  // The top tile: the whole raster, always resident.
  const raster::TileId top{pyramid_->levels() - 1, 0, 0};
  std::vector<float> t(std::size_t(border_) * border_ * pyramid_->channels());
  pyramid_->readTile(top, t.data());
  upload(0, t);
  slotInfo_[0] = {top, 0, true};
  resident_[keyOf(top)] = 0;
  for (int i = 0; i < std::max(options_.workers, 1); ++i) workers_.emplace_back([this] { work(); });
}

TilePool::~TilePool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  space_.notify_all();
  idle_.notify_all();
  for (auto& w : workers_) w.join();
  if (texture_) glDeleteTextures(1, &texture_);
}

std::size_t TilePool::gpuBytes() const {
  return std::size_t(options_.slots) * border_ * border_ * (options_.internalFormat == GL_R8 ? 1 : 4);
}

std::size_t TilePool::cpuBoundBytes() const {
  const std::size_t tile = std::size_t(border_) * border_ * pyramid_->channels() * sizeof(float);
  return std::size_t(options_.maxReady + std::max(options_.workers, 1)) * tile +
         std::size_t(options_.maxQueued) * (sizeof(Request) + 48) +
         std::size_t(options_.slots) * (sizeof(SlotInfo) + 48);
}

TilePool::Stats TilePool::stats() const {
  std::lock_guard lock(mutex_);
  Stats s = stats_;
  s.resident = int(resident_.size());
  s.queued = int(queue_.size());
  s.ready = int(ready_.size());
  return s;
}

std::vector<std::pair<raster::TileId, int>> TilePool::residentTiles() const {
  std::vector<std::pair<raster::TileId, int>> out;
  out.reserve(resident_.size());
  for (const auto& [key, slot] : resident_) out.emplace_back(slotInfo_[std::size_t(slot)].id, slot);
  return out;
}

int TilePool::residentSlot(raster::TileId id) {
  auto it = resident_.find(keyOf(id));
  if (it == resident_.end()) return -1;
  slotInfo_[std::size_t(it->second)].lastUsed = frame_;
  return it->second;
}

void TilePool::request(raster::TileId id) {
  if (resident_.count(keyOf(id))) return;
  std::lock_guard lock(mutex_);
  ++stats_.requests;
  const std::uint64_t k = keyOf(id);
  if (auto it = wanted_.find(k); it != wanted_.end()) {
    it->second = frame_;  // still wanted
    return;
  }
  if (int(queue_.size()) >= options_.maxQueued) {
    ++stats_.dropped;
    return;
  }
  wanted_[k] = frame_;
  queue_.push_back({id, frame_});
  wake_.notify_one();
}

int TilePool::slotOf(raster::TileId want, raster::TileId* drawn) {
  raster::TileId id = want;
  for (;;) {
    const int s = residentSlot(id);
    if (s >= 0) {
      if (!(id == want)) request(want);
      if (drawn) *drawn = id;
      return s;
    }
    id = {id.level + 1, id.x / 2, id.y / 2};  // the top is pinned: this ends
  }
}

void TilePool::upload(int slot, const std::vector<float>& bordered) {
  const int c = pyramid_->channels();
  std::vector<float> v(std::size_t(border_) * border_);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const float x = bordered[i * c];
    v[i] = std::isnan(x) ? options_.nodataValue : x;
  }
  glTextureSubImage3D(texture_, 0, 0, 0, slot, border_, border_, 1, GL_RED, GL_FLOAT, v.data());
}

void TilePool::endFrame() {
  std::vector<std::pair<raster::TileId, std::vector<float>>> got;
  {
    std::lock_guard lock(mutex_);
    const std::size_t n = std::min<std::size_t>(ready_.size(), std::size_t(options_.maxUploadsPerFrame));
    got.assign(std::make_move_iterator(ready_.end() - std::ptrdiff_t(n)), std::make_move_iterator(ready_.end()));
    ready_.resize(ready_.size() - n);
    // Requests nobody asked for in the last two frames are stale (the view moved on).
    std::deque<Request> keep;
    for (const Request& r : queue_) {
      const auto it = wanted_.find(keyOf(r.id));
      if (it != wanted_.end() && it->second + 2 >= frame_) keep.push_back(r);
      else if (it != wanted_.end()) wanted_.erase(it);
    }
    queue_.swap(keep);
  }
  if (!got.empty()) space_.notify_all();
  for (auto& [id, data] : got) {
    const std::uint64_t k = keyOf(id);
    {
      std::lock_guard lock(mutex_);
      wanted_.erase(k);
    }
    if (resident_.count(k)) continue;
    // A free slot, else the least recently used one not used this frame.
    int best = -1;
    for (int s = 0; s < options_.slots; ++s) {
      const SlotInfo& si = slotInfo_[std::size_t(s)];
      if (si.pinned || si.lastUsed >= frame_) continue;
      if (si.id.level < 0) {
        best = s;
        break;
      }
      if (best < 0 || si.lastUsed < slotInfo_[std::size_t(best)].lastUsed) best = s;
    }
    if (best < 0) continue;  // everything is in use this frame: drop it, it will be asked again
    if (slotInfo_[std::size_t(best)].id.level >= 0) resident_.erase(keyOf(slotInfo_[std::size_t(best)].id));
    upload(best, data);
    slotInfo_[std::size_t(best)] = {id, 0, false};
    resident_[k] = best;
    ++stats_.uploads;
    ++residency_;
  }
  ++frame_;
}

void TilePool::waitIdle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [&] {
    return stop_ || (queue_.empty() && loading_ == 0) || int(ready_.size()) >= options_.maxReady;
  });
}

void TilePool::work() {
  const std::size_t floats = std::size_t(border_) * border_ * pyramid_->channels();
  for (;;) {
    raster::TileId id;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      id = queue_.back().id;  // the newest request first: what the view needs now
      queue_.pop_back();
      ++loading_;
    }
    std::vector<float> t(floats);
    bool ok = true;
    try {
      pyramid_->readTile(id, t.data());
    } catch (const std::exception&) {
      // A tile that cannot be read is drawn from its ancestor; it stays in
      // wanted_ so it is not asked for again.
      ok = false;
    }
    std::unique_lock lock(mutex_);
    if (ok) {
      space_.wait(lock, [&] { return stop_ || int(ready_.size()) < options_.maxReady; });
      if (stop_) return;
      ready_.emplace_back(id, std::move(t));
    }
    --loading_;
    idle_.notify_all();
  }
}

}  // namespace geocean::gl
