#include "globe/render/WorldTextures.h"

#include "globe/gl/Texture.h"
#include "globe/world/WaterPyramid.h"

namespace geocean::render {

WorldTextures::WorldTextures(const world::WorldData& data)
    : grids_(std::make_shared<const world::WorldGrids>(data.elevation, data.water)) {
  world::checkLayer(data.imagery, "imagery", 3);
  const auto& l = data.imagery;
  imagery_ = gl::srgbGeoTexture(l.values.data(), l.channels, l.width, l.height);
  imageryGeo_ = l.geo();
  const auto& e = grids_->elevation();
  elevation_ = gl::redGeoTexture(e.values.data(), e.channels, e.width, e.height, GL_R32F, false);
  // Mipmapped so that far coasts average to partial coverage instead of aliasing.
  const auto& w = grids_->water();
  water_ = gl::redGeoTexture(w.values.data(), w.channels, w.width, w.height, GL_R8, true);
  if (data.waterSource) waterTiles_ = std::make_unique<gl::TilePool>(world::waterPyramid(data.waterSource, data.waterEncoding));
}

WorldTextures::WorldTextures(const world::WorldData& data, std::shared_ptr<const raster::TilePyramid> water,
                             gl::TilePoolOptions pool)
    : WorldTextures(data) {
  if (water) waterTiles_ = std::make_unique<gl::TilePool>(std::move(water), pool);
}

WorldTextures::~WorldTextures() {
  const GLuint t[] = {imagery_, elevation_, water_};
  glDeleteTextures(3, t);
}

void WorldTextures::bind() const {
  glBindTextureUnit(0, imagery_);
  glBindTextureUnit(1, elevation_);
  glBindTextureUnit(2, water_);
}

}  // namespace geocean::render
