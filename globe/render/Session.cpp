#include "globe/render/Session.h"

#include "globe/gl/GlDebug.h"

#include <stdexcept>
#include <utility>

namespace geocean::render {

Session Session::headless(world::WorldData data, int width, int height, TerrainOptions terrain) {
  Session s;
  std::string err;
  s.context = gl::HeadlessContext::create(err, gl::glDebugWanted());
  if (!s.context) throw std::runtime_error("no headless OpenGL 4.5 context: " + err);
  gl::enableGlDebug();
  s.world = std::make_shared<WorldTextures>(std::move(data));
  s.renderer = std::make_unique<GlobeRenderer>(s.world, terrain);
  s.target = std::make_unique<gl::Framebuffer>(width, height);
  return s;
}

FrameTimes Session::render(const camera::ViewPose& pose, const FrameSettings& settings) {
  if (pose.width != target->width() || pose.height != target->height())
    target = std::make_unique<gl::Framebuffer>(pose.width, pose.height);
  target->bind();
  return renderer->render(pose, settings);
}

glm::dvec3 sunForView(const camera::ViewPose& pose, double azimuthDeg, double elevationDeg) {
  return sunFromLocal(pose.latDeg, pose.lonDeg, azimuthDeg, elevationDeg);
}

}  // namespace geocean::render
