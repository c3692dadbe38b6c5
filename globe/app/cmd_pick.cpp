// `geocean pick`: the first hit on terrain or sea along a ray, through the
// Embree scene of plugin/pick/Picker.h (double-refined).
#include "globe/app/Command.h"
#include "globe/app/LayerOptions.h"
#include "globe/app/QueryIo.h"
#include "globe/camera/Camera.h"
#include "globe/raster/World.h"
#include "plugin/pick/Picker.h"
#include "plugin/ocean/Ocean.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace geocean::app {
namespace {

struct PickOptions {
  std::string ray, rays, cameraPose, size = "1280x720", pixel, format = "text";
  LayerOptions layers;
  double fovDeg = 60.0;
  bool noTerrain = false, global = false;
};

void appendDouble(std::string& s, double v) {
  char b[32];
  auto r = std::to_chars(b, b + sizeof b, v);
  s.append(b, r.ptr);
}

void format(const pick::PickResult& r, const std::string& fmt, std::string& out) {
  if (fmt == "json") {
    out += "{\"hit\":";
    out += r.hit ? "true" : "false";
    const char* keys[] = {",\"lat\":", ",\"lon\":", ",\"height_m\":", ",\"distance_m\":"};
    const double vals[] = {r.latDeg, r.lonDeg, r.heightM, r.distanceM};
    for (int k = 0; k < 4; ++k) {
      out += keys[k];
      if (r.hit) {
        appendDouble(out, vals[k]);
      } else {
        out += "null";
      }
    }
    out += ",\"surface\":";
    if (r.hit) {
      out += '"';
      out += ocean::toString(r.surface);
      out += '"';
    } else {
      out += "null";
    }
    out += "}\n";
  } else {
    out += r.hit ? "true," : "false,";
    const double vals[] = {r.latDeg, r.lonDeg, r.heightM, r.distanceM};
    for (double v : vals) {
      if (r.hit) appendDouble(out, v);
      out += ',';
    }
    if (r.hit) out += ocean::toString(r.surface);
    out += '\n';
  }
}

// The picker's inputs from the ocean façade: the terrain and the classes.
struct World {
  std::shared_ptr<const raster::Raster> elevation;
  ocean::Classifier classifier;
};

World openWorld(const PickOptions& o) {
  raster::OpenOptions ro;
  if (o.global) ro.georef = raster::Georef::GlobalEquirect;
  LayerOptions layers = o.layers;
  layers.noElevation = o.noTerrain;
  ocean::Ocean ocean;
  applyLayers(ocean, layers, ro);
  const auto snap = ocean.current();
  // The terrain: the stack's drawing elevation (its finest regional layer
  // when there are several; one raster, as the Embree scene takes it).
  return {snap->elevation, snap->classifier()};
}

int runPick(const PickOptions& o) {
  if (o.format != "text" && o.format != "json") {
    std::fprintf(stderr, "geocean pick: --format '%s' is not text or json\n", o.format.c_str());
    return kExitBadInput;
  }
  const int modes = !o.ray.empty() + !o.rays.empty() + !o.cameraPose.empty();
  if (modes != 1) {
    std::fprintf(stderr, "geocean pick: give exactly one of --ray, --rays or --camera\n");
    return kExitBadInput;
  }
  std::vector<pick::PickRay> rays;
  std::vector<double> v;
  if (!o.ray.empty()) {
    if (auto e = parseNumberList(o.ray, 6, "--ray", v); !e.empty()) {
      std::fprintf(stderr, "geocean pick: %s\n", e.c_str());
      return kExitBadInput;
    }
    rays.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}});
    if (!(glm::length(rays[0].dir) > 0.0)) {
      std::fprintf(stderr, "geocean pick: --ray direction %g,%g,%g is zero\n", v[3], v[4], v[5]);
      return kExitBadInput;
    }
  } else if (!o.cameraPose.empty()) {
    if (auto e = parseNumberList(o.cameraPose, 5, "--camera", v); !e.empty()) {
      std::fprintf(stderr, "geocean pick: %s\n", e.c_str());
      return kExitBadInput;
    }
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(o.size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w <= 0 || h <= 0) {
      std::fprintf(stderr, "geocean pick: --size '%s' is not WIDTHxHEIGHT with positive integers\n", o.size.c_str());
      return kExitBadInput;
    }
    std::vector<double> px;
    if (o.pixel.empty()) {
      std::fprintf(stderr, "geocean pick: --camera needs --pixel X,Y\n");
      return kExitBadInput;
    }
    if (auto e = parseNumberList(o.pixel, 2, "--pixel", px); !e.empty()) {
      std::fprintf(stderr, "geocean pick: %s\n", e.c_str());
      return kExitBadInput;
    }
    if (px[0] < 0 || px[0] > w || px[1] < 0 || px[1] > h) {
      std::fprintf(stderr, "geocean pick: --pixel %g,%g is outside the %dx%d viewport\n", px[0], px[1], w, h);
      return kExitBadInput;
    }
    try {
      const camera::Camera cam = camera::Camera::fromGeodetic({v[0], v[1], v[2], v[3], v[4], 0.0}, o.fovDeg, w, h);
      // Pixel coordinates name pixels: X,Y is the centre of pixel (X, Y).
      rays.push_back({cam.eyeEcef(), cam.pixelRay(px[0] + 0.5, px[1] + 0.5)});
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "geocean pick: --camera/--fov: %s\n", e.what());
      return kExitBadInput;
    }
  }

  std::unique_ptr<World> world;
  try {
    world = std::make_unique<World>(openWorld(o));
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "geocean pick: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geocean pick: %s\n", e.what());
    return kExitDataError;
  }
  std::string out;
  if (o.format == "text") out += "hit,lat,lon,height_m,distance_m,surface\n";
  if (!rays.empty()) {
    // One ray: only the terrain cells along it (the whole world's mesh takes ~1 s to build).
    const pick::Picker picker(world->elevation, world->classifier, rays[0].originEcef, rays);
    format(picker.pick(rays[0]), o.format, out);
    std::fwrite(out.data(), 1, out.size(), stdout);
    return kExitOk;
  }

  // Batch: CSV ox,oy,oz,dx,dy,dz; stream in blocks, one result per row.
  std::ifstream file;
  std::istream* in = &std::cin;
  if (o.rays != "-") {
    file.open(o.rays);
    if (!file) {
      std::fprintf(stderr, "geocean pick: --rays %s: cannot open\n", o.rays.c_str());
      return kExitDataError;
    }
    in = &file;
  }
  std::unique_ptr<pick::Picker> picker;
  std::vector<pick::PickResult> res;
  std::string line;
  long row = 0;
  auto flush = [&] {
    if (rays.empty()) return;
    if (!picker) picker = std::make_unique<pick::Picker>(world->elevation, world->classifier, rays[0].originEcef);
    res.resize(rays.size());
    picker->pickBatch(rays.data(), rays.size(), res.data());
    for (const auto& r : res) format(r, o.format, out);
    std::fwrite(out.data(), 1, out.size(), stdout);
    out.clear();
    rays.clear();
  };
  while (std::getline(*in, line)) {
    ++row;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (row == 1 && isRayHeaderRow(line)) continue;  // header "ox,oy,oz,dx,dy,dz"
    const std::string what = "--rays " + o.rays + " row " + std::to_string(row);
    RayRow rr;
    if (auto e = parseRayRow(line, what, rr); !e.empty()) {
      flush();  // rows before the bad one are answered
      std::fflush(stdout);
      std::fprintf(stderr, "geocean pick: %s\n", e.c_str());
      return kExitBadInput;
    }
    rays.push_back({{rr.origin[0], rr.origin[1], rr.origin[2]}, {rr.direction[0], rr.direction[1], rr.direction[2]}});
    if (rays.size() == 8192) flush();
  }
  flush();
  if (picker == nullptr && o.format == "text") std::fwrite(out.data(), 1, out.size(), stdout);
  std::fflush(stdout);
  return kExitOk;
}

const Register reg{{"pick", "first hit on terrain or sea along a ray (Embree, refined in double)",
                    [](CLI::App& sub) {
                      auto o = std::make_shared<PickOptions>();
                      sub.add_option("--ray", o->ray, "OX,OY,OZ,DX,DY,DZ: ECEF origin (m) and direction")
                          ->allow_extra_args(false);
                      sub.add_option("--rays", o->rays, "CSV file of ox,oy,oz,dx,dy,dz rows, or - for stdin");
                      sub.add_option("--camera", o->cameraPose, "LAT,LON,ALT,HEADING,PITCH (deg, m; pitch -90 looks down)");
                      sub.add_option("--fov", o->fovDeg, "vertical field of view, degrees (default 60)");
                      sub.add_option("--size", o->size, "viewport WxH in pixels (default 1280x720)");
                      sub.add_option("--pixel", o->pixel, "X,Y: pixel column and row (0,0 = top-left); the ray passes through its centre");
                      sub.add_option("--format", o->format, "text (CSV) or json");
                      addLayerOptions(sub, o->layers);
                      sub.add_flag("--global", o->global, "rasters are global equirectangular, north up");
                      sub.add_flag("--no-terrain", o->noTerrain, "pick the sea surface only");
                      return [o] { return runPick(*o); };
                    }}};

}  // namespace
}  // namespace geocean::app
