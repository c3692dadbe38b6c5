// Where the default world's rasters live. The product reads only the
// project's own data/ (made by geocean-import-world), never ../shared.
#pragma once

#include <string>

namespace geocean::raster {

struct WorldFiles {
  std::string mask;       // land/sea/lake mask, 5 arc-minutes, uint8 (0 ocean, 1 land, 2 lake)
  std::string maskFine;   // the same at 1.25 arc-minutes
  std::string elevation;  // ETOPO relief, 20 arc-minutes, int16 metres (ocean negative)
  std::string imagery;    // Blue Marble, RGB uint8
};

// The data directory: $GEOCEAN_DATA if set, else data/ next to the source
// tree or the installed share/geocean/data, found relative to the executable.
std::string dataDir();
WorldFiles defaultWorld();

}  // namespace geocean::raster
