// The sea-state and optics options the drawing commands (render, fly, view)
// share: `--wind M_PER_S | --beaufort N` as `geocean query` takes them, and
// `--reflection-size N` (issue 13 items 7-8).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace geocean::render {
struct FrameSettings;
}

namespace geocean::app {

struct WindOptions {
  double windMps = 10.0;
  std::string beaufort;  // empty: --wind (or its default) decides
  CLI::Option* wind = nullptr;
};

// Adds --wind (default windMps) and --beaufort.
void addWindOptions(CLI::App& sub, WindOptions& w);

// The wind speed the options ask for: --beaufort's is the middle of the WMO
// class at 10 m converted to 19.5 m (waves::SeaState::fromBeaufort, as the
// query and the C ABI take it). Prints "geocean <command>: ..." naming the
// option and value and returns kExitBadInput for a bad value or both
// options; else kExitOk.
int resolveWind(const char* command, const WindOptions& w, double& windMps);

// Adds --reflection-size (0, the default: the viewport's size).
void addReflectionSizeOption(CLI::App& sub, int& size);
// Adds --reflection-every (1, the default: every frame) for flights and views.
void addReflectionEveryOption(CLI::App& sub, int& every);

// Adds --grid direct|ispg: the ocean's screen grid projector (issue 13
// item 8: paper 000's ISPG drawable beside the default, for comparison).
void addGridOption(CLI::App& sub, std::string& grid);

// The sun's light on the water (issue 13 item 6): --no-shadows,
// --shadow-model physical|paper, --sun-model microfacet|phong.
struct LightOptions {
  bool noShadows = false;
  std::string shadowModel = "physical";
  std::string sunModel = "microfacet";
};
void addLightOptions(CLI::App& sub, LightOptions& o);
// Into a frame's settings (the values are checked by the options).
void applyLightOptions(const LightOptions& o, render::FrameSettings& fs);

}  // namespace geocean::app
