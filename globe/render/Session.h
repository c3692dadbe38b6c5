// A headless rendering session: EGL context, the default world on the GPU,
// the globe renderer and an offscreen target. Shared by `geocean render`,
// `geocean fly` and the GL tests.
#pragma once

#include "globe/gl/HeadlessContext.h"
#include "globe/gl/Framebuffer.h"
#include "globe/render/GlobeRenderer.h"

#include <memory>

namespace geocean::render {

struct Session {
  std::unique_ptr<gl::HeadlessContext> context;
  std::shared_ptr<WorldTextures> world;
  std::unique_ptr<GlobeRenderer> renderer;
  std::unique_ptr<gl::Framebuffer> target;

  // Throws std::runtime_error (no GL context) or raster::RasterError (data).
  // Takes the data (WorldTextures): move it in when done with it.
  static Session headless(world::WorldData data, int width, int height, TerrainOptions terrain = {});
  FrameTimes render(const camera::ViewPose& pose, const FrameSettings& settings);
  // The frame, opaque: its alpha is not the picture's (the sea's coverage
  // blend leaves a^2 + (1 - a) at the horizon), and PNG writers take RGBA as
  // premultiplied, dividing such pixels towards white (the quick-start
  // flight's white line along the horizon). Blending alpha "over" instead
  // cost the sea's draws ~10-25 ms a frame on llvmpipe (docs/PERFORMANCE.md).
  gl::Image image() const {
    gl::Image img = target->readColor();
    for (std::size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
    return img;
  }
};

// Default sun: `elevationDeg` above the horizon at the camera's nadir, from `azimuthDeg`.
glm::dvec3 sunForView(const camera::ViewPose& pose, double azimuthDeg = 135.0, double elevationDeg = 55.0);

}  // namespace geocean::render
