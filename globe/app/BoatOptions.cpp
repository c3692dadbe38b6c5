#include "globe/app/BoatOptions.h"

#include "globe/app/Command.h"

#include <cstdio>

namespace geocean::app {

void addBoatOptions(CLI::App& sub, BoatOptions& o) {
  sub.add_option("--boats", o.boats,
                 "N floating boats around the target on water (simulated by the plugin on the drawn sea)");
  sub.add_option("--follow", o.follow, "the camera chases boat I (1..N of --boats)");
}

int addBoats(const char* command, const BoatOptions& o, render::GlobeRenderer& renderer,
             std::shared_ptr<host::PluginOceanLayer> ocean, double latDeg, double lonDeg,
             std::shared_ptr<host::PluginBoats>& boats) {
  boats.reset();
  if (o.boats < 0 || o.boats > 10000) {
    std::fprintf(stderr, "geocean %s: --boats %d is not in 0..10000\n", command, o.boats);
    return kExitBadInput;
  }
  if (o.follow < 0 || o.follow > o.boats) {
    std::fprintf(stderr, "geocean %s: --follow %d is not a boat of --boats %d (1..%d)\n", command, o.follow,
                 o.boats, o.boats);
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
