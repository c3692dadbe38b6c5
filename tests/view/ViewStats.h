// The CSV that `geocean view --stats` writes, one row per frame; shared by
// the window tests and the memory test.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace geocean::test {

struct StatsRow {
  int frame = 0;
  double latDeg = 0, lonDeg = 0, altM = 0, seaM = 0, fps = 0;
  long rssKb = 0, heapInUseKb = 0, heapHeldKb = 0;
  int tiles = 0;
  long tilesBuilt = 0;
};

// Checks the header; a malformed row is a test failure (and is skipped).
inline std::vector<StatsRow> readStats(const std::string& path) {
  std::vector<StatsRow> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "frame,wall_s,lat,lon,alt_m,sea_height_m,fps,rss_kb,heap_in_use_kb,heap_held_kb,tiles,tiles_built");
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    if (f.size() != 12) {
      ADD_FAILURE() << "bad stats row in " << path << ": " << line;
      continue;
    }
    rows.push_back({std::stoi(f[0]), std::stod(f[2]), std::stod(f[3]), std::stod(f[4]), std::stod(f[5]),
                    std::stod(f[6]), std::stol(f[7]), std::stol(f[8]), std::stol(f[9]), std::stoi(f[10]),
                    std::stol(f[11])});
  }
  return rows;
}

}  // namespace geocean::test
