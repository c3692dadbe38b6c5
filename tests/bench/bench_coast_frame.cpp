// bench_coast_frame (issue 15 item 8): the per-frame cost of the near-shore
// terms on this machine's GL (llvmpipe here). A round island (radius 100 m,
// a 1:4 beach down to 20 m of flat bottom, as OceanCoast.ARoundIsland-
// ShelterIsDrawnAt30mAnd300m), a 10 m/s Gerstner sea from the west, a
// coast field of 161^2 nodes of 10 m (`--coast-region` equivalent). Each
// view is drawn alternately by an OceanRenderer with the field
// (wv_gerstnerCoast: texel reads, local dispersion, curl and collapse) and
// one without (the deep-water phase with local shoaling: the reference), so
// load from other processes hits both alike; and a third with the field but
// issue 15 item 4's distance bands compiled out (OceanOptions::coastBands
// false): the bands' own cost; and a fourth with the bands but without their
// breaking spray (OceanRenderer::setSpray(false)): the spray's own cost
// (the bands' ratio is taken without it). Reports the ocean pass's
// median process-CPU and wall time per frame (FrameTimes, glFinish between
// passes) and the ratio. Not run by ctest; figures in docs/PERFORMANCE.md.
// --split (issue 15 item 4, the middle band's mesh): instead, where the
// ocean pass's time goes and what the middle band's coarse mesh saves, in the island's views and the 1:50 spilling
// beach's (CoastScene.h; the band-edge test's view from 60 m, and 30 m and
// 300 m): the field's renderer drawn whole, and drawn with
// GL_RASTERIZER_DISCARD (the grid's CPU build, the uploads and the vertex
// stage with primitive assembly, no fragment), each with and without the
// coarse mesh, alternately; the vertex share is their ratio, the rest is
// fragments; and the fine mesh whole with the vertices' normal (the
// fragment normal's cost: the drawing before the coarse mesh was on).
//   bench_coast_frame [--frames N] [--size WxH] [--split]
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/Raster.h"
#include "globe/render/CliParse.h"
#include "globe/render/Session.h"
#include "globe/render/Terrain.h"
#include "globe/world/WorldData.h"
#include "plugin/ocean/Ocean.h"
#include "tests/render/CoastScene.h"
#include "tests/render/DirectOcean.h"
#include "tests/support/Median.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <tuple>
#include <memory>
#include <string>
#include <vector>

using namespace geocean;

namespace {

using geocean::test::median;

// The ocean layer with the rasteriser off for its draw (--split).
class VertexOnlyLayer : public render::test::DirectOceanLayer {
 public:
  using DirectOceanLayer::DirectOceanLayer;
  bool discard = false;
  void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
            const render::LayerInputs& in) override {
    if (discard) glEnable(GL_RASTERIZER_DISCARD);
    DirectOceanLayer::draw(cam, light, bare, in);
    if (discard) glDisable(GL_RASTERIZER_DISCARD);
  }
};

// Ocean pass CPU ms of `layer`'s ocean drawn whole and vertex-only, each
// with the middle band's coarse mesh (blocks of 2 cells) and without it
// (OceanRenderer::setMiddleMeshBlock(1)), and a fifth draw: whole, fine,
// with the vertices' interpolated normal (setFragmentNormal(false): the
// drawing before the coarse mesh was on): the five alternately, medians of
// frames - 1 (the first dropped); the vertex share and the mesh's ratios.
void splitRow(const char* name, int frames, const std::function<render::FrameTimes(const render::FrameSettings&)>& draw,
              VertexOnlyLayer& layer, double lat, double lon) {
  std::vector<double> cpu[5];
  std::size_t blocks = 0;
  for (int f = 0; f < frames; ++f)
    for (int k = 0; k < 5; ++k) {
      layer.discard = k == 2 || k == 3;
      layer.ocean()->setMiddleMeshBlock(k % 2 == 0 || k == 4 ? 1 : 2);
      layer.ocean()->setFragmentNormal(k != 4);
      render::FrameSettings fs;
      fs.timeS = 30.0 + f / 30.0;
      fs.sunEcef = render::sunFromLocal(lat, lon, 150.0, 40.0);
      fs.timed = true;
      const render::FrameTimes t = draw(fs);
      if (k == 1) blocks = layer.ocean()->lastCoarseBlocks();
      if (f > 0) cpu[k].push_back(t.layersCpuMs);
    }
  layer.discard = false;
  layer.ocean()->setMiddleMeshBlock(2);
  layer.ocean()->setFragmentNormal(true);
  const double whole = median(cpu[0]), wholeC = median(cpu[1]), vertex = median(cpu[2]), vertexC = median(cpu[3]);
  const double old = median(cpu[4]);
  std::printf("%-22s | %8.1f %8.1f  %5.3f | %8.1f | %8.1f %8.1f  %5.3f | %5.3f | %6zu | %8.1f  %5.3f  %5.3f\n", name,
              whole, vertex, vertex / whole, whole - vertex, wholeC, vertexC, vertexC / vertex, wholeC / whole, blocks,
              old, whole / old, wholeC / old);
}

constexpr int kW = 400, kH = 400;
// On a tile corner (lat 0, lon 0), as the test: the host terrain sees the island.
constexpr double kLat = 0.0, kLon = 0.0, kRadiusM = 100.0;
const raster::GeoTransform kPlace{-0.02, 0.02, 0.0001, -0.0001, false};

}  // namespace

int main(int argc, char** argv) {
  int frames = 15;
  std::string size = "960x540";
  bool split = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--split") {
      split = true;
      continue;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "bench_coast_frame: %s needs a value\n", a.c_str());
      return 2;
    }
    if (a == "--frames") frames = std::atoi(argv[++i]);
    else if (a == "--size") size = argv[++i];
    else {
      std::fprintf(stderr, "bench_coast_frame: unknown option '%s'\n", a.c_str());
      return 2;
    }
  }
  if (frames < 3) {
    std::fprintf(stderr, "bench_coast_frame: --frames %d must be at least 3\n", frames);
    return 2;
  }
  camera::ViewPose base;
  try {
    render::parseSize(size, base);
  } catch (const render::ArgError& e) {
    std::fprintf(stderr, "bench_coast_frame: %s\n", e.what());
    return 2;
  }

  const geo::EnuFrame enu = geo::enuFrame({kLat, kLon, 0.0});
  std::vector<float> elev(std::size_t(kW) * kH), land(std::size_t(kW) * kH), grass(std::size_t(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::dvec3 off = geo::toEcef({0.02 - (y + 0.5) * 0.0001, -0.02 + (x + 0.5) * 0.0001, 0.0}) - enu.originEcef;
      const double h = std::clamp(0.25 * (kRadiusM - std::hypot(glm::dot(off, enu.east), glm::dot(off, enu.north))),
                                  -20.0, 12.0);
      elev[std::size_t(y) * kW + x] = float(h);
      land[std::size_t(y) * kW + x] = h > 0.0 ? 1.0f : 0.0f;
    }
  for (std::size_t i = 0; i < grass.size(); i += 3) grass[i] = 194.0f, grass[i + 1] = 178.0f, grass[i + 2] = 128.0f;
  const auto elevation = raster::Raster::fromPixels(elev, kW, kH, 1, kPlace, std::nullopt, "island");
  const auto mask = raster::Raster::fromPixels(land, kW, kH, 1, kPlace, std::nullopt, "island_mask");

  ocean::Ocean o;
  o.setRasters(mask, elevation);
  waves::SeaState sea;
  sea.windSpeedMps = 10.0;
  sea.windFromDeg = 270.0;
  sea.anchorLatDeg = kLat;
  o.setSeaState(waves::Model::Gerstner, sea);
  waves::CoastField::Region r;
  r.latDeg = kLat, r.lonDeg = kLon, r.cellM = 10.0, r.nodes = 161;
  o.setCoastRegion(r);
  const auto snap = o.current();
  if (!snap->waves->coastField()) {
    std::fprintf(stderr, "bench_coast_frame: no coast field was built\n");
    return 1;
  }

  world::WorldData wd = world::loadDefaultWorld();
  wd.imagery = world::layerOf(*raster::Raster::fromPixels(grass, kW, kH, 3, kPlace, std::nullopt, "grass"));
  wd.elevation = world::layerOf(*elevation, 0);
  wd.water = world::waterLayerOf(*mask);
  render::Session s = render::Session::headless(wd, base.width, base.height);
  auto grids = std::make_shared<const world::WorldGrids>(world::layerOf(*elevation, 0), world::waterLayerOf(*mask));
  ocean_render::OceanOptions oo;
  oo.model = waves::Model::Gerstner;
  oo.sea = snap->seaState;
  oo.coast = snap->waves->coastFieldShared();
  // The default options: the middle band's coarse mesh on (--split draws it with and without).
  auto withCoast = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
  oo.coastBands = false;  // issue 15 item 4's distance bands compiled out
  auto noBands = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
  oo.coastBands = true;
  auto noSpray = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
  noSpray->setSpray(false);  // issue 15 item 4's spray (Spray.h) left out
  oo.coast = nullptr;
  auto deepOnly = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
  auto layer = std::make_shared<VertexOnlyLayer>(withCoast);
  s.renderer->addLayer(layer);

  if (split) {
    std::printf("bench_coast_frame --split %dx%d, %d frames per view and mode (the first dropped); ocean pass CPU ms\n",
                base.width, base.height, frames);
    std::printf("%-22s | fine mesh:  whole   vertex  share | fragment | coarse middle: whole vertex  "
                "vertex/fine | whole/fine | blocks | fine, vertex normal: whole  fine/it  coarse/it\n", "view");
    for (const auto& [name, northM, altM, pitchDeg] :
         {std::tuple{"island 30 m", 350.0, 30.0, -12.0}, std::tuple{"island 300 m", 900.0, 300.0, -35.0}}) {
      camera::ViewPose p = base;
      p.latDeg = kLat + northM / 110574.0, p.lonDeg = kLon, p.altM = altM;
      p.headingDeg = 180.0, p.pitchDeg = pitchDeg;
      splitRow(name, frames, [&](const render::FrameSettings& fs) { return s.render(p, fs); }, *layer, kLat, kLon);
    }
    // The 1:50 spilling beach (CoastScene.h), its own world, in this context.
    const auto beach = render::test::spillingBeach();
    const ocean_render::OceanOptions bo = beach->options();  // coarseMiddle on by default
    auto beachOcean = std::make_shared<ocean_render::OceanRenderer>(beach->grids, beach->snap->landSea, bo);
    auto beachLayer = std::make_shared<VertexOnlyLayer>(beachOcean);
    render::GlobeRenderer beachRenderer(beach->world);
    beachRenderer.addLayer(beachLayer);
    constexpr double kShore = render::test::kSpillingShoreLon, kMPerDeg = 111320.0;
    struct BeachView {
      const char* name;
      double latDeg, lonDeg, altM, headingDeg, pitchDeg;
    };
    for (const BeachView& v : {BeachView{"beach 60 m (band test)", 0.284, kShore - 70.0 / kMPerDeg, 60.0, 0.0, -30.0},
                               BeachView{"beach 30 m", 0.3, kShore - 400.0 / kMPerDeg, 30.0, 75.0, -22.0},
                               BeachView{"beach 300 m", 0.3, kShore - 1500.0 / kMPerDeg, 300.0, 80.0, -40.0}}) {
      camera::ViewPose p = base;
      p.latDeg = v.latDeg, p.lonDeg = v.lonDeg, p.altM = v.altM, p.headingDeg = v.headingDeg, p.pitchDeg = v.pitchDeg;
      splitRow(v.name, frames, [&](const render::FrameSettings& fs) {
        s.target->bind();
        return beachRenderer.render(p, fs);
      }, *beachLayer, v.latDeg, v.lonDeg);
    }
    return 0;
  }

  // The test's two views (from the north, looking south across the island) and one straight down.
  struct View {
    const char* name;
    double northM, altM, pitchDeg;
  };
  std::printf("bench_coast_frame %dx%d, %d frames per view and renderer (the first of each dropped)\n", base.width,
              base.height, frames);
  std::printf("%-22s | ocean pass cpu ms: field    none  ratio | wall ms: field   none  ratio | "
              "cpu ms: no bands  bands/no bands | cpu ms: no spray  spray/no spray\n", "view");
  for (const View& v : {View{"island 30 m", 350.0, 30.0, -12.0}, View{"island 300 m", 900.0, 300.0, -35.0},
                        View{"island 1 km, down", 0.0, 1000.0, -89.0}}) {
    camera::ViewPose p = base;
    p.latDeg = kLat + v.northM / 110574.0, p.lonDeg = kLon, p.altM = v.altM;
    p.headingDeg = 180.0, p.pitchDeg = v.pitchDeg;
    std::vector<double> cpu[4], wall[4];
    for (int f = 0; f < frames; ++f)
      for (int k = 0; k < 4; ++k) {
        layer->setOcean(k == 0 ? withCoast : k == 1 ? deepOnly : k == 2 ? noBands : noSpray);
        render::FrameSettings fs;
        fs.timeS = 30.0 + f / 30.0;
        fs.sunEcef = render::sunFromLocal(kLat, kLon, 150.0, 40.0);
        fs.timed = true;
        const render::FrameTimes t = s.render(p, fs);
        if (f == 0) continue;  // shader compiles, first uploads
        cpu[k].push_back(t.layersCpuMs);
        wall[k].push_back(t.layersMs);
      }
    const double c0 = median(cpu[0]), c1 = median(cpu[1]), w0 = median(wall[0]), w1 = median(wall[1]);
    const double c2 = median(cpu[2]), c3 = median(cpu[3]);
    std::printf("%-22s |                 %7.1f %7.1f  %5.2f |        %6.1f %6.1f  %5.2f |        %7.1f  %5.2f |"
                "        %7.1f  %5.2f\n",
                v.name, c0, c1, c0 / c1, w0, w1, w0 / w1, c2, c3 / c2, c3, c0 / c3);
  }
  return 0;
}
