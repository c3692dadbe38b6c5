#include "globe/app/CoastOption.h"

#include "globe/app/Command.h"
#include "globe/app/QueryIo.h"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace geocean::app {

void addCoastOption(CLI::App& sub, std::string& spec) {
  sub.add_option("--coast-region", spec,
                 "LAT,LON[,SIZE_M]: near-shore region (default 10000 m square, 500 .. 40000) where gerstner "
                 "waves take the local depth's wavelength and refract (needs --waves gerstner)");
}

int applyCoastRegion(const char* command, const std::string& spec, const host::PluginOceanLayer* ocean) {
  if (spec.empty()) return kExitOk;
  auto bad = [&](const std::string& m) {
    std::fprintf(stderr, "geocean %s: %s\n", command, m.c_str());
    return kExitBadInput;
  };
  if (!ocean) return bad("--coast-region needs the ocean (not --no-ocean)");
  const std::size_t parts = std::size_t(std::count(spec.begin(), spec.end(), ',')) + 1;
  if (parts != 2 && parts != 3) return bad("--coast-region '" + spec + "' is not LAT,LON[,SIZE_M]");
  std::vector<double> v;
  if (auto e = parseNumberList(spec, parts, "--coast-region", v); !e.empty()) return bad(e);
  if (auto e = checkLatLon(v[0], v[1], "--coast-region"); !e.empty()) return bad(e);
  const auto& api = ocean->plugin().api();
  if (!api.setCoastRegion) return bad("--coast-region needs an ocean plugin of ABI 1.5 or later");
  if (api.setCoastRegion(ocean->ocean(), v[0], v[1], parts == 3 ? v[2] : 10000.0) != GEOCEAN_OK)
    return bad("--coast-region '" + spec + "': " + api.lastError());
  return kExitOk;
}

}  // namespace geocean::app
