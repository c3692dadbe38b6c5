// Grid build cost against two limits measured in the same run: the bare
// analytic ray/ellipsoid loop over the same rays, and the memory bandwidth
// needed to write the vertex buffer. Also Embree's user geometry (float) on
// the same rays, and ISPG vs direct. Built, never run by ctest; see
// docs/PERFORMANCE.md "LOD grid and picking".
#include "globe/raster/World.h"
#include "plugin/grid/RayKernels.h"
#include "plugin/grid/ScreenGrid.h"
#include "plugin/landsea/LandSea.h"

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

using namespace geocean;

namespace {
// Gibraltar strait from 2 km, looking east and down: land, sea and sky.
const camera::Camera& benchCamera() {
  static const camera::Camera c = camera::Camera::fromGeodetic({36.0, -6.5, 2000.0, 90.0, -20.0, 0.0}, 60.0, 1280, 720);
  return c;
}

ocean::SurfaceClassifier worldClassifier() {
  static ocean::SurfaceClassifier c = [] {
    try {
      auto mask = raster::Raster::open(raster::defaultWorld().mask);
      return ocean::classifierFor(std::make_shared<ocean::LandSea>(mask, nullptr));
    } catch (const std::exception&) {
      return ocean::SurfaceClassifier{};  // no data: all ocean
    }
  }();
  return c;
}

void BM_GridBuild(benchmark::State& st) {
  const int n = int(st.range(0)), threads = int(st.range(1));
  grid::GridOptions o;
  o.cols = o.rows = n;
  o.threads = threads;
  o.maxDisplacementM = 5.0;
  o.mode = st.range(2) ? grid::GridMode::Ispg : grid::GridMode::Direct;
  grid::ScreenGrid g(o, st.range(3) ? worldClassifier() : ocean::SurfaceClassifier{});
  grid::GridFrame f;
  g.build(benchCamera(), f);
  for (auto _ : st) {
    g.build(benchCamera(), f);
    benchmark::DoNotOptimize(f.vertices.data());
  }
  st.counters["vertices/s"] = benchmark::Counter(double(n) * n, benchmark::Counter::kIsIterationInvariantRate);
  st.counters["land_cells"] = double(f.landCells);
  std::size_t horizon = 0;
  for (const grid::GridVertex& v : f.vertices) horizon += (v.flags & grid::kVertexHorizon) != 0;
  st.counters["horizon_frac"] = double(horizon) / double(f.vertices.size());
}

// The bare loop: the same rays (generation + intersection + store t),
// nothing else, with the grid's own vectorised, multi-versioned kernels
// (rayRow, intersectEllipsoidBatch). Before 2026-11-30 the rays were made
// here with a division per ray in a baseline-only loop, which made this
// reference ~1.4x slower and the grid's ratios look better than they were.
void BM_BareLoop(benchmark::State& st) {
  const int n = int(st.range(0)), threads = int(st.range(1));
  const camera::Camera& cam = benchCamera();
  tbb::task_arena arena(threads);
  std::vector<double> t(std::size_t(n) * n);
  const double eye[3] = {cam.eyeEcef().x, cam.eyeEcef().y, cam.eyeEcef().z};
  const glm::dvec3 F = cam.forward(), R = cam.right() * cam.tanHalfX(), U = cam.up() * cam.tanHalfY();
  const double Fa[3] = {F.x, F.y, F.z}, Ra[3] = {R.x, R.y, R.z}, Ua[3] = {U.x, U.y, U.z};
  for (auto _ : st) {
    arena.execute([&] {
      tbb::parallel_for(0, n, [&](int j) {
        thread_local std::vector<double> dx, dy, dz;
        dx.resize(n), dy.resize(n), dz.resize(n);
        const double y = -1.0 + 2.0 * j / (n - 1);
        grid::rayRow(Fa, Ra, Ua, -1.0, 2.0 / (n - 1), y, std::size_t(n), dx.data(), dy.data(), dz.data());
        grid::intersectEllipsoidBatch(eye, dx.data(), dy.data(), dz.data(), n, 0.0, t.data() + std::size_t(j) * n);
      });
    });
    benchmark::DoNotOptimize(t.data());
  }
  st.counters["rays/s"] = benchmark::Counter(double(n) * n, benchmark::Counter::kIsIterationInvariantRate);
}

// The lat/lon kernel before 2026-11-30 (Cephes' (4, 5) rational atan, 4
// divisions + 1 sqrt per vertex), kept as the reference for BM_LatLonCephes:
// same clones and FP flags as the library (tests/grid/CMakeLists.txt).
#define GEOCEAN_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
constexpr double kPi = 3.14159265358979323846, kPiO2 = 1.57079632679489661923, kPiO4 = 0.78539816339744830962;
inline double atanRatio(double num, double den) {
  const bool big = num > 0.41421356237309504880 * den;
  const double x = (big ? num - den : num) / (big ? num + den : den);
  const double base = big ? kPiO4 : 0.0;
  const double zz = x * x;
  const double p = (((-8.750608600031904122785e-1 * zz - 1.615753718733365076637e1) * zz -
                     7.500855792314704667340e1) * zz - 1.228866684490136173410e2) * zz -
                   6.485021904942025371773e1;
  const double q = ((((zz + 2.485846490142306297962e1) * zz + 1.650270098316988542046e2) * zz +
                     4.328810604912902668951e2) * zz + 4.853903996359136964868e2) * zz +
                   1.945506571482613964425e2;
  return base + (x * (zz * p / q) + x);
}

inline double atan2Fast(double y, double x) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool swap = ay > ax;
  const double num = swap ? ax : ay;
  const double den = std::max(swap ? ay : ax, 2.2250738585072014e-308);
  double r = atanRatio(num, den);
  r = swap ? kPiO2 - r : r;
  r = x < 0.0 ? kPi - r : r;
  return std::copysign(r, y);
}

inline double atan2PosX(double y, double x) {
  const double ay = std::fabs(y);
  const bool swap = ay > x;
  const double num = swap ? x : ay;
  const double den = std::max(swap ? ay : x, 2.2250738585072014e-308);
  double r = atanRatio(num, den);
  r = swap ? kPiO2 - r : r;
  return std::copysign(r, y);
}

GEOCEAN_CLONES
void cephesLatLonBatch(const double eye[3], const double* __restrict rx, const double* __restrict ry,
                       const double* __restrict rz, std::size_t n, double* __restrict latDeg,
                       double* __restrict lonDeg) {
  constexpr double e2c = (1.0 - geo::kWgs84F) * (1.0 - geo::kWgs84F);  // 1 - e^2 = (b/a)^2
  constexpr double toDeg = 180.0 / kPi;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = eye[0] + rx[i], y = eye[1] + ry[i], z = eye[2] + rz[i];
    const double p = std::sqrt(x * x + y * y);
    latDeg[i] = atan2PosX(z, e2c * p) * toDeg;
    lonDeg[i] = atan2Fast(y, x) * toDeg;
  }
}


// A lat/lon kernel alone over the hit points of the same rays, row by row
// as the grid passes them.
template <class Kernel>
void latLonBench(benchmark::State& st, Kernel kernel) {
  const int n = int(st.range(0)), threads = int(st.range(1));
  const camera::Camera& cam = benchCamera();
  tbb::task_arena arena(threads);
  const double eye[3] = {cam.eyeEcef().x, cam.eyeEcef().y, cam.eyeEcef().z};
  const glm::dvec3 F = cam.forward(), R = cam.right() * cam.tanHalfX(), U = cam.up() * cam.tanHalfY();
  const double Fa[3] = {F.x, F.y, F.z}, Ra[3] = {R.x, R.y, R.z}, Ua[3] = {U.x, U.y, U.z};
  // Per row: the hit span's eye-relative points, as the grid passes them.
  const auto sn = static_cast<std::size_t>(n);
  std::vector<std::vector<double>> px(sn), py(sn), pz(sn);
  std::vector<double> t(sn), rx(sn), ry(sn), rz(sn);
  std::size_t points = 0;
  for (int j = 0; j < n; ++j) {
    grid::surfaceHitsRow(eye, Fa, Ra, Ua, -1.0, 2.0 / (n - 1), -1.0 + 2.0 * j / (n - 1), std::size_t(n), t.data(),
                         rx.data(), ry.data(), rz.data());
    for (int i = 0; i < n; ++i)
      if (!std::isnan(t[std::size_t(i)])) {
        px[std::size_t(j)].push_back(rx[std::size_t(i)]);
        py[std::size_t(j)].push_back(ry[std::size_t(i)]);
        pz[std::size_t(j)].push_back(rz[std::size_t(i)]);
      }
    points += px[std::size_t(j)].size();
  }
  std::vector<double> lat(std::size_t(n) * n), lon(std::size_t(n) * n);
  for (auto _ : st) {
    arena.execute([&] {
      tbb::parallel_for(0, n, [&](int j) {
        const auto& x = px[std::size_t(j)];
        kernel(eye, x.data(), py[std::size_t(j)].data(), pz[std::size_t(j)].data(), x.size(),
               lat.data() + std::size_t(j) * n, lon.data() + std::size_t(j) * n);
      });
    });
    benchmark::DoNotOptimize(lat.data());
  }
  st.counters["points/s"] = benchmark::Counter(double(points), benchmark::Counter::kIsIterationInvariantRate);
  st.counters["hit_frac"] = double(points) / (double(n) * n);
}

// The grid's lat/lon kernel (two double atan2 and a sqrt per point): its
// largest part after the bare loop.
void BM_LatLonKernel(benchmark::State& st) { latLonBench(st, grid::surfaceLatLonBatch); }

// The same over Cephes' kernel: the A/B of the current kernel in one run.
void BM_LatLonCephes(benchmark::State& st) { latLonBench(st, cephesLatLonBatch); }

// Writing the vertex buffer's bytes (32 per vertex) at memory speed.
void BM_WriteVertexBytes(benchmark::State& st) {
  const int n = int(st.range(0)), threads = int(st.range(1));
  tbb::task_arena arena(threads);
  std::vector<grid::GridVertex> v(std::size_t(n) * n);
  for (auto _ : st) {
    arena.execute([&] {
      tbb::parallel_for(0, n, [&](int j) {
        std::memset(static_cast<void*>(v.data() + std::size_t(j) * n), j & 0xff, sizeof(grid::GridVertex) * n);
      });
    });
    benchmark::DoNotOptimize(v.data());
  }
  st.SetBytesProcessed(std::int64_t(st.iterations()) * n * n * std::int64_t(sizeof(grid::GridVertex)));
}

// Embree 3 with a float ray/ellipsoid user geometry (what Embree offers for
// an analytic surface), rtcIntersect16 over the same rays, eye at the origin.
struct FloatEllipsoid {
  float cx, cy, cz;  // ellipsoid centre relative to the eye
};
void ellBounds(const RTCBoundsFunctionArguments* a) {
  const auto* e = static_cast<const FloatEllipsoid*>(a->geometryUserPtr);
  const float A = float(geo::kWgs84A), B = float(geo::kWgs84B);
  *a->bounds_o = {e->cx - A, e->cy - A, e->cz - B, 0, e->cx + A, e->cy + A, e->cz + B, 0};
}
void ellIntersect(const RTCIntersectFunctionNArguments* a) {
  const auto* e = static_cast<const FloatEllipsoid*>(a->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(a->rayhit, a->N);
  RTCHitN* hit = RTCRayHitN_HitN(a->rayhit, a->N);
  const float ia = 1.0f / float(geo::kWgs84A), ib = 1.0f / float(geo::kWgs84B);
  for (unsigned i = 0; i < a->N; ++i) {
    if (a->valid[i] != -1) continue;
    const float ox = (RTCRayN_org_x(ray, a->N, i) - e->cx) * ia, oy = (RTCRayN_org_y(ray, a->N, i) - e->cy) * ia,
                oz = (RTCRayN_org_z(ray, a->N, i) - e->cz) * ib;
    const float dx = RTCRayN_dir_x(ray, a->N, i) * ia, dy = RTCRayN_dir_y(ray, a->N, i) * ia,
                dz = RTCRayN_dir_z(ray, a->N, i) * ib;
    const float A = dx * dx + dy * dy + dz * dz, B = ox * dx + oy * dy + oz * dz, C = ox * ox + oy * oy + oz * oz - 1.0f;
    const float disc = B * B - A * C;
    if (disc < 0.0f) continue;
    const float t = (-B - std::sqrt(disc)) / A;
    if (t < RTCRayN_tnear(ray, a->N, i) || t > RTCRayN_tfar(ray, a->N, i)) continue;
    RTCRayN_tfar(ray, a->N, i) = t;
    RTCHitN_geomID(hit, a->N, i) = a->geomID;
    RTCHitN_primID(hit, a->N, i) = 0;
  }
}

void BM_EmbreeUserEllipsoid(benchmark::State& st) {
  const int n = int(st.range(0)), threads = int(st.range(1));
  const camera::Camera& cam = benchCamera();
  RTCDevice dev = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(dev);
  FloatEllipsoid ell{float(-cam.eyeEcef().x), float(-cam.eyeEcef().y), float(-cam.eyeEcef().z)};
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, &ell);
  rtcSetGeometryBoundsFunction(g, ellBounds, nullptr);
  rtcSetGeometryIntersectFunction(g, ellIntersect);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  tbb::task_arena arena(threads);
  std::vector<float> t(std::size_t(n) * n);
  const glm::dvec3 F = cam.forward(), R = cam.right() * cam.tanHalfX(), U = cam.up() * cam.tanHalfY();
  for (auto _ : st) {
    arena.execute([&] {
      tbb::parallel_for(0, n, [&](int j) {
        const double y = -1.0 + 2.0 * j / (n - 1);
        for (int i0 = 0; i0 < n; i0 += 16) {
          alignas(64) RTCRayHit16 rh;
          alignas(64) int valid[16];
          for (int k = 0; k < 16; ++k) {
            const int i = std::min(i0 + k, n - 1);
            const double x = -1.0 + 2.0 * i / (n - 1);
            const glm::dvec3 d = F + x * R + y * U;
            rh.ray.org_x[k] = rh.ray.org_y[k] = rh.ray.org_z[k] = 0.0f;
            rh.ray.dir_x[k] = float(d.x), rh.ray.dir_y[k] = float(d.y), rh.ray.dir_z[k] = float(d.z);
            rh.ray.tnear[k] = 0.0f;
            rh.ray.tfar[k] = INFINITY;
            rh.ray.mask[k] = ~0u;
            rh.ray.flags[k] = 0;
            rh.ray.time[k] = 0.0f;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            valid[k] = i0 + k < n ? -1 : 0;
          }
          RTCIntersectContext ctx;
          rtcInitIntersectContext(&ctx);
          ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
          rtcIntersect16(valid, scene, &ctx, &rh);
          for (int k = 0; k < 16 && i0 + k < n; ++k) t[std::size_t(j) * n + i0 + k] = rh.ray.tfar[k];
        }
      });
    });
    benchmark::DoNotOptimize(t.data());
  }
  st.counters["rays/s"] = benchmark::Counter(double(n) * n, benchmark::Counter::kIsIterationInvariantRate);
  rtcReleaseScene(scene);
  rtcReleaseDevice(dev);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {128, 256, 512, 1024})
    for (int threads : {1, 2}) b->Args({n, threads});
}
void gridSizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"n", "threads", "ispg", "landsea"});
  for (int n : {128, 256, 512, 1024})
    for (int threads : {1, 2}) b->Args({n, threads, 0, 1});
  for (int n : {128, 256, 512, 1024}) b->Args({n, 1, 0, 0});  // without land/sea
  for (int n : {128, 256, 512, 1024}) b->Args({n, 1, 1, 0});  // ISPG, without land/sea
}
}  // namespace

BENCHMARK(BM_GridBuild)->Apply(gridSizes)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BareLoop)->Apply(sizes)->ArgNames({"n", "threads"})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LatLonKernel)->Apply(sizes)->ArgNames({"n", "threads"})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LatLonCephes)->Apply(sizes)->ArgNames({"n", "threads"})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WriteVertexBytes)->Apply(sizes)->ArgNames({"n", "threads"})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_EmbreeUserEllipsoid)->Apply(sizes)->ArgNames({"n", "threads"})->UseRealTime()->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("kernel_isa", grid::kernelIsa());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
