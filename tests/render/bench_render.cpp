// bench_render: the scripted flight of `geocean fly` (orbit to 2 m above the
// sea, the same plan, sun and time step), each frame drawn with glFinish
// between passes, then once more with trivial shaders over the same meshes
// (the "bare" reference). Reports per-pass wall and process-CPU time per
// frame (CSV) and medians by altitude band. CPU time counts llvmpipe's
// rasteriser threads too and, unlike wall time, barely moves when other
// jobs share the cores, so it is the figure to compare between runs.
//   bench_render [--frames N] [--size WxH] [--to LAT,LON] [--csv FILE] [--no-ocean]
//                [--pixel-error PX]  (terrain LOD: split while a cell spans more pixels)
//                [--repeat N] [--sea-proxy]  (TerrainOptions::seaProxy)
//                [--min-of N]  (each frame drawn N times, per figure the least:
//                one process's own noise floor, for comparing shader variants)
//                [--only I,J,...]  (draw only these frames of the flight)
//                [--reflection-size N] [--no-reflections] [--no-refraction]
//                (the optics' switches, issue 13 item 7; `refl` is the
//                mirrored pass alone, inside `ocean`)
//                [--cell-px PX]  (the ocean grid's vertex spacing, OceanOptions::cellPx)
//                [--reduced-rate | --full-rate] [--rate-tolerance N (of 255)]
//                [--pixel-octave-end PX]  (OceanOptions::reducedRate, pixelOctaveEndPx)
//                [--mask FILE]  (a mask layer over the default world: the host's
//                terrain streams it, world::loadLayeredWorld; the ocean draws the
//                stack's grids, not the façade's streamed tiles)
//                [--no-shadows] [--shadow-model paper] [--sun-model phong]
//                (issue 13 item 6; `shadow` is the sun's depth pass alone,
//                inside `ocean`, over the frames that drew it)
// Set LP_NUM_THREADS to choose llvmpipe's thread count.
#include "globe/gl/Framebuffer.h"
#include "globe/render/CliParse.h"
#include "globe/render/Flight.h"
#include "globe/render/Session.h"
#include "globe/world/LayerStack.h"
#include "tests/render/DirectOcean.h"
#include "tests/support/Median.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

using namespace geocean;

namespace {

using geocean::test::median;

struct Row {
  double altM;
  render::FrameTimes t, bare;
  double gridMs;
};

void report(const char* label, const std::vector<Row>& rows, double lo, double hi) {
  std::vector<double> c[9], shadow;
  for (const Row& r : rows) {
    if (r.altM < lo || r.altM >= hi) continue;
    const double v[9] = {r.t.terrainCpuMs, r.t.layersCpuMs, r.t.skyCpuMs, r.t.totalCpuMs,
                         r.bare.terrainCpuMs, r.bare.layersCpuMs, r.bare.totalCpuMs, r.t.totalMs,
                         r.t.reflectionCpuMs};
    for (int i = 0; i < 9; ++i) c[i].push_back(v[i]);
    if (r.t.shadowDrawn) shadow.push_back(r.t.shadowCpuMs);
  }
  if (c[0].empty()) return;
  const double bt = median(c[6]);
  std::printf("%-14s %3zu frames | cpu ms: terrain %7.1f ocean %7.1f (refl %6.1f) sky %5.1f total %7.1f | bare: "
              "terrain %6.1f ocean %6.1f total %6.1f | ratio %5.2f | wall total %7.1f | shadow %6.1f in %zu\n",
              label, c[0].size(), median(c[0]), median(c[1]), median(c[8]), median(c[2]), median(c[3]), median(c[4]),
              median(c[5]), bt, bt > 0 ? median(c[3]) / bt : 0.0, median(c[7]), shadow.empty() ? 0.0 : median(shadow),
              shadow.size());
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 40;
  std::string size = "1280x720", to = "36.0,-5.6", csvPath, maskPath;
  bool ocean = true;
  int repeat = 1;  // draws per frame before the timed one
  int minOf = 1;   // timed draws per frame, the least of each figure kept
  std::vector<int> only;
  bool detail = true;
  double cellPx = 0.0;
  int reflectionSize = 0;
  bool reflections = true, refraction = true, shadows = true, reducedRate = false;
  std::string pngPrefix;
  double rateTol = -1.0, pixelEndPx = -1.0;
  bool fullRate = false;
  render::ShadowModel shadowModel = render::ShadowModel::Physical;
  render::SunModel sunModel = render::SunModel::Microfacet;
  render::TerrainOptions terrain;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_render: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--frames") frames = std::atoi(next().c_str());
    else if (a == "--size") size = next();
    else if (a == "--to") to = next();
    else if (a == "--csv") csvPath = next();
    else if (a == "--no-ocean") ocean = false;
    else if (a == "--mask") maskPath = next();
    else if (a == "--pixel-error") terrain.pixelErrorPx = std::atof(next().c_str());
    else if (a == "--repeat") repeat = std::atoi(next().c_str());
    else if (a == "--min-of") minOf = std::max(1, std::atoi(next().c_str()));
    else if (a == "--only") {
      try {
        const std::string list = next();
        for (double v : render::parseNumbers(list, std::size_t(std::count(list.begin(), list.end(), ',')) + 1,
                                             "--only I,J,..."))
          only.push_back(int(v));
      } catch (const render::ArgError& e) {
        std::fprintf(stderr, "bench_render: %s\n", e.what());
        return 2;
      }
    }
    else if (a == "--sea-proxy") terrain.seaProxy = true;
    else if (a == "--cell-px") cellPx = std::atof(next().c_str());
    else if (a == "--no-detail") detail = false;  // the ocean without its detail normal layer
    else if (a == "--reflection-size") reflectionSize = std::atoi(next().c_str());
    else if (a == "--no-reflections") reflections = false;
    else if (a == "--no-shadows") shadows = false;
    else if (a == "--shadow-model") shadowModel = next() == "paper" ? render::ShadowModel::Paper : render::ShadowModel::Physical;
    else if (a == "--sun-model") sunModel = next() == "phong" ? render::SunModel::Phong : render::SunModel::Microfacet;
    else if (a == "--no-refraction") refraction = false;
    else if (a == "--reduced-rate") reducedRate = true;  // OceanOptions::reducedRate
    else if (a == "--full-rate") fullRate = true;  // OceanOptions::reducedRate off
    else if (a == "--pixel-octave-end") {  // OceanOptions::pixelOctaveEndPx
      pixelEndPx = std::atof(next().c_str());
      if (!(pixelEndPx >= 1.0)) {
        std::fprintf(stderr, "bench_render: --pixel-octave-end %g must be at least 1 (pixels)\n", pixelEndPx);
        return 2;
      }
    }
    else if (a == "--rate-tolerance") rateTol = std::atof(next().c_str()) / 255.0;  // of 255; implies --reduced-rate
    else if (a == "--png") pngPrefix = next();     // each timed frame written as PREFIX<frame>.png
    else {
      std::fprintf(stderr, "bench_render: unknown option '%s'\n", a.c_str());
      return 2;
    }
  }
  camera::ViewPose base;
  render::FlightPlan plan;
  try {
    render::parseSize(size, base);
    const auto t = render::parseNumbers(to, 2, "--to LAT,LON");
    plan.toLatDeg = t[0], plan.toLonDeg = t[1], plan.fromLatDeg = t[0], plan.fromLonDeg = t[1] - 40.0;
  } catch (const render::ArgError& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 2;
  }
  if (frames < 2) {
    std::fprintf(stderr, "bench_render: --frames %d must be at least 2\n", frames);
    return 2;
  }
  plan.headingDeg = 90.0;  // as geocean fly
  render::Session s = render::Session::headless(
      maskPath.empty() ? world::loadDefaultWorld() : world::loadLayeredWorld({{world::LayerKind::Mask, maskPath, "", 0}}, true),
      base.width, base.height, terrain);
  std::shared_ptr<ocean_render::OceanRenderer> oceanLayer;
  if (ocean) {
    ocean_render::OceanOptions oo;
    oo.detailNormals = detail;
    if (reducedRate || rateTol >= 0.0) oo.reducedRate = true;
    if (fullRate) oo.reducedRate = false;
    if (pixelEndPx > 0.0) oo.pixelOctaveEndPx = pixelEndPx;
    if (rateTol >= 0.0) oo.reducedRateTolerance = rateTol;
    if (cellPx > 0.0) oo.cellPx = cellPx;
    const std::string err =
        render::test::addDirectOcean(*s.renderer, s.world->grids(), "noise", 10.0, 270.0, &oceanLayer, nullptr, oo);
    if (!err.empty()) {
      std::fprintf(stderr, "bench_render: %s\n", err.c_str());
      return 2;
    }
  }
  const glm::dvec3 sun = render::sunFromLocal(plan.toLatDeg, plan.toLonDeg, 135.0, 35.0);
  std::vector<Row> rows;
  std::ofstream csv;
  if (!csvPath.empty()) {
    csv.open(csvPath);
    csv << "frame,alt_m,tiles,terrain_ms,ocean_ms,sky_ms,total_ms,terrain_cpu_ms,ocean_cpu_ms,sky_cpu_ms,"
           "total_cpu_ms,grid_ms,bare_terrain_cpu_ms,bare_ocean_cpu_ms,bare_total_cpu_ms,reflection_cpu_ms,shadow_cpu_ms\n";
  }
  for (int f = 0; f < frames; ++f) {
    if (!only.empty() && std::find(only.begin(), only.end(), f) == only.end()) continue;
    const camera::ViewPose pose = render::flightPose(plan, double(f) / (frames - 1), base);
    render::FrameSettings fs;
    fs.timeS = f / 30.0;
    fs.sunEcef = sun;
    fs.timed = true;
    fs.reflectionSize = reflectionSize;
    fs.reflections = reflections;
    fs.refraction = refraction;
    fs.shadows = shadows;
    fs.shadowModel = shadowModel;
    fs.sunModel = sunModel;
    Row r;
    r.altM = pose.altM;
    for (int k = 1; k < repeat; ++k) s.render(pose, fs);
    r.t = s.render(pose, fs);
    if (!pngPrefix.empty()) gl::writePng(pngPrefix + std::to_string(f) + ".png", s.image());
    if (oceanLayer && oceanLayer->lastDrawDeferred())
      std::fprintf(stderr, "frame %d alt %.0f m: full-rate share %.3f\n", f, pose.altM, oceanLayer->lastFullRateShare());
    for (int k = 1; k < minOf; ++k) {
      const render::FrameTimes t = s.render(pose, fs);
      for (auto m : {&render::FrameTimes::skyCpuMs, &render::FrameTimes::terrainCpuMs, &render::FrameTimes::layersCpuMs,
                     &render::FrameTimes::totalCpuMs, &render::FrameTimes::reflectionCpuMs,
                     &render::FrameTimes::shadowCpuMs, &render::FrameTimes::skyMs, &render::FrameTimes::terrainMs,
                     &render::FrameTimes::layersMs, &render::FrameTimes::totalMs})
        r.t.*m = std::min(r.t.*m, t.*m);
    }
    r.gridMs = oceanLayer ? oceanLayer->lastGridMs() : 0.0;
    fs.bare = true;
    r.bare = s.render(pose, fs);
    if (f > 0 || !only.empty()) rows.push_back(r);  // frame 0 compiles shaders
    if (csv.is_open()) {
      char line[512];
      std::snprintf(line, sizeof line, "%d,%.1f,%d,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f\n",
                    f, pose.altM, r.t.terrain.tilesDrawn, r.t.terrainMs, r.t.layersMs, r.t.skyMs, r.t.totalMs,
                    r.t.terrainCpuMs, r.t.layersCpuMs, r.t.skyCpuMs, r.t.totalCpuMs, r.gridMs, r.bare.terrainCpuMs,
                    r.bare.layersCpuMs, r.bare.totalCpuMs, r.t.reflectionCpuMs, r.t.shadowCpuMs);
      csv << line;
    }
  }
  report("all", rows, 0.0, 1e30);
  report(">= 100 km", rows, 1e5, 1e30);
  report("1 - 100 km", rows, 1e3, 1e5);
  report("< 1 km", rows, 0.0, 1e3);
  return 0;
}
