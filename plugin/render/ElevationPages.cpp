#include "plugin/render/ElevationPages.h"

#include "globe/world/WaterPyramid.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

namespace geocean::ocean_render {

ElevationPages::ElevationPages(std::vector<std::shared_ptr<const raster::TilePyramid>> layers) {
  if (layers.empty()) throw std::invalid_argument("elevation pages: no layer");
  if (layers.size() > std::size_t(world::kMaxStreamedLayers))
    throw std::invalid_argument("elevation pages: " + std::to_string(layers.size()) + " streamed reliefs, at most " +
                                std::to_string(world::kMaxStreamedLayers) + " (the first: " +
                                layers.front()->source().path() + ")");
  gl::TilePoolOptions o;
  o.internalFormat = GL_R32F;
  o.nodataValue = NAN;  // the next layer, or the grid, answers there
  for (auto& p : layers) {
    layers_.push_back(PagedPool::make(std::move(p), o, "elevation pages"));
    o.slots = WaterPages::defaultBelowPool().slots;  // a layer below answers only where those above have no data
  }
}

void ElevationPages::abandonGl() {
  for (PagedPool& l : layers_) l.abandonGl();
}

void ElevationPages::endFrame() {
  for (PagedPool& l : layers_) l.pool->endFrame();
}

std::vector<std::string> ElevationPages::defines() const {
  return {"GEOCEAN_ELEV_PAGES " + std::to_string(layers_.size())};
}

int ElevationPages::wantLevel(double footprintM, double latStepDeg, int top) {
  const float r = std::max(float(footprintM), 1e-6f) / (std::abs(float(latStepDeg)) * 111320.0f);
  return std::clamp(int(std::floor(std::log2(r))), 0, top);
}

std::size_t ElevationPages::request(const grid::GridFrame& f, double cellRadians) {
  std::size_t missing = 0;
  for (PagedPool& l : layers_) missing += request(l, f, cellRadians);
  return missing;
}

std::size_t ElevationPages::request(PagedPool& layer, const grid::GridFrame& f, double cellRadians) {
  const raster::TilePyramid& p = layer.pool->pyramid();
  const raster::GeoTransform& t = p.source().transform();
  const int T = p.tileSize(), top = p.levels() - 1;
  std::vector<std::uint8_t> drawn(f.vertices.size(), 0);
  for (int j = 0; j + 1 < f.rows; ++j)
    for (int i = 0; i + 1 < f.cols; ++i)
      if (!f.cellSkip[std::size_t(j) * (f.cols - 1) + i])
        for (const int v : {j * f.cols + i, j * f.cols + i + 1, (j + 1) * f.cols + i, (j + 1) * f.cols + i + 1})
          drawn[std::size_t(v)] = 1;
  PagedPool::Asked asked;
  std::size_t missing = 0;
  for (std::size_t k = 0; k < f.vertices.size(); ++k) {
    if (!drawn[k]) continue;
    const grid::GridVertex& v = f.vertices[k];
    const double footprintM = glm::length(glm::dvec3(v.eyeRelM[0], v.eyeRelM[1], v.eyeRelM[2])) * cellRadians;
    const int level = wantLevel(footprintM, t.latStepDeg, top);
    const double s = double(1 << level);
    const double x = (t.nearLon(v.lonDeg) - t.originLonDeg) / t.lonStepDeg / s - 0.5;
    const double y = (v.latDeg - t.originLatDeg) / t.latStepDeg / s - 0.5;
    const int W = p.levelWidth(level), H = p.levelHeight(level);
    // Past a regional layer's edge its nearest texel is outside: the next layer answers.
    if (!t.global && (x < -1.0 || y < -1.0 || x > W || y > H)) continue;
    const long x0 = long(std::floor(x)), y0 = long(std::floor(y));
    for (long dy = 0; dy < 2; ++dy)
      for (long dx = 0; dx < 2; ++dx) {
        long gx = x0 + dx;
        gx = t.global ? ((gx % W) + W) % W : std::clamp(gx, 0L, long(W - 1));
        const long gy = std::clamp(y0 + dy, 0L, long(H - 1));
        missing += layer.ask({level, int(gx / T), int(gy / T)}, asked);
      }
  }
  return missing;
}

void ElevationPages::complete(const grid::GridFrame& f, double cellRadians) {
  PagedPool::completeAll(layers_, [&] { return request(f, cellRadians); });
}

void ElevationPages::bind(const gl::GlProgram& prog, float refLatDeg, float refLonDeg) {
  const auto at = [&](const char* name, std::size_t i) {
    return prog.uniform((std::string(name) + "[" + std::to_string(i) + "]").c_str());
  };
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    PagedPool& layer = layers_[k];
    layer.refresh();
    const raster::TilePyramid& p = layer.pool->pyramid();
    const raster::GeoTransform& t = p.source().transform();
    glBindTextureUnit(GLuint(25 + k), layer.pool->texture());
    glBindTextureUnit(GLuint(29 + k), layer.table);
    glUniform1i(at("uEPageTop", k), p.levels() - 1);
    const std::vector<GLint> levels = layer.levelsUniform();
    glUniform4iv(at("uEPageLevel", k * 24), GLsizei(p.levels()), levels.data());
    glUniform2i(at("uEPageTile", k), p.tileSize(), t.global ? 1 : 0);
    glUniform2f(at("uEPageStep", k), float(t.lonStepDeg), float(t.latStepDeg));
    // The reference (the floats the shader subtracts, as doubles) in the
    // layer's level 0, texel edges at integers, split in double.
    const double refLon = t.global ? double(refLonDeg) : t.nearLon(double(refLonDeg));
    const double x = (refLon - t.originLonDeg) / t.lonStepDeg, y = (double(refLatDeg) - t.originLatDeg) / t.latStepDeg;
    const double ix = std::floor(x), iy = std::floor(y);
    glUniform2i(at("uEPageRefTexel", k), GLint(ix), GLint(iy));
    glUniform2f(at("uEPageRefFrac", k), float(x - ix), float(y - iy));
    const double centre = t.originLonDeg + 0.5 * p.levelWidth(0) * t.lonStepDeg;
    glUniform1f(at("uEPageRefOff", k), float(refLon - centre));
  }
}

}  // namespace geocean::ocean_render
