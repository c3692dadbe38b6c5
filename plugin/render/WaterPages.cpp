#include "plugin/render/WaterPages.h"

#include "globe/world/WaterPyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <unordered_set>
#include <utility>

namespace geocean::ocean_render {

gl::TilePoolOptions WaterPages::defaultBelowPool() {
  gl::TilePoolOptions o;
  o.slots = 96;  // a layer below answers only where the first has no data
  return o;
}

PagedPool PagedPool::make(std::shared_ptr<const raster::TilePyramid> pyramid, gl::TilePoolOptions pool,
                          const char* what) {
  PagedPool l;
  l.pool = std::make_unique<gl::TilePool>(std::move(pyramid), pool);
  const raster::TilePyramid& p = l.pool->pyramid();
  if (p.levels() > 24)
    throw std::invalid_argument(p.source().path() + ": " + what + ": more than 24 pyramid levels");
  l.tableW = p.tilesX(0);
  for (int k = 0; k < p.levels(); ++k) {
    l.rowOf.push_back(l.tableH);
    l.tableH += p.tilesY(k);
  }
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (l.tableW > maxSize || l.tableH > maxSize)
    throw std::invalid_argument(p.source().path() + ": " + what + ": the page table (" + std::to_string(l.tableW) +
                                " x " + std::to_string(l.tableH) + ") exceeds GL_MAX_TEXTURE_SIZE " +
                                std::to_string(maxSize));
  glCreateTextures(GL_TEXTURE_2D, 1, &l.table);
  glTextureStorage2D(l.table, 1, GL_R32I, l.tableW, l.tableH);
  glTextureParameteri(l.table, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(l.table, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  l.cpu.assign(std::size_t(l.tableW) * l.tableH, -1);
  return l;
}

PagedPool::PagedPool(PagedPool&& o) noexcept { *this = std::move(o); }

PagedPool& PagedPool::operator=(PagedPool&& o) noexcept {
  if (this == &o) return *this;
  if (table) glDeleteTextures(1, &table);
  pool = std::move(o.pool);
  table = std::exchange(o.table, 0);
  tableW = o.tableW, tableH = o.tableH;
  rowOf = std::move(o.rowOf);
  cpu = std::move(o.cpu);
  version = o.version;
  return *this;
}

PagedPool::~PagedPool() {
  if (table) glDeleteTextures(1, &table);
}

void PagedPool::abandonGl() {
  if (pool) pool->abandonGl();
  table = 0;
}

std::size_t PagedPool::ask(const raster::TileId& id, Asked& asked) {
  const std::uint64_t key = (std::uint64_t(id.level) << 56) | (std::uint64_t(id.y) << 28) | std::uint64_t(id.x);
  if (key == asked.last) return 0;
  asked.last = key;
  if (!asked.seen.insert(key).second || pool->residentSlot(id) >= 0) return 0;
  pool->request(id);
  return 1;
}

void PagedPool::refresh() {
  if (pool->residencyVersion() == version) return;
  version = pool->residencyVersion();
  std::fill(cpu.begin(), cpu.end(), -1);
  for (const auto& [id, slot] : pool->residentTiles())
    cpu[std::size_t(rowOf[std::size_t(id.level)] + id.y) * tableW + id.x] = slot;
  glTextureSubImage2D(table, 0, 0, 0, tableW, tableH, GL_RED_INTEGER, GL_INT, cpu.data());
}

std::vector<GLint> PagedPool::levelsUniform() const {
  const raster::TilePyramid& p = pool->pyramid();
  std::vector<GLint> levels;
  for (int l = 0; l < p.levels(); ++l)
    levels.insert(levels.end(), {p.levelWidth(l), p.levelHeight(l), p.tilesX(l), rowOf[std::size_t(l)]});
  return levels;
}

WaterPages::WaterPages(std::shared_ptr<const raster::TilePyramid> pyramid, gl::TilePoolOptions pool,
                       std::vector<std::shared_ptr<const raster::TilePyramid>> below, gl::TilePoolOptions belowPool) {
  if (below.size() + 1 > std::size_t(world::kMaxStreamedLayers))
    throw std::invalid_argument("water pages: " + std::to_string(below.size() + 1) + " streamed layers, at most " +
                                std::to_string(world::kMaxStreamedLayers) + " (the first: " + pyramid->source().path() +
                                ")");
  const bool several = !below.empty();
  const gl::TilePoolOptions first = gl::chainedWaterPool(pool, pyramid->source(), several);
  layers_.push_back(PagedPool::make(std::move(pyramid), first, "water pages"));
  for (auto& b : below) {
    const gl::TilePoolOptions o = gl::chainedWaterPool(belowPool, b->source(), several);
    layers_.push_back(PagedPool::make(std::move(b), o, "water pages"));
  }
}

void WaterPages::abandonGl() {
  for (Layer& l : layers_) l.abandonGl();
}

void WaterPages::endFrame() {
  for (Layer& l : layers_) l.pool->endFrame();
}

std::vector<std::string> WaterPages::defines() const {
  std::vector<std::string> d{"GEOCEAN_WATER_PAGES 1"};
  if (!pyramid().source().transform().global) d.push_back("GEOCEAN_WATER_PAGES_REGIONAL 1");
  if (layers_.size() > 1) d.push_back("GEOCEAN_WATER_PAGES_LAYERS " + std::to_string(layers_.size()));
  return d;
}

std::size_t WaterPages::request(const grid::GridFrame& f, double cellPx) {
  std::size_t missing = 0;
  for (Layer& l : layers_) missing += request(l, f, cellPx);
  return missing;
}

std::size_t WaterPages::request(Layer& layer, const grid::GridFrame& f, double cellPx) {
  const raster::TilePyramid& p = layer.pool->pyramid();
  const raster::GeoTransform& t = p.source().transform();
  const int tileShift = std::countr_zero(unsigned(p.tileSize())), top = p.levels() - 1;  // a power of two
  // Level-0 texel coordinates of every vertex, once (a vertex is the corner
  // of four cells; the libm calls per cell were half of a low view's 13 ms).
  const double around = 360.0 / std::abs(t.lonStepDeg);
  texelX_.resize(f.vertices.size()), texelY_.resize(f.vertices.size());
  for (std::size_t k = 0; k < f.vertices.size(); ++k) {
    const grid::GridVertex& v = f.vertices[k];
    texelX_[k] = (t.nearLon(v.lonDeg) - t.originLonDeg) / t.lonStepDeg;  // across 180: the layer's longitude
    texelY_[k] = (v.latDeg - t.originLatDeg) / t.latStepDeg;
  }
  PagedPool::Asked asked;
  std::size_t missing = 0;
  for (int j = 0; j + 1 < f.rows; ++j)
    for (int i = 0; i + 1 < f.cols; ++i) {
      if (f.cellSkip[std::size_t(j) * (f.cols - 1) + i]) continue;
      const std::size_t a = std::size_t(j) * f.cols + i, b = a + 1, c = a + f.cols, d = c + 1;
      // Level-0 texels along the cell's two edges, per pixel: the
      // fragment shader's length(fwidth(texel position)); longitude
      // differences the short way round.
      const auto texels2 = [&](std::size_t u, std::size_t v) {
        double dx = texelX_[v] - texelX_[u];
        if (std::abs(dx) > 0.5 * around) dx -= around * std::nearbyint(dx / around);
        const double dy = texelY_[v] - texelY_[u];
        return dx * dx + dy * dy;
      };
      const double tpp = std::sqrt(std::max(texels2(a, b), texels2(a, c))) / cellPx;
      const int want = tpp < 1.0 ? 0 : std::min(std::ilogb(tpp), top);  // floor(log2)
      const double toLevel = 1.0 / double(1 << want);  // a power of two: exact
      const int W = p.levelWidth(want), H = p.levelHeight(want);
      for (const std::size_t v : {a, b, c, d}) {
        double x = texelX_[v] * toLevel, y = texelY_[v] * toLevel;
        // A regional pyramid: past the filter's reach (2 texels) of its
        // edge the grid answers (geo_uv.glsl levelClear), nothing to load.
        if (!t.global && (x < -2.0 || y < -2.0 || x > W + 2.0 || y > H + 2.0)) continue;
        if (t.global && (x < 0.0 || x >= W)) x = x - W * std::floor(x / W);
        x = std::clamp(x, 0.0, W - 1.0), y = std::clamp(y, 0.0, H - 1.0);
        missing += layer.ask({want, int(x) >> tileShift, int(y) >> tileShift}, asked);  // x, y >= 0
      }
    }
  return missing;
}

void WaterPages::complete(const grid::GridFrame& f, double cellPx) {
  PagedPool::completeAll(layers_, [&] { return request(f, cellPx); });
}

void WaterPages::bind(const gl::GlProgram& prog) {
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    Layer& layer = layers_[k];
    layer.refresh();
    const raster::TilePyramid& p = layer.pool->pyramid();
    const raster::GeoTransform& t = p.source().transform();
    const std::vector<GLint> levels = layer.levelsUniform();
    if (k == 0) {
      glBindTextureUnit(6, layer.pool->texture());
      glBindTextureUnit(7, layer.table);
      glUniform1i(prog.uniform("uPageTop"), p.levels() - 1);
      glUniform4iv(prog.uniform("uPageLevel"), GLsizei(p.levels()), levels.data());
      glUniform4f(prog.uniform("uPageGeo"), float(t.originLonDeg), float(t.originLatDeg), float(t.lonStepDeg),
                  float(t.latStepDeg));
      glUniform2i(prog.uniform("uPageTile"), p.tileSize(), t.global ? 1 : 0);
      continue;
    }
    // Layer k >= 1: element k - 1 of the uPageB arrays (geo_uv.glsl).
    glBindTextureUnit(GLuint(8 + k), layer.pool->texture());
    glBindTextureUnit(GLuint(21 + k), layer.table);
    const auto at = [&](const char* name, std::size_t i) {
      return prog.uniform((std::string(name) + "[" + std::to_string(i) + "]").c_str());
    };
    glUniform1i(at("uPageBTop", k - 1), p.levels() - 1);
    glUniform4iv(at("uPageBLevel", (k - 1) * 24), GLsizei(p.levels()), levels.data());
    glUniform4f(at("uPageBGeo", k - 1), float(t.originLonDeg), float(t.originLatDeg), float(t.lonStepDeg),
                float(t.latStepDeg));
    glUniform2i(at("uPageBTile", k - 1), p.tileSize(), t.global ? 1 : 0);
  }
}

}  // namespace geocean::ocean_render
