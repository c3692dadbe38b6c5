// What the C-ABI tests share: the built plugin, loaded once per test
// program through the host's run-time loader (globe/host) as an engine
// loads it, and an ocean handle destroyed at scope exit.
#pragma once

#include "globe/host/OceanPlugin.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace geocean::capitest {

inline const host::OceanPlugin& plugin() {
  static std::unique_ptr<host::OceanPlugin> p = [] {
    std::string error;
    auto loaded = host::OceanPlugin::load(GEOCEAN_PLUGIN_BUILD_PATH, error);
    if (!loaded) ADD_FAILURE() << error;
    return loaded;
  }();
  return *p;
}
inline const host::OceanApi& api() { return plugin().api(); }
inline std::string lastError() { return api().lastError(); }

struct OceanHandle {
  geocean_ocean* h = nullptr;
  OceanHandle() { EXPECT_EQ(api().create(GEOCEAN_ABI_VERSION, &h), GEOCEAN_OK); }
  ~OceanHandle() { api().destroy(h); }
  OceanHandle(const OceanHandle&) = delete;
  OceanHandle& operator=(const OceanHandle&) = delete;
};

}  // namespace geocean::capitest
