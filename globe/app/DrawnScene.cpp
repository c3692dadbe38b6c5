#include "globe/app/DrawnScene.h"

#include "globe/app/CoastOption.h"
#include "globe/app/Command.h"
#include "globe/host/OceanLayer.h"
#include "globe/render/CliParse.h"
#include "globe/render/GlobeRenderer.h"

#include <cstdio>

namespace geocean::app {

void addDrawnSceneOptions(CLI::App& sub, DrawnSceneOptions& o, DrawnCommand which) {
  const bool frames = which != DrawnCommand::Render;
  if (which != DrawnCommand::View) sub.add_flag("--no-ocean", o.noOcean, "terrain and distant-sea shading only");
  sub.add_flag("--no-reflections", o.noReflections,
               "no planar reflection of sky and terrain in the sea (the sky BRDF alone)");
  sub.add_flag("--no-refraction", o.noRefraction, "no bottom seen through the water (the depth tint alone)");
  sub.add_option("--waves", o.waves, "wave model: noise (default), noise-paper (paper 002, with its seam), gerstner, fft");
  addWindOptions(sub, o.wind);
  addReflectionSizeOption(sub, o.reflectionSize);
  addLightOptions(sub, o.light);
  if (frames) addReflectionEveryOption(sub, o.reflectionEvery);
  addGridOption(sub, o.grid);
  sub.add_option("--wind-dir", o.windFromDeg, "direction the wind blows from, degrees (default 270)");
  addCoastOption(sub, o.coastRegion, frames ? &o.coastFollow : nullptr);
  addLayerOptions(sub, o.layers);
  addImageryOption(sub, o.layers);
  addBoatOptions(sub, o.boats);
}

std::string checkDrawnScene(const DrawnSceneOptions& o) {
  try {
    render::checkReflectionSize(o.reflectionSize);
    render::checkReflectionEvery(o.reflectionEvery);
  } catch (const render::ArgError& e) {
    return e.what();
  }
  for (std::string e : {checkDrawnSea(o.waves, o.wind.windMps, o.windFromDeg),
                        o.coastRegion.empty() ? std::string() : checkCoastRegion(o.coastRegion),
                        checkCoastFollow(o.coastFollow, o.coastRegion), checkBoatOptions(o.boats)})
    if (!e.empty()) return e;
  return {};
}

int addDrawnOcean(const char* command, const DrawnSceneOptions& o, double windMps, render::GlobeRenderer& renderer,
                  const std::vector<world::LayerSource>& sources, std::shared_ptr<host::PluginOceanLayer>& ocean) {
  if (!o.noOcean) {
    const std::string err = host::addPluginOcean(renderer, o.waves, windMps, o.windFromDeg, &ocean, sources,
                                                 !o.layers.noDefaultWorld);
    if (!err.empty()) {
      std::fprintf(stderr, "geocean %s: %s\n", command, err.c_str());
      return kExitBadInput;
    }
  }
  if (ocean) ocean->setGridIspg(o.grid == "ispg");
  return applyCoastRegion(command, o.coastRegion, ocean.get(), o.coastFollow);
}

void applyDrawnScene(const DrawnSceneOptions& o, render::FrameSettings& fs) {
  fs.reflections = !o.noReflections;
  fs.refraction = !o.noRefraction;
  fs.reflectionSize = o.reflectionSize;
  fs.reflectionEvery = o.reflectionEvery;
  applyLightOptions(o.light, fs);
}

}  // namespace geocean::app
