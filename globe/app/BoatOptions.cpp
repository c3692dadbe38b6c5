#include "globe/app/BoatOptions.h"

#include "globe/app/Command.h"

#include <cstdio>

namespace geocean::app {

void addBoatOptions(CLI::App& sub, BoatOptions& o) {
  sub.add_option("--boats", o.boats,
                 "N floating boats around the target on water (simulated by the plugin on the drawn sea)");
  sub.add_option("--follow", o.follow, "the camera chases boat I (1..N of --boats)");
}

std::string checkBoatOptions(const BoatOptions& o) {
  if (o.boats < 0 || o.boats > 10000) return "--boats " + std::to_string(o.boats) + " is not in 0..10000";
  if (o.follow < 0 || o.follow > o.boats)
    return "--follow " + std::to_string(o.follow) + " is not a boat of --boats " + std::to_string(o.boats) + " (1.." +
           std::to_string(o.boats) + ")";
  return {};
}

int addBoats(const char* command, const BoatOptions& o, render::GlobeRenderer& renderer,
             std::shared_ptr<host::PluginOceanLayer> ocean, double latDeg, double lonDeg,
             std::shared_ptr<host::PluginBoats>& boats) {
  boats.reset();
  if (const std::string e = checkBoatOptions(o); !e.empty()) {
    std::fprintf(stderr, "geocean %s: %s\n", command, e.c_str());
    return kExitBadInput;
  }
  if (o.boats == 0) return kExitOk;
  if (!ocean) {
    std::fprintf(stderr, "geocean %s: --boats needs the ocean (it cannot go with --no-ocean)\n", command);
    return kExitBadInput;
  }
  std::string err;
  boats = host::PluginBoats::spawn(std::move(ocean), o.boats, latDeg, lonDeg, 1u, err);
  if (!boats) {
    std::fprintf(stderr, "geocean %s: %s\n", command, err.c_str());
    return kExitBadInput;
  }
  if (o.follow > int(boats->count())) {
    std::fprintf(stderr, "geocean %s: --follow %d: only %zu boats found water\n", command, o.follow, boats->count());
    return kExitBadInput;
  }
  renderer.addSceneObject(boats);
  return kExitOk;
}

}  // namespace geocean::app
