// Boats for the drawing commands (`render`, `fly`, `view --boats N`):
// floating bodies simulated by the ocean plugin through its C ABI (1.4,
// geocean_bodies_*), on the very sea the plugin draws, drawn by the host's
// BoatRenderer at the poses the ABI gives, as a SceneObject of the globe
// renderer (so the mirrored reflection pass draws them too). The host
// never links plugin code.
#pragma once

#include "globe/camera/Camera.h"
#include "globe/host/OceanLayer.h"
#include "globe/render/Boats.h"
#include "globe/render/SceneObject.h"

#include <memory>
#include <string>
#include <vector>

namespace geocean::host {

class PluginBoats : public render::SceneObject {
 public:
  // n boats (lengths 12..30 m, headings and engines from `seed`) on the
  // water within a disc around (latDeg, lonDeg) whose radius grows with
  // sqrt(n) (a sunflower pattern, about 110 m apart); points on land are
  // skipped. Needs the GL context current (the meshes) and a plugin of
  // ABI >= 1.4. On failure returns null and sets `error`.
  static std::shared_ptr<PluginBoats> spawn(std::shared_ptr<PluginOceanLayer> ocean, int n, double latDeg,
                                            double lonDeg, std::uint32_t seed, std::string& error);
  ~PluginBoats() override;
  PluginBoats(const PluginBoats&) = delete;
  PluginBoats& operator=(const PluginBoats&) = delete;

  // Steps the simulation to timeS (the fixed step of the ABI: the same
  // poses at a time whatever frames led there) and takes the interpolated
  // poses for drawing. Throws std::runtime_error with the plugin's message.
  void update(double timeS) override;
  void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
            const camera::Camera* mirroredFrom) override;
  void drawDepth(const glm::mat4& viewProj, const glm::dvec3& originEcef) override {
    renderer_->drawDepth(viewProj, originEcef);
  }

  std::size_t count() const { return poses_.size(); }
  // The poses of the last update (interpolated), in spawn order.
  const std::vector<geocean_body_pose>& poses() const { return poses_; }
  double lengthM(std::size_t i) const { return lengths_[i]; }
  geocean_bodies* bodies() const { return bodies_; }

  // A camera chasing boat i (0-based): 3 lengths behind its bow direction
  // and 1.2 lengths up, looking at it; fov and size from `base`.
  camera::ViewPose chase(std::size_t i, const camera::ViewPose& base) const;

 private:
  PluginBoats() = default;
  std::shared_ptr<PluginOceanLayer> ocean_;  // outlives bodies_ (the ABI's rule)
  geocean_bodies* bodies_ = nullptr;
  std::unique_ptr<render::BoatRenderer> renderer_;
  std::vector<double> lengths_;
  std::vector<glm::vec3> colors_;
  std::vector<int> meshes_;
  std::vector<geocean_body_pose> poses_;
};

// The point a pose looks at on the ellipsoid (its nadir if the view misses
// the Earth), where --boats are spawned.
void viewTarget(const camera::ViewPose& pose, double& latDeg, double& lonDeg);

}  // namespace geocean::host
