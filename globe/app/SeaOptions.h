// The sea-state and optics options the drawing commands (render, fly, view)
// share: `--wind M_PER_S | --beaufort N` as `geocean query` takes them, and
// `--reflection-size N` (issue 13 items 7-8).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

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

}  // namespace geocean::app
