// bench_coast_follow (issue 15 item 1): how long the coast region's follow
// rebuild takes (Ocean::followCoastRegion: the new region built on its
// worker from the current snapshot, published at a later call) and how it
// scales with the region's size and node count. The scene is
// OceanCoast.RegionFollowsAFlightAlongTheCoast's: a 1:50 planar shelf down
// from a straight shore, a 10 m/s Gerstner sea blowing onshore; each round
// moves the nadir 0.6 region sizes along the shore (so every call starts a
// build), waits for the worker and publishes. Reported per rebuild: the
// wall time from Started to the build's end and the process CPU time over
// it (the worker plus the island table's TBB threads), and, as the same-run
// reference in alternate rounds, CoastField::build of the same region on
// the calling thread (what the worker spends on the field; the rest is the
// snapshot copy and the SeaQuery). Load from other processes hits both
// alike. A second reference, in each round too: 4096 deep-water Gerstner
// heights (WaveField::surfaceAt, the scalar query of bench_coast's
// BM_DeepQuery/0), so a build reads as so many queries' CPU time on any
// machine. --dutch instead: the bundled world off the Dutch coast (no deep
// inflow, so the region reads waves::OuterPhase): the outer phase's build
// alone (200 km, 401^2 nodes, components on TBB), the first region
// (setCoastRegion: outer + field), the follow rebuilds that reuse the outer,
// and the field alone without it on this thread (the reference).
// Not run by ctest; figures in docs/PERFORMANCE.md.
//   bench_coast_follow [--rounds N] [--components N] [--dutch 1]
#include "globe/geo/Ellipsoid.h"
#include "globe/raster/Raster.h"
#include "plugin/ocean/Ocean.h"
#include "plugin/waves/CoastField.h"
#include "tests/support/Median.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace geocean;

namespace {

using geocean::test::median;

double cpuS() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
double wallS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// 0.001-degree cells over lon -0.3 .. 0.1, lat -0.5 .. 1.5: the shore on
// lon 0.04, depth 2 % of the distance from it (534 m at lon -0.2, as the
// tests' shelf; deeper further out).
constexpr int kW = 400, kH = 2000;
const raster::GeoTransform kPlace{-0.3, 1.5, 0.001, -0.001, false};
double lonOf(int x) { return -0.3 + (x + 0.5) * 0.001; }

// The depth as the façade samples it (plugin/ocean/Ocean.cpp, depthAbout).
std::function<double(double, double)> depthAbout(const std::shared_ptr<const ocean::Snapshot>& snap, double latDeg,
                                                 double lonDeg) {
  const geo::EnuFrame f = geo::enuFrame({latDeg, lonDeg, 0.0});
  return [snap, f](double e, double n) {
    const geo::Geodetic g = geo::fromEcef(f.originEcef + f.east * e + f.north * n);
    world::Surface s;
    snap->landSea->classifyBatch(&g.latDeg, &g.lonDeg, 1, &s);
    if (s != world::Surface::Ocean) return 0.0;
    float el = std::numeric_limits<float>::quiet_NaN();
    snap->landSea->elevationBatch(&g.latDeg, &g.lonDeg, 1, &el);
    return std::isnan(el) ? waves::kDeepWaterM : std::max(-double(el), 1.0);
  };
}

int benchDutch(int rounds, int components) {
  std::vector<double> ow, oc, sw, sc, fw, fc, bw, bc;
  int outerComps = 0;
  for (int k = 0; k < rounds; ++k) {
    ocean::Ocean o;
    o.setDefaultWorld(ocean::Ocean::defaultWorldDir());
    waves::SeaState sea;
    sea.windSpeedMps = 12.0;
    sea.windFromDeg = 270.0;
    sea.gerstnerComponents = components;
    o.setSeaState(waves::Model::Gerstner, sea);
    waves::CoastField::Region r;
    r.latDeg = 52.6, r.lonDeg = 4.45, r.nodes = 201, r.cellM = 50.0;
    const auto snap0 = o.current();
    double lat = 0.0, lon = 0.0;
    waves::OuterPhase::latticePoint(r.latDeg, r.lonDeg, lat, lon);
    std::string err;
    const double w0 = wallS(), c0 = cpuS();
    const waves::OuterPhase op = waves::OuterPhase::build(*snap0->waves, lat, lon, depthAbout(snap0, lat, lon), err);
    const double w1 = wallS(), c1 = cpuS();
    if (op.empty()) {
      std::fprintf(stderr, "bench_coast_follow: %s\n", err.c_str());
      return 1;
    }
    o.setCoastRegion(r);
    const double w2 = wallS(), c2 = cpuS();
    const auto snap = o.current();
    outerComps = snap->waves->coastField()->outerComponents();
    // One follow rebuild 0.6 sizes north (the outer kept).
    if (o.followCoastRegion(r.latDeg + 0.054, r.lonDeg) != ocean::Ocean::CoastFollow::Started) return 1;
    o.waitForCoastBuild();
    const double w3 = wallS(), c3 = cpuS();
    if (o.followCoastRegion(r.latDeg + 0.054, r.lonDeg) != ocean::Ocean::CoastFollow::Swapped) return 1;
    if (o.current()->coastOuter != snap->coastOuter) {
      std::fprintf(stderr, "bench_coast_follow: the follow build did not keep the outer phase\n");
      return 1;
    }
    // The reference: the first region's field without the outer, this thread.
    const double w4 = wallS(), c4 = cpuS();
    const waves::CoastField cf =
        waves::CoastField::build(*snap->waves, r, depthAbout(snap, r.latDeg, r.lonDeg), err);
    const double w5 = wallS(), c5 = cpuS();
    if (cf.empty()) return 1;
    if (k == 0) continue;
    ow.push_back(1e3 * (w1 - w0)), oc.push_back(1e3 * (c1 - c0));
    sw.push_back(1e3 * (w2 - w1)), sc.push_back(1e3 * (c2 - c1));
    fw.push_back(1e3 * (w3 - w2)), fc.push_back(1e3 * (c3 - c2));
    bw.push_back(1e3 * (w5 - w4)), bc.push_back(1e3 * (c5 - c4));
  }
  std::printf("bench_coast_follow --dutch: 52.6 N 4.45 E, 12 m/s from 270, %d components (%d read the outer), "
              "region 201^2 x 50 m; medians of %d rounds (first dropped), wall / CPU ms\n",
              components, outerComps, rounds - 1);
  std::printf("outer phase alone (401^2 x 500 m)      %8.0f / %7.0f\n", median(ow), median(oc));
  std::printf("setCoastRegion (outer + field)         %8.0f / %7.0f\n", median(sw), median(sc));
  std::printf("follow rebuild (outer kept)            %8.0f / %7.0f\n", median(fw), median(fc));
  std::printf("field alone, no outer (reference)      %8.0f / %7.0f\n", median(bw), median(bc));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 5, components = 16;
  bool dutch = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "bench_coast_follow: %s needs a value\n", a.c_str());
      return 2;
    }
    if (a == "--rounds") rounds = std::atoi(argv[++i]);
    else if (a == "--components") components = std::atoi(argv[++i]);
    else if (a == "--dutch") dutch = std::atoi(argv[++i]) != 0;
    else {
      std::fprintf(stderr, "bench_coast_follow: unknown option '%s'\n", a.c_str());
      return 2;
    }
  }
  if (rounds < 2 || components < 1 || components > 64) {
    std::fprintf(stderr, "bench_coast_follow: --rounds %d must be >= 2 and --components %d in 1 .. 64\n", rounds,
                 components);
    return 2;
  }
  if (dutch) return benchDutch(rounds, components);
  std::vector<float> elev(std::size_t(kW) * kH), land(std::size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      elev[std::size_t(y) * kW + x] = float(-0.02 * (0.04 - lonOf(x)) * 111320.0);
      land[std::size_t(y) * kW + x] = lonOf(x) > 0.04 ? 1.0f : 0.0f;
    }
  const auto elevation = raster::Raster::fromPixels(elev, kW, kH, 1, kPlace, std::nullopt, "shelf");
  const auto mask = raster::Raster::fromPixels(land, kW, kH, 1, kPlace, std::nullopt, "shelf_mask");

  struct Case {
    const char* name;
    int nodes;
    double sizeM;
  };
  std::printf("bench_coast_follow: %d rounds per case (first dropped), %d Gerstner components, 10 m/s onshore\n",
              rounds, components);
  std::printf("%-34s | follow rebuild: wall ms  cpu ms | same-thread build: wall ms  cpu ms | rebuild / build (wall) "
              "| deep query cpu us | rebuild cpu in deep queries\n",
              "region");
  // 201 nodes over the size is the C ABI's and the CLI's rule (10 km the default); the
  // last rows vary the node count at 50 m cells (the façade's Region::nodes).
  for (const Case& c : {Case{"201^2 nodes, 2.5 km (12.5 m cells)", 201, 2500.0},
                        Case{"201^2 nodes, 10 km (default)", 201, 10000.0},
                        Case{"201^2 nodes, 40 km (200 m cells)", 201, 40000.0},
                        Case{"101^2 nodes, 5 km (50 m cells)", 101, 5000.0},
                        Case{"401^2 nodes, 20 km (50 m cells)", 401, 20000.0}}) {
    ocean::Ocean o;
    o.setRasters(mask, elevation);
    waves::SeaState sea;
    sea.windSpeedMps = 10.0;
    sea.windFromDeg = 240.0;
    sea.anchorLatDeg = 0.3;
    sea.gerstnerComponents = components;
    o.setSeaState(waves::Model::Gerstner, sea);
    waves::CoastField::Region r;
    r.latDeg = 0.0, r.lonDeg = -0.01, r.nodes = c.nodes, r.cellM = c.sizeM / (c.nodes - 1);
    o.setCoastRegion(r);
    if (!o.current()->waves->coastField()) {
      std::fprintf(stderr, "bench_coast_follow: no coast field was built for %s\n", c.name);
      return 1;
    }
    std::vector<double> fw, fc, bw, bc, qc;
    double lat = r.latDeg;
    for (int k = 0; k < rounds; ++k) {
      // The follow rebuild: 0.6 sizes north, outside the middle half.
      lat += 0.6 * c.sizeM / 110574.0;
      const double w0 = wallS(), c0 = cpuS();
      if (o.followCoastRegion(lat, r.lonDeg) != ocean::Ocean::CoastFollow::Started) {
        std::fprintf(stderr, "bench_coast_follow: no build started for %s\n", c.name);
        return 1;
      }
      o.waitForCoastBuild();
      const double w1 = wallS(), c1 = cpuS();
      if (o.followCoastRegion(lat, r.lonDeg) != ocean::Ocean::CoastFollow::Swapped) {
        std::fprintf(stderr, "bench_coast_follow: the build for %s was not published\n", c.name);
        return 1;
      }
      // The reference: the same region's field on this thread.
      const auto snap = o.current();
      const geo::EnuFrame f = geo::enuFrame({snap->coastRegion->latDeg, snap->coastRegion->lonDeg, 0.0});
      // As the façade samples the depth (plugin/ocean/Ocean.cpp, buildCoastField).
      const auto depthAt = [&](double e, double n) {
        const geo::Geodetic g = geo::fromEcef(f.originEcef + f.east * e + f.north * n);
        world::Surface s;
        snap->landSea->classifyBatch(&g.latDeg, &g.lonDeg, 1, &s);
        if (s != world::Surface::Ocean) return 0.0;
        float el = std::numeric_limits<float>::quiet_NaN();
        snap->landSea->elevationBatch(&g.latDeg, &g.lonDeg, 1, &el);
        return std::isnan(el) ? waves::kDeepWaterM : std::max(-double(el), 1.0);
      };
      std::string err;
      const double w2 = wallS(), c2 = cpuS();
      const waves::CoastField cf = waves::CoastField::build(*snap->waves, *snap->coastRegion, depthAt, err);
      const double w3 = wallS(), c3 = cpuS();
      if (cf.empty()) {
        std::fprintf(stderr, "bench_coast_follow: %s\n", err.c_str());
        return 1;
      }
      // The query reference: 4096 deep-water heights 55 m apart west of the
      // shelf, the sea without a coast field (CPU time, this thread).
      waves::WaveField plain = *snap->waves;
      plain.setCoast(nullptr);
      const double c4 = cpuS();
      double sum = 0.0;
      for (int i = 0; i < 4096; ++i)
        sum += plain.surfaceAt(0.25 + 0.0005 * (i % 64), -0.25 + 0.0005 * (i / 64), 3.5, waves::kDeepWaterM).heightM;
      const double c5 = cpuS();
      if (!std::isfinite(sum)) return 1;
      if (k == 0) continue;  // first touches of the rasters and allocator
      qc.push_back(1e6 * (c5 - c4) / 4096.0);
      fw.push_back(1e3 * (w1 - w0)), fc.push_back(1e3 * (c1 - c0));
      bw.push_back(1e3 * (w3 - w2)), bc.push_back(1e3 * (c3 - c2));
    }
    std::printf("%-34s |                 %8.0f %7.0f |            %8.0f %7.0f |                  %5.2f | %17.2f | %9.0f\n",
                c.name, median(fw), median(fc), median(bw), median(bc), median(fw) / median(bw), median(qc),
                1e3 * median(fc) / median(qc));
  }
  return 0;
}
