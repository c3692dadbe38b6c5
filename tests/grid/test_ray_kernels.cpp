// The SIMD batch kernels against the scalar double path (geo::intersectEllipsoid,
// itself tested against long double) and GeographicLib's inverse.
#include "plugin/grid/RayKernels.h"
#include "plugin/grid/ScreenGrid.h"

#include "globe/geo/Ellipsoid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace geocean;

TEST(RayKernels, BatchMatchesScalarIntersection) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), logAlt(-1.0, 7.3);
  int hits = 0, compared = 0;
  for (int e = 0; e < 200; ++e) {
    const double alt = std::pow(10.0, logAlt(rng));
    const glm::dvec3 eye = geo::toEcef({90 * u(rng), 180 * u(rng), e % 10 == 0 ? -alt : alt});
    const double eyeArr[3] = {eye.x, eye.y, eye.z};
    const std::size_t n = 37;  // odd: exercises the vector remainder
    std::vector<double> dx(n), dy(n), dz(n), t(n);
    for (std::size_t i = 0; i < n; ++i) {
      glm::dvec3 d = glm::dvec3(u(rng), u(rng), u(rng)) - 0.7 * glm::normalize(eye);
      d *= 0.5 + u(rng) * 0.4;  // not unit: t is in units of |d|
      dx[i] = d.x, dy[i] = d.y, dz[i] = d.z;
    }
    for (double offset : {0.0, 25.0}) {
      grid::intersectEllipsoidBatch(eyeArr, dx.data(), dy.data(), dz.data(), n, offset, t.data());
      for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 d(dx[i], dy[i], dz[i]);
        const geo::RayHit h = geo::intersectEllipsoid(eye, d, offset);
        // Near-grazing rays may flip between hit and miss; skip the ones whose
        // closest approach is within 1 m of the surface.
        const double len = glm::length(d);
        const geo::RayHit in = geo::intersectEllipsoid(eye, d, offset - 1.0), out = geo::intersectEllipsoid(eye, d, offset + 1.0);
        if (in.hit != out.hit) continue;
        ++compared;
        ASSERT_EQ(h.hit, !std::isnan(t[i])) << e << " " << i;
        if (!h.hit) continue;
        ++hits;
        // 1 mm along the ray (the scalar path is within 1 mm of long double).
        EXPECT_NEAR(t[i] * len, h.tFirst() * len, 1e-3) << e << " " << i;
      }
    }
  }
  EXPECT_GT(hits, 2000);
  EXPECT_GT(compared, 12000);
}

TEST(RayKernels, OneMetreAboveTheSea) {
  for (double lat : {0.0, 89.99, -45.0}) {
    for (double lon : {0.0, 180.0, -179.9999}) {
      const glm::dvec3 eye = geo::toEcef({lat, lon, 1.0});
      const glm::dvec3 d = -geo::surfaceNormal(lat, lon);
      const double e[3] = {eye.x, eye.y, eye.z};
      double t = 0;
      grid::intersectEllipsoidBatch(e, &d.x, &d.y, &d.z, 1, 0.0, &t);
      EXPECT_NEAR(t, 1.0, 1e-6);  // GeographicLib Forward is exact to rounding (~1 nm here)
    }
  }
}

TEST(RayKernels, SurfaceLatLonMatchesGeographicLib) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const glm::dvec3 eye = geo::toEcef({10.0, 20.0, 3e5});
  const double e[3] = {eye.x, eye.y, eye.z};
  std::vector<double> rx, ry, rz;
  std::vector<geo::Geodetic> truth;
  for (int i = 0; i < 5000; ++i) {
    geo::Geodetic g{90 * u(rng), 180 * u(rng), 0.0};
    if (i < 8) g = {i < 4 ? 90.0 : -90.0, 45.0 * i, 0.0};  // poles
    if (i >= 8 && i < 12) g = {0.0, 180.0 - (i - 8) * 1e-9, 0.0};  // the antimeridian
    const glm::dvec3 p = geo::toEcef(g);
    rx.push_back(p.x - eye.x), ry.push_back(p.y - eye.y), rz.push_back(p.z - eye.z);
    truth.push_back(g);
  }
  std::vector<double> lat(rx.size()), lon(rx.size());
  grid::surfaceLatLonBatch(e, rx.data(), ry.data(), rz.data(), rx.size(), lat.data(), lon.data());
  for (std::size_t i = 0; i < rx.size(); ++i) {
    // 1e-11 deg = 1 micrometre: the rounding of the ECEF point (1e-9 m) and
    // the kernel's own 1e-15 rad (SurfaceLatLonMatchesLongDouble); far below
    // the 7 nm of GeographicLib.
    EXPECT_NEAR(lat[i], truth[i].latDeg, 1e-11) << i;
    if (std::abs(truth[i].latDeg) < 90.0) {
      const double dLon = geo::wrapLonDeg(lon[i] - truth[i].lonDeg);
      EXPECT_NEAR(dLon * std::cos(truth[i].latDeg * M_PI / 180), 0.0, 1e-11) << i;
    }
  }
  const double nan = std::nan(""), zero = 0;
  double la, lo;
  grid::surfaceLatLonBatch(e, &nan, &zero, &zero, 1, &la, &lo);
  EXPECT_TRUE(std::isnan(la) && std::isnan(lo));
}

// The kernel's arctangent on its own: lat = atan2(z, (1 - e^2) p) and
// lon = atan2(y, x) of the same double inputs in long double (64-bit
// mantissa), over every octant and both reductions (|ratio| on both sides of
// tan(pi/8)), at any radius, plus the special points. Bound 1e-13 deg: the
// rational's 1.6e-16 rad, the rounding of the reduced argument and of the
// octant constants (<= 1e-15 rad together, 5.7e-14 deg) and of the final
// multiplication by 180/pi (half an ulp of 180, 1.4e-14 deg).
TEST(RayKernels, SurfaceLatLonMatchesLongDouble) {
  constexpr double e2c = (1.0 - geo::kWgs84F) * (1.0 - geo::kWgs84F);  // as the kernel
  const long double toDeg = 180.0L / 3.141592653589793238462643383279502884L;
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1, 1), logR(-3.0, 8.0);
  std::vector<double> x, y, z;
  for (int i = 0; i < 200000; ++i) {
    const double r = std::pow(10.0, logR(rng));
    x.push_back(r * u(rng)), y.push_back(r * u(rng)), z.push_back(r * u(rng));
  }
  // Near the reduction thresholds tan(pi/8), 1 (octant swap) and the axes.
  for (double t : {0.41421356237309504880, 1.0, 1e-12, 0.0})
    for (double e : {-1e-15, 0.0, 1e-15})
      for (double sx : {-1.0, 1.0})
        for (double sy : {-1.0, 1.0}) {
          x.push_back(sx * 6.4e6), y.push_back(sy * 6.4e6 * (t + e)), z.push_back(sy * 6.4e6 * e2c * (t + e));
          x.push_back(sx * 6.4e6 * (t + e)), y.push_back(sy * 6.4e6), z.push_back(sx * 3e6);
        }
  std::vector<double> lat(x.size()), lon(x.size());
  const double eye0[3] = {-0.0, -0.0, -0.0};  // -0 + v = v for every v, signed zeros included
  double worst = 0;
  // The dispatched path (FMA on AVX2/AVX-512 CPUs) and the portable one.
  for (auto* kernel : {grid::surfaceLatLonBatch, grid::surfaceLatLonBatchPortable}) {
  kernel(eye0, x.data(), y.data(), z.data(), x.size(), lat.data(), lon.data());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const long double p = std::sqrt((long double)x[i] * x[i] + (long double)y[i] * y[i]);
    const double refLat = double(std::atan2((long double)z[i], (long double)e2c * p) * toDeg);
    const double refLon = double(std::atan2((long double)y[i], (long double)x[i]) * toDeg);
    ASSERT_NEAR(lat[i], refLat, 1e-13) << x[i] << " " << y[i] << " " << z[i];
    ASSERT_NEAR(lon[i], refLon, 1e-13) << x[i] << " " << y[i] << " " << z[i];
    worst = std::max({worst, std::abs(lat[i] - refLat), std::abs(lon[i] - refLon)});
  }
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", worst);
  RecordProperty("max_error_deg", buf);
}

// Signed zeros as std::atan2 (the poles and lon 180 from both sides), NaN in
// any coordinate gives NaN in the angles that use it.
TEST(RayKernels, SurfaceLatLonSpecialValues) {
  const double eye0[3] = {-0.0, -0.0, -0.0};  // -0 + v = v for every v, signed zeros included
  const double nan = std::numeric_limits<double>::quiet_NaN(), b = geo::kWgs84B, a = geo::kWgs84A;
  struct Case { double x, y, z; };
  const Case cases[] = {{0.0, 0.0, b},   {-0.0, 0.0, b},   {0.0, -0.0, -b},  {-0.0, -0.0, -b},
                        {-a, 0.0, 0.0},  {-a, -0.0, -0.0}, {a, 0.0, 0.0},    {a, -0.0, 0.0},
                        {0.0, a, 0.0},   {0.0, -a, -0.0}};
  for (auto* kernel : {grid::surfaceLatLonBatch, grid::surfaceLatLonBatchPortable})
  for (const Case& c : cases) {
    double la = 0, lo = 0;
    kernel(eye0, &c.x, &c.y, &c.z, 1, &la, &lo);
    const double refLat = std::atan2(c.z, std::sqrt(c.x * c.x + c.y * c.y)) * 180.0 / M_PI;
    const double refLon = std::atan2(c.y, c.x) * 180.0 / M_PI;
    EXPECT_NEAR(la, refLat, 1e-13) << c.x << " " << c.y << " " << c.z;
    EXPECT_NEAR(lo, refLon, 1e-13) << c.x << " " << c.y << " " << c.z;
    EXPECT_EQ(std::signbit(la), std::signbit(refLat)) << c.x << " " << c.y << " " << c.z;
    EXPECT_EQ(std::signbit(lo), std::signbit(refLon)) << c.x << " " << c.y << " " << c.z;
  }
  for (int k = 0; k < 3; ++k) {
    double p[3] = {a * 0.6, a * 0.8, 1000.0};
    p[k] = nan;
    for (auto* kernel : {grid::surfaceLatLonBatch, grid::surfaceLatLonBatchPortable}) {
      double la = 0, lo = 0;
      kernel(eye0, &p[0], &p[1], &p[2], 1, &la, &lo);
      EXPECT_TRUE(std::isnan(la)) << k;  // z, and x, y through p
      if (k < 2) {
        EXPECT_TRUE(std::isnan(lo)) << k;
      }
    }
  }
}

TEST(RayKernels, ReportsTheDispatchedIsa) {
  const std::string isa = grid::kernelIsa();
  EXPECT_TRUE(isa == "x86-64-v4" || isa == "x86-64-v3" || isa == "baseline") << isa;
}

// packRow (AVX-512 permutes on CPUs that have it, else GCC's vectorised
// interleave, stored directly or streamed from L1 blocks) against the field-by-field definition of GridVertex,
// bit for bit: odd lengths for the remainders, NaN t (horizon), columns on
// both sides of |x| = 1 and off-screen rows.
TEST(RayKernels, PackRowWritesEveryField) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t n : {1u, 7u, 8u, 9u, 64u, 65u, 203u, 515u}) {
    std::vector<double> t(n), rx(n), ry(n), rz(n), lat(n), lon(n);
    std::vector<std::uint8_t> surf(n);
    for (std::size_t i = 0; i < n; ++i) {
      t[i] = i % 5 == 0 ? std::nan("") : 1e3 * (1 + u(rng));
      rx[i] = 1e6 * u(rng), ry[i] = 1e4 * u(rng), rz[i] = 3.0 * u(rng);
      lat[i] = 90 * u(rng), lon[i] = 180 * u(rng);
      surf[i] = std::uint8_t(i % 3);
    }
    const double x0 = -1.3, dx = 2.6 / double(std::max<std::size_t>(n - 1, 1));
    for (bool rowOff : {false, true}) {
      for (std::size_t shift : {0u, 8u, 16u}) {  // 8: not 16-byte aligned; 16: streamed below
        const bool stream = shift != 8;
        std::vector<unsigned char> raw(n * sizeof(grid::GridVertex) + 64);
        auto base = (reinterpret_cast<std::uintptr_t>(raw.data()) + 31) / 32 * 32 + shift;
        auto* out = reinterpret_cast<grid::GridVertex*>(base);
        for (int portable = 0; portable < 2; ++portable) {
          std::memset(static_cast<void*>(out), 0xAB, n * sizeof(grid::GridVertex));
          (portable ? grid::packRowPortable : grid::packRow)(t.data(), rx.data(), ry.data(), rz.data(), lat.data(),
                                                             lon.data(), surf.data(), x0, dx, rowOff, n, out, stream);
          for (std::size_t i = 0; i < n; ++i) {
            const grid::GridVertex& v = out[i];
            const double x = x0 + double(int(i)) * dx;
            const unsigned flags = (std::isnan(t[i]) ? grid::kVertexHorizon : 0) |
                                   ((rowOff || std::fabs(x) > 1.0) ? grid::kVertexOffscreen : 0);
            ASSERT_EQ(v.eyeRelM[0], float(rx[i])) << n << " " << i;
            ASSERT_EQ(v.eyeRelM[1], float(ry[i])) << n << " " << i;
            ASSERT_EQ(v.eyeRelM[2], float(rz[i])) << n << " " << i;
            ASSERT_EQ(v.surface, surf[i]) << n << " " << i;
            ASSERT_EQ(v.flags, flags) << n << " " << i;
            ASSERT_EQ(v.reserved, 0) << n << " " << i;
            ASSERT_EQ(std::memcmp(&v.latDeg, &lat[i], 8), 0) << n << " " << i;
            ASSERT_EQ(std::memcmp(&v.lonDeg, &lon[i], 8), 0) << n << " " << i;
          }
        }
      }
    }
  }
}
