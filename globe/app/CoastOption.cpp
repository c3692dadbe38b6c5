#include "globe/app/CoastOption.h"

#include "globe/app/Command.h"
#include "globe/app/QueryIo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace geocean::app {

const CLI::Validator nonEmpty(
    [](std::string& v) { return v.empty() ? std::string("the value is empty") : std::string(); }, "NONEMPTY");

void addCoastOption(CLI::App& sub, std::string& spec, bool* follow) {
  sub.add_option("--coast-region", spec,
                 "LAT,LON[,SIZE_M]: near-shore region (default 10000 m square, 500 .. 40000) where gerstner "
                 "waves take the local depth's wavelength and refract (needs --waves gerstner)")
      ->check(nonEmpty);
  if (follow)
    sub.add_flag("--coast-follow", *follow,
                 "the --coast-region follows the camera: rebuilt around its nadir (on a worker thread) when the "
                 "nadir leaves the region's middle half");
}

namespace {
std::string g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}
}  // namespace

std::string checkDrawnSea(const std::string& waves, double windMps, double windFromDeg) {
  if (waves != "noise" && waves != "noise-paper" && waves != "gerstner" && waves != "fft")
    return "--waves '" + waves + "' is not a GPU wave model (noise, noise-paper, gerstner, fft)";
  if (!(windMps >= 0.2 && windMps <= 60.0)) return "--wind " + g(windMps) + " m/s is outside 0.2 .. 60 m/s";
  if (!std::isfinite(windFromDeg)) return "--wind-dir " + g(windFromDeg) + " is not a finite angle";
  return {};
}

std::string checkCoastRegion(const std::string& spec) {
  const std::size_t parts = std::size_t(std::count(spec.begin(), spec.end(), ',')) + 1;
  if (parts != 2 && parts != 3) return "--coast-region '" + spec + "' is not LAT,LON[,SIZE_M]";
  std::vector<double> v;
  if (auto e = parseNumberList(spec, parts, "--coast-region", v); !e.empty()) return e;
  if (auto e = checkLatLon(v[0], v[1], "--coast-region"); !e.empty()) return e;
  if (parts == 3 && !(v[2] >= 500.0 && v[2] <= 40000.0))
    return "--coast-region '" + spec + "': size " + g(v[2]) + " m is outside 500 .. 40000 m";
  return {};
}

std::string checkCoastFollow(bool follow, const std::string& spec) {
  return follow && spec.empty() ? "--coast-follow needs --coast-region LAT,LON[,SIZE_M] (where to start)" : "";
}

int applyCoastRegion(const char* command, const std::string& spec, host::PluginOceanLayer* ocean, bool follow) {
  auto bad = [&](const std::string& m) {
    std::fprintf(stderr, "geocean %s: %s\n", command, m.c_str());
    return kExitBadInput;
  };
  if (auto e = checkCoastFollow(follow, spec); !e.empty()) return bad(e);
  if (spec.empty()) return kExitOk;
  if (!ocean) return bad("--coast-region needs the ocean (not --no-ocean)");
  if (auto e = checkCoastRegion(spec); !e.empty()) return bad(e);
  std::vector<double> v;
  const std::size_t parts = std::size_t(std::count(spec.begin(), spec.end(), ',')) + 1;
  parseNumberList(spec, parts, "--coast-region", v);  // checked above
  const auto& api = ocean->plugin().api();
  if (!api.setCoastRegion) return bad("--coast-region needs an ocean plugin of ABI 1.5 or later");
  if (api.setCoastRegion(ocean->ocean(), v[0], v[1], parts == 3 ? v[2] : 10000.0) != GEOCEAN_OK)
    return bad("--coast-region '" + spec + "': " + api.lastError());
  if (follow && (ocean->plugin().pluginAbiVersion() & 0xffffu) < 7)
    return bad("--coast-follow needs an ocean plugin of ABI 1.7 or later");
  ocean->setFollowCoast(follow);
  return kExitOk;
}

}  // namespace geocean::app
