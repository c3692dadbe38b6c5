// The options `render`, `fly` and `view` share — the sea (wave model, wind,
// coast region), its optics and light, the raster layers and the boats —
// registered, checked and applied in one place, so the three commands take
// them alike (issue 13 item 8: view takes what render and fly take).
#pragma once

#include "globe/app/BoatOptions.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/SeaOptions.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace geocean::host {
class PluginOceanLayer;
}
namespace geocean::render {
class GlobeRenderer;
struct FrameSettings;
}  // namespace geocean::render
namespace geocean::world {
struct LayerSource;
}

namespace geocean::app {

// What differs between the three: fly and view draw many frames (the
// mirrored pass may be reused, the coast region may follow the camera);
// view always draws the sea (no --no-ocean).
enum class DrawnCommand { Render, Fly, View };

struct DrawnSceneOptions {
  bool noOcean = false;
  bool noReflections = false, noRefraction = false;
  LightOptions light;
  std::string waves = "noise";
  WindOptions wind;
  double windFromDeg = 270.0;
  int reflectionSize = 0;
  int reflectionEvery = 1;
  std::string grid = "direct";
  std::string coastRegion;  // LAT,LON[,SIZE_M] (CoastOption.h)
  bool coastFollow = false;
  LayerOptions layers;
  BoatOptions boats;
};

void addDrawnSceneOptions(CLI::App& sub, DrawnSceneOptions& o, DrawnCommand which);

// Every check that needs no GL context (so a bad value exits 2 with or
// without a display): the first error naming the option and value, or empty.
// --beaufort is resolved apart (resolveWind), as it prints its own.
std::string checkDrawnScene(const DrawnSceneOptions& o);

// The plugin's ocean on `renderer` (none with --no-ocean), its grid
// projector and coast region. Prints "geocean <command>: ..." and returns
// kExitBadInput on failure, else kExitOk.
int addDrawnOcean(const char* command, const DrawnSceneOptions& o, double windMps, render::GlobeRenderer& renderer,
                  const std::vector<world::LayerSource>& sources, std::shared_ptr<host::PluginOceanLayer>& ocean);

// Reflections, refraction, the map's size and reuse, and the light into a
// frame's settings.
void applyDrawnScene(const DrawnSceneOptions& o, render::FrameSettings& fs);

}  // namespace geocean::app
