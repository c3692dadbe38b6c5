// libFuzzer: any bytes as a `geocean pick --rays` file, split into rows the
// way cmd_pick.cpp does (std::getline, CR stripped, blank rows skipped, a
// header only on row 1) and parsed by globe/app/QueryIo's parseRayRow.
// Checked beyond "no crash, no UB": an accepted ray has six finite numbers
// and a direction of non-zero length, and its %.17g text parses back to the
// same doubles; a refused row's message starts with what names its row.
#include "globe/app/QueryIo.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

using namespace geocean::app;

namespace {
[[noreturn]] void failure(const char* what, const std::string& line, const std::string& detail) {
  std::fprintf(stderr, "fuzz_rays_csv: %s\n  row: '%s'\n  %s\n", what, line.c_str(), detail.c_str());
  std::abort();
}
bool same(const RayRow& a, const RayRow& b) {
  for (int i = 0; i < 3; ++i)
    if (a.origin[i] != b.origin[i] || a.direction[i] != b.direction[i]) return false;
  return true;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string line;
  long row = 0;
  while (std::getline(in, line)) {
    ++row;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (row == 1 && isRayHeaderRow(line)) continue;
    const std::string what = "--rays fuzz.csv row " + std::to_string(row);
    RayRow r;
    const std::string e = parseRayRow(line, what, r);
    if (!e.empty()) {
      if (e.compare(0, what.size() + 1, what + ":") != 0) failure("error does not name the row", line, e);
      break;  // the CLI stops at the first bad row
    }
    double len2 = 0;
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(r.origin[i]) || !std::isfinite(r.direction[i])) failure("accepted a value that is not finite", line, "");
      len2 += r.direction[i] * r.direction[i];
    }
    if (!(std::sqrt(len2) > 0.0)) failure("accepted a zero direction", line, "");
    char b[200];
    std::snprintf(b, sizeof b, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", r.origin[0], r.origin[1], r.origin[2],
                  r.direction[0], r.direction[1], r.direction[2]);
    RayRow q;
    if (const std::string e2 = parseRayRow(b, what, q); !e2.empty()) failure("its own output is refused", line, e2);
    if (!same(r, q)) failure("round trip changed the values", line, b);
  }
  return 0;
}
