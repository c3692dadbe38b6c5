// The ocean as a layer of Geocean's globe renderer, drawn by the plugin
// through its C ABI (geocean_update + geocean_draw in the renderer's
// context). The viewer thereby hosts the ocean exactly as another engine
// would: the plugin is dlopened, nothing of it is linked.
#pragma once

#include "globe/host/OceanPlugin.h"
#include "globe/render/GlobeRenderer.h"
#include "globe/render/Layer.h"
#include "globe/world/LayerStack.h"

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
  // The plugin's answers (geocean_get_layer_info, geocean_covers_opaquely;
  // a plugin older than 1.2 claims nothing). Throw std::runtime_error with
  // the plugin's message if a call fails, as does draw.
  render::LayerInfo info() const override;
  bool coversOpaquely(double lat0Deg, double lat1Deg, double lon0Deg, double lon1Deg,
                      double pixelFootprintM) const override;
  void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
            const render::LayerInputs& inputs) override;

  geocean_ocean* ocean() const { return ocean_; }
  // Single pictures (geocean render): the ocean waits for the streamed
  // tiles each draw asks for (GEOCEAN_DRAW_COMPLETE_TILES), as the
  // terrain's TerrainOptions::waitForTiles.
  void setCompleteTiles(bool on) { completeTiles_ = on; }
  // --grid ispg: the plugin's grid from paper 000's ISPG (GEOCEAN_DRAW_GRID_ISPG).
  void setGridIspg(bool on) { gridIspg_ = on; }
  // The coast region follows the camera (GEOCEAN_DRAW_FOLLOW_COAST, ABI 1.7).
  void setFollowCoast(bool on) { followCoast_ = on; }
  const OceanPlugin& plugin() const { return *plugin_; }

 private:
  std::shared_ptr<const OceanPlugin> plugin_;
  geocean_ocean* ocean_;
  render::LayerInfo info_;  // asked once: it does not change with the ocean's state
  bool completeTiles_ = false;
  bool gridIspg_ = false;
  bool followCoast_ = false;
};

// The host view for a camera: the same numbers the renderer draws its
// terrain with (the camera's double-precision projection).
geocean_view hostView(const geocean_view& defaults, const camera::Camera& cam, const camera::Lighting& light);

// Loads the plugin (OceanPlugin::loadForExecutable), gives an ocean the
// default world (unless !defaultWorld), the raster layers over it (ABI 1.3,
// in this order: the host's world::openLayerStack builds the same stack)
// and the sea state (model by CLI name, wind) and adds it to the renderer.
// Returns an error message naming the option, the file or the plugin
// problem (empty on success).
std::string addPluginOcean(render::GlobeRenderer& renderer, const std::string& modelName, double windMps,
                           double windFromDeg, std::shared_ptr<PluginOceanLayer>* created = nullptr,
                           const std::vector<world::LayerSource>& layers = {}, bool defaultWorld = true);
// A new sea state for a running ocean (the viewer's panel): the model by CLI
// name and the wind, as addPluginOcean takes them. Returns the error (empty
// on success).
std::string setPluginSeaState(PluginOceanLayer& ocean, const std::string& modelName, double windMps,
                              double windFromDeg);

// Replaces a running ocean's raster layers (the viewer's panel hides and
// shows them): every layer removed, then `layers` added as addPluginOcean
// adds them; the base (default world) stays. Returns the error (empty on
// success); on error the ocean may hold some of the new layers.
std::string setPluginLayers(PluginOceanLayer& ocean, const std::vector<world::LayerSource>& layers);

}  // namespace geocean::host
