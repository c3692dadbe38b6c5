#include "globe/render/WorldTextures.h"

#include "globe/gl/Texture.h"
#include "globe/world/WaterPyramid.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

namespace geocean::render {

WorldTextures::WorldTextures(world::WorldData data)
    : grids_(std::make_shared<const world::WorldGrids>(std::move(data.elevation), std::move(data.water))) {
  world::checkLayer(data.imagery, "imagery", 3);
  const auto& l = data.imagery;
  imagery_ = gl::srgbGeoTexture(l.values.data(), l.channels, l.width, l.height);
  imageryGeo_ = l.geo();
  std::vector<float>().swap(data.imagery.values);  // 175 MB of floats for the Blue Marble, on the GPU now
  const auto& e = grids_->elevation();
  elevation_ = gl::redGeoTexture(e.values.data(), e.channels, e.width, e.height, GL_R32F, false);
  // Mipmapped so that far coasts average to partial coverage instead of aliasing.
  const auto& w = grids_->water();
  water_ = gl::redGeoTexture(w.values.data(), w.channels, w.width, w.height, GL_R8, true);
  if (int(data.imageryLayers.size()) > world::kMaxImageryLayers)
    throw std::invalid_argument("more than " + std::to_string(world::kMaxImageryLayers) + " imagery layers");
  for (world::ImageryLayer& il : data.imageryLayers) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (il.width > maxSize || il.height > maxSize)
      throw std::runtime_error(il.name + ": imagery of " + std::to_string(il.width) + "x" + std::to_string(il.height) +
                               " is larger than a GL texture (" + std::to_string(maxSize) + ")");
    // Premultiplied sRGB: filtering and mipmaps blend valid texels with the
    // transparent nodata ones without darkening. A regional layer fades to
    // the layer below outside its edge (transparent border).
    GLuint t = gl::createGeoTexture(GL_SRGB8_ALPHA8, il.width, il.height, true);
    if (!il.global) {
      const float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
      glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
      glTextureParameterfv(t, GL_TEXTURE_BORDER_COLOR, border);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t, 0, 0, 0, il.width, il.height, GL_RGBA, GL_UNSIGNED_BYTE, il.rgba.data());
    glGenerateTextureMipmap(t);
    std::vector<std::uint8_t>().swap(il.rgba);
    imageryLayers_.push_back(t);
    imageryLayerGeo_.push_back(il.geo());
  }
  if (data.elevationTilesBelow.size() + 1 > std::size_t(world::kMaxStreamedLayers))
    throw std::invalid_argument(data.elevationTilesBelow.back()->source().path() + ": more than " +
                                std::to_string(world::kMaxStreamedLayers) + " streamed elevation layers");
  if (data.elevationTiles) {
    gl::TilePoolOptions o;
    o.internalFormat = GL_R32F;
    o.nodataValue = NAN;  // the shader falls back to the elevation grid there
    elevationTiles_ = std::make_unique<gl::TilePool>(data.elevationTiles, o);
    o.slots /= 2;  // as the water's: a layer below answers only where those above have no data
    for (const auto& p : data.elevationTilesBelow) elevationTilesBelow_.push_back(std::make_unique<gl::TilePool>(p, o));
  }
  // Several streamed masks (gl::chainedWaterPool); the layers below hold
  // half the slots (they answer only where those above have no data).
  const bool several = !data.waterSourcesBelow.empty();
  if (data.waterSourcesBelow.size() + 1 > std::size_t(world::kMaxStreamedLayers))
    throw std::invalid_argument(data.waterSourcesBelow.back()->path() + ": more than " +
                                std::to_string(world::kMaxStreamedLayers) + " streamed water layers");
  const auto options = [&](const raster::Raster& r, bool below) {
    gl::TilePoolOptions o;
    if (below) o.slots /= 2;
    return gl::chainedWaterPool(o, r, several);
  };
  if (data.waterSource)
    waterTiles_ = std::make_unique<gl::TilePool>(data.waterFromRelief ? world::reliefWaterPyramid(data.waterSource)
                                                                       : world::waterPyramid(data.waterSource, data.waterEncoding),
                                                 options(*data.waterSource, false));
  for (std::size_t i = 0; i < data.waterSourcesBelow.size(); ++i) {
    const bool relief = i < data.waterFromReliefBelow.size() && data.waterFromReliefBelow[i];
    waterTilesBelow_.push_back(std::make_unique<gl::TilePool>(
        relief ? world::reliefWaterPyramid(data.waterSourcesBelow[i])
               : world::waterPyramid(data.waterSourcesBelow[i], data.waterEncodingsBelow[i]),
        options(*data.waterSourcesBelow[i], true)));
  }
  indexRegionalWater();
}

void WorldTextures::indexRegionalWater() {
  regionalIndex_.clear();
  for (int k = 0; k < waterTileLayers(); ++k) {
    const gl::TilePool* p = waterTiles(k);
    regionalIndex_.push_back(world::isStreamedRegional(p->pyramid().source())
                                 ? std::make_unique<world::WaterIndex>(world::regionalWaterCover(p->pyramid()))
                                 : nullptr);
  }
}

WorldTextures::WorldTextures(world::WorldData data, std::shared_ptr<const raster::TilePyramid> water,
                             gl::TilePoolOptions pool)
    : WorldTextures(std::move(data)) {
  if (water) waterTiles_ = std::make_unique<gl::TilePool>(std::move(water), pool);
  indexRegionalWater();
}

WorldTextures::~WorldTextures() {
  const GLuint t[] = {imagery_, elevation_, water_};
  glDeleteTextures(3, t);
  if (!imageryLayers_.empty()) glDeleteTextures(GLsizei(imageryLayers_.size()), imageryLayers_.data());
}

void WorldTextures::bind() const {
  glBindTextureUnit(0, imagery_);
  glBindTextureUnit(1, elevation_);
  glBindTextureUnit(2, water_);
  for (std::size_t i = 0; i < imageryLayers_.size(); ++i) glBindTextureUnit(GLuint(8 + i), imageryLayers_[i]);
}

}  // namespace geocean::render
