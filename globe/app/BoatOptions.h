// --boats N and --follow I for the drawing commands (render, fly, view):
// floating bodies spawned around the target on water, simulated by the
// ocean plugin (ABI 1.4) at its fixed step by simulated time and drawn by
// the host (globe/host/Boats).
#pragma once

#include "globe/host/Boats.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace geocean::app {

struct BoatOptions {
  int boats = 0;   // how many (0: none)
  int follow = 0;  // 1-based boat the camera chases (0: none)
};

void addBoatOptions(CLI::App& sub, BoatOptions& o);

// --boats 0..10000 and --follow 0..boats, before any GL context: the error
// naming the option and value, or empty.
std::string checkBoatOptions(const BoatOptions& o);

// Spawns o.boats around (latDeg, lonDeg) and adds them to the renderer; null
// boats when o.boats is 0. Prints "geocean <command>: ..." and returns
// kExitBadInput on a bad option (a --follow beyond --boats, --boats
// without the ocean), kExitOk otherwise.
int addBoats(const char* command, const BoatOptions& o, render::GlobeRenderer& renderer,
             std::shared_ptr<host::PluginOceanLayer> ocean, double latDeg, double lonDeg,
             std::shared_ptr<host::PluginBoats>& boats);

}  // namespace geocean::app
