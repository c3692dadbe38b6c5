// libFuzzer: any bytes as a `geocean query --points` file, split into rows the
// way cmd_query.cpp does (lines, CR stripped by the parser, header only on
// row 1, blank rows skipped) and parsed by globe/app/QueryIo's
// parsePointRow. Checked beyond "no crash, no UB":
//  - an accepted row holds finite values in range (lat [-90, 90], lon
//    [-180, 360], time within +-waves::kMaxTimeS), and printing them back with %.17g and
//    parsing again gives the same doubles (nothing lost or invented);
//  - a refused row's message names its row ("row N: ...").
#include "globe/app/QueryIo.h"
#include "plugin/waves/TimeRange.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

using namespace geocean::app;

namespace {
[[noreturn]] void failure(const char* what, std::string_view line, const std::string& detail) {
  std::fprintf(stderr, "fuzz_points_csv: %s\n  row: '%.*s'\n  %s\n", what, int(line.size()), line.data(),
               detail.c_str());
  std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  long r = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++r;
    if (r == 1 && isHeaderRow(line)) continue;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    PointRow p;
    const std::string e = parsePointRow(line, r, p);
    if (!e.empty()) {
      const std::string prefix = "row " + std::to_string(r) + ":";
      if (e.compare(0, prefix.size(), prefix) != 0) failure("error does not name the row", line, e);
      break;  // the CLI stops at the first bad row
    }
    if (!(p.latDeg >= -90.0 && p.latDeg <= 90.0) || !(p.lonDeg >= -180.0 && p.lonDeg <= 360.0))
      failure("accepted a point out of range", line, std::to_string(p.latDeg) + "," + std::to_string(p.lonDeg));
    if (p.timeS && !geocean::waves::timeInRange(*p.timeS)) failure("accepted a time out of range", line, "");
    char b[120];
    if (p.timeS)
      std::snprintf(b, sizeof b, "%.17g,%.17g,%.17g", p.latDeg, p.lonDeg, *p.timeS);
    else
      std::snprintf(b, sizeof b, "%.17g,%.17g", p.latDeg, p.lonDeg);
    PointRow q;
    if (const std::string e2 = parsePointRow(b, r, q); !e2.empty()) failure("its own output is refused", line, e2);
    if (q.latDeg != p.latDeg || q.lonDeg != p.lonDeg || q.timeS.has_value() != p.timeS.has_value() ||
        (q.timeS && *q.timeS != *p.timeS))
      failure("round trip changed the values", line, b);
  }
  return 0;
}
