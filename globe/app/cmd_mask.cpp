// `geocean mask`: a land/sea/lake mask from GSHHG's full-resolution
// shorelines (issue 12), rasterised by GMT's grdlandmask (Debian `gmt` and
// `gmt-gshhg-full`, run as a subprocess: GMT is LGPL and stays out of the
// product) into a tiled, deflate-compressed GeoTIFF that Raster::open reads
// with the default mask encoding (0 ocean, 1 land, 2 lake). Big masks are
// made in bands of whole tile rows, one grdlandmask run each, so memory
// stays bounded (about 64 MB a band) and the terminal shows progress.
#include "globe/app/Command.h"
#include "globe/raster/GeoTiffWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace geocean::app {
namespace {

namespace fs = std::filesystem;

struct MaskArgs {
  std::string region;      // W/E/S/N, degrees
  bool global = false;
  std::string resolution;  // GMT increment: 3s, 15s, 0.5m, 0.01d
  std::string out;
  std::string gmt = "gmt";
  std::string minArea = "0";  // grdlandmask -A (km^2): features smaller are left out
  int tile = 256;
  int bandRows = 0;  // 0: about 64 M cells a band
  bool quiet = false;
};

struct BadArg : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};
struct GmtError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.12g", v);
  return b;
}

// GMT's increment syntax: a number and a unit (s arc-seconds, m arc-minutes,
// d degrees). Returns degrees.
double parseResolution(const std::string& s) {
  if (s.size() < 2) throw BadArg("--resolution '" + s + "': want a number and a unit, e.g. 3s, 15s, 0.5m, 0.01d");
  const char unit = s.back();
  const double div = unit == 's' ? 3600.0 : unit == 'm' ? 60.0 : unit == 'd' ? 1.0 : 0.0;
  if (div == 0.0) throw BadArg("--resolution '" + s + "': unit '" + std::string(1, unit) + "' is not s, m or d");
  const std::string num = s.substr(0, s.size() - 1);
  char* end = nullptr;
  const double v = std::strtod(num.c_str(), &end);
  if (end == num.c_str() || *end || !std::isfinite(v) || v <= 0.0)
    throw BadArg("--resolution '" + s + "': '" + num + "' is not a positive number");
  const double deg = v / div;
  // Finer than GSHHG's full resolution (~100 m) only makes bigger files; 0.1" is a typo's guard.
  if (deg < 0.1 / 3600.0) throw BadArg("--resolution '" + s + "' is finer than 0.1s");
  if (deg > 10.0) throw BadArg("--resolution '" + s + "' is coarser than 10 degrees");
  return deg;
}

struct Region {
  double w, e, s, n;
};

Region parseRegion(const std::string& r) {
  std::vector<double> v;
  std::stringstream in(r);
  std::string item;
  while (std::getline(in, item, '/')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(x)) throw BadArg("--region '" + r + "': '" + item + "' is not a number");
    v.push_back(x);
  }
  if (v.size() != 4) throw BadArg("--region '" + r + "': want W/E/S/N (four numbers, degrees)");
  Region g{v[0], v[1], v[2], v[3]};
  if (!(g.s >= -90.0 && g.n <= 90.0 && g.s < g.n))
    throw BadArg("--region '" + r + "': latitudes S=" + fmt(g.s) + ", N=" + fmt(g.n) + " must satisfy -90 <= S < N <= 90");
  if (!(g.w >= -360.0 && g.e <= 360.0 && g.w < g.e && g.e - g.w <= 360.0))
    throw BadArg("--region '" + r + "': longitudes W=" + fmt(g.w) + ", E=" + fmt(g.e) +
                 " must satisfy W < E, E - W <= 360, within [-360, 360]");
  return g;
}

// Whole cells along a span, or a clear error (GMT would silently move the edge).
int cellsAlong(double span, double inc, const char* what, const std::string& resolution) {
  const double n = span / inc;
  const double r = std::round(n);
  if (r < 1.0 || std::abs(n - r) > 1e-6)
    throw BadArg("--region: the " + std::string(what) + " span " + fmt(span) + " degrees is not a whole number of " +
                 resolution + " cells (" + fmt(n) + ")");
  if (r > 2e6) throw BadArg("--region: " + fmt(r) + " cells along the " + what + " is too many");
  return int(r);
}

// Runs argv in dir with stdout and stderr to dir/gmt.log; returns the exit
// status (127 when the program cannot be run).
int run(const std::vector<std::string>& argv, const fs::path& dir) {
  const std::string log = (dir / "gmt.log").string();
  const pid_t pid = fork();
  if (pid < 0) throw GmtError(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    if (chdir(dir.c_str()) != 0) _exit(126);
    if (!freopen(log.c_str(), "w", stdout) || dup2(fileno(stdout), 2) < 0) _exit(126);
    std::vector<char*> a;
    for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
    a.push_back(nullptr);
    execvp(a[0], a.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw GmtError(std::string("waitpid failed: ") + std::strerror(errno));
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string readLog(const fs::path& dir) {
  std::ifstream in(dir / "gmt.log");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// A band of rows from grdlandmask as GMT's native byte grid (`=bb`): a
// 892-byte header (n_columns, n_rows, registration as int32, then the
// region and increments) and the cells row by row, north row first.
std::vector<std::uint8_t> landmaskBand(const MaskArgs& a, const fs::path& dir, double w, double e, double s, double n,
                                       int cols, int rows) {
  const fs::path grid = dir / "band.grd";
  const std::vector<std::string> argv = {a.gmt, "grdlandmask", "-R" + fmt(w) + "/" + fmt(e) + "/" + fmt(s) + "/" + fmt(n),
                                         "-I" + a.resolution, "-r", "-Df", "-N0/1/2/1/2", "-A" + a.minArea,
                                         "-G" + grid.string() + "=bb"};
  const int rc = run(argv, dir);
  if (rc == 127)
    throw GmtError("cannot run '" + a.gmt + "' (GMT): install Debian's gmt and gmt-gshhg-full, or name it with --gmt");
  if (rc != 0) {
    std::string log = readLog(dir);
    std::string hint;
    if (log.find("shoreline") != std::string::npos || log.find("gshhg") != std::string::npos ||
        log.find("GSHHG") != std::string::npos)
      hint = " (the full-resolution shorelines come with Debian's gmt-gshhg-full)";
    throw GmtError("'" + a.gmt + " grdlandmask' failed (exit " + std::to_string(rc) + ")" + hint + ": " + log);
  }
  std::ifstream in(grid, std::ios::binary);
  std::int32_t hdr[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(hdr), sizeof hdr);
  if (!in || hdr[0] != cols || hdr[1] != rows || hdr[2] != 1)
    throw GmtError("grdlandmask made a " + std::to_string(hdr[0]) + " x " + std::to_string(hdr[1]) +
                   " grid (registration " + std::to_string(hdr[2]) + "), expected " + std::to_string(cols) + " x " +
                   std::to_string(rows) + " pixel-registered, for -R" + fmt(w) + "/" + fmt(e) + "/" + fmt(s) + "/" +
                   fmt(n));
  std::vector<std::uint8_t> cells(std::size_t(cols) * rows);
  in.seekg(892);
  in.read(reinterpret_cast<char*>(cells.data()), std::streamsize(cells.size()));
  if (!in) throw GmtError(grid.string() + ": short grid from grdlandmask");
  for (std::uint8_t v : cells)
    if (v > 2) throw GmtError("grdlandmask wrote mask value " + std::to_string(v) + " (not 0/1/2)");
  return cells;
}

struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "geocean-mask-XXXXXX").string();
    if (!mkdtemp(t.data())) throw GmtError("cannot make a temporary directory for GMT: " + std::string(std::strerror(errno)));
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

int runMask(const MaskArgs& a) {
  Region g{};
  double inc = 0.0;
  int width = 0, height = 0;
  try {
    if (a.global == !a.region.empty()) throw BadArg("give exactly one of --region W/E/S/N and --global");
    inc = parseResolution(a.resolution);
    g = a.global ? Region{-180.0, 180.0, -90.0, 90.0} : parseRegion(a.region);
    width = cellsAlong(g.e - g.w, inc, "longitude", a.resolution);
    height = cellsAlong(g.n - g.s, inc, "latitude", a.resolution);
    if (std::int64_t(width) * height > (std::int64_t(1) << 34))
      throw BadArg("--region at " + a.resolution + " is " + std::to_string(width) + " x " + std::to_string(height) +
                   " cells, more than the reader's 2^34");
    if (a.tile < 16 || a.tile > 4096 || a.tile % 16) throw BadArg("--tile " + std::to_string(a.tile) + ": want a multiple of 16 in [16, 4096]");
    if (a.bandRows < 0) throw BadArg("--band-rows " + std::to_string(a.bandRows) + " is negative");
    if (a.out.empty()) throw BadArg("--out FILE is required");
    if (a.minArea.empty() || a.minArea.find_first_not_of("0123456789.") != std::string::npos)
      throw BadArg("--min-area '" + a.minArea + "' is not a number of km^2");
  } catch (const BadArg& e) {
    std::fprintf(stderr, "geocean mask: %s\n", e.what());
    return kExitBadInput;
  }
  try {
    TempDir tmp;
    // Bands of whole tile rows, about 64 M cells each.
    const int tileRows = a.bandRows > 0 ? (a.bandRows + a.tile - 1) / a.tile
                                        : std::max(1, int((std::int64_t(64) << 20) / (std::int64_t(width) * a.tile)));
    const int bandRows = std::min(height, tileRows * a.tile);
    const int bands = (height + bandRows - 1) / bandRows;
    const bool tty = isatty(fileno(stderr));
    const auto t0 = std::chrono::steady_clock::now();
    if (!a.quiet)
      std::fprintf(stderr, "geocean mask: %d x %d cells at %s (GSHHG full resolution via GMT), %d band%s\n", width,
                   height, a.resolution.c_str(), bands, bands == 1 ? "" : "s");
    std::vector<std::uint8_t> band;
    int bandIndex = -1;
    raster::GeoTiffWriteOptions o;
    o.transform.originLonDeg = g.w;
    o.transform.originLatDeg = g.n;
    o.transform.lonStepDeg = (g.e - g.w) / width;
    o.transform.latStepDeg = -(g.n - g.s) / height;
    o.transform.global = std::abs(g.e - g.w - 360.0) < 1e-9;
    o.tileSize = a.tile;
    o.compression = raster::Compression::Deflate;
    o.deflateLevel = 6;
    const std::string tmpOut = a.out + ".partial";
    raster::writeGeoTiffTiles(tmpOut, width, height, 1, raster::SampleType::U8, o, [&](int x0, int y0, void* tile) {
      const int b = y0 / bandRows;
      if (b != bandIndex) {
        const int r0 = b * bandRows, rows = std::min(bandRows, height - r0);
        // Band edges from whole cells of the region, so bands abut exactly.
        const double n = g.n - r0 * inc, s = (r0 + rows == height) ? g.s : g.n - (r0 + rows) * inc;
        band = landmaskBand(a, tmp.path, g.w, g.e, s, n, width, rows);
        bandIndex = b;
        if (!a.quiet) {
          const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          const double left = el / (b + 1) * (bands - b - 1);
          std::fprintf(stderr, "%sgeocean mask: band %d/%d (%.0f%%), %.0f s elapsed, about %.0f s left%s",
                       tty ? "\r" : "", b + 1, bands, 100.0 * (b + 1) / bands, el, left, tty ? "   " : "\n");
          std::fflush(stderr);
        }
      }
      auto* t = static_cast<std::uint8_t*>(tile);
      const int r0 = bandIndex * bandRows, rows = int(band.size() / std::size_t(width));
      for (int y = 0; y < a.tile; ++y)
        for (int x = 0; x < a.tile; ++x) {
          const int gx = x0 + x, gy = y0 + y - r0;
          // Past the raster's edge the tile's padding: land, as the reader never shows it.
          t[y * a.tile + x] = (gx < width && gy >= 0 && gy < rows) ? band[std::size_t(gy) * width + gx] : 1;
        }
    });
    fs::rename(tmpOut, a.out);
    if (!a.quiet) {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::fprintf(stderr, "%sgeocean mask: wrote %s (%d x %d, 0 ocean / 1 land / 2 lake) in %.1f s\n", tty ? "\n" : "",
                   a.out.c_str(), width, height, el);
    }
  } catch (const GmtError& e) {
    std::fprintf(stderr, "geocean mask: %s\n", e.what());
    std::error_code ec;
    fs::remove(a.out + ".partial", ec);
    return kExitDataError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geocean mask: %s\n", e.what());
    std::error_code ec;
    fs::remove(a.out + ".partial", ec);
    return kExitDataError;
  }
  return kExitOk;
}

const Register reg{{"mask", "Build a land/sea/lake mask GeoTIFF from GSHHG full-resolution shorelines (needs GMT)",
                    [](CLI::App& sub) -> std::function<int()> {
                      auto a = std::make_shared<MaskArgs>();
                      sub.add_option("--region", a->region, "W/E/S/N in degrees (e.g. -6/-5/35.75/36.25)");
                      sub.add_flag("--global", a->global, "The whole Earth (-180/180/-90/90)");
                      sub.add_option("--resolution", a->resolution, "Cell size: 3s, 15s, 0.5m, 0.01d")->required();
                      sub.add_option("--out", a->out, "Output GeoTIFF")->required();
                      sub.add_option("--gmt", a->gmt, "The GMT program (default: gmt on PATH)");
                      sub.add_option("--min-area", a->minArea, "Leave out features under this many km^2 (GMT -A)");
                      sub.add_option("--tile", a->tile, "Tile size in pixels (default 256)");
                      sub.add_option("--band-rows", a->bandRows,
                                     "Rows per GMT run, rounded up to whole tiles (default: about 64 M cells)");
                      sub.add_flag("--quiet", a->quiet, "No progress on stderr");
                      return [a] { return runMask(*a); };
                    }}};

}  // namespace
}  // namespace geocean::app
