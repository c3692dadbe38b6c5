// The ocean façade (plugin/ocean/Ocean.h): known places on the default
// world, setters and snapshots, and the particle velocities against linear
// wave theory and against time differences of the displacement.
#include "plugin/ocean/Ocean.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/raster/World.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

namespace {

using geocean::ocean::NotReady;
using geocean::ocean::Ocean;
using geocean::ocean::Points;
using geocean::ocean::Surface;
using geocean::ocean::SurfaceOutputs;
using geocean::waves::Model;
using geocean::waves::SeaState;
constexpr double kG = 9.80665;  // the kernel's g (WV_G), standard gravity

// The build's data directory, whatever $GEOCEAN_DATA says.
void loadDefaultWorld(Ocean& o) { o.setDefaultWorld(GEOCEAN_DATA_DIR); }

// All outputs of one query, sized for n points.
struct Answers {
  std::vector<Surface> surface;
  std::vector<float> elevation;
  std::vector<double> height, normal, w, uv;
  explicit Answers(std::size_t n) : surface(n), elevation(n), height(n), normal(3 * n), w(n), uv(2 * n) {}
  SurfaceOutputs outputs() {
    return {surface.data(), elevation.data(), height.data(), normal.data(), w.data(), uv.data()};
  }
};

Answers query(const Ocean& o, const std::vector<double>& lat, const std::vector<double>& lon,
              const std::vector<double>& t) {
  Answers a(lat.size());
  o.current()->querySurface({lat.data(), lon.data(), lat.size(), t.data(), t.size() > 1}, a.outputs());
  return a;
}

// Places whose class is common knowledge: open Pacific, Swiss plateau, Sahara,
// Lake Superior; the central Pacific abyssal plain is deeper than 3 km.
TEST(OceanCore, KnownPlacesOnTheDefaultWorld) {
  Ocean o;
  loadDefaultWorld(o);
  const std::vector<double> lat = {0.0, 46.8, 23.0, 47.7}, lon = {-150.0, 8.2, 10.0, -87.5};
  std::vector<Surface> c(4);
  o.current()->classify(lat.data(), lon.data(), 4, c.data());
  EXPECT_EQ(c[0], Surface::Ocean);
  EXPECT_EQ(c[1], Surface::Land);
  EXPECT_EQ(c[2], Surface::Land);
  EXPECT_EQ(c[3], Surface::Lake);
  std::vector<float> e(4);
  o.current()->elevationAt(lat.data(), lon.data(), 4, e.data());
  EXPECT_LT(e[0], -3000.0f);
  EXPECT_GT(e[1], 300.0f);  // the Swiss plateau lies 400 .. 700 m high
  // The combined query agrees with the single ones and needs no sea state for them.
  Answers a(4);
  SurfaceOutputs out;
  out.surface = a.surface.data();
  out.elevationM = a.elevation.data();
  o.current()->querySurface({lat.data(), lon.data(), 4, nullptr, false}, out);
  EXPECT_EQ(a.surface, c);
  EXPECT_EQ(a.elevation, e);
}

TEST(OceanCore, MissingPrerequisitesSayWhich) {
  Ocean o;
  const double lat = 0, lon = 0, t = 0;
  Surface c{};
  float e = 0;
  try {
    o.current()->classify(&lat, &lon, 1, &c);
    ADD_FAILURE() << "classify without rasters";
  } catch (const NotReady& x) {
    EXPECT_EQ(x.missing, NotReady::Missing::Rasters);
  }
  Answers a(1);
  try {
    o.current()->querySurface({&lat, &lon, 1, &t, false}, a.outputs());
    ADD_FAILURE() << "sea surface without a sea state";
  } catch (const NotReady& x) {
    EXPECT_EQ(x.missing, NotReady::Missing::SeaState);
  }
  std::vector<float> plane(4, 100.0f);  // a mask alone: no elevation
  o.setMask(geocean::raster::Raster::fromPixels(plane, 2, 2, 1, {}, std::nullopt, "mask"));
  EXPECT_THROW(o.current()->elevationAt(&lat, &lon, 1, &e), NotReady);
  EXPECT_THROW(o.setSeaState(Model::Gerstner, SeaState{.windSpeedMps = 100.0}), std::invalid_argument);
  EXPECT_THROW(o.setMaskEncoding(geocean::ocean::MaskEncoding::parse("0=sea")), std::invalid_argument);
}

// The façade's own time check (plugin/waves/TimeRange.h, fuzz finding 5):
// a C++ caller gets the same refusal as the bindings, naming the index.
TEST(OceanCore, SeaTimesBeyondTheBoundAreRefused) {
  Ocean o;
  o.setSeaState(Model::Gerstner, SeaState{});
  const double lat[2] = {0, 1}, lon[2] = {-150, -150};
  Answers a(2);
  for (const bool thisThread : {false, true}) {
    auto query = [&](const double* t, bool perPoint) {
      const Points p{lat, lon, 2, t, perPoint};
      thisThread ? o.current()->querySurfaceOnThisThread(p, a.outputs()) : o.current()->querySurface(p, a.outputs());
    };
    const double ok[2] = {1e12, -1e12}, big[2] = {0.0, 1e33}, nan[1] = {std::nan("")};
    EXPECT_NO_THROW(query(ok, true));
    try {
      query(big, true);
      ADD_FAILURE() << "t = 1e33 s accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "sea-surface query: timeS[1] 1e+33 s is outside -1e12 .. 1e12 s");
    }
    try {
      query(nan, false);
      ADD_FAILURE() << "t = NaN accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "sea-surface query: timeS[0] nan is not finite");
    }
  }
}

// Fuzz finding 7 (regressions/fuzz_capi_sea_state/fft_latitude_1e308_nan_point.bin):
// with no rasters every point is ocean, also one off the globe; at a
// latitude or longitude near DBL_MAX the radians overflowed, the FFT kernel
// got a NaN point (UB converting its cell to int) and answered 0 m. Off the
// globe (|lat| > 90, |lon| > 360) the class stays, the sea is NaN.
TEST(OceanCore, PointsOffTheGlobeHaveNoSea) {
  for (const Model m : {Model::Fft, Model::Gerstner, Model::Noise}) {
    Ocean o;
    o.setSeaState(m, SeaState{});
    const double big = std::numeric_limits<double>::max();
    const std::vector<double> lat = {big, 0.0, 0.0, 91.0, 10.0}, lon = {0.0, big, 3.7e307, 0.0, 361.0};
    const Answers a = query(o, lat, lon, {5.0});
    for (std::size_t i = 0; i < lat.size(); ++i) {
      EXPECT_EQ(a.surface[i], Surface::Ocean) << i;  // no rasters: as classified
      EXPECT_TRUE(std::isnan(a.height[i]) && std::isnan(a.normal[3 * i]) && std::isnan(a.w[i]))
          << toString(m) << " point " << i << ": " << a.height[i];
    }
    const Answers on = query(o, {90.0, -90.0, 0.0}, {0.0, 360.0, -360.0}, {5.0});  // the edges are on it
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isfinite(on.height[i])) << toString(m) << " " << i;
  }
}

// The mask encoding is part of the state: swapping ocean and land swaps the
// Pacific and Switzerland; an old snapshot keeps the old answers.
TEST(OceanCore, MaskEncodingAndSnapshots) {
  Ocean o;
  loadDefaultWorld(o);
  const std::vector<double> lat = {0.0, 46.8}, lon = {-150.0, 8.2};
  const auto before = o.current();
  o.setMaskEncoding(geocean::ocean::MaskEncoding::parse("0=land,1=ocean,2=lake"));
  const auto after = o.current();
  EXPECT_NE(before, after);
  EXPECT_EQ(before->mask, after->mask);  // the rasters are shared, not reloaded
  std::vector<Surface> c0(2), c1(2);
  before->classify(lat.data(), lon.data(), 2, c0.data());
  after->classify(lat.data(), lon.data(), 2, c1.data());
  EXPECT_EQ(c0, (std::vector<Surface>{Surface::Ocean, Surface::Land}));
  EXPECT_EQ(c1, (std::vector<Surface>{Surface::Land, Surface::Ocean}));
  // A sea state change keeps the land/sea; a raster change rebuilds it.
  o.setSeaState(Model::Noise, SeaState{});
  EXPECT_EQ(o.current()->landSea, after->landSea);
  o.clearRasters();
  EXPECT_EQ(o.current()->landSea, nullptr);
  EXPECT_NE(o.current()->sea, nullptr);  // deep ocean everywhere
}

// One time for all equals the same time given per point, bit for bit; per-
// point times equal separate one-time queries.
TEST(OceanCore, PerPointTimesEqualOneTimeQueries) {
  for (Model m : {Model::Noise, Model::NoisePaper, Model::Gerstner, Model::Fft}) {
    Ocean o;
    loadDefaultWorld(o);
    o.setSeaState(m, SeaState{});
    const std::vector<double> lat = {0.0, 10.0, -33.9, 46.8, 35.95, -60.0},
                              lon = {-150.0, -140.0, 151.5, 8.2, -5.6, 20.0};
    const std::vector<double> times = {0.0, 7.5, 12.25, 100.0, 3.0, 99.5};
    const Answers perPoint = query(o, lat, lon, times);
    for (std::size_t i = 0; i < lat.size(); ++i) {
      const Answers one = query(o, {lat[i]}, {lon[i]}, {times[i]});
      EXPECT_EQ(one.surface[0], perPoint.surface[i]);
      if (perPoint.surface[i] != Surface::Ocean) {
        EXPECT_TRUE(std::isnan(perPoint.height[i]) && std::isnan(perPoint.w[i]) && std::isnan(perPoint.uv[2 * i]))
            << toString(m) << " point " << i;
        continue;
      }
      EXPECT_EQ(one.height[0], perPoint.height[i]) << toString(m) << " point " << i;
      EXPECT_EQ(one.w[0], perPoint.w[i]) << toString(m) << " point " << i;
      EXPECT_EQ(one.uv[0], perPoint.uv[2 * i]) << toString(m) << " point " << i;
      EXPECT_EQ(one.uv[1], perPoint.uv[2 * i + 1]) << toString(m) << " point " << i;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(one.normal[k], perPoint.normal[3 * i + k]);
    }
  }
}

// A single Gerstner component at the anchor (no taper), at depth h: linear
// wave theory gives the surface particle's horizontal velocity
// u = omega * eta / tanh(k h) along the travel direction (deep water:
// u = omega * eta, amplitude a * omega), with k from omega^2 = g k tanh(k h).
// Tolerance: the rest point is found to 1e-5 m and the kernel's wave number
// is within 1e-8 of the dispersion relation, so 1e-6 of a * omega / tanh.
double dispersionK(double omega, double h) {
  double lo = 0.0, hi = omega * omega / kG / std::tanh(1e-3) + 10.0;  // bisection: independent of the kernel
  for (int i = 0; i < 200; ++i) {
    const double k = 0.5 * (lo + hi);
    (omega * omega > kG * k * std::tanh(k * h) ? lo : hi) = k;
  }
  return 0.5 * (lo + hi);
}

void checkLinearTheory(double depthM) {
  Ocean o;
  if (depthM < 1e6) {
    // Elevation -depth everywhere (a global 1-degree raster): ocean of that depth.
    geocean::raster::GeoTransform t{-180.0, 90.0, 1.0, -1.0, true};
    o.setElevation(geocean::raster::Raster::fromPixels(std::vector<float>(360 * 180, float(-depthM)), 360, 180, 1, t,
                                                        std::nullopt, "flat sea floor"));
  }
  SeaState s;
  s.gerstnerComponents = 1;
  s.windSpeedMps = 8.0;
  o.setSeaState(Model::Gerstner, s);
  const auto& c = o.current()->waves->components().at(0);
  const double h = depthM < 1e6 ? depthM : 1e30;
  const double th = h < 1e6 ? std::tanh(dispersionK(c.omega, h) * h) : 1.0;
  std::vector<double> lat, lon, t;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 5; ++j) {
      lat.push_back(-0.01 + 0.0005 * i);
      lon.push_back(0.01 * j - 0.02);
      t.push_back(0.37 * (i + 3 * j));
    }
  const Answers a = query(o, lat, lon, t);
  // The travel direction: from the sample with the largest |eta|.
  std::size_t best = 0;
  for (std::size_t i = 0; i < lat.size(); ++i)
    if (std::abs(a.height[i]) > std::abs(a.height[best])) best = i;
  const double sgn = a.height[best] > 0 ? 1.0 : -1.0;
  const double ue = sgn * a.uv[2 * best], un = sgn * a.uv[2 * best + 1], len = std::hypot(ue, un);
  ASSERT_GT(len, 0.0);
  const double ampU = c.amplitudeM * c.omega / th;
  double maxU = 0.0;
  for (std::size_t i = 0; i < lat.size(); ++i) {
    ASSERT_EQ(a.surface[i], Surface::Ocean);
    const double uTheory = c.omega * a.height[i] / th;
    EXPECT_NEAR(a.uv[2 * i], uTheory * ue / len, 1e-6 * ampU) << "depth " << depthM << " point " << i;
    EXPECT_NEAR(a.uv[2 * i + 1], uTheory * un / len, 1e-6 * ampU) << "depth " << depthM << " point " << i;
    maxU = std::max(maxU, std::hypot(a.uv[2 * i], a.uv[2 * i + 1]));
  }
  if (h > 1e6) {
    EXPECT_NEAR(maxU, c.amplitudeM * c.omega, 0.02 * c.amplitudeM * c.omega);  // crests sampled
  }
}

TEST(OceanCore, HorizontalVelocityIsLinearWaveTheoryInDeepWater) { checkLinearTheory(1e30); }
TEST(OceanCore, HorizontalVelocityIsLinearWaveTheoryInShallowWater) { checkLinearTheory(4.0); }

// Every model: the reported velocity is the time derivative of the
// horizontal displacement of the particle now above the point, by central
// differences at its rest point. The rest point is found here by a plain
// fixed-point iteration on WaveField::sample (not the façade's inversion).
// Step 1 ms: truncation (omega dt)^2 / 6 < 3e-6 of |u| for omega < 5 rad/s;
// rounding of 1 m displacements over 2 ms, ~1e-13 m/s.
TEST(OceanCore, HorizontalVelocityIsTheDisplacementsTimeDerivative) {
  for (Model m : {Model::Noise, Model::NoisePaper, Model::Gerstner, Model::Fft}) {
    Ocean o;
    o.setSeaState(m, SeaState{});
    const auto snap = o.current();
    const auto& field = *snap->waves;
    const std::vector<double> lat = {10.0, -33.9, 45.0, 0.3}, lon = {-140.0, 151.5, -30.0, 0.1};
    const std::vector<double> times = {12.5, 40.0, 3.0, 77.7};
    const Answers a = query(o, lat, lon, times);
    for (std::size_t i = 0; i < lat.size(); ++i) {
      const geocean::geo::EnuFrame f = geocean::geo::enuFrame({lat[i], lon[i], 0.0});
      glm::dvec3 off(0.0);
      geocean::geo::Geodetic rest{lat[i], lon[i], 0.0};
      for (int it = 0; it < 300; ++it) {
        const auto d = field.sample(rest.latDeg, rest.lonDeg, times[i]).displacementEnuM;
        const geocean::geo::EnuFrame fr = geocean::geo::enuFrame(rest);
        glm::dvec3 hor = fr.toEcef({d.x, d.y, 0.0});
        hor -= glm::dot(hor, f.up) * f.up;
        off = -hor;
        rest = geocean::geo::fromEcef(f.originEcef + off);
      }
      const double dt = 1e-3;
      const auto d1 = field.sample(rest.latDeg, rest.lonDeg, times[i] + dt).displacementEnuM;
      const auto d0 = field.sample(rest.latDeg, rest.lonDeg, times[i] - dt).displacementEnuM;
      const double ue = (d1.x - d0.x) / (2 * dt), un = (d1.y - d0.y) / (2 * dt);
      const double scale = std::max(std::hypot(ue, un), 1e-3);
      EXPECT_NEAR(a.uv[2 * i], ue, 1e-4 * scale + 1e-9) << toString(m) << " point " << i;
      EXPECT_NEAR(a.uv[2 * i + 1], un, 1e-4 * scale + 1e-9) << toString(m) << " point " << i;
      if (m == Model::Noise || m == Model::NoisePaper) {
        // Height fields: particles move vertically only.
        EXPECT_EQ(a.uv[2 * i], 0.0);
        EXPECT_EQ(a.uv[2 * i + 1], 0.0);
      } else {
        EXPECT_GT(std::hypot(ue, un), 1e-3) << toString(m) << ": the test must see moving water";
      }
    }
  }
}

// The vertical velocity is d(height)/dt at the fixed point (central
// differences, 1 ms: truncation below 1e-5 of |w| as above).
TEST(OceanCore, VerticalVelocityIsTheHeightsTimeDerivative) {
  for (Model m : {Model::Noise, Model::Gerstner, Model::Fft}) {
    Ocean o;
    o.setSeaState(m, SeaState{});
    const std::vector<double> lat = {10.0, -33.9, 45.0}, lon = {-140.0, 151.5, -30.0};
    for (double t : {5.0, 61.0}) {
      const Answers a = query(o, lat, lon, {t}), p = query(o, lat, lon, {t + 1e-3}), q = query(o, lat, lon, {t - 1e-3});
      for (std::size_t i = 0; i < lat.size(); ++i) {
        const double fd = (p.height[i] - q.height[i]) / 2e-3;
        EXPECT_NEAR(a.w[i], fd, 1e-4 * std::max(std::abs(fd), 1e-2)) << toString(m) << " point " << i;
      }
    }
  }
}

TEST(OceanCore, DefaultWorldDirPrefersTheEnvironmentThenTheResolver) {
  setenv("GEOCEAN_DATA", "/from/env", 1);
  EXPECT_EQ(Ocean::defaultWorldDir([] { return std::string("/installed"); }), "/from/env");
  unsetenv("GEOCEAN_DATA");
  EXPECT_EQ(Ocean::defaultWorldDir([] { return std::string("/installed"); }), "/installed");
  EXPECT_EQ(Ocean::defaultWorldDir([] { return std::string(); }), geocean::raster::dataDir());
  EXPECT_THROW(Ocean().setDefaultWorld("/nonexistent"), geocean::raster::RasterError);
}

// The picker's classifier is the snapshot's land/sea; none without rasters.
TEST(OceanCore, ClassifierForThePicker) {
  Ocean o;
  loadDefaultWorld(o);
  const auto cls = o.current()->classifier();
  ASSERT_TRUE(cls);
  const double lat[] = {0.0, 46.8}, lon[] = {-150.0, 8.2};
  Surface c[2];
  cls(lat, lon, 2, c);
  EXPECT_EQ(c[0], Surface::Ocean);
  EXPECT_EQ(c[1], Surface::Land);
  EXPECT_FALSE(Ocean().current()->classifier());
}

}  // namespace

// Issue 15: the coast region makes the façade's sea-state outputs depth-aware:
// over a planar beach (straight north-south contours, elevation raster made
// here) the peak wavelength follows the dispersion relation at the local
// depth and the direction waves come from turns toward the shore normal.
// Issue 15 item 2: the island table is recomputed when the wind turns
// (Ocean::setSeaState publishes a new field). A round island 1.5 km across,
// 40 m of sea about it; 3 km either side of it along the wind, the lee's
// waves are lower than the weather side's, and turning the wind round
// swaps the sides (paper 003 sec. 3: the occlusion lies down-wave).
TEST(OceanCore, AWindTurnRebuildsTheIslandsShelter) {
  Ocean o;
  const int w = 400, h = 400;  // 0.001-degree cells about (0.3, 0)
  std::vector<float> px(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double lon = -0.2 + (x + 0.5) * 0.001, lat = 0.5 - (y + 0.5) * 0.001;
      const double r = std::hypot(lon, lat - 0.3) * 111320.0;
      px[std::size_t(y) * w + x] = float(r < 750.0 ? 20.0 : -40.0);
    }
  o.setElevation(geocean::raster::Raster::fromPixels(px, w, h, 1, {-0.2, 0.5, 0.001, -0.001, false}, std::nullopt,
                                                     "island"));
  geocean::waves::CoastField::Region r;
  r.latDeg = 0.3, r.lonDeg = 0.0, r.cellM = 50.0, r.nodes = 201;
  o.setCoastRegion(r);
  const std::vector<double> lat = {0.3, 0.3}, lon = {-0.027, 0.027};  // 3 km west, 3 km east
  auto hs = [&](double windFromDeg) {
    SeaState s;
    s.windFromDeg = windFromDeg;
    s.anchorLatDeg = 0.3;
    o.setSeaState(Model::Gerstner, s);
    std::vector<double> out(2, 0.0);
    SurfaceOutputs so;
    so.hsM = out.data();
    const double t = 0.0;
    o.current()->querySurface({lat.data(), lon.data(), 2, &t, false}, so);
    return out;
  };
  const std::vector<double> fromWest = hs(270.0), fromEast = hs(90.0);
  std::printf("hs west / east: wind from the west %.3f / %.3f m, from the east %.3f / %.3f m\n", fromWest[0],
              fromWest[1], fromEast[0], fromEast[1]);
  ASSERT_NE(o.current()->waves->coastField(), nullptr);
  EXPECT_LT(fromWest[1], 0.9 * fromWest[0]);  // the lee is east
  EXPECT_LT(fromEast[0], 0.9 * fromEast[1]);  // now west
  // The same island, mirrored: the two sides swap within 2 % (the grid's
  // nodes and the wave directions' sampling are symmetric to that).
  EXPECT_NEAR(fromWest[1], fromEast[0], 0.02 * fromWest[0]);
  EXPECT_NEAR(fromWest[0], fromEast[1], 0.02 * fromWest[0]);
}

TEST(OceanCore, CoastRegionRefractsTheSeaStateOutputs) {
  Ocean o;
  // 0.001-degree cells over lon -0.2 .. 0.2, lat 0.1 .. 0.5; the shoreline at
  // lon 0.04, bottom slope 1:50 (bilinear keeps it exactly planar).
  const int w = 400, h = 400;
  std::vector<float> px(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double lon = -0.2 + (x + 0.5) * 0.001;
      px[std::size_t(y) * w + x] = float(-0.02 * (0.04 - lon) * 111320.0);
    }
  o.setElevation(geocean::raster::Raster::fromPixels(px, w, h, 1, {-0.2, 0.5, 0.001, -0.001, false}, std::nullopt,
                                                     "beach"));
  SeaState s;
  s.windFromDeg = 240.0;
  s.anchorLatDeg = 0.3;
  o.setSeaState(Model::Gerstner, s);
  const std::vector<double> lat = {0.3, 0.3}, lon = {-0.03, 0.033};  // 156 m and 16 m deep
  auto seaState = [&](std::vector<double>& lp, std::vector<double>& from) {
    lp.assign(2, 0.0);
    from.assign(2, 0.0);
    std::vector<float> elev(2);
    SurfaceOutputs out;
    out.peakWavelengthM = lp.data();
    out.waveFromDeg = from.data();
    out.elevationM = elev.data();
    const double t = 0.0;
    o.current()->querySurface({lat.data(), lon.data(), 2, &t, false}, out);
    return elev;
  };
  std::vector<double> lp0, from0, lp1, from1;
  seaState(lp0, from0);
  geocean::waves::CoastField::Region r;
  r.latDeg = 0.3;
  r.lonDeg = 0.0;
  r.cellM = 50.0;
  r.nodes = 201;
  o.setCoastRegion(r);
  const std::vector<float> elev = seaState(lp1, from1);
  ASSERT_NE(o.current()->waves->coastField(), nullptr);
  const double wp = 0.877 * kG / s.windSpeedMps;
  // Without the field: the reference (deep) depth's wavelength everywhere.
  EXPECT_NEAR(lp0[1], 2.0 * M_PI * kG / (wp * wp), 1e-9 * lp0[1]);
  // With it: the dispersion relation at the local depth (-elevation).
  EXPECT_NEAR(lp1[1], 2.0 * M_PI / dispersionK(wp, -double(elev[1])), 1e-6 * lp1[1]);
  EXPECT_LT(lp1[1], 0.9 * lp0[1]);  // 16 m: L / L0 = tanh(k h) = 0.87
  // Refraction: the shallow point's waves come more nearly from the west (270).
  EXPECT_GT(from1[1], from1[0] + 3.0);
  EXPECT_LT(from1[1], 275.0);
  // Bad region: named field and value; the state stays.
  r.nodes = 3;
  try {
    o.setCoastRegion(r);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nodes = 3"), std::string::npos) << e.what();
  }
  EXPECT_EQ(o.current()->coastRegion->nodes, 201);
  o.clearCoastRegion();
  EXPECT_EQ(o.current()->waves->coastField(), nullptr);
}
