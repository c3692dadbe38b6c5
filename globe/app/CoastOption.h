// `--coast-region LAT,LON[,SIZE_M]` of the drawing commands (issue 15): the
// near-shore region of a Gerstner sea, set on the plugin's ocean through
// the C ABI (geocean_set_coast_region, since 1.5), as `geocean query
// --coast-region` sets it on the façade.
#pragma once

#include "globe/host/OceanLayer.h"

#include <CLI/CLI.hpp>

#include <string>

namespace geocean::app {

// Adds the option; `spec` stays empty without it.
void addCoastOption(CLI::App& sub, std::string& spec);

// Sets the region on `ocean` when spec is non-empty (ocean may be null only
// then: --no-ocean with --coast-region is bad input). A failure is printed
// as "geocean <command>: ..." naming the option and value; returns the exit
// code (kExitOk, kExitBadInput).
int applyCoastRegion(const char* command, const std::string& spec, const host::PluginOceanLayer* ocean);

}  // namespace geocean::app
