// Floating bodies against physics: Archimedes (the analytically clipped box),
// the equilibrium draft, the heave and roll periods of hydrostatics, the
// capsize of a box with negative metacentric height, the heave response to
// long and short regular (Airy) waves, calm-sea drift, convergence in dt,
// stability at dt = 1/15 and determinism on the ocean façade's Gerstner sea.
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/OceanSea.h"
#include "plugin/bodies/Simulation.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

using namespace geocean;
using namespace geocean::bodies;
using test::orientationAt;
using test::stateAt;

namespace {

constexpr double kRho = 1025.0;
constexpr double kPi = std::numbers::pi;
const geo::Geodetic kAt{30.0, -40.0, 0.0};  // open Atlantic

// A regular Airy wave travelling east along the equator's parallel through
// lon 0: eta = a r(t) cos(k x - w t), x = east distance, r a cosine ramp over
// rampS (so the wave starts without a transient); deep water, w^2 = g k.
class AiryWave final : public SeaSurface {
 public:
  AiryWave(double amplitudeM, double wavelengthM, double g, double rampS)
      : a_(amplitudeM), k_(2 * kPi / wavelengthM), w_(std::sqrt(g * 2 * kPi / wavelengthM)), ramp_(rampS) {}
  void sample(const double*, const double* lon, const double* t, std::size_t n, bool, SeaSample* out) const override {
    for (std::size_t i = 0; i < n; ++i) {
      const double x = lon[i] * kPi / 180.0 * 6378137.0;
      const double r = t[i] >= ramp_ ? 1.0 : 0.5 * (1.0 - std::cos(kPi * std::max(t[i], 0.0) / ramp_));
      const double ph = k_ * x - w_ * t[i];
      out[i].heightM = a_ * r * std::cos(ph);
      out[i].verticalVelocityMps = a_ * r * w_ * std::sin(ph);
      out[i].horizontalVelocityEnMps = {a_ * r * w_ * std::cos(ph), 0.0};
    }
  }
  double decayWaveNumberPerM() const override { return k_; }
  void sampleSlopes(const double* lat, const double* lon, const double* t, std::size_t n,
                    SeaSample* out) const override {
    sample(lat, lon, t, n, true, out);
    for (std::size_t i = 0; i < n; ++i) {
      const double x = lon[i] * kPi / 180.0 * 6378137.0;
      const double r = t[i] >= ramp_ ? 1.0 : 0.5 * (1.0 - std::cos(kPi * std::max(t[i], 0.0) / ramp_));
      out[i].horizontalVelocityEnMps = {0.0, 0.0};
      out[i].slopeEn = {-a_ * r * k_ * std::sin(k_ * x - w_ * t[i]), 0.0};
    }
  }
  // One wavelength: HullForce's sea grid follows it.
  double shortestWavelengthM() const override { return 2 * kPi / k_; }
  double omega() const { return w_; }

 private:
  double a_, k_, w_, ramp_;
};

struct Floater {
  std::unique_ptr<Simulation> sim;
  BodyId id = 0;
  std::shared_ptr<HullForce> force;
  const BodyState& state() const { return sim->body(id).state; }
  geo::Geodetic where() const { return geo::fromEcef(state().positionEcef); }
};

Floater makeFloater(const HullMesh& hull, double density, std::shared_ptr<const SeaSurface> sea,
                    const geo::Geodetic& at, double rollDeg = 0.0, double pitchDeg = 0.0, double dt = 1.0 / 120.0,
                    HullForceOptions opt = {}) {
  Floater f;
  f.sim = std::make_unique<Simulation>(SimulationConfig{.stepS = dt});
  BodyState s = stateAt(at);
  s.orientation = orientationAt(at, rollDeg, pitchDeg);
  f.id = f.sim->addBody(hull.massProperties(density), s);
  f.force = std::make_shared<HullForce>(std::make_shared<HullMesh>(hull), std::move(sea), opt);
  f.sim->addBodyForce(f.id, f.force);
  return f;
}

// Volume of the box [0,a]x[0,b]x[0,c] where n . y <= t (every n_i != 0):
// inclusion-exclusion over the corners, sum (-1)^|v| max(0, t - n.(v*size))^3
// / (6 n1 n2 n3) with the axes flipped so every n_i > 0.
double clippedBoxVolume(glm::dvec3 n, double t, const glm::dvec3& size) {
  for (int i = 0; i < 3; ++i)
    if (n[i] < 0) t -= n[i] * size[i], n[i] = -n[i];
  double v = 0.0;
  for (int m = 0; m < 8; ++m) {
    double s = t;
    int bits = 0;
    for (int i = 0; i < 3; ++i)
      if (m >> i & 1) s -= n[i] * size[i], ++bits;
    if (s > 0) v += (bits % 2 ? -1.0 : 1.0) * s * s * s;
  }
  return v / (6.0 * n.x * n.y * n.z);
}

// Upward zero crossings of x(t) - mean, linearly interpolated.
std::vector<double> upCrossings(const std::vector<double>& t, const std::vector<double>& x, double mean) {
  std::vector<double> c;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < mean && x[i] >= mean)
      c.push_back(t[i - 1] + (t[i] - t[i - 1]) * (mean - x[i - 1]) / (x[i] - x[i - 1]));
  return c;
}

// Least squares of x(t) on 1, cos w t, sin w t, cos w2 t, sin w2 t: the
// amplitude at w with the free oscillation at w2 taken out.
double amplitudeAt(const std::vector<double>& t, const std::vector<double>& x, double w, double w2) {
  constexpr int K = 5;
  double A[K][K] = {}, b[K] = {};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double f[K] = {1.0, std::cos(w * t[i]), std::sin(w * t[i]), std::cos(w2 * t[i]), std::sin(w2 * t[i])};
    for (int r = 0; r < K; ++r) {
      b[r] += f[r] * x[i];
      for (int c = 0; c < K; ++c) A[r][c] += f[r] * f[c];
    }
  }
  for (int p = 0; p < K; ++p)  // Gauss-Jordan (the normal matrix is positive definite)
    for (int r = 0; r < K; ++r) {
      if (r == p) continue;
      const double m = A[r][p] / A[p][p];
      for (int c = 0; c < K; ++c) A[r][c] -= m * A[p][c];
      b[r] -= m * b[p];
    }
  return std::hypot(b[1] / A[1][1], b[2] / A[2][2]);
}

double heaveNaturalOmega(const Floater& f, double density, const HullMesh& h) {
  const glm::dvec3 ext = h.maxCorner() - h.minCorner();
  const double m = density * h.volumeM3();
  const double g = f.sim->context(f.state()).gravityMps2;
  return std::sqrt(kRho * g * ext.x * ext.y / (m + f.force->fullHeaveAddedMassKg()));
}

}  // namespace

TEST(BodyBuoyancy, HeldPoseForceIsRhoGTimesTheAnalyticallyClippedVolume) {
  const glm::dvec3 size(6.0, 3.0, 2.0);
  const HullMesh box = HullMesh::box(size, 3);
  auto sea = std::make_shared<FlatSea>();
  for (double roll : {5.0, 17.0, 40.0})
    for (double pitch : {3.0, -11.0})
      for (double h0 : {-0.7, 0.0, 0.45}) {
        const geo::Geodetic at{kAt.latDeg, kAt.lonDeg, h0};
        Floater f = makeFloater(box, 500.0, sea, at, roll, pitch);
        const StepContext ctx = f.sim->context(f.state());
        const HullEvaluation e = f.force->evaluate(f.state(), f.sim->body(f.id).mass, ctx);
        // The sea (height 0) in body axes: up . x <= -h0, x about the centre.
        const glm::dvec3 up = f.state().ecefToBody(ctx.enu.up);
        const double V = clippedBoxVolume(up, -h0 + glm::dot(up, 0.5 * size), size);
        const glm::dvec3 F = ctx.enu.toLocal(e.wrench.force());
        const double W = kRho * ctx.gravityMps2 * V;
        // 1e-4 (the brief); what is left is the ellipsoid's curvature under
        // a 6 m box, ~(3 m)^2 / 2R / draft ~ 1e-6.
        EXPECT_NEAR(F.z, W, 1e-4 * W) << roll << " " << pitch << " " << h0;
        EXPECT_LT(std::hypot(F.x, F.y), 1e-4 * W);
        EXPECT_NEAR(e.submergedVolumeM3, V, 1e-4 * V);
      }
}

TEST(BodyBuoyancy, BoxFloatsAtDraftRhoBodyOverRhoWaterTimesHeight) {
  const double H = 2.0;
  const HullMesh box = HullMesh::box({4.0, 4.0, H});
  for (double density : {300.0, 600.0, 900.0}) {
    const double draft = density / kRho * H;
    Floater f = makeFloater(box, density, std::make_shared<FlatSea>(), {kAt.latDeg, kAt.lonDeg, H / 2 - draft + 0.2});
    std::vector<double> h;
    for (int i = 1; i <= 120 * 90; ++i) {
      f.sim->advanceTo(i / 120.0);
      if (i > 120 * 60) h.push_back(f.where().heightM);
    }
    double mean = 0.0;
    for (double v : h) mean += v / h.size();
    const double measured = H / 2 - mean;
    EXPECT_NEAR(measured, draft, 0.005 * draft) << density;  // the brief's 0.5 %
    std::printf("[ measured ] density %.0f: draft %.6f m vs (rho_b/rho_w) H %.6f m (%.2e)\n", density, measured, draft,
                measured / draft - 1);
  }
}

TEST(BodyBuoyancy, HeavePeriodIsTwoPiRootOfMassPlusAddedMassOverRhoGAwp) {
  const HullMesh box = HullMesh::box({10.0, 10.0, 4.0});
  const double density = 500.0, draft = density / kRho * 4.0;
  Floater f = makeFloater(box, density, std::make_shared<FlatSea>(), {kAt.latDeg, kAt.lonDeg, 2.0 - draft + 0.1});
  const double T = 2 * kPi / heaveNaturalOmega(f, density, box);
  std::vector<double> t, h;
  for (int i = 1; i <= 120 * 30; ++i) {
    f.sim->advanceTo(i / 120.0);
    t.push_back(f.sim->time());
    h.push_back(f.where().heightM);
  }
  const auto c = upCrossings(t, h, 2.0 - draft);
  ASSERT_GE(c.size(), 4u);
  const double measured = (c.back() - c.front()) / (c.size() - 1);
  EXPECT_NEAR(measured, T, 0.02 * T) << "a33 = " << f.force->fullHeaveAddedMassKg();
  std::printf("[ measured ] heave period %.4f s vs 2 pi sqrt((m + a33) / rho g A_wp) %.4f s (a33 %.0f kg)\n", measured, T,
              f.force->fullHeaveAddedMassKg());
}

TEST(BodyStability, RollPeriodFollowsTheMetacentricHeight) {
  // L 20, B 8, H 4, rho_b/rho_w = 1/2: draft 2, KB = 1, BM = B^2 / 12 d,
  // KG = 2, GM = KB + BM - KG; T = 2 pi sqrt((I44 + a44) / (rho g V GM))
  // with the added roll inertia a44 the model uses (its own test:
  // test_added_mass.cpp).
  const double L = 20.0, B = 8.0, H = 4.0, density = kRho / 2.0;
  const HullMesh box = HullMesh::box({L, B, H});
  const double d = H / 2, GM = d / 2 + B * B / (12 * d) - H / 2;
  Floater f = makeFloater(box, density, std::make_shared<FlatSea>(), {kAt.latDeg, kAt.lonDeg, 0.0}, 3.0);
  const geo::EnuFrame enu = geo::enuFrame(kAt);
  const double m = density * L * B * H;
  const double g = f.sim->context(f.state()).gravityMps2;
  const double a44 =
      f.force->evaluate(f.state(), f.sim->body(f.id).mass, f.sim->context(f.state())).addedInertiaKgM2.x;
  ASSERT_GT(a44, 0.0);
  const double T = 2 * kPi * std::sqrt((m * (B * B + H * H) / 12.0 + a44) / (kRho * g * L * B * d * GM));
  std::vector<double> t, r;
  for (int i = 1; i <= 120 * 25; ++i) {
    f.sim->advanceTo(i / 120.0);
    t.push_back(f.sim->time());
    r.push_back(test::rollDeg(f.state(), enu));
  }
  const auto c = upCrossings(t, r, 0.0);
  ASSERT_GE(c.size(), 3u);
  const double measured = (c.back() - c.front()) / (c.size() - 1);
  EXPECT_NEAR(measured, T, 0.03 * T) << "GM = " << GM;
  std::printf("[ measured ] roll period %.4f s vs GM formula %.4f s (GM %.3f m, a44 %.3g of I44)\n", measured, T, GM,
              a44 / (m * (B * B + H * H) / 12.0));
}

TEST(BodyStability, BoxWithNegativeMetacentricHeightCapsizes) {
  // B 2, H 4, half density: GM = 1 + 4/24 - 2 = -0.83 m; from 1 degree the
  // roll grows as exp(sqrt(rho g V |GM| / I44) t) ~ exp(2.2 t).
  const HullMesh tall = HullMesh::box({10.0, 2.0, 4.0});
  Floater f = makeFloater(tall, kRho / 2, std::make_shared<FlatSea>(), {kAt.latDeg, kAt.lonDeg, 0.0}, 1.0);
  const geo::EnuFrame enu = geo::enuFrame(kAt);
  f.sim->advanceTo(20.0);
  EXPECT_GT(std::abs(test::rollDeg(f.state(), enu)), 45.0);
  // The same box on its side (B 4, H 2: GM = 0.5 + 16/12 - 1 > 0) stays upright.
  Floater g = makeFloater(HullMesh::box({10.0, 4.0, 2.0}), kRho / 2, std::make_shared<FlatSea>(),
                          {kAt.latDeg, kAt.lonDeg, 0.0}, 1.0);
  double worst = 0.0;
  for (int i = 1; i <= 20; ++i) {
    g.sim->advanceTo(i);
    worst = std::max(worst, std::abs(test::rollDeg(g.state(), enu)));
  }
  EXPECT_LT(worst, 1.01);
}

TEST(BodyWaves, HeaveFollowsLongSwellAndIgnoresShortWaves) {
  const HullMesh box = HullMesh::box({10.0, 10.0, 4.0}, 8);
  const double density = 500.0, draft = density / kRho * 4.0;
  const geo::Geodetic at{0.0, 0.0, 2.0 - draft};
  struct Case {
    double lambda, amp, lo, hi;
  };
  // lambda = 20 L: response 0.95..1.05; lambda = L/2: < 0.3 (the brief).
  for (const Case c : {Case{200.0, 0.5, 0.95, 1.05}, Case{5.0, 0.15, 0.0, 0.3}}) {
    Simulation probe;
    const double g = probe.context(stateAt(at)).gravityMps2;
    auto sea = std::make_shared<AiryWave>(c.amp, c.lambda, g, 40.0);
    Floater f = makeFloater(box, density, sea, at, 0.0, 0.0, 1.0 / 120.0);
    const double wn = heaveNaturalOmega(f, density, box);
    std::vector<double> t, h;
    for (int i = 1; i <= 120 * 100; ++i) {
      f.sim->advanceTo(i / 120.0);
      if (f.sim->time() > 45.0) {
        t.push_back(f.sim->time());
        h.push_back(f.where().heightM);
      }
    }
    const double response = amplitudeAt(t, h, sea->omega(), wn) / c.amp;
    std::printf("[ measured ] lambda %.0f m: heave response %.4f\n", c.lambda, response);
    EXPECT_GE(response, c.lo) << "lambda " << c.lambda;
    EXPECT_LE(response, c.hi) << "lambda " << c.lambda;
  }
}

TEST(BodyWaves, SurgeAndSwayFollowTheWaterInLongSwell) {
  // In a wave 20 L long a floating body moves with the water (linear
  // theory: the water's horizontal excursion at the surface is the
  // amplitude a): the Froude-Krylov force gives rho V du/dt and the
  // long-wave diffraction term a_ii du/dt, together (m + a_ii) du/dt. Head
  // on (surge) and beam on (sway); response 0.95..1.05 as the heave's.
  const HullMesh box = HullMesh::box({12.0, 6.0, 4.0}, 8);
  const double density = 500.0, draft = density / kRho * 4.0, amp = 0.5, lambda = 240.0;
  const geo::Geodetic at{0.0, 0.0, 2.0 - draft};
  for (double headingDeg : {0.0, 90.0}) {  // bow east (the wave's way), then north
    Simulation probe;
    const double g = probe.context(stateAt(at)).gravityMps2;
    auto sea = std::make_shared<AiryWave>(amp, lambda, g, 40.0);
    Floater f = makeFloater(box, density, sea, at);
    const geo::EnuFrame enu = geo::enuFrame(at);
    f.sim->body(f.id).state.orientation =
        glm::normalize(glm::quat_cast(enu.rotation()) * glm::angleAxis(headingDeg * kPi / 180.0, glm::dvec3(0, 0, 1)));
    const HullEvaluation e = f.force->evaluate(f.state(), f.sim->body(f.id).mass, f.sim->context(f.state()));
    const double aii = headingDeg == 0.0 ? e.addedMassKg.x : e.addedMassKg.y;
    std::vector<double> t, x;
    for (int i = 1; i <= 120 * 100; ++i) {
      f.sim->advanceTo(i / 120.0);
      if (f.sim->time() > 45.0) {
        t.push_back(f.sim->time());
        x.push_back(enu.toLocal(f.state().positionEcef - enu.originEcef).x);
      }
    }
    // Least squares on 1, t (the mean drift), cos and sin of w t.
    const double w = sea->omega();
    double A[4][4] = {}, b[4] = {};
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double fn[4] = {1.0, t[i], std::cos(w * t[i]), std::sin(w * t[i])};
      for (int r = 0; r < 4; ++r) {
        b[r] += fn[r] * x[i];
        for (int c = 0; c < 4; ++c) A[r][c] += fn[r] * fn[c];
      }
    }
    for (int p = 0; p < 4; ++p)
      for (int r = 0; r < 4; ++r) {
        if (r == p) continue;
        const double m = A[r][p] / A[p][p];
        for (int c = 0; c < 4; ++c) A[r][c] -= m * A[p][c];
        b[r] -= m * b[p];
      }
    const double response = std::hypot(b[2] / A[2][2], b[3] / A[3][3]) / amp;
    std::printf("[ measured ] heading %.0f: horizontal response %.4f (a_ii %.3g of m)\n", headingDeg, response,
                aii / f.sim->body(f.id).mass.massKg());
    EXPECT_GT(aii, 0.05 * f.sim->body(f.id).mass.massKg());  // the term matters: without it ~m / (m + a_ii)
    EXPECT_GE(response, 0.95) << headingDeg;
    EXPECT_LE(response, 1.05) << headingDeg;
  }
}

TEST(BodyDrag, ABoxUnderThrustReachesTheSpeedWhereTheDragLawsBalanceIt) {
  // A 20 x 5 x 4 m box at draft 2 m pushed along its length on still water
  // settles where F = 1/2 rho U^2 (C_D B T + C_f S): bow stagnation and
  // stern suction, C_D = 1 (Hoerner 1965), on the B x T faces, and skin
  // friction on the bottom and sides S = L B + 2 L T with the ITTC-1957
  // line C_f = 0.075 / (log10(U L / nu) - 2)^2. No wave-making resistance
  // (not modelled: Hydro.h).
  const double L = 20.0, B = 5.0, H = 4.0, T = 2.0, F = 2e4, nu = WaterProperties{}.kinematicViscosityM2ps;
  const HullMesh box = HullMesh::box({L, B, H});
  Floater f = makeFloater(box, kRho / 2, std::make_shared<FlatSea>(), {kAt.latDeg, kAt.lonDeg, 0.0});
  f.sim->addBodyForce(f.id, std::make_shared<Thrust>(F));
  f.sim->advanceTo(150.0);  // ~15 time constants (m + a11) / (rho C U)
  const double u = glm::length(f.state().velocityEcef);
  double U = 2.0;  // the balance, by fixed-point iteration
  for (int i = 0; i < 50; ++i) {
    const double l = std::log10(U * L / nu) - 2.0, cf = 0.075 / (l * l);
    U = std::sqrt(2.0 * F / (kRho * (1.0 * B * T + cf * (L * B + 2 * L * T))));
  }
  // The drag's moment trims the box by ~3e-4 rad and the friction turns
  // nothing else: areas within 0.1 %, the speed within 0.5 %.
  EXPECT_NEAR(u, U, 0.005 * U);
  std::printf("[ measured ] speed %.4f m/s vs the drag laws' %.4f m/s (%.2e)\n", u, U, u / U - 1);
}

TEST(BodyBuoyancy, BodyAtRestOnACalmSeaDriftsLessThanAMillimetrePerMinute) {
  const double H = 2.0, density = 600.0;
  // Both stable: the box's GM = d/2 + B^2/12d - H/2 = 0.73 m.
  for (const HullMesh& hull : {HullMesh::box({4.0, 4.0, H}), HullMesh::boat(12.0)}) {
    // Start at the box's draft (the boat settles from there).
    Floater f = makeFloater(hull, density, std::make_shared<FlatSea>(), {45.0, 7.0, H / 2 - density / kRho * H});
    // Settle to the equilibrium pose, then hold it at rest: what drifts
    // after that is what the forces of a calm sea do to a body at rest.
    f.sim->advanceTo(60.0);
    f.sim->body(f.id).state.velocityEcef = glm::dvec3(0.0);
    f.sim->body(f.id).state.angularVelocityBody = glm::dvec3(0.0);
    const glm::dvec3 p0 = f.state().positionEcef;
    f.sim->advanceTo(120.0);
    const geo::EnuFrame enu = geo::enuFrame(geo::fromEcef(p0));
    const glm::dvec3 d = enu.toLocal(f.state().positionEcef - p0);
    EXPECT_LT(std::hypot(d.x, d.y), 1e-3) << hull.kind();
    std::printf("[ measured ] %s at rest: %.3g m in 60 s\n", hull.kind().c_str(), std::hypot(d.x, d.y));
  }
}

namespace {

std::shared_ptr<const SeaSurface> gerstnerSea() {
  static std::shared_ptr<const SeaSurface> sea = [] {
    ocean::Ocean o;
    waves::SeaState s;
    s.windSpeedMps = 9.0;
    s.anchorLatDeg = kAt.latDeg;
    s.anchorLonDeg = kAt.lonDeg;
    s.seed = 7;
    o.setSeaState(waves::Model::Gerstner, s);
    return std::make_shared<OceanSea>(o.current());
  }();
  return sea;
}

BodyState boatAfter(double seconds, double dt, double thrustN = 0.0) {
  const HullMesh boat = HullMesh::boat(20.0);
  Floater f = makeFloater(boat, 400.0, gerstnerSea(), {kAt.latDeg, kAt.lonDeg, 0.0}, 0.0, 0.0, dt);
  if (thrustN != 0.0) f.sim->addBodyForce(f.id, std::make_shared<Thrust>(thrustN));
  f.sim->advanceTo(seconds);
  return f.state();
}

}  // namespace

TEST(BodyWaves, OceanSeaIsTheFacadesSurface) {
  const auto sea = gerstnerSea();
  const auto& snap = static_cast<const OceanSea&>(*sea).snapshot();
  double lat[3] = {30.0, 30.001, 29.99}, lon[3] = {-40.0, -40.002, -39.99}, t[3] = {0.0, 3.5, 11.25};
  double h[3], w[3], uv[6];
  ocean::SurfaceOutputs o;
  o.heightM = h, o.verticalVelocityMps = w, o.horizontalVelocityEnMps = uv;
  snap.querySurface(ocean::Points{lat, lon, 3, t, true}, o);
  SeaSample s[3];
  sea->sample(lat, lon, t, 3, true, s);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(s[i].heightM, h[i]);
    EXPECT_EQ(s[i].verticalVelocityMps, w[i]);
    EXPECT_EQ(s[i].horizontalVelocityEnMps.x, uv[2 * i]);
  }
  EXPECT_GT(std::abs(h[0] - h[1]) + std::abs(h[1] - h[2]), 0.0);  // it is a wavy sea
}

TEST(BodyWaves, HalvingTheStepChangesASixtySecondTrajectoryByOrderDt) {
  const double seconds = 60.0;
  const BodyState a = boatAfter(seconds, 1.0 / 30), b = boatAfter(seconds, 1.0 / 60), c = boatAfter(seconds, 1.0 / 120);
  const double e1 = glm::length(a.positionEcef - b.positionEcef), e2 = glm::length(b.positionEcef - c.positionEcef);
  // First order: the difference halves with dt (ratio 2; 1.5..2.7 allows
  // the O(dt^2) remainder at these steps).
  std::printf("[ measured ] 60 s: |x(1/30) - x(1/60)| %.4g m, |x(1/60) - x(1/120)| %.4g m, ratio %.3f\n", e1, e2, e1 / e2);
  EXPECT_GT(e1 / e2, 1.5) << e1 << " " << e2;
  EXPECT_LT(e1 / e2, 2.7) << e1 << " " << e2;
  EXPECT_LT(e2, 0.5);
}

TEST(BodyWaves, StepOfOneFifteenthIsStable) {
  const HullMesh boat = HullMesh::boat(20.0);
  for (const HullMesh& hull : {HullMesh::boat(20.0), HullMesh::box({3.0, 2.0, 1.0}), HullMesh::cylinder(0.5, 2.0)}) {
    Floater f = makeFloater(hull, 450.0, gerstnerSea(), {kAt.latDeg, kAt.lonDeg, 0.3}, 4.0, 2.0, 1.0 / 15);
    const geo::EnuFrame enu = geo::enuFrame(kAt);
    double worstRoll = 0.0, worstH = 0.0, worstV = 0.0;
    for (int i = 1; i <= 15 * 120; ++i) {
      f.sim->advanceTo(i / 15.0);
      worstRoll = std::max(worstRoll, std::abs(test::rollDeg(f.state(), enu)));
      worstH = std::max(worstH, std::abs(f.where().heightM));
      worstV = std::max(worstV, glm::length(f.state().velocityEcef));
    }
    // Hs of a 9 m/s sea is ~1.8 m: bounded motion, nothing blowing up.
    EXPECT_LT(worstH, 3.0) << hull.kind();
    EXPECT_LT(worstV, 5.0) << hull.kind();
    if (hull.kind() != "cylinder") {
      EXPECT_LT(worstRoll, 30.0) << hull.kind();
    }
  }
}

TEST(BodyWaves, DeterministicForASeedAndFrameTimes) {
  const BodyState a = boatAfter(20.0, 1.0 / 60, 2e4), b = boatAfter(20.0, 1.0 / 60, 2e4);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
  // The same steps through irregular frames.
  const HullMesh boat = HullMesh::boat(20.0);
  Floater f = makeFloater(boat, 400.0, gerstnerSea(), {kAt.latDeg, kAt.lonDeg, 0.0}, 0.0, 0.0, 1.0 / 60);
  f.sim->addBodyForce(f.id, std::make_shared<Thrust>(2e4));
  for (double t = 0.0; t < 20.0; t += 0.0137) f.sim->advanceTo(t);
  f.sim->advanceTo(20.0);
  EXPECT_EQ(std::memcmp(&f.state(), &a, sizeof a), 0);
}

TEST(BodyContactPoints, PaperProxyFloatsWhereItsColumnsCarryItsWeight) {
  // Paper 000 eq. 3-4 with the hollow-cylinder proxy: equilibrium when the
  // submerged fraction f of every column is m / (rho V), the points' plane
  // at depth (f - 1/2) 2R below the surface.
  const double L = 12.0, R = 1.5, m = 0.4 * kRho * kPi * R * R * L;
  auto cp = ContactPointForce::hollowCylinderProxy(L, R, 4, std::make_shared<FlatSea>());
  Simulation sim({.stepS = 1.0 / 60});
  BodyState s = stateAt({kAt.latDeg, kAt.lonDeg, 0.5});
  s.orientation = orientationAt(kAt);
  const BodyId id = sim.addBody(MassProperties::isotropicFrom(MassProperties::hollowCylinder(m, 0.8 * R, R, L)), s);
  sim.addBodyForce(id, cp);
  double mean = 0.0;
  int n = 0;
  for (int i = 1; i <= 60 * 120; ++i) {
    sim.advanceTo(i / 60.0);
    if (i > 60 * 90) mean += geo::fromEcef(sim.body(id).state.positionEcef).heightM, ++n;
  }
  mean /= n;
  const double expected = -(0.4 - 0.5) * 2 * R;  // the plane 0.3 m above the surface
  EXPECT_NEAR(mean, expected, 0.005 * 2 * R);
}

TEST(BodyContactPoints, TheTorqueOfAHeldRollIsTheColumnsMoment) {
  // Paper 000 eq. 4: the torque is the sum of r_i x F_i over the points.
  // The proxy's points sit at y = +-R/2 (body axes); rolled by theta with
  // its centre on a flat sea, a point's column is submerged by
  // f = 1/2 -+ (R/2) sin(theta) / 2R, its force rho g (V/n) f acts up at the
  // lever +-(R/2) cos(theta): the sum is -rho g V R sin(theta) cos(theta) / 8
  // about the bow axis, and the force is still rho g V / 2.
  const double L = 12.0, R = 1.5, V = kPi * R * R * L;
  auto cp = ContactPointForce::hollowCylinderProxy(L, R, 4, std::make_shared<FlatSea>());
  for (double rollDeg : {5.0, 10.0, 30.0, -20.0}) {
    Simulation sim;
    BodyState s = stateAt(kAt);  // centre of mass on the still water
    s.orientation = orientationAt(kAt, rollDeg);
    const BodyId id = sim.addBody(MassProperties::box(1e4, {L, 2 * R, 2 * R}), s);
    const Body& b = sim.body(id);
    const StepContext ctx = sim.context(b.state);
    Wrench w;
    cp->accumulate(b, ctx, w);
    const double th = rollDeg * kPi / 180.0, g = ctx.gravityMps2;
    const glm::dvec3 tau = ctx.enu.toLocal(w.torque()), F = ctx.enu.toLocal(w.force());
    const double expected = -kRho * g * V * R * std::sin(th) * std::cos(th) / 8.0;
    // The points lie within 6 m of the centre: the ellipsoid's curvature
    // lowers them by up to 3e-6 m, 1e-6 of a column.
    EXPECT_NEAR(tau.x, expected, 1e-5 * std::abs(expected)) << rollDeg;
    EXPECT_NEAR(F.z, 0.5 * kRho * g * V, 1e-5 * kRho * g * V) << rollDeg;
    EXPECT_LT(std::hypot(tau.y, tau.z), 1e-5 * std::abs(expected)) << rollDeg;
  }
}

TEST(BodyHydroValidation, BadInputsNameTheField) {
  auto hull = std::make_shared<HullMesh>(HullMesh::box({1, 1, 1}));
  HullForceOptions o;
  o.water.densityKgM3 = -3;
  try {
    HullForce f(hull, std::make_shared<FlatSea>(), o);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("water density = -3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(HullForce(nullptr, std::make_shared<FlatSea>()), std::invalid_argument);
  EXPECT_THROW(Thrust(std::nan("")), std::invalid_argument);
  EXPECT_THROW(ContactPointForce::hollowCylinderProxy(10, -1, 4, std::make_shared<FlatSea>()), std::invalid_argument);
  EXPECT_NEAR(rectangularPlateAddedMassCoefficient(1.0), 0.579, 1e-12);
  EXPECT_NEAR(rectangularPlateAddedMassCoefficient(10.0), 0.947, 1e-12);
  EXPECT_THROW(rectangularPlateAddedMassCoefficient(0.5), std::invalid_argument);
}

TEST(BodyWaves, SeaGridUnderTheHullGivesTheForcesOfEveryVertexQueried) {
  // The default sea grid (2.5 nodes per shortest wavelength) against the
  // reference, every vertex queried, on the façade's Gerstner sea at
  // 10 m/s (lambda_min 5.7 m): a 20 m boat at 400 random poses (heave
  // +-0.5 m, tilt up to 8.6 degrees, any heading and time). Measured: force
  // error rms 2.2e-4, max 9.3e-4 of the weight; torque rms 5e-5, max
  // 1.7e-4 of weight x length. Bounds: twice the measured maxima.
  ocean::Ocean o;
  waves::SeaState st;
  st.windSpeedMps = 10.0, st.anchorLatDeg = 30.0, st.anchorLonDeg = -40.0;
  o.setSeaState(waves::Model::Gerstner, st);
  auto sea = std::make_shared<OceanSea>(o.current());
  ASSERT_NEAR(sea->shortestWavelengthM(), 5.71, 0.01);
  const double L = 20.0;
  auto hull = std::make_shared<HullMesh>(HullMesh::boat(L));
  HullForceOptions every;
  every.seaGridPointsPerWavelength = 0.0;
  const HullForce ref(hull, sea, every), grid(hull, sea);
  const MassProperties mp = hull->massProperties(0.45 * kRho);
  std::uint64_t seed = 5;
  auto uniform = [&] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(seed >> 11) * 0x1.0p-53;
  };
  double worstF = 0.0, worstT = 0.0, sumF2 = 0.0;
  int nodes = 0;
  const int n = 400;
  for (int k = 0; k < n; ++k) {
    geo::Geodetic at{30.0 + uniform() * 0.01, -40.0 + uniform() * 0.01, (uniform() - 0.5) * 1.0 -
                                                                            hull->restingWaterlineZ(0.45)};
    const geo::EnuFrame f = geo::enuFrame(at);
    BodyState s = stateAt(at);
    const double h = uniform() * 2 * kPi;
    const glm::dvec3 axis = glm::normalize(glm::dvec3(uniform() - 0.5, uniform() - 0.5, 0.0));
    const glm::dquat heading = glm::angleAxis(h, glm::dvec3(0, 0, 1)), tilt = glm::angleAxis((uniform() - 0.5) * 0.3, axis);
    s.orientation = glm::normalize(glm::quat_cast(f.rotation()) * tilt * heading);
    Simulation sim({.stepS = 1.0 / 60});
    StepContext ctx = sim.context(s);
    ctx.timeS = 10.0 + uniform() * 1000.0;
    const HullEvaluation a = ref.evaluate(s, mp, ctx), b = grid.evaluate(s, mp, ctx);
    ASSERT_EQ(a.seaGridNodes, 0);
    ASSERT_GT(b.seaGridNodes, 0);
    nodes = std::max(nodes, b.seaGridNodes);
    const double W = mp.massKg() * ctx.gravityMps2;
    const double dF = glm::length(a.wrench.force() - b.wrench.force()) / W;
    worstF = std::max(worstF, dF), sumF2 += dF * dF;
    worstT = std::max(worstT, glm::length(a.wrench.torque() - b.wrench.torque()) / (W * L));
  }
  std::printf("[ measured ] sea grid (<= %d nodes for %zu vertices): force error rms %.2e max %.2e of the weight, torque max %.2e of W L\n",
              nodes, hull->vertices().size(), std::sqrt(sumF2 / n), worstF, worstT);
  EXPECT_LT(nodes, int(hull->vertices().size()) / 2);
  EXPECT_LT(worstF, 2e-3);
  EXPECT_LT(worstT, 4e-4);
}

namespace {

// Still water (height 0) west of a meridian, land (NaN) east of it, under a
// wavy sea's decay wave number (as the façade's near Tarifa): the coast.
class CoastSea final : public SeaSurface {
 public:
  CoastSea(double coastLonDeg, double decayPerM) : coast_(coastLonDeg), k_(decayPerM) {}
  void sample(const double*, const double* lon, const double*, std::size_t n, bool, SeaSample* out) const override {
    for (std::size_t i = 0; i < n; ++i)
      out[i] = SeaSample{lon[i] < coast_ ? 0.0 : std::numeric_limits<double>::quiet_NaN(), 0.0, {0.0, 0.0}};
  }
  double decayWaveNumberPerM() const override { return k_; }
  void sampleSlopes(const double* lat, const double* lon, const double* t, std::size_t n, SeaSample* out) const override {
    sample(lat, lon, t, n, false, out);
  }

 private:
  double coast_, k_;
};

}  // namespace

// Issue 14 soak: a boat driven onto the Tarifa shore (`geocean view --fly-to
// 36.0,-5.6 --boats 20`, frame 362) had its centre over land and its stern
// afloat; the heave damping's exp(-k keel) of the centre's NaN keel depth
// made the force NaN (the step then failed). A box at rest with its centre
// 0.75 m east of the coast: only the hull west of it carries pressure.
TEST(BodyBuoyancy, HullAcrossACoastWithItsCentreOverLandFeelsTheWaterUnderItsWetPart) {
  const glm::dvec3 size(6.0, 3.0, 2.0);
  const HullMesh box = HullMesh::box(size, 4);  // vertex columns at x = -3, -1.5, 0, 1.5, 3
  const geo::Geodetic at{36.0, -5.6, 0.2};       // bottom 0.8 m under the still water
  const geo::EnuFrame enu = geo::enuFrame(at);
  const double coastLon = geo::fromEcef(enu.originEcef + enu.toEcef(glm::dvec3(-0.75, 0.0, 0.0))).lonDeg;
  auto sea = std::make_shared<CoastSea>(coastLon, 2.0 * kPi / 50.0);
  Floater f = makeFloater(box, 500.0, sea, at);
  const StepContext ctx = f.sim->context(f.state());
  const HullEvaluation e = f.force->evaluate(f.state(), f.sim->body(f.id).mass, ctx);
  EXPECT_TRUE(std::isnan(e.seaHeightM));  // the centre is on land
  const glm::dvec3 F = ctx.enu.toLocal(e.wrench.force());
  // At rest in still water only the hydrostatic pressure acts: on the wet
  // bottom (the column x in [-3, -1.5] of the mesh: triangles that reach a
  // vertex over land clip to nothing) rho g d A, and on the west end face
  // rho g B d^2 / 2 eastwards. 1e-4: the ellipsoid's curvature under the
  // 6 m box, (3 m)^2 / 2R ~ 1e-6 m on a 0.8 m depth.
  const double g = ctx.gravityMps2, d = 0.8;
  const double up = kRho * g * d * 1.5 * size.y, east = kRho * g * size.y * d * d / 2.0;
  EXPECT_NEAR(F.z, up, 1e-4 * up);
  EXPECT_NEAR(F.x, east, 1e-4 * east);
  EXPECT_NEAR(F.y, 0.0, 1e-4 * up);
  EXPECT_NO_THROW(f.sim->step());  // it failed with "force on body 0.x = nan N"
}
