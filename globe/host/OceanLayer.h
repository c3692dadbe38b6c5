// The ocean as a layer of Geocean's globe renderer, drawn by the plugin
// through its C ABI (geocean_update + geocean_draw in the renderer's
// context). The viewer thereby hosts the ocean exactly as another engine
// would: the plugin is dlopened, nothing of it is linked.
#pragma once

#include "globe/host/OceanPlugin.h"
#include "globe/render/GlobeRenderer.h"

#include <memory>
#include <string>

namespace geocean::host {

class PluginOceanLayer : public render::Layer {
 public:
  // Takes an ocean already given its rasters and sea state. Destroys it
  // (releasing its GL objects: call with the renderer's context current).
  PluginOceanLayer(std::shared_ptr<const OceanPlugin> plugin, geocean_ocean* ocean);
  ~PluginOceanLayer() override;
  PluginOceanLayer(const PluginOceanLayer&) = delete;
  PluginOceanLayer& operator=(const PluginOceanLayer&) = delete;

  const char* name() const override { return "ocean"; }
  // Throws std::runtime_error with the plugin's message if a call fails.
  void draw(const render::ViewMatrices& vm, const render::ViewPose& pose, const render::Lighting& light,
            bool bare) override;

  geocean_ocean* ocean() const { return ocean_; }
  const OceanPlugin& plugin() const { return *plugin_; }

 private:
  std::shared_ptr<const OceanPlugin> plugin_;
  geocean_ocean* ocean_;
};

// The host view for the renderer's matrices: the same numbers the renderer
// draws its terrain with (projection rebuilt in double from the pose).
geocean_view hostView(const geocean_view& defaults, const render::ViewMatrices& vm, const render::ViewPose& pose,
                      const render::Lighting& light);

// Loads the plugin (OceanPlugin::loadForExecutable), gives an ocean the
// default world and the sea state (model by CLI name, wind) and adds it to
// the renderer. Returns an error message naming the option or the plugin
// problem (empty on success).
std::string addPluginOcean(render::GlobeRenderer& renderer, const std::string& modelName, double windMps,
                           double windFromDeg, std::shared_ptr<PluginOceanLayer>* created = nullptr);

}  // namespace geocean::host
