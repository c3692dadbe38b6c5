// `geocean query`: surface class, terrain elevation and the sea surface
// (height above the ellipsoid, normal, vertical velocity) at points, one
// point from the command line or a stream of CSV rows.
#include "globe/app/Command.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/QueryIo.h"
#include "globe/raster/World.h"
#include "plugin/ocean/Ocean.h"

#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace geocean::app {
namespace {

struct QueryOptions {
  std::vector<std::string> latLon;  // positional LAT LON
  std::string points;               // CSV file or "-"
  std::string format = "text";
  LayerOptions layers;
  bool global = false;
  // Sea state (strings: parsed here so that bad values get our messages).
  std::string waves = "noise", time = "0", wind, beaufort, windDir = "270", fetch = "0", seed = "1",
              anchor = "0,0";
  std::string coastRegion;  // LAT,LON[,SIZE_M]: the near-shore phase field (gerstner)
};

// The sea state and model from the options, or an error message.
struct WaveSetup {
  waves::Model model = waves::Model::Noise;
  bool noSea = false;  // --waves none: class and elevation only
  waves::SeaState sea;
  double timeS = 0.0;
  std::optional<waves::CoastField::Region> coast;
};
std::string parseWaveOptions(const QueryOptions& o, WaveSetup& w) {
  auto number = [](const std::string& opt, const std::string& v, double& out) -> std::string {
    const auto x = parseNumber(v);
    if (!x) return opt + " '" + v + "' is not a finite number";
    out = *x;
    return {};
  };
  const auto model = waves::parseModel(o.waves);
  w.noSea = o.waves == "none";
  if (!model && !w.noSea)
    return "--waves '" + o.waves + "' is not a wave model (noise, noise-paper, gerstner, fft, none)";
  if (model) w.model = *model;
  if (auto e = number("--time", o.time, w.timeS); !e.empty()) return e;
  if (auto e = checkTime(w.timeS, "--time"); !e.empty()) return e;
  if (!o.wind.empty() && !o.beaufort.empty()) return "give either --wind or --beaufort, not both";
  if (!o.beaufort.empty()) {
    double b = 0.0;
    if (auto e = number("--beaufort", o.beaufort, b); !e.empty()) return e;
    const auto sea = b == std::floor(b) ? waves::SeaState::fromBeaufort(int(b)) : std::nullopt;
    if (!sea) return "--beaufort " + o.beaufort + " is not a Beaufort number 0..12";
    w.sea = *sea;
  } else if (!o.wind.empty()) {
    if (auto e = number("--wind", o.wind, w.sea.windSpeedMps); !e.empty()) return e;
    if (!(w.sea.windSpeedMps >= 0.2 && w.sea.windSpeedMps <= 60.0))
      return "--wind " + o.wind + " m/s is outside 0.2 .. 60 m/s";
  }
  if (auto e = number("--wind-dir", o.windDir, w.sea.windFromDeg); !e.empty()) return e;
  if (auto e = number("--fetch", o.fetch, w.sea.fetchM); !e.empty()) return e;
  if (w.sea.fetchM < 0.0) return "--fetch " + o.fetch + " m is negative";
  if (w.sea.fetchM > 0.0 && w.sea.fetchM < 1.0)
    return "--fetch " + o.fetch + " m is below 1 m (0: fully developed)";
  {
    std::uint32_t seed = 0;
    const auto [p, ec] = std::from_chars(o.seed.data(), o.seed.data() + o.seed.size(), seed);
    if (o.seed.empty() || ec != std::errc() || p != o.seed.data() + o.seed.size())
      return "--seed '" + o.seed + "' is not an integer 0 .. 4294967295";
    w.sea.seed = seed;
  }
  {
    const auto comma = o.anchor.find(',');
    const auto lat = comma == std::string::npos ? std::nullopt : parseNumber(std::string_view(o.anchor).substr(0, comma));
    const auto lon = comma == std::string::npos ? std::nullopt : parseNumber(std::string_view(o.anchor).substr(comma + 1));
    if (!lat || !lon) return "--anchor '" + o.anchor + "' is not LAT,LON";
    if (auto e = checkLatLon(*lat, *lon, "--anchor"); !e.empty()) return e;
    w.sea.anchorLatDeg = *lat;
    w.sea.anchorLonDeg = *lon;
  }
  if (!o.coastRegion.empty()) {
    if (w.model != waves::Model::Gerstner || w.noSea) return "--coast-region needs --waves gerstner";
    std::vector<double> v;
    const std::size_t parts = std::size_t(std::count(o.coastRegion.begin(), o.coastRegion.end(), ',')) + 1;
    if (parts != 2 && parts != 3) return "--coast-region '" + o.coastRegion + "' is not LAT,LON[,SIZE_M]";
    if (auto e = parseNumberList(o.coastRegion, parts, "--coast-region", v); !e.empty()) return e;
    if (auto e = checkLatLon(v[0], v[1], "--coast-region"); !e.empty()) return e;
    const double size = parts == 3 ? v[2] : 10000.0;
    if (!(size >= 500.0 && size <= 40000.0))
      return "--coast-region size " + o.coastRegion.substr(o.coastRegion.rfind(',') + 1) +
             " m is outside 500 .. 40000 m";
    waves::CoastField::Region r;
    r.latDeg = v[0];
    r.lonDeg = v[1];
    r.nodes = 201;
    r.cellM = size / (r.nodes - 1);
    w.coast = r;
  }
  return {};
}

void appendDouble(std::string& s, double v) {
  char b[32];
  auto r = std::to_chars(b, b + sizeof b, v);
  s.append(b, r.ptr);
}
void appendFloat(std::string& s, float v) {
  if (std::isnan(v)) {
    s += "null";
    return;
  }
  char b[32];
  auto r = std::to_chars(b, b + sizeof b, v);
  s.append(b, r.ptr);
}

void appendSea(std::string& s, double v, bool sea) {
  if (!sea || std::isnan(v))
    s += "null";
  else
    appendDouble(s, v);
}

// One block's answers, one entry per row (normal: 3 per row).
struct Results {
  std::vector<ocean::Surface> surface;
  std::vector<float> elevationM;
  std::vector<double> seaHeightM, normalEnu, verticalVelocityMps;
  std::vector<double> hsM, peakPeriodS, peakWavelengthM, waveFromDeg;  // the local sea state
};

class Querier {
 public:
  Querier(const QueryOptions& o, bool batch, const WaveSetup& w) : format_(o.format), timeS_(w.timeS) {
    raster::OpenOptions ro;
    if (o.global) ro.georef = raster::Georef::GlobalEquirect;
    // A single point reads only its tiles (libtiff); batches load the
    // (small) default rasters into memory for throughput.
    if (!batch) ro.fewLookups = true;
    applyLayers(ocean_, o.layers, ro);
    if (!w.noSea) ocean_.setSeaState(w.model, w.sea);  // parseWaveOptions checked the ranges first
    if (w.coast) ocean_.setCoastRegion(*w.coast);
    snap_ = ocean_.current();
    withSea_ = !w.noSea;
  }

  void run(const std::vector<PointRow>& pts, Results& r) const {
    const std::size_t n = pts.size();
    r.surface.resize(n);
    r.elevationM.resize(n);
    r.seaHeightM.resize(n);
    r.normalEnu.resize(3 * n);
    r.verticalVelocityMps.resize(n);
    for (auto* v : {&r.hsM, &r.peakPeriodS, &r.peakWavelengthM, &r.waveFromDeg}) v->resize(n);
    std::vector<double> lat(n), lon(n), t(n);
    for (std::size_t i = 0; i < n; ++i) {
      lat[i] = pts[i].latDeg;
      lon[i] = pts[i].lonDeg;
      t[i] = pts[i].timeS.value_or(timeS_);  // a row's own time overrides --time
    }
    ocean::SurfaceOutputs out;
    out.surface = r.surface.data();
    out.elevationM = r.elevationM.data();
    if (withSea_) {
      out.heightM = r.seaHeightM.data();
      out.normalEnu = r.normalEnu.data();
      out.verticalVelocityMps = r.verticalVelocityMps.data();
      out.hsM = r.hsM.data();
      out.peakPeriodS = r.peakPeriodS.data();
      out.peakWavelengthM = r.peakWavelengthM.data();
      out.waveFromDeg = r.waveFromDeg.data();
    } else {
      for (auto* v : {&r.seaHeightM, &r.hsM, &r.peakPeriodS, &r.peakWavelengthM, &r.waveFromDeg})
        std::fill(v->begin(), v->end(), std::numeric_limits<double>::quiet_NaN());
    }
    snap_->querySurface({lat.data(), lon.data(), n, t.data(), true}, out);
  }

  void header(std::string& out) const {
    if (format_ == "text")
      out +=
          "lat,lon,surface,elevation_m,time_s,sea_height_m,normal_e,normal_n,normal_u,vertical_velocity_mps,"
          "hs_m,peak_period_s,peak_wavelength_m,wave_from_deg\n";
  }

  // Row i of r. Sea fields are null where there is no sea surface (land, lakes).
  void format(const PointRow& p, const Results& r, std::size_t i, std::string& out) const {
    const ocean::Surface s = r.surface[i];
    const float elev = r.elevationM[i];
    const double height = r.seaHeightM[i];
    const double* nrm = &r.normalEnu[3 * i];
    const bool sea = s == ocean::Surface::Ocean && !std::isnan(height);
    const double t = p.timeS.value_or(timeS_);
    if (format_ == "json") {
      out += "{\"lat\":";
      appendDouble(out, p.latDeg);
      out += ",\"lon\":";
      appendDouble(out, p.lonDeg);
      out += ",\"time_s\":";
      appendDouble(out, t);
      out += ",\"surface\":\"";
      out += ocean::toString(s);
      out += "\",\"elevation_m\":";
      appendFloat(out, elev);
      out += ",\"sea_height_m\":";
      appendSea(out, height, sea);
      out += ",\"normal\":";
      if (sea) {
        out += '[';
        appendDouble(out, nrm[0]);
        out += ',';
        appendDouble(out, nrm[1]);
        out += ',';
        appendDouble(out, nrm[2]);
        out += ']';
      } else {
        out += "null";
      }
      out += ",\"vertical_velocity_mps\":";
      appendSea(out, r.verticalVelocityMps[i], sea);
      out += ",\"hs_m\":";
      appendSea(out, r.hsM[i], sea);
      out += ",\"peak_period_s\":";
      appendSea(out, r.peakPeriodS[i], sea);
      out += ",\"peak_wavelength_m\":";
      appendSea(out, r.peakWavelengthM[i], sea);
      out += ",\"wave_from_deg\":";
      appendSea(out, r.waveFromDeg[i], sea);
      out += "}\n";
    } else {
      appendDouble(out, p.latDeg);
      out += ',';
      appendDouble(out, p.lonDeg);
      out += ',';
      out += ocean::toString(s);
      out += ',';
      appendFloat(out, elev);
      out += ',';
      appendDouble(out, t);
      for (double v : {height, nrm[0], nrm[1], nrm[2], r.verticalVelocityMps[i], r.hsM[i], r.peakPeriodS[i],
                       r.peakWavelengthM[i], r.waveFromDeg[i]}) {
        out += ',';
        appendSea(out, v, sea);
      }
      out += '\n';
    }
  }

 private:
  std::string format_;
  double timeS_ = 0.0;
  bool withSea_ = false;
  ocean::Ocean ocean_;
  std::shared_ptr<const ocean::Snapshot> snap_;
};

int runQuery(const QueryOptions& o) {
  if (o.format != "text" && o.format != "json") {
    std::fprintf(stderr, "geocean query: --format '%s' is not text or json\n", o.format.c_str());
    return kExitBadInput;
  }
  WaveSetup waveSetup;
  if (auto e = parseWaveOptions(o, waveSetup); !e.empty()) {
    std::fprintf(stderr, "geocean query: %s\n", e.c_str());
    return kExitBadInput;
  }
  const bool batch = !o.points.empty();
  if (batch == !o.latLon.empty()) {
    std::fprintf(stderr, "geocean query: give either LAT LON or --points FILE\n");
    return kExitBadInput;
  }
  std::vector<PointRow> single;
  if (!batch) {
    if (o.latLon.size() != 2) {
      std::fprintf(stderr, "geocean query: expected LAT LON, got %zu values\n", o.latLon.size());
      return kExitBadInput;
    }
    const auto lat = parseNumber(o.latLon[0]), lon = parseNumber(o.latLon[1]);
    if (!lat || !lon) {
      std::fprintf(stderr, "geocean query: %s '%s' is not a finite number\n", lat ? "LON" : "LAT",
                   (lat ? o.latLon[1] : o.latLon[0]).c_str());
      return kExitBadInput;
    }
    if (auto e = checkLatLon(*lat, *lon, "geocean query"); !e.empty()) {
      std::fprintf(stderr, "%s\n", e.c_str());
      return kExitBadInput;
    }
    single.push_back({*lat, *lon, std::nullopt});
  }

  std::unique_ptr<Querier> q;
  try {
    q = std::make_unique<Querier>(o, batch, waveSetup);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "geocean query: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geocean query: %s\n", e.what());
    return kExitDataError;
  }

  std::string out;
  Results res;
  q->header(out);
  if (!batch) {
    q->run(single, res);
    q->format(single[0], res, 0, out);
    std::fwrite(out.data(), 1, out.size(), stdout);
    return kExitOk;
  }

  std::FILE* in = stdin;
  if (o.points != "-") {
    in = std::fopen(o.points.c_str(), "rb");
    if (!in) {
      std::fprintf(stderr, "geocean query: --points %s: cannot open\n", o.points.c_str());
      return kExitDataError;
    }
  }
  struct Closer {
    std::FILE* f;
    ~Closer() {
      if (f != stdin) std::fclose(f);
    }
  } closer{in};

  // A pipeline over blocks of whole lines: read (in order) -> split, parse,
  // compute and format (blocks in parallel) -> write (in order), so reading
  // and writing overlap the work instead of running between its stages.
  constexpr std::size_t kBlock = std::size_t(1) << 20;
  struct Block {
    std::string text;   // whole lines
    long firstRow = 0;  // row number of the block's first line
    std::string out, error;
  };
  std::string carry, error;
  long row = 0;
  bool eof = false, stop = false;
  std::fwrite(out.data(), 1, out.size(), stdout);  // the header
  out.clear();
  tbb::parallel_pipeline(
      8,
      tbb::make_filter<void, std::shared_ptr<Block>>(
          tbb::filter_mode::serial_in_order,
          [&](tbb::flow_control& fc) -> std::shared_ptr<Block> {
            if (eof || stop) {
              fc.stop();
              return nullptr;
            }
            auto blk = std::make_shared<Block>();
            blk->text = std::move(carry);
            carry.clear();
            const std::size_t keep = blk->text.size();
            blk->text.resize(keep + kBlock);
            const std::size_t got = std::fread(blk->text.data() + keep, 1, kBlock, in);
            blk->text.resize(keep + got);
            eof = got < kBlock;
            if (eof && !blk->text.empty() && blk->text.back() != '\n') blk->text.push_back('\n');
            const std::size_t lastNl = blk->text.rfind('\n');
            const std::size_t cut = lastNl == std::string::npos ? 0 : lastNl + 1;
            if (cut == 0 && blk->text.size() >= kBlock) {
              // No line end in a whole block: not a point row, and buffering
              // it until one comes would hold memory without bound.
              blk->text.clear();
              blk->firstRow = row + 1;
              blk->error = "row " + std::to_string(row + 1) + ": longer than 1 MiB (no line end), not a point row";
              eof = true;
              return blk;
            }
            carry.assign(blk->text, cut, std::string::npos);  // the partial last line waits
            blk->text.resize(cut);
            blk->firstRow = row + 1;
            row += long(std::count(blk->text.begin(), blk->text.end(), '\n'));
            return blk;
          }) &
          tbb::make_filter<std::shared_ptr<Block>, std::shared_ptr<Block>>(
              tbb::filter_mode::parallel,
              [&](std::shared_ptr<Block> blk) {
                std::vector<PointRow> pts;
                long r = blk->firstRow - 1;
                std::size_t pos = 0;
                for (std::size_t nl; (nl = blk->text.find('\n', pos)) != std::string::npos; pos = nl + 1) {
                  const std::string_view line(blk->text.data() + pos, nl - pos);
                  ++r;
                  if (r == 1 && isHeaderRow(line)) continue;
                  if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;  // blank line
                  PointRow p;
                  if (auto e = parsePointRow(line, r, p); !e.empty()) {
                    blk->error = std::move(e);
                    break;
                  }
                  pts.push_back(p);
                }
                Results br;
                q->run(pts, br);
                for (std::size_t i = 0; i < pts.size(); ++i)
                  q->format(pts[i], br, i, blk->out);
                return blk;
              }) &
          tbb::make_filter<std::shared_ptr<Block>, void>(tbb::filter_mode::serial_in_order,
                                                         [&](std::shared_ptr<Block> blk) {
                                                           if (stop) return;
                                                           std::fwrite(blk->out.data(), 1, blk->out.size(), stdout);
                                                           if (!blk->error.empty()) {
                                                             error = std::move(blk->error);
                                                             stop = true;  // later blocks are dropped
                                                           }
                                                         }));
  std::fflush(stdout);
  if (!error.empty()) {
    // Rows before the bad one were answered; the batch stops loudly here.
    std::fprintf(stderr, "geocean query: --points %s: %s\n", o.points.c_str(), error.c_str());
    return kExitBadInput;
  }
  if (std::ferror(in)) {
    std::fprintf(stderr, "geocean query: --points %s: read error after row %ld\n", o.points.c_str(), row);
    return kExitDataError;
  }
  return kExitOk;
}

// `geocean demo`: the famous-places tour through the same query path.
int runDemo(const LayerOptions& layers) {
  struct Place {
    const char* name;
    double lat, lon;
  };
  static const Place kPlaces[] = {
      {"Mariana Trench", 11.35, 142.2},   {"Point Nemo", -48.88, -123.39}, {"Strait of Gibraltar", 35.95, -5.6},
      {"Sydney offshore", -33.9, 151.5},  {"Sahara", 23.0, 10.0},          {"Mount Everest", 27.99, 86.93},
      {"Caspian Sea", 42.0, 50.5},        {"Lake Victoria", -1.0, 33.0},   {"Lake Superior", 47.7, -87.5},
      {"North Pole", 90.0, 0.0},          {"South Pole", -90.0, 0.0},      {"Fiji, lon 180", -17.0, 180.0},
  };
  QueryOptions o;
  o.layers = layers;
  std::unique_ptr<Querier> qp;
  try {
    qp = std::make_unique<Querier>(o, /*batch=*/true, WaveSetup{});
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "geocean demo: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geocean demo: %s\n", e.what());
    return kExitDataError;
  }
  Querier& q = *qp;
  std::vector<PointRow> pts;
  for (const auto& p : kPlaces) pts.push_back({p.lat, p.lon, std::nullopt});
  Results r;
  q.run(pts, r);
  std::printf("Geocean default world: %s\n", raster::dataDir().c_str());
  std::printf("Sea: noise model, wind 10 m/s from 270 deg, t = 0 s\n");
  std::printf("%-22s %9s %9s  %-6s %12s %13s\n", "place", "lat", "lon", "class", "elevation_m", "sea_height_m");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    char sea[32] = "-";
    if (!std::isnan(r.seaHeightM[i])) std::snprintf(sea, sizeof sea, "%.3f", r.seaHeightM[i]);
    std::printf("%-22s %9.3f %9.3f  %-6s %12.1f %13s\n", kPlaces[i].name, pts[i].latDeg, pts[i].lonDeg,
                ocean::toString(r.surface[i]), double(r.elevationM[i]), sea);
  }
  return kExitOk;
}

const Register kDemo{{"demo", "Query a handful of famous places on the default world",
                      [](CLI::App& sub) -> std::function<int()> {
                        auto layers = std::make_shared<LayerOptions>();
                        addLayerOptions(sub, *layers);
                        return [layers] { return runDemo(*layers); };
                      }}};

const Register kRegister{{"query", "Surface class (ocean/land/lake), terrain elevation and the sea surface at points",
                          [](CLI::App& sub) -> std::function<int()> {
                            auto o = std::make_shared<QueryOptions>();
                            sub.add_option("coords", o->latLon, "LAT LON in degrees (negative values are fine)")
                                ->expected(0, 2);
                            sub.add_option("--points", o->points, "CSV rows lat,lon[,time] (optional header); - for stdin");
                            sub.add_option("--format", o->format, "text (CSV) or json (one object per line)");
                            addLayerOptions(sub, o->layers);
                            sub.add_flag("--global", o->global, "rasters are whole-Earth equirectangular without georeferencing");
                            sub.add_option("--waves", o->waves, "wave model: noise (default), noise-paper, gerstner, fft; none: class and elevation only");
                            sub.add_option("--time", o->time, "simulation time in s (default 0); a row's own time overrides it");
                            sub.add_option("--wind", o->wind, "wind speed at 19.5 m, m/s (0.2 .. 60; default 10)");
                            sub.add_option("--beaufort", o->beaufort, "wind as a Beaufort number 0..12 (instead of --wind)");
                            sub.add_option("--wind-dir", o->windDir, "direction the wind blows FROM, deg clockwise from north (default 270)");
                            sub.add_option("--fetch", o->fetch, "fetch in m: 0 = fully developed (Pierson-Moskowitz, default), > 0 = JONSWAP");
                            sub.add_option("--seed", o->seed, "random seed of the sea (default 1)");
                            sub.add_option("--anchor", o->anchor, "LAT,LON where --wind-dir holds exactly (default 0,0)");
                            sub.add_option("--coast-region", o->coastRegion,
                                           "LAT,LON[,SIZE_M]: waves feel the coast in this square (gerstner; "
                                           "default 10000 m, 201^2 nodes): local wavelength, refraction");
                            sub.positionals_at_end(false);
                            return [o] { return runQuery(*o); };
                          }}};

}  // namespace
}  // namespace geocean::app
