// Body-steps per second: each hull kind on each wave model (one core), many
// bodies at once (one and two threads: two Simulations side by side, as the
// Simulation itself steps on one thread), and paper 000's contact-point
// bodies. Prints a Markdown table for docs/PERFORMANCE.md.
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Terrain.h"

#include <glm/gtc/quaternion.hpp>
#include <tbb/global_control.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace geocean;
using namespace geocean::bodies;

namespace {

double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
// Body-steps per second of process CPU time (all threads) of the last
// bodyStepsPerSecond: unlike wall time it does not drop when other
// processes share the cores.
double gCpuRate = 0.0;

std::shared_ptr<const SeaSurface> makeSea(const char* model) {
  if (std::string(model) == "none") return std::make_shared<FlatSea>();
  ocean::Ocean o;
  waves::SeaState s;
  s.windSpeedMps = 10.0;
  s.anchorLatDeg = 30.0, s.anchorLonDeg = -40.0;
  o.setSeaState(*waves::parseModel(model), s);
  return std::make_shared<OceanSea>(o.current());
}

// n bodies on a grid 60 m apart around (30, -40), stepped `steps` times at 60 Hz.
double bodyStepsPerSecond(const HullMesh& hull, bool points, std::shared_ptr<const SeaSurface> sea, int n, int steps,
                          int threads, bool parallel = false, HullForceOptions options = {},
                          ContactPointOptions pointOptions = {}) {
  const double waterline = hull.restingWaterlineZ(0.45);  // once: it is not a step's cost
  auto work = [&](int part, double& seconds) {
    Simulation sim({.stepS = 1.0 / 60, .parallel = parallel});
    auto hf = std::make_shared<HullForce>(std::make_shared<HullMesh>(hull), sea, options);
    const glm::dvec3 ext = hull.maxCorner() - hull.minCorner();
    auto cp = ContactPointForce::hollowCylinderProxy(ext.x, 0.5 * ext.y, 4, sea, pointOptions);
    for (int i = part; i < n; i += threads) {
      const geo::Geodetic p{30.0 + (i / 20) * 5.4e-4, -40.0 + (i % 20) * 6.2e-4, -waterline};
      const geo::EnuFrame f = geo::enuFrame(p);
      BodyState s;
      s.positionEcef = f.originEcef;
      s.orientation = glm::quat_cast(f.rotation());
      const BodyId id = sim.addBody(hull.massProperties(0.45 * 1025), s);
      sim.addBodyForce(id, points ? std::shared_ptr<const ForceModel>(cp) : hf);
    }
    sim.advanceTo(10 / 60.0);  // warm up
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) sim.step();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<double> secs(threads);
  const double c0 = cpuSeconds();
  std::vector<std::thread> pool;
  for (int p = 0; p < threads; ++p) pool.emplace_back(work, p, std::ref(secs[p]));
  for (auto& t : pool) t.join();
  gCpuRate = double(n) * steps / (cpuSeconds() - c0);  // includes the warm-up steps: a small bias, the same for all
  double worst = 0;
  for (double s : secs) worst = std::max(worst, s);
  return double(n) * steps / worst;
}

}  // namespace

// 200 boats on Gerstner, one Simulation stepped sequentially on one
// thread: the sea grid under each hull (HullForce's default) against the
// reference, every vertex queried, in the same run, rounds alternated.
void seaGridTable(const HullMesh& boat, std::shared_ptr<const SeaSurface> gerstner) {
  std::printf("| 200 boats, gerstner, 1 thread | round | sea points per boat-step | body-steps per CPU-s | ratio to every vertex | Hz at one core |\n|---|---|---|---|---|---|\n");
  for (int round = 1; round <= 3; ++round) {
    double ref = 0.0;
    for (double ppw : {0.0, 2.5, 3.0}) {
      HullForceOptions o;
      o.seaGridPointsPerWavelength = ppw;
      // The grid's node count for an upright boat (it varies a little with the heel).
      HullForce probe(std::make_shared<HullMesh>(boat), gerstner, o);
      const geo::Geodetic p{30.0, -40.0, -boat.restingWaterlineZ(0.45)};
      const geo::EnuFrame f = geo::enuFrame(p);
      BodyState s;
      s.positionEcef = f.originEcef;
      s.orientation = glm::quat_cast(f.rotation());
      Simulation one({.stepS = 1.0 / 60});
      const int nodes = probe.evaluate(s, boat.massProperties(0.45 * 1025), one.context(s)).seaGridNodes;
      const int points = nodes > 0 ? nodes + 2 : int(boat.vertices().size()) + 2;
      bodyStepsPerSecond(boat, false, gerstner, 200, 120, 1, false, o);
      const double cpu = gCpuRate;
      if (ppw == 0.0) ref = cpu;
      std::printf("| %s | %d | %d | %.0f | %.2f | %.1f |\n",
                  ppw == 0.0 ? "every vertex (reference)" : (ppw == 2.5 ? "grid, 2.5 per lambda_min" : "grid, 3 per lambda_min"),
                  round, points, cpu, cpu / ref, cpu / 200.0);
    }
  }
}

// 1,000 contact-point bodies (paper 000, 8 points each) in one Simulation,
// sequential on one thread, against the goal (60 Hz on one core = 60,000
// body-steps per CPU-second). References in the same run, rounds
// alternated: the same bodies with the water's velocity queried at every
// point (the code before ContactPointOptions::waterVelocityAtEachPoint
// became false) and on the flat sea (no sea query at all).
void pointsTable(const HullMesh& boat, std::shared_ptr<const SeaSurface> flat, std::shared_ptr<const SeaSurface> gerstner) {
  std::printf("| 1,000 contact-point bodies, 1 thread | round | body-steps per CPU-s | ratio to every point's velocity | Hz at one core | of the 60 Hz goal |\n|---|---|---|---|---|---|\n");
  for (int round = 1; round <= 3; ++round) {
    ContactPointOptions every;
    every.waterVelocityAtEachPoint = true;
    bodyStepsPerSecond(boat, true, gerstner, 1000, 60, 1, false, {}, every);
    const double ref = gCpuRate;
    std::printf("| gerstner, velocity at every point (reference) | %d | %.0f | 1.00 | %.1f | %.2f |\n", round, ref,
                ref / 1000.0, ref / 60000.0);
    bodyStepsPerSecond(boat, true, gerstner, 1000, 60, 1, false);
    const double g = gCpuRate;
    std::printf("| gerstner, velocity at the centre (default) | %d | %.0f | %.2f | %.1f | %.2f |\n", round, g, g / ref,
                g / 1000.0, g / 60000.0);
    bodyStepsPerSecond(boat, true, flat, 1000, 60, 1, false);
    const double f = gCpuRate;
    std::printf("| flat sea | %d | %.0f | %.2f | %.1f | %.2f |\n", round, f, f / ref, f / 1000.0, f / 60000.0);
  }
}

// Terrain sweeps: the cell walk against the quadtree of maxima on the
// 512 x 512 scene of bench_terrain (2 m cells, 50 m relief), segments from
// 5-60 m above the ground going down 0-70 m and 60-100 m above it going
// down 0-20 m (half each), of each ground length;
// CPU microseconds per sweep, the same segments both ways, rounds alternated.
void sweepTable() {
  constexpr int kN = 512;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5), u(0.0, 1.0);
  std::vector<double> h(std::size_t(kN) * kN);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i)
      h[std::size_t(j) * kN + i] = 20 * std::sin(i / 37.0) * std::cos(j / 23.0) + 5 * std::sin(i / 7.0 + j / 11.0) + jitter(rng);
  const HeightField T(geo::Geodetic{46.5, 8.0, 0.0}, kN, kN, 2.0, h);
  std::printf("| ground length | round | cell walk (us per sweep) | quadtree (us per sweep) | walk / quadtree | hits |\n|---|---|---|---|---|---|\n");
  for (double len : {3.0, 30.0, 300.0, 1000.0}) {
    std::vector<std::pair<glm::dvec3, glm::dvec3>> segs;
    for (int k = 0; k < 4000; ++k) {
      const glm::dvec3 a(1024.0 * u(rng), 1024.0 * u(rng), 0.0);
      const double az = 2 * M_PI * u(rng);
      glm::dvec3 b = a + len * glm::dvec3(std::cos(az), std::sin(az), 0.0);
      // Half near the ground (most hit soon), half 60-100 m above it (most fly clear).
      const double z = (std::isnan(T.heightAt(a.x, a.y)) ? 0.0 : T.heightAt(a.x, a.y)) +
                       (k % 2 ? 5.0 + 55.0 * u(rng) : 60.0 + 40.0 * u(rng));
      segs.push_back({{a.x, a.y, z}, {b.x, b.y, z - (k % 2 ? 70.0 : 20.0) * u(rng)}});
    }
    for (int round = 1; round <= 3; ++round) {
      double sec[2];
      int hits = 0;
      for (int way = 0; way < 2; ++way) {
        const double c0 = cpuSeconds();  // CPU time: preemption by other processes is not counted
        int n = 0;
        for (const auto& [a, b] : segs) n += (way == 0 ? T.sweepCellWalk(a, b) : T.sweepQuadtree(a, b)).has_value();
        sec[way] = cpuSeconds() - c0;
        hits = n;
      }
      std::printf("| %.0f m | %d | %.3f | %.3f | %.2f | %d / %zu |\n", len, round, 1e6 * sec[0] / segs.size(),
                  1e6 * sec[1] / segs.size(), sec[0] / sec[1], hits, segs.size());
    }
  }
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "sweeps") {  // only the terrain sweep table
    sweepTable();
    return 0;
  }
  const HullMesh box = HullMesh::box({8.0, 4.0, 2.0}), cyl = HullMesh::cylinder(1.0, 3.0),
                 boat = HullMesh::boat(20.0);
  if (argc > 1 && std::string(argv[1]) == "points") {  // only the 1,000 contact-point bodies table
    pointsTable(boat, makeSea("none"), makeSea("gerstner"));
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "grid") {  // only the sea-grid table
    seaGridTable(boat, makeSea("gerstner"));
    return 0;
  }
  const char* models[] = {"none", "noise", "gerstner", "fft"};
  // Per second of process CPU time: wall time drops when other processes share the cores.
  std::printf("| body-steps per CPU-s, hull (triangles) | none | noise | gerstner | fft |\n|---|---|---|---|---|\n");
  struct H {
    const char* name;
    const HullMesh* h;
    bool points;
  } hulls[] = {{"box", &box, false}, {"cylinder", &cyl, false}, {"boat", &boat, false}, {"contact points (8)", &boat, true}};
  std::vector<std::shared_ptr<const SeaSurface>> seas;
  for (const char* m : models) seas.push_back(makeSea(m));
  for (const H& h : hulls) {
    std::printf("| %s (%zu) |", h.name, h.points ? std::size_t(0) : h.h->triangleCount());
    for (std::size_t m = 0; m < seas.size(); ++m) {
      bodyStepsPerSecond(*h.h, h.points, seas[m], 20, 300, 1);
      std::printf(" %.0f |", gCpuRate);
    }
    std::printf("\n");
  }
  if (argc > 1 && std::string(argv[1]) == "hulls") return 0;  // only the hull x wave model table
  const auto gerstner = seas[2];
  for (int threads : {1, 2}) {
    const double boats = bodyStepsPerSecond(boat, false, gerstner, 200, 120, threads);
    const double pts = bodyStepsPerSecond(boat, true, gerstner, 1000, 60, threads);
    std::printf("threads %d (sequential Simulations side by side): 200 boats on gerstner %.0f body-steps/s = %.1f Hz; 1000 contact-point bodies %.0f body-steps/s = %.1f Hz\n",
                threads, boats, boats / 200, pts, pts / 1000);
  }
  // One Simulation, its per-body phases sequential (the reference) or on
  // TBB (SimulationConfig::parallel), with TBB limited to 1 and to 2
  // threads; alternated twice in this run so load from other processes
  // hits both alike.
  std::printf("| 200 boats, gerstner, one Simulation | round | body-steps/s (wall) | Hz (wall) | wall ratio | body-steps per CPU-s | CPU ratio |\n|---|---|---|---|---|---|---|\n");
  for (int round = 1; round <= 2; ++round) {
    const double seq = bodyStepsPerSecond(boat, false, gerstner, 200, 120, 1, false), seqCpu = gCpuRate;
    std::printf("| sequential | %d | %.0f | %.1f | 1.00 | %.0f | 1.00 |\n", round, seq, seq / 200, seqCpu);
    for (int tt : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, tt);
      const double par = bodyStepsPerSecond(boat, false, gerstner, 200, 120, 1, true), parCpu = gCpuRate;
      std::printf("| TBB, %d thread%s | %d | %.0f | %.1f | %.2f | %.0f | %.2f |\n", tt, tt > 1 ? "s" : "", round, par,
                  par / 200, par / seq, parCpu, parCpu / seqCpu);
    }
  }
  seaGridTable(boat, gerstner);
  for (int tt : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, tt);
    const double seq = bodyStepsPerSecond(boat, true, gerstner, 1000, 60, 1, false);
    const double par = bodyStepsPerSecond(boat, true, gerstner, 1000, 60, 1, true);
    std::printf("1000 contact-point bodies, TBB %d thread(s): sequential %.0f, TBB %.0f body-steps/s (%.1f Hz), ratio %.2f\n",
                tt, seq, par, par / 1000, par / seq);
  }
}
