// `--coast-region LAT,LON[,SIZE_M]` of the drawing commands (issue 15): the
// near-shore region of a Gerstner sea, set on the plugin's ocean through
// the C ABI (geocean_set_coast_region, since 1.5), as `geocean query
// --coast-region` sets it on the façade.
#pragma once

#include "globe/host/OceanLayer.h"

#include <CLI/CLI.hpp>

#include <string>

namespace geocean::app {

// A CLI11 check for options whose empty value would read as "not given"
// (`--coast-region ''`, `view --fly-to ''`): exit 2 naming the option.
extern const CLI::Validator nonEmpty;

// Adds the option; `spec` stays empty without it (given empty: bad input).
// With `follow`, also `--coast-follow` (the region follows the camera).
void addCoastOption(CLI::App& sub, std::string& spec, bool* follow = nullptr);

// The drawing commands' sea options checked before any window or GL
// context (so a bad one exits 2 with or without a display): `--waves` one of
// the GPU models, `--wind` 0.2 .. 60 m/s and a finite `--wind-dir` (the
// plugin's ranges, geocean_set_sea_state), and `--coast-region` as below.
// Each returns the error naming the option and the value, or empty.
std::string checkDrawnSea(const std::string& waves, double windMps, double windFromDeg);
// LAT,LON[,SIZE_M] with SIZE_M 500 .. 40000 m (geocean_set_coast_region's range).
std::string checkCoastRegion(const std::string& spec);
// --coast-follow needs a --coast-region (where the region starts).
std::string checkCoastFollow(bool follow, const std::string& spec);

// Sets the region on `ocean` when spec is non-empty (ocean may be null only
// then: --no-ocean with --coast-region is bad input). A failure is printed
// as "geocean <command>: ..." naming the option and value; returns the exit
// code (kExitOk, kExitBadInput). `follow` (--coast-follow, needs the
// region): each draw re-centres it on the camera (GEOCEAN_DRAW_FOLLOW_COAST).
int applyCoastRegion(const char* command, const std::string& spec, host::PluginOceanLayer* ocean,
                     bool follow = false);

}  // namespace geocean::app
