#include "globe/app/SeaOptions.h"

#include "globe/app/Command.h"
#include "globe/render/CliParse.h"
#include "globe/render/GlobeRenderer.h"
#include "plugin/ocean/Ocean.h"  // waves::SeaState through the façade

#include <cmath>
#include <cstdio>

namespace geocean::app {

void addWindOptions(CLI::App& sub, WindOptions& w) {
  w.wind = sub.add_option("--wind", w.windMps, "wind speed, m/s at 19.5 m (default 10)");
  sub.add_option("--beaufort", w.beaufort, "wind as a Beaufort number 0..12 (instead of --wind)");
}

int resolveWind(const char* command, const WindOptions& w, double& windMps) {
  windMps = w.windMps;
  if (w.beaufort.empty()) return kExitOk;
  auto bad = [&](const std::string& m) {
    std::fprintf(stderr, "geocean %s: %s\n", command, m.c_str());
    return kExitBadInput;
  };
  if (w.wind && w.wind->count() > 0) return bad("give either --wind or --beaufort, not both");
  double b = 0.0;
  try {
    b = render::parseNumbers(w.beaufort, 1, "--beaufort")[0];
  } catch (const render::ArgError& e) {
    return bad(e.what());
  }
  const auto sea = b == std::floor(b) && std::abs(b) <= 12.0 ? waves::SeaState::fromBeaufort(int(b)) : std::nullopt;
  if (!sea) return bad("--beaufort " + w.beaufort + " is not a Beaufort number 0..12");
  windMps = sea->windSpeedMps;
  return kExitOk;
}

void addReflectionSizeOption(CLI::App& sub, int& size) {
  sub.add_option("--reflection-size", size,
                 "N: the longer side of the mirrored pass's map in pixels, 16..8192 (paper 001: 512, 1024, "
                 "2048); default: the viewport's size");
}

void addReflectionEveryOption(CLI::App& sub, int& every) {
  sub.add_option("--reflection-every", every,
                 "M: the mirrored pass runs every M-th frame and the others reuse its map (paper 001), 1..1000; "
                 "default 1");
}

void addGridOption(CLI::App& sub, std::string& grid) {
  sub.add_option("--grid", grid,
                 "ocean grid projector: direct (default: each vertex's ray meets the ellipsoid) or ispg (paper "
                 "000's projected grid, for comparison)")
      ->check(CLI::IsMember({"direct", "ispg"}));
}

void addLightOptions(CLI::App& sub, LightOptions& o) {
  sub.add_flag("--no-shadows", o.noShadows, "no sun shadows of terrain and boats on the water");
  sub.add_option("--shadow-model", o.shadowModel,
                 "the water in shadow: physical (default: the sun's direct light removed, the sky's kept) or "
                 "paper (paper 001: the pixel darkened by 0.5)")
      ->check(CLI::IsMember({"physical", "paper"}));
  sub.add_option("--sun-model", o.sunModel,
                 "the sun's specular on the water: microfacet (default: Cox-Munk glitter) or phong (paper 001 "
                 "eq. 19)")
      ->check(CLI::IsMember({"microfacet", "phong"}));
}

void applyLightOptions(const LightOptions& o, render::FrameSettings& fs) {
  fs.shadows = !o.noShadows;
  fs.shadowModel = o.shadowModel == "paper" ? render::ShadowModel::Paper : render::ShadowModel::Physical;
  fs.sunModel = o.sunModel == "phong" ? render::SunModel::Phong : render::SunModel::Microfacet;
}

}  // namespace geocean::app
