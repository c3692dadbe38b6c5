#include "plugin/render/WaterPages.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

namespace geocean::ocean_render {

WaterPages::WaterPages(std::shared_ptr<const raster::TilePyramid> pyramid, gl::TilePoolOptions pool)
    : pool_(std::make_unique<gl::TilePool>(std::move(pyramid), pool)) {
  const raster::TilePyramid& p = pool_->pyramid();
  if (p.levels() > 24) throw std::invalid_argument("water pages: more than 24 pyramid levels");
  tableW_ = p.tilesX(0);
  for (int l = 0; l < p.levels(); ++l) {
    rowOf_.push_back(tableH_);
    tableH_ += p.tilesY(l);
  }
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (tableW_ > maxSize || tableH_ > maxSize)
    throw std::invalid_argument("water pages: the page table (" + std::to_string(tableW_) + " x " +
                                std::to_string(tableH_) + ") exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize));
  glCreateTextures(GL_TEXTURE_2D, 1, &table_);
  glTextureStorage2D(table_, 1, GL_R32I, tableW_, tableH_);
  glTextureParameteri(table_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(table_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  cpu_.assign(std::size_t(tableW_) * tableH_, -1);
}

WaterPages::~WaterPages() {
  if (!abandoned_ && table_) glDeleteTextures(1, &table_);
}

void WaterPages::abandonGl() {
  abandoned_ = true;
  pool_->abandonGl();
}

std::size_t WaterPages::request(const grid::GridFrame& f, double cellPx) {
  const raster::TilePyramid& p = pool_->pyramid();
  const raster::GeoTransform& t = p.source().transform();
  const int T = p.tileSize(), top = p.levels() - 1;
  const double sx = 1.0 / std::abs(t.lonStepDeg), sy = 1.0 / std::abs(t.latStepDeg);
  std::unordered_set<std::uint64_t> seen;
  std::size_t missing = 0;
  const auto vertex = [&](int i, int j) -> const grid::GridVertex& { return f.vertices[std::size_t(j) * f.cols + i]; };
  for (int j = 0; j + 1 < f.rows; ++j)
    for (int i = 0; i + 1 < f.cols; ++i) {
      if (f.cellSkip[std::size_t(j) * (f.cols - 1) + i]) continue;
      // Level-0 texels along the cell's two edges, per pixel: the
      // fragment shader's length(fwidth(texel position)).
      const grid::GridVertex &a = vertex(i, j), &b = vertex(i + 1, j), &c = vertex(i, j + 1);
      const auto texels = [&](const grid::GridVertex& u, const grid::GridVertex& v) {
        const double dl = std::remainder(v.lonDeg - u.lonDeg, 360.0);
        return std::hypot(dl * sx, (v.latDeg - u.latDeg) * sy);
      };
      const double tpp = std::max(texels(a, b), texels(a, c)) / cellPx;
      const int want = tpp < 1.0 ? 0 : std::min(int(std::floor(std::log2(tpp))), top);
      for (const grid::GridVertex* v : {&a, &b, &c, &vertex(i + 1, j + 1)}) {
        const double s = double(1 << want);
        double x = (t.nearLon(v->lonDeg) - t.originLonDeg) / t.lonStepDeg / s;  // across 180: the layer's longitude
        double y = (v->latDeg - t.originLatDeg) / t.latStepDeg / s;
        const int W = p.levelWidth(want), H = p.levelHeight(want);
        // A regional pyramid: past the filter's reach (2 texels) of its
        // edge the grid answers (geo_uv.glsl levelClear), nothing to load.
        if (!t.global && (x < -2.0 || y < -2.0 || x > W + 2.0 || y > H + 2.0)) continue;
        if (t.global) x = x - W * std::floor(x / W);
        x = std::clamp(x, 0.0, W - 1.0), y = std::clamp(y, 0.0, H - 1.0);
        const raster::TileId id{want, int(x) / T, int(y) / T};
        const std::uint64_t key = (std::uint64_t(want) << 56) | (std::uint64_t(id.y) << 28) | std::uint64_t(id.x);
        if (!seen.insert(key).second) continue;
        if (pool_->residentSlot(id) < 0) {
          ++missing;
          pool_->request(id);
        }
      }
    }
  return missing;
}

void WaterPages::complete(const grid::GridFrame& f, double cellPx) {
  // Bounded: a view needing more tiles than the pool holds draws what fits.
  for (int round = 0; round < 64 && request(f, cellPx) > 0; ++round) {
    pool_->waitIdle();
    pool_->endFrame();
  }
}

void WaterPages::refreshTable() {
  if (pool_->residencyVersion() == version_) return;
  version_ = pool_->residencyVersion();
  std::fill(cpu_.begin(), cpu_.end(), -1);
  for (const auto& [id, slot] : pool_->residentTiles())
    cpu_[std::size_t(rowOf_[std::size_t(id.level)] + id.y) * tableW_ + id.x] = slot;
  glTextureSubImage2D(table_, 0, 0, 0, tableW_, tableH_, GL_RED_INTEGER, GL_INT, cpu_.data());
}

void WaterPages::bind(const gl::GlProgram& prog) {
  refreshTable();
  const raster::TilePyramid& p = pool_->pyramid();
  const raster::GeoTransform& t = p.source().transform();
  glBindTextureUnit(6, pool_->texture());
  glBindTextureUnit(7, table_);
  std::vector<GLint> levels;
  for (int l = 0; l < p.levels(); ++l)
    levels.insert(levels.end(), {p.levelWidth(l), p.levelHeight(l), p.tilesX(l), rowOf_[std::size_t(l)]});
  glUniform1i(prog.uniform("uPageTop"), p.levels() - 1);
  glUniform4iv(prog.uniform("uPageLevel"), GLsizei(p.levels()), levels.data());
  glUniform4f(prog.uniform("uPageGeo"), float(t.originLonDeg), float(t.originLatDeg), float(t.lonStepDeg),
              float(t.latStepDeg));
  glUniform2i(prog.uniform("uPageTile"), p.tileSize(), t.global ? 1 : 0);
}

}  // namespace geocean::ocean_render
