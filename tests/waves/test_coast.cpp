// Waves that feel the coast (issue 15 items 1, 7): the Gerstner kernel with a
// coast field, over synthetic bathymetry made here, against linear wave
// theory: the dispersion relation w^2 = g k tanh(k h), Snell's law over
// straight parallel contours (k sin(theta) conserved), shoaling and
// refraction H/H0 = Ks Kr with Ks = sqrt(cg0 / cg), Kr = sqrt(cos theta0 /
// cos theta), and the breaking limits H <= 0.78 h, H <= 0.142 L tanh(k h).
// Everything is measured from the drawn surface: the phase from (eta,
// deta/dt) of a single component, its gradient by finite differences.
#include "globe/geo/Ellipsoid.h"
#include "plugin/waves/CoastField.h"
#include "plugin/waves/WaveField.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace geocean::waves;
namespace geo = geocean::geo;

namespace {
constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;

// One component travelling roughly east, `obliqueDeg` (+-15) off the grid's
// x axis at the region's centre.
WaveField oneComponent(double windMps, double travelDeg, double referenceDepthM = kDeepWaterM) {
  SeaState sea;
  sea.referenceDepthM = referenceDepthM;
  sea.windSpeedMps = windMps;
  sea.gerstnerComponents = 1;
  sea.anchorLatDeg = 0.3;
  sea.anchorLonDeg = 0.3;
  std::string err;
  // The component's direction is drawn about the wind: search seeds for
  // one within 3 degrees of the wanted travel bearing (deterministic).
  for (std::uint32_t seed = 1; seed < 4000; ++seed) {
    sea.seed = seed;
    sea.windFromDeg = travelDeg + 180.0;
    auto w = WaveField::create(Model::Gerstner, sea, err);
    EXPECT_TRUE(w) << err;
    const double b = w->seaStateAt(0.3, 0.3).waveFromDeg - 180.0;
    if (std::abs(std::remainder(b - travelDeg, 360.0)) < 3.0) return *w;
  }
  ADD_FAILURE() << "no seed gives a travel bearing near " << travelDeg;
  return *WaveField::create(Model::Gerstner, sea, err);
}

struct Probe {
  const WaveField& field;
  std::function<double(double, double)> depth;  // of (east, north) in the grid's plane
  double omega;
  // Geodetic point at (east, north) of the grid's tangent plane.
  geo::Geodetic at(double e, double n) const {
    const CoastField* c = field.coastField();
    return geo::fromEcef(c->centreEcef() + c->east() * e + c->north() * n);
  }
  // Phase and amplitude of the single component at rest point (e, n).
  std::pair<double, double> phaseAmp(double e, double n, double t) const {
    const geo::Geodetic g = at(e, n);
    const WaveSample s = field.sample(g.latDeg, g.lonDeg, t, depth(e, n));
    const double x = s.displacementEnuM.z, y = s.verticalVelocityMps / omega;
    return {std::atan2(y, x), std::hypot(x, y)};
  }
  // grad(psi) (rad/m) in (east, north) of the grid, central differences.
  glm::dvec2 gradPhase(double e, double n) const {
    const double h = 0.5, t = 12.25;
    auto d = [&](double e0, double n0, double e1, double n1) {
      return std::remainder(phaseAmp(e1, n1, t).first - phaseAmp(e0, n0, t).first, 2.0 * kPi) / (2.0 * h);
    };
    // psi = k.x - w t: the gradient of the measured atan2 phase.
    return {d(e - h, n, e + h, n), d(e, n - h, e, n + h)};
  }
};

// islandRadiusM: the occlusion's reach (0: the default, 6 wavelengths); the
// beaches' straight shores cast no shadow, a short reach saves the build's time.
std::shared_ptr<const CoastField> buildField(const WaveField& w, double cellM, int nodes,
                                             const std::function<double(double, double)>& depth,
                                             double islandRadiusM = 0.0) {
  CoastField::Region r;
  r.islandRadiusM = islandRadiusM;
  r.latDeg = 0.3;
  r.lonDeg = 0.3;
  r.cellM = cellM;
  r.nodes = nodes;
  r.margin = 8;
  std::string err;
  auto c = std::make_shared<const CoastField>(CoastField::build(w, r, depth, err));
  EXPECT_FALSE(c->empty()) << err;
  return c;
}

// Depth h for k h = kh at frequency omega: k = w^2 / (g tanh(kh)).
double depthForKh(double omega, double kh) { return kh * kG * std::tanh(kh) / (omega * omega); }

double groupSpeed(double omega, double k, double h) {
  const double kh = k * h;
  return 0.5 * (1.0 + (kh < 20 ? 2.0 * kh / std::sinh(2.0 * kh) : 0.0)) * omega / k;
}
}  // namespace

// Item 7: the wavelength over a flat shelf follows the dispersion relation
// within 2% for k h in [0.1, 3]; the shelf is reached from deep water over
// a smooth ramp (straight contours), so the phase has no jump anywhere.
TEST(Coast, WavelengthFollowsTheDispersionRelation) {
  WaveField w = oneComponent(20.0, 80.0);  // 10 degrees off the shelf's normal; a swell of ~10 s
  const double omega = w.components()[0].omega, k0 = w.components()[0].kRef;
  for (double kh : {0.1, 0.3, 1.0, 3.0}) {
    const double ht = depthForKh(omega, kh), kt = waveNumberExact(omega, ht);
    ASSERT_GT(ht, 0.1) << "near the kernel's 0.05 m floor's reach: omega " << omega;
    const double cell = std::min(2.0 * kPi / k0, 2.0 * kPi / kt) / 20.0;
    const double hDeep = 5.0 / k0;
    auto depth = [&](double e, double) {
      const double u = std::clamp((e + 60 * cell) / (40 * cell), 0.0, 1.0);  // ramp over e in [-60, -20] cells
      return hDeep + (ht - hDeep) * (0.5 - 0.5 * std::cos(kPi * u));
    };
    w.setCoast(buildField(w, cell, 401, depth));
    Probe p{w, depth, omega};
    for (double e : {20.0, 40.0, 60.0})
      for (double n : {-30.0, 0.0, 30.0}) {
        const double kMeasured = glm::length(p.gradPhase(e * cell, n * cell));
        EXPECT_NEAR(kMeasured, kt, 0.02 * kt) << "kh " << kh << " at (" << e << ", " << n << ") cells";
      }
  }
}

// Item 7: over a planar beach with straight contours and oblique incidence,
// sin(theta) / c is constant within 3% from deep water to the break point;
// H/H0 is within 5% of Ks Kr until breaking, then H <= 0.78 h and Miche.
// travelDeg: the component's bearing (the shore runs north-south, land to
// the east); from e = shadowFrom cells on, H only at most Ks Kr (the land
// up-wave of an offshore wave: below). Returns the wave field (with its
// coast field) for more checks.
WaveField obliqueBeach(double travelDeg, double referenceDepthM = kDeepWaterM, double shadowFrom = 1e9) {
  WaveField w = oneComponent(10.0, travelDeg, referenceDepthM);
  const double omega = w.components()[0].omega, k0 = w.components()[0].kRef;
  const double a0 = w.components()[0].amplitudeM;
  const double l0 = 2.0 * kPi / k0;
  const double hDeep = 4.0 / k0;  // k h = 4: deep water
  const double cell = l0 / 40.0;
  // Shoreline at e = +150 cells, hDeep at e = -150 cells and beyond.
  auto depth = [=](double e, double) { return std::min(hDeep, hDeep * (150.0 * cell - e) / (300.0 * cell)); };
  w.setCoast(buildField(w, cell, 601, depth));
  Probe p{w, depth, omega};
  // The deep-water reference: incidence angle and the height there.
  const glm::dvec2 g0 = p.gradPhase(-200 * cell, 0.0);
  const double sin0 = g0.y / glm::length(g0), cos0 = g0.x / glm::length(g0);
  EXPECT_GT(std::abs(sin0), 0.4) << "not oblique";
  const double snell0 = sin0 / (omega / glm::length(g0));
  double lastH = 0.0;
  bool broken = false;
  int checkedBefore = 0, checkedAfter = 0;
  for (double e = -150.0; e < 149.0; e += 3.0) {
    const double x = e * cell, h = depth(x, 0.0);
    const double k = waveNumberExact(omega, h);
    const glm::dvec2 g = p.gradPhase(x, 0.0);
    const double sinT = g.y / glm::length(g), cosT = g.x / glm::length(g);
    // Peak amplitude over a wave period at this rest point.
    double amp = 0.0;
    for (int i = 0; i < 4; ++i) amp = std::max(amp, p.phaseAmp(x, 0.0, 3.0 + i * 0.7).second);
    const double hWave = 2.0 * amp;
    // Linear theory, from the formulas (not from the field): Snell's angle
    // from k0 sin(theta0) = k sin(theta), Ks and Kr (the same both ways
    // along a ray: energy flux is conserved in a ray tube).
    const double sinTheory = sin0 * k0 / k, cosTheory = std::sqrt(1.0 - sinTheory * sinTheory);
    const double ks = std::sqrt(groupSpeed(omega, k0, 1e9) / groupSpeed(omega, k, h));
    const double kr = std::sqrt(std::abs(cos0) / cosTheory);
    const double hLinear = 2.0 * a0 * ks * kr;
    const double miche = 0.142 * (2.0 * kPi / k) * std::tanh(k * h);
    if (!broken && hLinear < 0.78 * h && hLinear < miche) {
      EXPECT_NEAR(sinT / (omega / glm::length(g)), snell0, 0.03 * std::abs(snell0)) << "e " << e << " h " << h;
      EXPECT_NEAR(sinT, sinTheory, 0.03 * std::abs(sinTheory)) << "e " << e << " h " << h;
      if (e < shadowFrom)
        EXPECT_NEAR(hWave, hLinear, 0.05 * hLinear) << "e " << e << " h " << h << " cos " << cosT;
      else
        EXPECT_LT(hWave, 1.05 * hLinear) << "e " << e << " h " << h;
      ++checkedBefore;
    } else {
      broken = true;
      EXPECT_LE(hWave, 0.78 * h * (1.0 + 1e-9)) << "e " << e << " h " << h;
      EXPECT_LE(hWave, miche * (1.0 + 1e-9)) << "e " << e << " h " << h;
      ++checkedAfter;
    }
    lastH = hWave;
  }
  EXPECT_GT(checkedBefore, 50);
  EXPECT_GT(checkedAfter, 3);
  EXPECT_GT(lastH, 0.0);
  return w;
}

TEST(Coast, PlanarBeachSnellShoalingAndBreaking) {
  obliqueBeach(60.0);  // 30 degrees off the beach's normal (east)
}

// A component travelling offshore (30 degrees off the beach's normal, west)
// leaves the beach as the wave of the water beyond: the field carries it
// from the deep side (the time-reversed wave), so Snell and Ks Kr hold as
// onshore (rays are reversible: energy flux is conserved in a ray tube
// either way), and over the flat water beyond the beach its phase is the
// kernel's plane wave, as without a field. The sea's reference depth is
// that water's (k h = 4), so there the field is exactly 0 and the phase
// bit for bit the field-less sea's. The forward solve from its inflow
// edges (the shore, and the north-south edges' shallow ends) gave there
// whatever arrived first: up to 3.1 rad off (measured with it forced).
// Within 64 nodes of the shore (the island table's reach) the land up-wave
// shadows it (no energy comes from land): there H is only bounded above.
TEST(Coast, OffshoreTravellingWaveLeavesTheBeachAsTheWaveBeyond) {
  const double omega = oneComponent(10.0, 300.0).components()[0].omega;
  const double hFlat = depthForKh(omega, 4.0);
  const WaveField w = obliqueBeach(300.0, hFlat, 150.0 - 64.0);
  ASSERT_EQ(w.components()[0].omega, omega) << "the same component";
  WaveField plain = w;
  plain.setCoast(nullptr);
  const double cell = 2.0 * kPi / w.components()[0].kRef / 40.0;
  const Probe with{w, [&](double, double) { return hFlat; }, omega};
  // The phase (atan2 of eta and deta/dt / omega) of either field at one rest point.
  auto phase = [&](const WaveField& f, const geo::Geodetic& g) {
    const WaveSample s = f.sample(g.latDeg, g.lonDeg, 7.5, hFlat);
    return std::atan2(s.verticalVelocityMps / omega, s.displacementEnuM.z);
  };
  double worst = 0.0;
  int n = 0;
  // The flat water from 10 cells off the beach's foot to the margin (8 cells).
  for (double e = -290.0; e <= -160.0; e += 10.0)
    for (double nn = -290.0; nn <= 290.0; nn += 20.0) {
      const geo::Geodetic g = with.at(e * cell, nn * cell);
      worst = std::max(worst, std::abs(std::remainder(phase(w, g) - phase(plain, g), 2.0 * kPi))), ++n;
    }
  std::printf("offshore wave over the flat water beyond the beach: worst phase difference to the field-less sea "
              "%.3g rad at %d points\n",
              worst, n);
  EXPECT_EQ(worst, 0.0);
}

// Which components are carried from their outflow edges: exactly those
// travelling offshore. A shelf whose straight contours run 20 degrees east
// of north (deeper to the west-north-west; 1:50, 170 .. 300 m at the west
// edge), the land in the east, so the north edge is deeper than the south
// one; a 32-component sea from 240 degrees (travel 60 +- 90). A component
// travelling toward deeper water (s0 . d > sin 10 degrees, d the way down
// the slope) is reversed; one travelling toward the shore (s0 . d < -sin
// 10 degrees) is not, even with the deeper north edge among its outflow
// edges (a first rule that left land out of the comparison reversed one
// here, and 12 of 16 off Nazare, where their fields then came from the
// shore side and the picture showed white blobs everywhere). Within 10 degrees of the contours
// the 5 % flux margin decides: not checked.
TEST(Coast, OnlyComponentsTravellingOffshoreAreCarriedFromTheirOutflowEdges) {
  SeaState sea;
  sea.windSpeedMps = 10.0;
  sea.windFromDeg = 240.0;
  sea.anchorLatDeg = 0.3;
  sea.anchorLonDeg = 0.3;
  sea.gerstnerComponents = 32;
  std::string err;
  auto w = WaveField::create(Model::Gerstner, sea, err);
  ASSERT_TRUE(w) << err;
  const double a = 20.0 * kPi / 180.0;
  const glm::dvec2 down(-std::cos(a), std::sin(a));  // toward deeper water
  auto depth = [&](double e, double n) { return std::min(300.0, 0.02 * (4000.0 + glm::dot(down, glm::dvec2(e, n)))); };
  const auto c = buildField(*w, 50.0, 201, depth, 100.0);
  const double margin = std::sin(10.0 * kPi / 180.0);
  int offshore = 0, onshore = 0;
  for (int i = 0; i < c->components(); ++i) {
    const WaveField::Component& k = w->components()[std::size_t(i)];
    const glm::dvec3 radial = glm::normalize(c->centreEcef());
    const glm::dvec3 g = glm::normalize(radial * glm::dot(k.source, radial) - k.source);
    const glm::dvec2 s0(glm::dot(g, c->east()), glm::dot(g, c->north()));
    const double toward = glm::dot(s0, down);
    std::printf("component %2d: travel (%.3f, %.3f), s0 . d %+.3f, %s\n", i, s0.x, s0.y, toward,
                c->reversed(i) ? "reversed" : "forward");
    if (toward > margin) {
      EXPECT_TRUE(c->reversed(i)) << "component " << i << " travels offshore";
      ++offshore;
    } else if (toward < -margin) {
      EXPECT_FALSE(c->reversed(i)) << "component " << i << " travels onshore";
      ++onshore;
    }
  }
  EXPECT_GE(offshore, 2);
  EXPECT_GE(onshore, 16);
}

// Deep water stays bit for bit what it was: inside the coast field's region
// where the waves do not feel the bottom, and outside the region.
TEST(Coast, DeepWaterIsBitIdenticalWithAField) {
  SeaState sea;
  sea.windSpeedMps = 12.0;
  sea.anchorLatDeg = 0.3;
  sea.anchorLonDeg = 0.3;
  std::string err;
  const auto plain = WaveField::create(Model::Gerstner, sea, err);
  ASSERT_TRUE(plain) << err;
  WaveField w = *plain;
  // A shoal in the north-east corner of a 10 km region, 3 km deep elsewhere.
  auto depth = [](double e, double n) {
    const double r = std::hypot(e - 3500.0, n - 3500.0);
    return r < 1000.0 ? 5.0 + r * 0.05 : 3000.0;
  };
  w.setCoast(buildField(w, 25.0, 401, depth));
  ASSERT_NE(w.coastField(), nullptr);
  Probe p{w, depth, 1.0};
  int same = 0, changed = 0;
  for (double e = -4500.0; e <= 4500.0; e += 1500.0)
    for (double n = -4500.0; n <= 9000.0; n += 1500.0) {
      const geo::Geodetic g = p.at(e, n);
      const double h = depth(e, n);
      const SurfacePoint a = plain->surfaceAt(g.latDeg, g.lonDeg, 7.5, h), b = w.surfaceAt(g.latDeg, g.lonDeg, 7.5, h);
      // Up-wave of the shoal (every component travels with an eastward
      // part: cos^2 spreading about east) and outside the grid: exact.
      if (e < 2000.0 || n > 5100.0) {
        EXPECT_EQ(a.heightM, b.heightM) << e << ", " << n;
        EXPECT_EQ(a.normalEnu, b.normalEnu) << e << ", " << n;
        ++same;
      } else if (a.heightM != b.heightM) {
        ++changed;
      }
    }
  EXPECT_GT(same, 30);
  EXPECT_GT(changed, 0);  // and the shoal does change the sea over it
}

// The sea state output sees the coast: shorter peak wavelength (dispersion
// at the local depth), direction turned toward the shore normal.
TEST(Coast, SeaStateOutputsSeeRefraction) {
  WaveField w = oneComponent(10.0, 60.0);
  const double k0 = w.components()[0].kRef, l0 = 2.0 * kPi / k0, hDeep = 4.0 / k0, cell = l0 / 40.0;
  auto depth = [&](double e, double) { return std::min(hDeep, hDeep * (150.0 * cell - e) / (300.0 * cell)); };
  w.setCoast(buildField(w, cell, 601, depth));
  Probe p{w, depth, 1.0};
  const geo::Geodetic deep = p.at(-200 * cell, 0.0), shelf = p.at(100 * cell, 0.0);
  const LocalSeaState s0 = w.seaStateAt(deep.latDeg, deep.lonDeg, depth(-200 * cell, 0.0));
  const LocalSeaState s1 = w.seaStateAt(shelf.latDeg, shelf.lonDeg, depth(100 * cell, 0.0));
  const double wp = 2.0 * kPi / s1.peakPeriodS;
  EXPECT_NEAR(s1.peakWavelengthM, 2.0 * kPi / waveNumberExact(wp, depth(100 * cell, 0.0)), 1e-9 * s1.peakWavelengthM);
  EXPECT_LT(s1.peakWavelengthM, 0.8 * s0.peakWavelengthM);
  // From 240 (travel 60) turning toward the shore normal's from-direction, 270.
  EXPECT_GT(s1.waveFromDeg, s0.waveFromDeg + 5.0);
  EXPECT_LT(s1.waveFromDeg, 270.0);
}

// ---- Islands (item 2): diffraction behind a semi-infinite breakwater -------

namespace {
// Fresnel integrals C(x), S(x) by composite Simpson (2000 panels per unit:
// error far below 1e-6 for |x| <= 20); independent of the code under test.
std::complex<double> fresnelCS(double x) {
  const int m = std::max(2, int(std::ceil(std::abs(x) * 2000.0)) * 2);
  const double h = x / m;
  std::complex<double> sum = 0.0;
  for (int i = 0; i <= m; ++i) {
    const double t = i * h, wgt = (i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += wgt * std::complex<double>(std::cos(0.5 * kPi * t * t), std::sin(0.5 * kPi * t * t));
  }
  return sum * h / 3.0;
}
// Sommerfeld's exact solution for a rigid (fully reflecting) semi-infinite
// breakwater (Penney & Price 1952; Coastal Engineering Manual II-7): the
// breakwater on theta = 0 from the tip, the wave coming from theta0 in (0, pi);
// |u| at polar (r, theta) about the tip, theta in [0, 2 pi], relative to the
// incident amplitude. u = e^{-ikr cos(theta - theta0)} F(s1) + e^{-ikr cos(theta + theta0)} F(s2),
// s = 2 sqrt(k r / pi) cos((theta -+ theta0) / 2), F(s) = (1 - i)/2 int_{-inf}^{s} e^{i pi t^2 / 2} dt.
double sommerfeld(double k, double r, double theta, double theta0) {
  const std::complex<double> I(0.0, 1.0);
  auto F = [&](double s) { return (1.0 - I) * 0.5 * (std::complex<double>(0.5, 0.5) + fresnelCS(s)); };
  const double c = 2.0 * std::sqrt(k * r / kPi);
  const std::complex<double> u = std::exp(-I * k * r * std::cos(theta - theta0)) * F(c * std::cos(0.5 * (theta - theta0))) +
                                 std::exp(-I * k * r * std::cos(theta + theta0)) * F(c * std::cos(0.5 * (theta + theta0)));
  return std::abs(u);
}

struct Breakwater {
  double dirRad;  // from the tip (the region's centre) along the breakwater, in the grid (east = 0, ccw)
  double widthM;
  double depthM = 200.0;
  double operator()(double e, double n) const {
    const double along = e * std::cos(dirRad) + n * std::sin(dirRad), across = -e * std::sin(dirRad) + n * std::cos(dirRad);
    return along > 0.0 && std::abs(across) < 0.5 * widthM ? -5.0 : depthM;
  }
};
}  // namespace

// Relative amplitude behind the breakwater, from the island table and from the
// query (the kernel's amplitude of the single component over its amplitude
// far up-wave), against Sommerfeld's solution.
TEST(Coast, BreakwaterDiffractionFollowsSommerfeld) {
  for (double wind : {8.0}) {
    WaveField w = oneComponent(wind, 90.0);
    const double omega = w.components()[0].omega, k = w.components()[0].kRef, lambda = 2.0 * kPi / k;
    const double cell = lambda / 5.0;
    for (double thetaIncDeg : {90.0, 60.0, 120.0}) {
      // Travel direction in the grid (the table's), and the breakwater so
      // that the wave comes from theta0 = thetaInc relative to it.
      CoastField::Region r;
      r.latDeg = 0.3, r.lonDeg = 0.3, r.cellM = cell, r.nodes = 161, r.islandRadiusM = 12.0 * lambda;  // 60 nodes
      std::string err;
      // First the direction (any depth: the travel direction is the region's centre's).
      const CoastField probe = CoastField::build(w, r, [](double, double) { return 1e4; }, err);
      ASSERT_FALSE(probe.empty()) << err;
      const double gamma = std::atan2(probe.islandInputs().travel[0].y, probe.islandInputs().travel[0].x);
      const double theta0 = thetaIncDeg * kPi / 180.0;
      const Breakwater bw{gamma + kPi - theta0, 2.5 * cell};
      auto c = std::make_shared<const CoastField>(CoastField::build(w, r, bw, err));
      ASSERT_FALSE(c->empty()) << err;
      w.setCoast(c);
      Probe p{w, bw, omega};
      const double a0 = p.phaseAmp(-60 * cell * std::cos(gamma), -60 * cell * std::sin(gamma), 3.0).second;
      const int n = r.nodes, half = n / 2;
      // Nearest node to (e, n): its position and its table entry.
      auto node = [&](double e, double nn, double& ex, double& nx) {
        const int i = half + int(std::lround(e / cell)), j = half + int(std::lround(nn / cell));
        ex = (i - half) * cell, nx = (j - half) * cell;
        return c->islands()[std::size_t(j) * n + i].z;
      };
      auto reference = [&](double e, double nn) {
        const double rr = std::hypot(e, nn);
        double th = std::atan2(nn, e) - bw.dirRad;  // from the breakwater, ccw
        th -= 2.0 * kPi * std::floor(th / (2.0 * kPi));
        return sommerfeld(k, rr, th, theta0);
      };
      // On the geometric shadow line (the tip's ray along the travel), 3-5 wavelengths on.
      for (double dist : {3.0, 4.0, 5.0}) {
        double e, nn;
        const double table = node(dist * lambda * std::cos(gamma), dist * lambda * std::sin(gamma), e, nn);
        const double ref = reference(e, nn), query = p.phaseAmp(e, nn, 3.0).second / a0;
        std::printf("wind %.0f inc %.0f shadow line %.0f L: table %.3f query %.3f sommerfeld %.3f\n", wind,
                    thetaIncDeg, dist, table, query, ref);
        EXPECT_NEAR(table, 0.5, 0.1) << "inc " << thetaIncDeg << " at " << dist << " wavelengths";
        EXPECT_NEAR(table, ref, 0.1);
        EXPECT_NEAR(query, table, 0.02);
      }
      // Into the shadow (toward the breakwater's lee face) at 4 wavelengths
      // from the tip: falling monotonically, as the reference.
      double prev = 1.0;
      const double side = std::sin(bw.dirRad - gamma) > 0 ? 1.0 : -1.0;
      for (double intoDeg : {8.0, 16.0, 24.0, 32.0, 40.0}) {
        // Stay 20 degrees off the lee face (a 2.5-cell wall of nodes: 7 cells away there).
        if (intoDeg >= 180.0 - thetaIncDeg - 20.0) break;
        const double a = gamma + side * intoDeg * kPi / 180.0;
        double e, nn;
        const double table = node(4.0 * lambda * std::cos(a), 4.0 * lambda * std::sin(a), e, nn);
        const double ref = reference(e, nn);
        std::printf("  into %.0f deg: table %.3f sommerfeld %.3f\n", intoDeg, table, ref);
        EXPECT_LT(table, prev) << "inc " << thetaIncDeg << " into " << intoDeg;
        EXPECT_NEAR(table, ref, 0.1) << "inc " << thetaIncDeg << " into " << intoDeg;
        prev = table;
      }
    }
  }
}

// Shorter waves are lower in the same shadow (Sommerfeld: the Fresnel
// parameter grows with sqrt(k r)): two seas on one grid and one breakwater.
TEST(Coast, BreakwaterShadowIsDeeperForShorterWaves) {
  WaveField shortW = oneComponent(8.0, 90.0), longW = oneComponent(12.0, 90.0);
  const double lShort = 2.0 * kPi / shortW.components()[0].kRef, lLong = 2.0 * kPi / longW.components()[0].kRef;
  ASSERT_GT(lLong, 1.5 * lShort);
  CoastField::Region r;
  r.latDeg = 0.3, r.lonDeg = 0.3, r.cellM = lShort / 5.0, r.nodes = 161, r.islandRadiusM = 12.0 * lShort;
  std::string err;
  const Breakwater bw{0.5 * kPi, 2.5 * r.cellM};  // north from the tip; both seas travel east within 3 degrees
  const CoastField a = CoastField::build(shortW, r, bw, err), b = CoastField::build(longW, r, bw, err);
  ASSERT_FALSE(a.empty() || b.empty()) << err;
  const int n = r.nodes, half = n / 2;
  for (double intoDeg : {10.0, 20.0, 30.0}) {
    const double ang = intoDeg * kPi / 180.0, dist = 4.0 * lShort;
    const int i = half + int(std::lround(dist * std::cos(ang) / r.cellM)), j = half + int(std::lround(dist * std::sin(ang) / r.cellM));
    const double sa = a.islands()[std::size_t(j) * n + i].z, sb = b.islands()[std::size_t(j) * n + i].z;
    std::printf("into %.0f deg at %.0f m: short (%.0f m) %.3f, long (%.0f m) %.3f\n", intoDeg, dist, lShort, sa, lLong, sb);
    EXPECT_LT(sa, sb - 0.03) << intoDeg;
  }
}

// Item 7: the sheltered side of a round island has lower waves, which
// recover with distance behind it. Reference: Fresnel diffraction behind an
// opaque strip of the island's width (Born & Wolf sec. 8.7: on the axis at
// distance z, u = 1 - (1 - i)(C(v) + i S(v)), v = R sqrt(2 / (lambda z))),
// what the island looks like to a wave once z is a few radii; within 0.1
// as the breakwater's table (the same method bias), and rising with z.
// Points within half the occlusion reach (12 wavelengths, capped at 64
// nodes): the table fades a shadow out between R/2 and R by design.
TEST(Coast, ARoundIslandShelterRecoversWithDistanceAsFresnelDiffraction) {
  WaveField w = oneComponent(8.0, 90.0);
  const double omega = w.components()[0].omega, k = w.components()[0].kRef, lambda = 2.0 * kPi / k;
  const double radius = 1.5 * lambda, cell = lambda / 5.0;
  CoastField::Region r;
  r.latDeg = 0.3, r.lonDeg = 0.3, r.cellM = cell, r.nodes = 161, r.islandRadiusM = 12.0 * lambda;
  std::string err;
  const CoastField probe = CoastField::build(w, r, [](double, double) { return 1e4; }, err);
  ASSERT_FALSE(probe.empty()) << err;
  const glm::dvec2 travel = glm::normalize(glm::dvec2(probe.islandInputs().travel[0]));
  const auto island = [&](double e, double n) { return std::hypot(e, n) < radius ? -5.0 : 200.0; };
  auto c = std::make_shared<const CoastField>(CoastField::build(w, r, island, err));
  ASSERT_FALSE(c->empty()) << err;
  w.setCoast(c);
  Probe p{w, island, omega};
  // The incident amplitude up-wave, and its value in front of the island.
  const double a0 = p.phaseAmp(-14.0 * lambda * travel.x, -14.0 * lambda * travel.y, 3.0).second;
  const double front = p.phaseAmp(-3.0 * lambda * travel.x, -3.0 * lambda * travel.y, 3.0).second / a0;
  std::printf("round island R %.0f m (%.1f wavelengths of %.0f m): up-wave %.3f\n", radius, radius / lambda, lambda, front);
  EXPECT_NEAR(front, 1.0, 0.05);
  double prev = 0.0;
  for (double zL : {3.0, 4.5, 6.0}) {
    const double z = zL * lambda;
    const double behind = p.phaseAmp(z * travel.x, z * travel.y, 3.0).second / a0;
    const std::complex<double> I(0.0, 1.0);
    const double v = radius * std::sqrt(2.0 / (lambda * z));
    const double ref = std::abs(1.0 - (1.0 - I) * fresnelCS(v));
    std::printf("  %.0f wavelengths behind: %.3f, Fresnel strip %.3f\n", zL, behind, ref);
    EXPECT_LT(behind, 0.9) << zL;
    EXPECT_GT(behind, prev) << zL;
    EXPECT_NEAR(behind, ref, 0.1) << zL;
    prev = behind;
  }
}

// ---- Curl and breaking (item 3, paper 003 eq. 5-6) -------------------------

namespace {
// Pierson-Moskowitz's deep-water Hs and peak wavelength (the sea every
// SeaState without fetch draws): m0 = a g^2 / (5 wp^4), wp = 0.877 g / U.
double pmSteepness(double u) {
  const double wp = 0.877 * kG / u;
  const double hs = 4.0 * std::sqrt(0.0081 / 5.0) * kG / (wp * wp), l0 = 2.0 * kPi * kG / (wp * wp);
  return hs / l0;
}
// A planar beach: depth `slope` per m from the shoreline at e = shoreM (land east of it).
std::function<double(double, double)> planarBeach(double slope, double shoreM) {
  return [=](double e, double) { return slope * (shoreM - e); };
}
WaveField fullSea(double windMps) {
  SeaState sea;
  sea.windSpeedMps = windMps;
  sea.windFromDeg = 270.0;  // travelling east, onto the beaches' shore
  sea.anchorLatDeg = 0.3;
  sea.anchorLonDeg = 0.3;
  sea.seed = 5;
  std::string err;
  auto w = WaveField::create(Model::Gerstner, sea, err);
  EXPECT_TRUE(w) << err;
  return *w;
}

// Forward lean of the crest nearest rest point e0 on the line north = 0 at
// time t, from the drawn profile (x + displacement, height) of one
// component: (back - front) / (back + front), back and front the distances
// from the crest to the zero crossings behind and ahead of it; 0 for a
// symmetric crest, > 0 when it leans shoreward (east). NaN if not found.
double crestLean(const WaveField& w, const std::function<double(double, double)>& depth, double e0, double lenM,
                 double t) {
  const CoastField* c = w.coastField();
  std::vector<double> x, z;
  for (double e = e0 - lenM; e <= e0 + lenM; e += lenM / 400.0) {
    const geo::Geodetic g = geo::fromEcef(c->centreEcef() + c->east() * e);
    const WaveSample s = w.sample(g.latDeg, g.lonDeg, t, std::max(depth(e, 0.0), 0.05));
    x.push_back(e + s.displacementEnuM.x);
    z.push_back(s.displacementEnuM.z);
  }
  int best = -1;
  for (int i = 1; i + 1 < int(z.size()); ++i)
    if (z[i] > 0 && z[i] >= z[i - 1] && z[i] >= z[i + 1] && (best < 0 || std::abs(x[i] - e0) < std::abs(x[best] - e0)))
      best = i;
  if (best < 0) return std::nan("");
  auto crossing = [&](int i) { return x[i] + (x[i + 1] - x[i]) * z[i] / (z[i] - z[i + 1]); };
  double back = std::nan(""), front = std::nan("");
  for (int i = best - 1; i >= 0; --i)
    if (z[i] <= 0) { back = x[best] - crossing(i); break; }
  for (int i = best; i + 1 < int(z.size()); ++i)
    if (z[i + 1] <= 0) { front = crossing(i) - x[best]; break; }
  return (back - front) / (back + front);
}
}  // namespace

// The breaker type on planar beaches of chosen slopes: the field's tan(beta)
// is the slope and its Iribarren number tan(beta) / sqrt(H0 / L0) the one
// computed here from Pierson-Moskowitz's closed forms (1%: the spectrum's
// Hs is integrated numerically, 0.2%); spilling, plunging, surging by
// Battjes' bounds 0.4 and 2, with curl only on the plunging beach and no
// collapse on the surging one.
TEST(Coast, IribarrenNumberClassifiesPlanarBeaches) {
  const double wind = 8.0, steep = std::sqrt(pmSteepness(wind));
  const WaveField w = fullSea(wind);
  struct Want {
    double slope;
    CoastField::Breaker type;
  };
  for (const Want& want : {Want{0.03, CoastField::Breaker::Spilling}, Want{0.16, CoastField::Breaker::Plunging},
                           Want{0.6, CoastField::Breaker::Surging}}) {
    const double xi = want.slope / steep;
    ASSERT_EQ(CoastField::breakerType(xi), want.type) << "slope " << want.slope << " xi " << xi;
    const auto c = buildField(w, 2.0, 201, planarBeach(want.slope, 150.0), 8.0);
    for (double e : {-120.0, -50.0, 0.0, 60.0, 110.0}) {
      const CoastField::Beach b = c->beachAt(e, 30.0);
      EXPECT_NEAR(b.tanBeta, want.slope, 1e-9 * want.slope) << "e " << e;
      EXPECT_NEAR(b.iribarren, xi, 0.01 * xi) << "slope " << want.slope << " e " << e;
      EXPECT_EQ(b.type, want.type) << CoastField::breakerName(b.type) << " slope " << want.slope << " xi " << b.iribarren;
      EXPECT_EQ(b.curlWeight > 0.0, want.type == CoastField::Breaker::Plunging) << "slope " << want.slope;
      EXPECT_EQ(b.breakWeight > 0.0, want.type != CoastField::Breaker::Surging) << "slope " << want.slope;
    }
    if (want.type == CoastField::Breaker::Plunging) {  // Region::breaking = false: the weights 0, xi kept
      CoastField::Region r = c->region();
      r.breaking = false;
      std::string err;
      const CoastField off = CoastField::build(w, r, planarBeach(want.slope, 150.0), err);
      ASSERT_FALSE(off.empty()) << err;
      const CoastField::Beach b = off.beachAt(0.0, 30.0);
      EXPECT_EQ(b.iribarren, c->beachAt(0.0, 30.0).iribarren);
      EXPECT_EQ(b.curlWeight, 0.0);
      EXPECT_EQ(b.breakWeight, 0.0);
    }
    std::printf("slope %.2f: xi %.3f (theory %.3f), %s\n", want.slope, c->beachAt(0.0, 30.0).iribarren, xi,
                CoastField::breakerName(c->beachAt(0.0, 30.0).type));
  }
}

// Eq. 5: on a plunging beach the crest of a wave leans forward, more as the
// depth decreases (k h 3 -> 0.7), and is symmetric in deep water; on a
// spilling beach at the same k h it stays symmetric (so the lean is the
// curl's, not the shoaling's).
TEST(Coast, CrestLeansForwardAsDepthDecreasesOnAPlungingBeach) {
  // A low wave (5 m/s wind's): unbroken down to k h = 0.7 (H < 0.78 h there).
  WaveField w = oneComponent(5.0, 90.0);
  const double omega = w.components()[0].omega, steep = std::sqrt(pmSteepness(5.0));
  for (double slope : {0.8 * steep, 0.15 * steep}) {  // xi 0.8 (plunging), 0.15 (spilling)
    // The ramp from k h = 4 to the shore across the grid, a deep strip west of it and land east.
    const double hDeep = depthForKh(omega, 4.0), ramp = hDeep / slope, shore = 0.5 * ramp;
    const double cell = std::clamp(ramp / 250.0, 0.5, 3.0);
    auto depth = [=](double e, double) { return std::min(hDeep, slope * (shore - e)); };
    const int nodes = 2 * int(std::ceil(0.6 * ramp / cell)) + 1;
    w.setCoast(buildField(w, cell, nodes, depth, 4.0 * cell));
    double last = -1.0;
    std::printf("slope %.3f (xi %.2f):", slope, slope / steep);
    for (double kh : {3.0, 1.5, 1.0, 0.7}) {
      const double h = depthForKh(omega, kh), e = shore - h / slope, len = 0.6 * 2.0 * kPi * h / kh;
      double lean = 0.0;
      int n = 0;
      for (int i = 0; i < 16; ++i) {  // over one period
        const double l = crestLean(w, depth, e, len, 3.0 + i * (2.0 * kPi / omega) / 16.0);
        if (std::isfinite(l)) lean += l, ++n;
      }
      ASSERT_GE(n, 8) << "kh " << kh;
      lean /= n;
      std::printf(" kh %.1f lean %.3f", kh, lean);
      if (slope > 0.5 * steep) {
        if (kh == 3.0) {
          EXPECT_LT(std::abs(lean), 0.03) << "deep water: symmetric";
        } else {
          EXPECT_GT(lean, last + 0.01) << "kh " << kh;
        }
        last = lean;
      } else {
        EXPECT_LT(std::abs(lean), 0.03) << "spilling beach, kh " << kh;
      }
    }
    std::printf("\n");
    if (slope > 0.5 * steep) {
      EXPECT_GT(last, 0.1) << "the shallowest crest leans";
    }
  }
}

// Eq. 6 and the foam: over a plunging beach a full sea's height at fixed
// points stays within 0.78 h crest to trough however it breaks; the
// breaking foam is 0 where the waves do not break and present in the
// surf zone.
TEST(Coast, BreakingCapsHeightsAndFoamsTheSurfZone) {
  const double wind = 8.0, slope = 0.1;  // xi 0.62: plunging
  WaveField w = fullSea(wind);
  const auto beach = planarBeach(slope, 400.0);
  auto depth = [&](double e, double n) { return std::min(beach(e, n), 60.0); };
  w.setCoast(buildField(w, 4.0, 301, depth, 16.0));
  ASSERT_EQ(w.coastField()->beachAt(300.0, 0.0).type, CoastField::Breaker::Plunging);
  Probe p{w, depth, 1.0};
  for (double h : {40.0, 8.0, 4.0, 2.0, 1.0}) {
    const double e = 400.0 - h / slope;
    double top = -1e9, bottom = 1e9, foam = 0.0;
    for (int i = 0; i < 60; ++i) {
      const double t = 1.0 + 0.41 * i;
      for (double n : {-40.0, 0.0, 40.0}) {
        const geo::Geodetic g = p.at(e, n);
        const SurfacePoint s = w.surfaceAt(g.latDeg, g.lonDeg, t, h);
        top = std::max(top, s.heightM);
        bottom = std::min(bottom, s.heightM);
        foam = std::max(foam, w.sample(g.latDeg, g.lonDeg, t, h).breakingFoam);
      }
    }
    // The curl's and the collapse's derivatives are the kernel's own: the
    // normal is perpendicular to the drawn surface and d(eta)/dt of the
    // particle is the time derivative (central differences, 1 mm and 1 ms
    // steps: truncation ~1e-6). The normal within 2.5e-3: the kernel's slope
    // takes k s for the phase gradient, which the field's bilinear phase
    // between nodes misses by ~1e-3 (measured 0.28e-3 at 40 m, 1.4e-3 at
    // 1 m; 2.0e-3 at 1 m with the stratified directions of issue 13 item 2);
    // without the curl's d(psx)/d(psi) it was 3.7e-3 .. 7.6e-3 at 4 .. 1 m.
    double worstNormal = 0.0, worstVelocity = 0.0;
    for (int i = 0; i < 20; ++i) {
      const double t = 2.0 + 0.53 * i, dx = 1e-3, dt = 1e-3;
      auto disp = [&](double de, double dn, double tt) {
        const geo::Geodetic g = p.at(e + de, dn);
        return w.sample(g.latDeg, g.lonDeg, tt, h);
      };
      const WaveSample s0 = disp(0, 0, t);
      const glm::dvec3 te = (glm::dvec3(2 * dx, 0, 0) + disp(dx, 0, t).displacementEnuM - disp(-dx, 0, t).displacementEnuM);
      const glm::dvec3 tn = (glm::dvec3(0, 2 * dx, 0) + disp(0, dx, t).displacementEnuM - disp(0, -dx, t).displacementEnuM);
      worstNormal = std::max({worstNormal, std::abs(glm::dot(s0.normalEnu, glm::normalize(te))),
                              std::abs(glm::dot(s0.normalEnu, glm::normalize(tn)))});
      const double dzdt = (disp(0, 0, t + dt).displacementEnuM.z - disp(0, 0, t - dt).displacementEnuM.z) / (2 * dt);
      worstVelocity = std::max(worstVelocity, std::abs(dzdt - s0.verticalVelocityMps));
    }
    EXPECT_LT(worstNormal, 2.5e-3) << "h " << h;
    EXPECT_LT(worstVelocity, 1e-4) << "h " << h;
    std::printf("h %.0f m: crest to trough %.3f m (0.78 h %.3f), foam max %.3f; normal . tangent %.2g, "
                "|w - dz/dt| %.2g m/s\n", h, top - bottom, 0.78 * h, foam, worstNormal, worstVelocity);
    EXPECT_LE(top - bottom, 0.78 * h * (1.0 + 1e-9)) << "h " << h;
    if (h >= 40.0) {
      EXPECT_EQ(foam, 0.0);
    }
    if (h <= 2.0) {
      EXPECT_GT(foam, 0.3) << "h " << h;
    }
  }
}

// Issue 15 item 4: the far distance band draws the breaking foam averaged
// over the waves' phases (WaveField::breakingFoamMean); at a fixed rest
// point the phases run through all their values in time, so the mean is
// the time average of the instantaneous foam (the near band's). 4000
// times over 2 h at depths through the surf zone; tolerance: 3 standard
// errors of the time average (from 40 block means of 100 consecutive
// samples, which decorrelates them), and 0.01 of absolute model error for the
// Gram-Charlier density (a sum of finitely many cosines is not Gaussian).
// Measured: 0.184 against time averages 0.184-0.188 (se 0.002).
TEST(Coast, BreakingFoamMeanIsTheTimeAverageOfTheFoam) {
  const double wind = 8.0, slope = 0.1;  // as BreakingCapsHeightsAndFoamsTheSurfZone
  WaveField w = fullSea(wind);
  const auto beach = planarBeach(slope, 400.0);
  auto depth = [&](double e, double n) { return std::min(beach(e, n), 60.0); };
  w.setCoast(buildField(w, 4.0, 301, depth, 16.0));
  Probe p{w, depth, 1.0};
  int foaming = 0;
  for (double h : {40.0, 4.0, 2.0, 1.0, 0.5}) {
    for (double n : {-40.0, 30.0}) {
      const double e = 400.0 - h / slope;
      const geo::Geodetic g = p.at(e, n);
      const WaveField::BreakingMean m = w.breakingFoamMean(g.latDeg, g.lonDeg, 0.0, h);
      constexpr int kBlocks = 40, kPer = 100;
      double sum = 0.0, sum2 = 0.0;
      for (int b = 0; b < kBlocks; ++b) {
        double block = 0.0;
        for (int i = 0; i < kPer; ++i) block += w.sample(g.latDeg, g.lonDeg, 1.0 + 1.83 * (b * kPer + i), h).breakingFoam;
        block /= kPer;
        sum += block, sum2 += block * block;
      }
      const double mean = sum / kBlocks, se = std::sqrt(std::max(0.0, sum2 / kBlocks - mean * mean) / (kBlocks - 1));
      std::printf("h %.1f m, n %.0f: foam time average %.4f (se %.4f), phase mean %.4f; local wavelength %.1f m\n", h,
                  n, mean, se, m.foam, m.wavelengthM);
      EXPECT_NEAR(m.foam, mean, 3.0 * se + 0.01) << "h " << h;
      EXPECT_GT(m.wavelengthM, 0.0);
      if (h >= 40.0) {
        EXPECT_EQ(m.foam, 0.0);
      }
      foaming += m.foam > 0.05;
    }
  }
  EXPECT_GE(foaming, 4) << "the surf zone foams on average";
  // The wavelength is the local one: shorter in shallower water.
  const geo::Geodetic deep = p.at(0.0, 0.0), shallow = p.at(390.0, 0.0);
  EXPECT_LT(w.breakingFoamMean(shallow.latDeg, shallow.lonDeg, 0.0, 1.0).wavelengthM,
            0.6 * w.breakingFoamMean(deep.latDeg, deep.lonDeg, 0.0, 40.0).wavelengthM);
}

// Issue 15 item 1's leftover, a shelf with no deep water in reach
// (waves::OuterPhase): deep water (4 km) west of 40 km before a line of
// longitude, a ramp to 20 m over 10 km, then 20 m on for 136 km: a
// region 30 km past the ramp has no deep inflow node.
namespace {
constexpr double kShelfLat = 0.3, kShelfLon = 0.3;
double shelfDepthAtLon(double lonDeg) {
  const double xKm = (lonDeg - kShelfLon) * 111.32;  // east of the reference line (at the equator, to 0.1 %)
  if (xKm < -40.0) return 4000.0;
  if (xKm < -30.0) return 4000.0 + (xKm + 40.0) / 10.0 * (20.0 - 4000.0);
  return 20.0;
}
// depthAt(east, north) of the tangent plane at (lat, lon), as the façade's.
std::function<double(double, double)> shelfDepthAbout(double latDeg, double lonDeg) {
  const geo::EnuFrame f = geo::enuFrame({latDeg, lonDeg, 0.0});
  return [f](double e, double n) { return shelfDepthAtLon(geo::fromEcef(f.originEcef + f.east * e + f.north * n).lonDeg); };
}
// The wave number of linear theory at depth h (Newton on w^2 = g k tanh(k h)).
double waveNumber(double omega, double h) {
  double k = omega * omega / kG / std::sqrt(std::tanh(omega * omega * h / kG));
  for (int i = 0; i < 50; ++i) {
    const double t = std::tanh(k * h), f = kG * k * t - omega * omega;
    k -= f / (kG * t + kG * k * h * (1.0 - t * t));
  }
  return k;
}
}  // namespace

// The outer phase's offset is the excess phase gathered from deep water:
// over straight contours (Snell: k sin(theta) = k0 sin(theta0) conserved)
// offset(x) = integral of sqrt(k(h)^2 - k0^2 sin^2 theta0) - k0 cos theta0
// from deep water to x (0 there), integrated here in 1 m steps with k from
// linear theory. A 15 m/s sea's peak component (k h ~ 1 at 20 m) gathers
// 110 rad 10 km past the ramp and 165 rad at 30 km. On the shelf, the
// gain between the two (the local wave number, what the waves show) is
// bounded by 0.1 %: measured 0.00 %. The whole offset by 1 %: measured
// 0.5 rad (0.5 %) low at both, all of it gathered in the ramp, where the
// depth falls from 100 m to 20 m within one 500 m cell (first-order in
// the cell there); a constant phase is no visible change in a random sea.
TEST(Coast, OuterPhaseIsTheExcessPhaseFromDeepWaterOverAWideShelf) {
  const WaveField w = oneComponent(15.0, 95.0);  // 5 degrees oblique to the contours; k h ~ 1 at 20 m
  double lat = 0.0, lon = 0.0;
  OuterPhase::latticePoint(kShelfLat, kShelfLon, lat, lon);
  EXPECT_EQ(lat, 0.25);
  EXPECT_EQ(lon, 0.25);
  std::string err;
  const OuterPhase op = OuterPhase::build(w, lat, lon, shelfDepthAbout(lat, lon), err);
  ASSERT_FALSE(op.empty()) << err;
  EXPECT_FALSE(op.reversed(0));
  const WaveField::Component& c = w.components()[0];
  // The travel at the reference line (the kernel's great circle there).
  const geo::EnuFrame f = geo::enuFrame({kShelfLat, kShelfLon, 0.0});
  const glm::dvec3 radial = glm::normalize(f.originEcef);
  const glm::dvec3 g = glm::normalize(radial * glm::dot(c.source, radial) - c.source);
  const double sinT0 = glm::dot(g, f.north), cosT0 = glm::dot(g, f.east);
  const double ky = c.kRef * sinT0;
  double got[3] = {0, 0, 0}, want[3] = {0, 0, 0};
  int m = 0;
  for (const double xKm : {-45.0, 10.0, 30.0}) {
    double expected = 0.0;
    for (double x = -45e3; x < xKm * 1e3; x += 1.0) {
      const double k = waveNumber(c.omega, shelfDepthAtLon(kShelfLon + (x + 0.5) / 111320.0));
      expected += std::sqrt(k * k - ky * ky) - c.kRef * cosT0;
    }
    const glm::dvec2 o = op.sample(0, f.originEcef + f.east * (xKm * 1e3));
    std::printf("%5.0f km past the reference line: outer offset %.3f rad, integral %.3f rad\n", xKm, o.x, expected);
    ASSERT_TRUE(std::isfinite(o.x));
    EXPECT_NEAR(o.x, expected, 1e-2 * std::abs(expected) + 1e-6) << xKm << " km";
    got[m] = o.x, want[m] = expected, ++m;
  }
  EXPECT_NEAR(got[2] - got[1], want[2] - want[1], 1e-3 * (want[2] - want[1])) << "the gain from 10 to 30 km";
}

// Two regions 2.8 km apart across the shelf's contours, 30 km past the
// ramp (no deep node in either): with the outer phase their heights over
// the interiors' overlap agree within 5 % of Hs (the bound of
// OceanCoast.FollowedRegionsAgreeWhereTheyOverlap, the model's own
// amplitude accuracy); each alone (the old rule: the plane wave at its
// own west edge) differs by (k - k0) x 2.8 km, tens of radians, so by
// about what two independent seas do. Measured (10 m/s, Hs 2.13 m, bound
// 0.107 m): with it max 0.0000 m (every node is 20 m deep, so both take
// the one outer field); alone median 0.33 m, max 1.8 m.
TEST(Coast, TwoRegionsOnAWideShelfAgreeThroughTheOuterPhase) {
  SeaState sea;
  sea.windSpeedMps = 10.0;
  sea.windFromDeg = 270.0;
  sea.anchorLatDeg = kShelfLat;
  sea.anchorLonDeg = kShelfLon;
  std::string err;
  const auto w = WaveField::create(Model::Gerstner, sea, err);
  ASSERT_TRUE(w) << err;
  double lat = 0.0, lon = 0.0;
  OuterPhase::latticePoint(kShelfLat, kShelfLon + 0.3, lat, lon);
  const OuterPhase op = OuterPhase::build(*w, lat, lon, shelfDepthAbout(lat, lon), err);
  ASSERT_FALSE(op.empty()) << err;
  const double lonA = kShelfLon + 0.3, lonB = lonA + 0.025;  // 33 and 36 km past the reference line
  auto region = [&](double lonDeg, bool outer) {
    CoastField::Region r;
    r.latDeg = kShelfLat, r.lonDeg = lonDeg, r.nodes = 201, r.cellM = 50.0;
    auto cf = std::make_shared<const CoastField>(CoastField::build(
        *w, r, shelfDepthAbout(r.latDeg, r.lonDeg), err,
        outer ? std::function<const OuterPhase*()>([&] { return &op; }) : std::function<const OuterPhase*()>()));
    EXPECT_FALSE(cf->empty()) << err;
    auto field = std::make_shared<WaveField>(*w);
    field->setCoast(cf);
    return field;
  };
  const double bound = 0.05 * w->spectrumHsM();
  for (const bool outer : {true, false}) {
    const auto a = region(lonA, outer), b = region(lonB, outer);
    if (outer) {
      EXPECT_GT(a->coastField()->outerComponents(), w->components().size() / 2);
      EXPECT_EQ(a->coastField()->outerComponents(), b->coastField()->outerComponents());
    } else {
      EXPECT_EQ(a->coastField()->outerComponents(), 0);
    }
    // Interiors' overlap (8-node margins left out): 100 m lattice.
    std::vector<double> d;
    for (double dn = -4500.0; dn <= 4500.0; dn += 100.0)
      for (double de = 2800.0 - 4500.0; de <= 4500.0; de += 100.0) {
        const geo::EnuFrame f = geo::enuFrame({kShelfLat, lonA, 0.0});
        const geo::Geodetic p = geo::fromEcef(f.originEcef + f.east * de + f.north * dn);
        d.push_back(std::abs(a->surfaceAt(p.latDeg, p.lonDeg, 41.5, 20.0).heightM -
                             b->surfaceAt(p.latDeg, p.lonDeg, 41.5, 20.0).heightM));
      }
    std::sort(d.begin(), d.end());
    std::printf("%s: over %zu points median |h_A - h_B| %.4f m, max %.4f m (Hs %.2f m, bound %.3f m)\n",
                outer ? "with the outer phase" : "each region alone", d.size(), d[d.size() / 2], d.back(),
                w->spectrumHsM(), bound);
    if (outer)
      EXPECT_LT(d.back(), bound);
    else
      EXPECT_GT(d[d.size() / 2], bound) << "the old rule was expected to fail here";
  }
}
