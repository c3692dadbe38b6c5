// The user's rasters as layers (issue 12), the same options for every
// command: repeatable --mask FILE and --elevation FILE over the bundled
// world, --no-default-world to remove it.
#pragma once

#include "globe/raster/Raster.h"
#include "globe/world/LayerStack.h"
#include "plugin/ocean/Ocean.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace geocean::app {

struct LayerOptions {
  std::vector<std::string> masks, elevations;
  std::vector<std::string> imagery;  // drawing commands only (addImageryOption)
  std::string maskEncoding;  // the --mask files' (without --mask: the default world's mask)
  bool noDefaultWorld = false;
  bool noElevation = false;  // pick --no-terrain: no elevation at all
};

// --mask, --elevation (repeatable), --no-default-world; --mask-encoding
// when withEncoding.
void addLayerOptions(CLI::App& sub, LayerOptions& o, bool withEncoding = true);

// --imagery FILE (repeatable) for the drawing commands (view, render, fly):
// RGB or RGBA 8-bit rasters drawn over the default Blue Marble, the finest
// (of equal priority) on top, the layer below where one has no data.
void addImageryOption(CLI::App& sub, LayerOptions& o);

// The bundled world (unless --no-default-world) as the base, each --mask
// and --elevation as a layer of priority 0 over it (the finer answers
// first). Throws raster::RasterError naming the file, std::invalid_argument
// for a bad encoding or --no-default-world without any raster.
void applyLayers(ocean::Ocean& ocean, const LayerOptions& o, const raster::OpenOptions& ro);

// The same layers by file, in applyLayers' order (masks, then elevations),
// for the drawing commands: the host's world (world::loadLayeredWorld) and
// the ocean plugin (host::addPluginOcean) build the same stack from them.
// Throws std::invalid_argument for --no-default-world without any raster.
std::vector<world::LayerSource> layerSources(const LayerOptions& o);

// The drawing commands' start: layerSources (for the ocean: no imagery) and
// the host's world built from them and the --imagery layers. A failure is printed as "geocean <command>: ..."; returns the exit
// code (kExitOk, kExitBadInput, kExitDataError).
int loadDrawnWorld(const char* command, const LayerOptions& o, std::vector<world::LayerSource>& sources,
                   world::WorldData& data);

// The viewer panel's layer list (gl::PanelState::layerNames): one label per
// --mask, --elevation and --imagery file, in that order ("mask  name.tif").
std::vector<std::string> layerLabels(const LayerOptions& o);
// The same options with only the layers whose `shown` entry (in
// layerLabels' order) is non-zero; missing entries count as shown.
LayerOptions shownLayers(const LayerOptions& o, const std::vector<char>& shown);

}  // namespace geocean::app
