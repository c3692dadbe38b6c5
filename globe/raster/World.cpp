#include "globe/raster/World.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#ifndef GEOCEAN_DATA_DIR
#define GEOCEAN_DATA_DIR ""
#endif

namespace geocean::raster {

std::string dataDir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("GEOCEAN_DATA"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    // build/geocean -> ../data; <prefix>/bin/geocean -> <prefix>/share/geocean/data
    for (const fs::path& c : {exe.parent_path().parent_path() / "data",
                              exe.parent_path().parent_path() / "share" / "geocean" / "data",
                              exe.parent_path().parent_path().parent_path() / "data"})
      if (fs::exists(c / "landmask_5m.tif", ec)) return c.string();
  }
  return GEOCEAN_DATA_DIR;
}

WorldFiles defaultWorld() {
  const std::string d = dataDir();
  return {d + "/landmask_5m.tif", d + "/landmask_1.25m.tif", d + "/etopo_20m.tif", d + "/bluemarble.tif"};
}

}  // namespace geocean::raster
