#include "plugin/waves/WaveField.h"

#include "plugin/waves/CoastField.h"
#include "plugin/waves/FftOcean.h"
#include "plugin/waves/WaveBatch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace geocean::waves {

namespace {

constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kA = 6378137.0;                 // WGS84 semi-major axis
constexpr double kF = 1.0 / 298.257223563;
constexpr double kB = kA * (1.0 - kF);
constexpr double kE2 = kF * (2.0 - kF);
constexpr double kMeanRadiusM = 6371008.8;       // IUGG mean radius: arc -> metres for wave phases
constexpr int kMaxComponents = 64;
constexpr int kMaxOctaves = 12;
// The sea-height query's horizontal inversion stops when the particle is
// this close (m) to the vertical of the point (issue #3 asks for 1 mm).
constexpr double kInversionToleranceM = 1e-5;

// Standard deviation of one octave of wv_perlin3 / wv_perlin2 over space,
// measured with 4M random samples (tests/waves/test_noise.cpp re-measures
// them): the noise models' amplitudes are calibrated to the spectrum's Hs.
constexpr double kPerlin3Std = 0.27008;
constexpr double kPerlin2Std = 0.21046;
// |wv_perlin3| <= |gradient| * |offset to a corner| = sqrt(2) * sqrt(3): a
// guaranteed (loose) bound because the trilinear weights are a convex blend.
constexpr double kPerlin3Bound = 2.449489742783178;

double deg2rad(double d) { return d * (kPi / 180.0); }

struct Enu {
  glm::dvec3 e, n, u;
};
// The point on the ellipsoid and its ENU frame from one set of sines and
// cosines.
struct Located {
  glm::dvec3 p;
  struct {
    glm::dvec3 e, n, u;
  } f;
};
Located locate(double latDeg, double lonDeg) {
  const double phi = deg2rad(latDeg), lam = deg2rad(lonDeg);
  const double sp = std::sin(phi), cp = std::cos(phi), sl = std::sin(lam), cl = std::cos(lam);
  const double n = kA / std::sqrt(1.0 - kE2 * sp * sp);
  return {{n * cp * cl, n * cp * sl, n * (1.0 - kE2) * sp}, {{-sl, cl, 0.0}, {-sp * cl, -sp * sl, cp}, {cp * cl, cp * sl, sp}}};
}

Enu enuAt(double latDeg, double lonDeg) {
  const double phi = deg2rad(latDeg), lam = deg2rad(lonDeg);
  const double sp = std::sin(phi), cp = std::cos(phi), sl = std::sin(lam), cl = std::cos(lam);
  return {{-sl, cl, 0.0}, {-sp * cl, -sp * sl, cp}, {cp * cl, cp * sl, sp}};
}

// SplitMix64: deterministic on every platform (unlike std distributions).
struct Rng {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

double roundToFloat(double x) { return double(float(x)); }

double wrapTwoPi(double x) {
  double r = std::fmod(x, kTwoPi);
  return r < 0.0 ? r + kTwoPi : r;
}

double spectrum(const SeaState& sea, double omega) {
  return sea.fetchM > 0.0 ? jonswap(omega, sea.windSpeedMps, sea.fetchM)
                          : piersonMoskowitz(omega, sea.windSpeedMps);
}

// Simpson integral of the spectrum over [w0, w1].
double bandVariance(const SeaState& sea, double w0, double w1) {
  const int n = 64;
  const double h = (w1 - w0) / n;
  double s = spectrum(sea, w0) + spectrum(sea, w1);
  for (int i = 1; i < n; ++i) s += spectrum(sea, w0 + i * h) * (i % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

constexpr double kInvGolden = 0.6180339887498949;  // 1 / golden ratio

// A Gerstner component's slope variance, up to a common factor.
double slopeWeight(const WaveField::Component& c) { return c.amplitudeM * c.amplitudeM * c.kRef * c.kRef; }

}  // namespace

double cos2SpreadingQuantile(double u) {
  // F(a) = 1/2 + (a + sin a cos a) / pi on [-pi/2, pi/2], increasing: bisect.
  double lo = -0.5 * kPi, hi = 0.5 * kPi;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 + (mid + std::sin(mid) * std::cos(mid)) / kPi < u ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

kd::WvFrame makeFrame(const glm::dvec3& o) {
  const double r = glm::length(o);
  const glm::dvec3 dO(o.x / (kA * kA), o.y / (kA * kA), o.z / (kB * kB));
  const double ld = glm::length(dO);
  kd::WvFrame f;
  f.radial = glm::dvec4(o / r, 1.0 / r);
  f.up = glm::dvec4(dO / ld, 0.0);
  f.upScale = glm::dvec4(1.0 / (kA * kA * ld), 1.0 / (kA * kA * ld), 1.0 / (kB * kB * ld), 0.0);
  return f;
}

// A lattice cell as the int32 the kernel hashes: cells are taken modulo
// 2^32, whose hash (uint arithmetic in wv_hashCell*) is the same, so the
// noise continues seamlessly where the drift v t leaves int32 (Unix-epoch
// times, 1.7e9 s, did for the finest octaves: the conversion overflowed).
// Exact for |cell| < 2^53; the same cells as before inside int32.
double wrapCell32(double cell) {
  if (!std::isfinite(cell)) return 0.0;
  const double m = cell - 4294967296.0 * std::floor(cell * (1.0 / 4294967296.0));
  return m >= 2147483648.0 ? m - 4294967296.0 : m;
}
// The fraction q - floor(q), 0 where q is infinite (v t overflowed, at
// |t| ~ 1e306 s and beyond): the cell is then 0 (wrapCell32), so the noise
// is that of cell 0, not NaN (the kernel's floor -> int of the NaN fraction
// was UB; fuzz_capi_sea_state found t ~ 1e307 s). A NaN q (NaN position)
// stays NaN, as the batch's NonFiniteInputStaysInItsLane asks.
double finiteFrac(double q, double fl) { return std::isinf(q) ? 0.0 : q - fl; }
glm::ivec3 wrapCells(const glm::dvec3& fl) {
  return {int(wrapCell32(fl.x)), int(wrapCell32(fl.y)), int(wrapCell32(fl.z))};
}

kd::WvOctave octaveAt(const WaveField::Octave& oc, const glm::dvec3& o, double tS) {
  const glm::dvec3 q(glm::dot(oc.row[0], o) + oc.velocity.x * tS, glm::dot(oc.row[1], o) + oc.velocity.y * tS,
                     glm::dot(oc.row[2], o) + oc.velocity.z * tS);
  const glm::dvec3 fl = glm::floor(q);
  kd::WvOctave w;
  w.row0 = glm::dvec4(oc.row[0], oc.amplitudeM);
  w.row1 = glm::dvec4(oc.row[1], double(oc.seed));
  w.row2 = glm::dvec4(oc.row[2], 0.0);
  w.fracO = glm::dvec4(finiteFrac(q.x, fl.x), finiteFrac(q.y, fl.y), finiteFrac(q.z, fl.z), 0.0);
  w.cellO = glm::ivec4(wrapCells(fl), 0);
  w.vel = glm::dvec4(oc.velocity, 0.0);
  return w;
}

kd::WvWave waveAt(const WaveField::Component& c, const glm::dvec3& radial, double tS) {
  const double cosT = glm::dot(c.source, radial);
  glm::dvec3 g = radial * cosT - c.source;  // away from the source, length sin(theta)
  double sinT = glm::length(g);
  if (sinT < 1e-15) {  // at the source or its antipode: any tangent (the taper is 0 there)
    g = glm::normalize(glm::cross(radial, std::abs(radial.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
    sinT = 0.0;
  } else {
    g /= sinT;
  }
  const double theta = std::atan2(sinT, cosT);
  const double kR = c.kRef * kMeanRadiusM;
  kd::WvWave w;
  w.dirO = glm::dvec4(g, sinT);
  w.binO = glm::dvec4(glm::cross(radial, g), cosT);
  w.phase = glm::dvec4(wrapTwoPi(kR * theta - c.omega * tS + c.phase0), kR, c.omega, c.amplitudeM);
  w.extra = glm::dvec4(c.kRef, c.choppiness, 0.0, 0.0);
  return w;
}

glm::vec4 toF(const glm::dvec4& v) { return glm::vec4(v); }

}  // namespace

const char* toString(Model m) {
  switch (m) {
    case Model::Noise: return "noise";
    case Model::NoisePaper: return "noise-paper";
    case Model::Gerstner: return "gerstner";
    case Model::Fft: return "fft";
  }
  return "?";
}

std::optional<Model> parseModel(std::string_view name) {
  if (name == "noise") return Model::Noise;
  if (name == "noise-paper") return Model::NoisePaper;
  if (name == "gerstner") return Model::Gerstner;
  if (name == "fft") return Model::Fft;
  return std::nullopt;
}

std::optional<SeaState> SeaState::fromBeaufort(int beaufort) {
  // Middle of each Beaufort class (m/s at 10 m, WMO); class 12 is >= 32.7.
  static constexpr double kMid[13] = {0.15, 0.9, 2.45, 4.4, 6.7, 9.35, 12.3, 15.5, 18.95, 22.6, 26.45, 30.55, 34.0};
  if (beaufort < 0 || beaufort > 12) return std::nullopt;
  SeaState s;
  s.windSpeedMps = std::max(kMid[beaufort] * 1.026, 0.2);
  return s;
}

double piersonMoskowitz(double omega, double windSpeedMps) {
  if (omega <= 0.0) return 0.0;
  const double wp = 0.877 * kG / windSpeedMps;
  return 0.0081 * kG * kG / std::pow(omega, 5.0) * std::exp(-1.25 * std::pow(wp / omega, 4.0));
}

double fullyDevelopedFetchM(double windSpeedMps) {
  // JONSWAP's peak 22 (g^2 / (U X))^(1/3) meets Pierson-Moskowitz's
  // 0.877 g / U at gX/U^2 = (22 / 0.877)^3 = 15,786.
  const double r = 22.0 / 0.877;
  return r * r * r * windSpeedMps * windSpeedMps / kG;
}

double jonswap(double omega, double windSpeedMps, double fetchM) {
  if (omega <= 0.0) return 0.0;
  const double u = windSpeedMps;
  // The growth laws hold up to full development only: past it Hs grew
  // without bound (142 m at 1e12 m) and u * 8e307 overflowed to NaN heights
  // (fuzz_capi_sea_state finding 8).
  const double x = std::min(fetchM, fullyDevelopedFetchM(u));
  const double wp = 22.0 * std::cbrt(kG * kG / (u * x));
  const double alpha = 0.076 * std::pow(u * u / (x * kG), 0.22);
  const double sigma = omega <= wp ? 0.07 : 0.09;
  const double r = std::exp(-(omega - wp) * (omega - wp) / (2.0 * sigma * sigma * wp * wp));
  return alpha * kG * kG / std::pow(omega, 5.0) * std::exp(-1.25 * std::pow(wp / omega, 4.0)) * std::pow(3.3, r);
}

double peakOmega(const SeaState& sea) {
  const double wpPm = 0.877 * kG / sea.windSpeedMps;
  if (sea.fetchM <= 0.0) return wpPm;
  // A fetch longer than the fully developed one changes nothing.
  const double x = std::min(sea.fetchM, fullyDevelopedFetchM(sea.windSpeedMps));
  return std::max(wpPm, 22.0 * std::cbrt(kG * kG / (sea.windSpeedMps * x)));
}

double waveNumberExact(double omega, double depthM) {
  const double kDeep = omega * omega / kG;
  if (!(depthM < 1e6) || kDeep * depthM > 40.0) return kDeep;
  // f(k) = g k tanh(k h) - w^2 is increasing; bracket then bisect + Newton.
  double lo = kDeep, hi = std::max(kDeep, omega / std::sqrt(kG * depthM)) * 2.0;
  while (kG * hi * std::tanh(hi * depthM) < omega * omega) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (kG * mid * std::tanh(mid * depthM) < omega * omega ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::optional<WaveField> WaveField::create(Model model, const SeaState& sea, std::string& error) {
  auto bad = [&](const char* field, double v, const char* want) {
    std::ostringstream os;
    os << "sea state: " << field << " = " << v << " is invalid (" << want << ")";
    error = os.str();
    return std::nullopt;
  };
  if (!std::isfinite(sea.windSpeedMps) || sea.windSpeedMps < 0.2 || sea.windSpeedMps > 60.0)
    return bad("windSpeedMps", sea.windSpeedMps, "expected 0.2 .. 60 m/s");
  if (!std::isfinite(sea.windFromDeg)) return bad("windFromDeg", sea.windFromDeg, "expected a finite angle");
  // 0 is fully developed; below 1 m of fetch JONSWAP's peak runs away
  // (1e-300 m: a peak frequency of 1e102 rad/s, NaN heights).
  if (!std::isfinite(sea.fetchM) || !(sea.fetchM == 0.0 || sea.fetchM >= 1.0))
    return bad("fetchM", sea.fetchM, "expected 0 (fully developed) or >= 1 m");
  if (!(sea.anchorLatDeg >= -90.0 && sea.anchorLatDeg <= 90.0))
    return bad("anchorLatDeg", sea.anchorLatDeg, "expected -90 .. 90");
  // Bounded, not just finite: lon * pi overflowed to NaN at -1.8e308
  // (fuzz_capi_sea_state finding 4: NaN FFT plane cells, UB).
  if (!(sea.anchorLonDeg >= -360.0 && sea.anchorLonDeg <= 360.0))
    return bad("anchorLonDeg", sea.anchorLonDeg, "expected -360 .. 360");
  // 1 cm and up: at 1e-300 m the shallow-water wave number ran to 1e150 and
  // every phase to NaN (fuzz_capi_sea_state finding 9).
  if (!(sea.referenceDepthM >= kMinReferenceDepthM))
    return bad("referenceDepthM", sea.referenceDepthM, "expected >= 0.01 m (1e30: deep water)");
  if (sea.gerstnerComponents < 1 || sea.gerstnerComponents > kMaxComponents)
    return bad("gerstnerComponents", sea.gerstnerComponents, "expected 1 .. 64");
  if (sea.noiseOctaves < 1 || sea.noiseOctaves > kMaxOctaves)
    return bad("noiseOctaves", sea.noiseOctaves, "expected 1 .. 12");

  WaveField w;
  w.model_ = model;
  w.sea_ = sea;
  w.omegaPeak_ = peakOmega(sea);
  w.peakWavelengthM_ = kTwoPi * kG / (w.omegaPeak_ * w.omegaPeak_);
  w.hsM_ = 4.0 * std::sqrt(bandVariance(sea, 0.2 * w.omegaPeak_, 1.5 * w.omegaPeak_) +
                           bandVariance(sea, 1.5 * w.omegaPeak_, 20.0 * w.omegaPeak_));
  const Enu a = enuAt(sea.anchorLatDeg, sea.anchorLonDeg);
  const double travel = deg2rad(sea.windFromDeg + 180.0);
  w.travelEn_ = {std::sin(travel), std::cos(travel)};
  w.travelEcef_ = a.e * std::sin(travel) + a.n * std::cos(travel);
  if (model == Model::Gerstner)
    w.buildGerstner();
  else if (model == Model::Fft)
    w.fft_ = std::make_shared<const FftOcean>(sea, w.hsM_, w.peakWavelengthM_, w.travelEcef_);
  else
    w.buildNoise();
  w.buildBounds();
  return w;
}

void WaveField::buildNoise() {
  Rng rng{sea_.seed * 0x2545F4914F6CDD1DULL + 1};
  const int n = sea_.noiseOctaves;
  double sumSq = 0.0;
  for (int i = 0; i < n; ++i) sumSq += std::pow(0.25, i);
  const double unitStd = model_ == Model::Noise ? kPerlin3Std : kPerlin2Std;
  const double a0 = hsM_ / (4.0 * unitStd * std::sqrt(sumSq));
  const double cellM = peakWavelengthM_;
  for (int i = 0; i < n; ++i) {
    Octave o;
    const double f = std::ldexp(1.0, i) / cellM;  // lattice units per metre
    o.frequencyPerM = f;
    // Random rotation (Shoemake): decorrelates octaves and averages out the
    // lattice's axis preference, so the density is the same in every direction.
    const double u1 = rng.uniform(), u2 = rng.uniform() * kTwoPi, u3 = rng.uniform() * kTwoPi;
    const double qx = std::sqrt(1 - u1) * std::sin(u2), qy = std::sqrt(1 - u1) * std::cos(u2);
    const double qz = std::sqrt(u1) * std::sin(u3), qw = std::sqrt(u1) * std::cos(u3);
    const double m[3][3] = {{1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)},
                            {2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)},
                            {2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)}};
    for (int r = 0; r < 3; ++r)
      o.row[r] = glm::dvec3(roundToFloat(m[r][0] * f), roundToFloat(m[r][1] * f), roundToFloat(m[r][2] * f));
    o.amplitudeM = roundToFloat(a0 * std::pow(0.5, i));
    o.seed = std::uint32_t(rng.next() & 0xFFFFFFu);  // exact as a float
    // Each octave drifts downwind with the deep-water phase speed of its
    // wavelength: eta(P, t) = N(M (P - c t)), so the lattice moves by v = -M c.
    const double wavelengthM = 1.0 / f;
    const double speed = -std::sqrt(kG * wavelengthM / kTwoPi);
    const glm::dvec3 vWorld = model_ == Model::Noise ? travelEcef_ * speed : glm::dvec3(travelEn_ * speed, 0.0);
    if (model_ == Model::Noise)
      o.velocity = glm::dvec3(roundToFloat(glm::dot(o.row[0], vWorld)), roundToFloat(glm::dot(o.row[1], vWorld)),
                              roundToFloat(glm::dot(o.row[2], vWorld)));
    else
      o.velocity = vWorld * f;  // 2D lattice velocity of the paper model (no rotation)
    octaves_.push_back(o);
  }
}

void WaveField::buildGerstner() {
  Rng rng{sea_.seed * 0x9E3779B97F4A7C15ULL + 7};
  const int n = sea_.gerstnerComponents;
  const double w0 = 0.6 * omegaPeak_, w1 = 4.0 * omegaPeak_;
  const Enu a = enuAt(sea_.anchorLatDeg, sea_.anchorLonDeg);
  const double travel = deg2rad(sea_.windFromDeg + 180.0);
  std::vector<double> drawn;  // a direction drawn from the spreading per component
  for (int j = 0; j < n; ++j) {
    // Bands equal in log(omega); the frequency is random inside its band so
    // that no two seas (or components) are commensurate.
    const double lo = w0 * std::pow(w1 / w0, double(j) / n), hi = w0 * std::pow(w1 / w0, double(j + 1) / n);
    Component c;
    c.omega = lo * std::pow(hi / lo, rng.uniform());
    c.amplitudeM = std::sqrt(2.0 * bandVariance(sea_, lo, hi));
    c.kRef = waveNumberExact(c.omega, sea_.referenceDepthM);
    c.phase0 = rng.uniform() * kTwoPi;
    c.choppiness = 1.0;
    // cos^2 spreading about the wind, by rejection: the direction of a lone
    // component; the draws also keep each seed's frequencies and phases.
    double dth = 0.0;
    for (;;) {
      dth = (rng.uniform() - 0.5) * kPi;
      if (rng.uniform() < std::cos(dth) * std::cos(dth)) break;
    }
    drawn.push_back(dth);
    components_.push_back(c);
  }
  const double u0 = rng.uniform();  // the seed's own offset of the direction sequence
  // Directions (the rule, plugin/waves/README.md): stratified over the cos^2
  // spreading by slope variance (a^2 k^2 / 2: what the near field shows),
  // strata in golden-ratio order. Independent draws (the old rejection
  // sampling) put 3-4 of 16 components within a few degrees of each other:
  // long parallel crests, the radial streaks seen from 2-30 m. Component j
  // takes the stratum at the rank of frac(u0 + j / golden ratio):
  // neighbours in frequency are >= 0.38 apart in that sequence, so no band
  // of frequencies shares a direction; each stratum's width is its
  // component's share of the slope variance and the direction its middle
  // quantile, so the slope-weighted directions follow the spreading within
  // half the largest share (the least any set of these weights can). A lone
  // component keeps its random direction.
  std::vector<std::pair<double, int>> order;
  double slopeSum = 0.0;
  for (int j = 0; j < n; ++j) {
    order.push_back({std::fmod(u0 + j * kInvGolden, 1.0), j});
    slopeSum += slopeWeight(components_[std::size_t(j)]);
  }
  std::sort(order.begin(), order.end());
  double below = 0.0;
  for (const auto& [key, j] : order) {
    Component& c = components_[std::size_t(j)];
    const double share = slopeWeight(c) / slopeSum;
    const double b = travel + (n == 1 ? drawn[0] : cos2SpreadingQuantile(below + 0.5 * share));
    below += share;
    // Source a quarter circumference up-wave of the anchor: at the anchor the
    // great circle runs exactly along bearing b.
    c.source = -(a.e * std::sin(b) + a.n * std::cos(b));
  }
  // The discretised spectrum keeps > 99% of the variance (the tail above
  // 4 w_p holds < 0.5%); rescale so the components carry exactly m0.
  double m0 = 0.0;
  for (const auto& c : components_) m0 += 0.5 * c.amplitudeM * c.amplitudeM;
  const double scale = hsM_ / (4.0 * std::sqrt(m0));
  for (auto& c : components_) c.amplitudeM *= scale;
}

void WaveField::buildBounds() {
  if (model_ == Model::Fft) {
    maxVerticalM_ = fft_->maxVerticalM();
    maxHorizontalM_ = fft_->maxHorizontalM();
    return;
  }
  if (model_ != Model::Gerstner) {
    double sum = 0.0;
    for (const auto& o : octaves_) sum += o.amplitudeM;
    maxVerticalM_ = kPerlin3Bound * sum;
    maxHorizontalM_ = 0.0;
    return;
  }
  // Scan depths with the kernel's own formulas (taper <= 1).
  kd::Kernel k;
  double vMax = 0.0, hMax = 0.0;
  for (int i = 0; i <= 600; ++i) {
    const double depth = i == 600 ? kDeepWaterM : 0.05 * std::pow(1e5, i / 599.0);
    double sumAz = 0.0, sumAx = 0.0, sumKAx = 0.0;
    for (const auto& c : components_) {
      double th = 1.0, ks = 1.0;
      if (c.omega * c.omega / kG * depth < WV_DEEP_KH) {
        const double kl = k.wv_waveNumber(c.omega, depth);
        th = std::tanh(kl * depth);
        const double nn = 0.5 * (1.0 + kl * depth * (1.0 - th * th) / th);
        ks = std::sqrt(kG * kl / (2.0 * c.omega * c.omega * nn));
      }
      const double az = c.amplitudeM * ks, ax = c.choppiness * az / th;
      sumAz += az;
      sumAx += ax;
      sumKAx += ax * c.kRef;
    }
    const double sB = std::min(1.0, 0.39 * depth / sumAz);
    const double lam = sB * std::min(1.0, 0.9 / (sB * sumKAx));
    vMax = std::max(vMax, sB * sumAz);
    hMax = std::max(hMax, lam * sumAx);
  }
  // 1% margin for depths between the scan points.
  maxVerticalM_ = vMax * 1.01;
  maxHorizontalM_ = hMax * 1.01;
}

void WaveField::cpuPatch(const glm::dvec3& o, double tS, CpuPatch& out) const {
  out.frame = makeFrame(o);
  out.octaves.clear();
  out.waves.clear();
  out.fftPlanes.clear();
  out.fftTexels.reset();
  if (model_ == Model::Fft) {
    fftPlanesAt(o, out.fftPlanes);
    out.fftTexels = fft_->tablesAt(tS);
  }
  if (model_ == Model::Noise)
    for (const auto& oc : octaves_) out.octaves.push_back(octaveAt(oc, o, tS));
  else if (model_ == Model::NoisePaper) {
    // O's longitude and its latitude as the kernel takes P's (atan of
    // z / ((1 - e^2) rho), the geodetic latitude on the ellipsoid); an origin
    // within 1e-12 rad (6 um) of the seam is on its west side, as the
    // query's wrap puts 180 degrees at -180.
    const double rho = std::hypot(o.x, o.y);
    double lam = std::atan2(o.y, o.x);
    if (kPi - std::abs(lam) < 1e-12) lam = -kPi;
    out.octaves.resize(octaves_.size());
    paperPatchAt(std::atan2(o.z, (1.0 - kE2) * rho), lam, rho, o.z, tS, out.octaves.data(), out.paper);
  } else if (model_ == Model::Gerstner)
    for (const auto& c : components_) out.waves.push_back(waveAt(c, glm::dvec3(out.frame.radial), tS));
  out.coast = kd::WvCoast{};
  out.coastTexels = nullptr;
  if (model_ == Model::Gerstner && coast_) {
    out.coast = coast_->at(o);
    out.coastTexels = coast_->texels().data();
  }
}

void WaveField::setCoast(std::shared_ptr<const CoastField> coast) {
  coast_ = coast && !coast->empty() && model_ == Model::Gerstner ? std::move(coast) : nullptr;
}

void WaveField::gpuPatch(const glm::dvec3& o, double tS, GpuPatch& out) const {
  CpuPatch p;
  cpuPatch(o, tS, p);
  out.frame = {toF(p.frame.radial), toF(p.frame.up), toF(p.frame.upScale)};
  out.octaves.clear();
  out.waves.clear();
  for (const auto& w : p.octaves)
    out.octaves.push_back({toF(w.row0), toF(w.row1), toF(w.row2), toF(w.fracO), w.cellO, toF(w.vel)});
  for (const auto& w : p.waves) out.waves.push_back({toF(w.dirO), toF(w.binO), toF(w.phase), toF(w.extra)});
  out.coast = {toF(p.coast.eAxis), toF(p.coast.nAxis), p.coast.cell};
  out.paper = {toF(p.paper.horiz), toF(p.paper.angles), toF(p.paper.trig)};
  out.fftPlanes.clear();
  out.fftTexels.clear();
  out.fftCascades = 0;
  if (model_ == Model::Fft) {
    out.fftCascades = FftOcean::kCascades;
    for (const auto& e : p.fftPlanes) out.fftPlanes.push_back({toF(e.uAxis), toF(e.vAxis), toF(e.axis), e.cell});
    out.fftTexels.reserve(p.fftTexels->size());
    for (const auto& t : *p.fftTexels) out.fftTexels.push_back(glm::vec4(t));
  }
}

void WaveField::fftPlanesAt(const glm::dvec3& o, std::vector<kd::WvFftPlane>& out) const {
  out.clear();
  const int n = FftOcean::kN;
  for (int p = 0; p < FftOcean::kPlanes; ++p)
    for (int c = 0; c < FftOcean::kCascades; ++c) {
      const double texPerM = n / fft_->lengthM(c);
      // Axes rounded to float: the CPU and the GPU then project with the
      // same numbers, and O's large coordinate is reduced here in double.
      const glm::dvec3 u(glm::vec3(fft_->uAxis(p) * texPerM)), v(glm::vec3(fft_->vAxis(p) * texPerM));
      const double tu = glm::dot(u, o) + fft_->offsetTexels(p, 0), tv = glm::dot(v, o) + fft_->offsetTexels(p, 1);
      const double fu = std::floor(tu), fv = std::floor(tv);
      kd::WvFftPlane e;
      e.uAxis = glm::dvec4(u, tu - fu);
      e.vAxis = glm::dvec4(v, tv - fv);
      e.axis = glm::dvec4(fft_->planeAxis(p), roundToFloat(1.0 / texPerM));
      const int base = c * n * n;
      e.cell = glm::ivec4(int(std::fmod(fu, double(n)) + n) % n, int(std::fmod(fv, double(n)) + n) % n, base, n);
      out.push_back(e);
    }
}

kd::WvResult WaveField::evaluate(const CpuPatch& p, const glm::dvec3& d, double depthM) const {
  kd::Kernel k{p.octaves.data(), p.waves.data(), p.fftPlanes.data(), p.fftTexels ? p.fftTexels->data() : nullptr,
               p.coastTexels};
  if (model_ == Model::Fft) return k.wv_fft(0, FftOcean::kPlanes, FftOcean::kCascades, d, p.frame);
  if (model_ == Model::Gerstner) return k.wv_gerstnerCoast(0, int(p.waves.size()), d, p.frame, depthM, p.coast);
  if (model_ == Model::NoisePaper) return k.wv_paperNoise(0, int(p.octaves.size()), d, p.paper);
  return k.wv_solidNoise(0, int(p.octaves.size()), d, p.frame);
}

double WaveField::foldJacobian(const CpuPatch& p, const glm::dvec3& d, double depthM) const {
  if (model_ == Model::Fft) {
    kd::Kernel k{p.octaves.data(), p.waves.data(), p.fftPlanes.data(), p.fftTexels ? p.fftTexels->data() : nullptr,
                 p.coastTexels};
    return k.wv_fftFold(0, FftOcean::kPlanes, FftOcean::kCascades, d, p.frame);
  }
  if (model_ == Model::Gerstner) return evaluate(p, d, depthM).jac.w;
  return 1.0;
}

namespace {
WaveSample toEnu(const kd::WvResult& r, const Enu& f) {
  WaveSample s;
  const glm::dvec3 disp(r.disp);
  s.displacementEnuM = {glm::dot(disp, f.e), glm::dot(disp, f.n), glm::dot(disp, f.u)};
  const glm::dvec3 nrm(r.normal);
  s.normalEnu = {glm::dot(nrm, f.e), glm::dot(nrm, f.n), glm::dot(nrm, f.u)};
  s.verticalVelocityMps = r.normal.w;
  const glm::dvec3 hv(r.hvel);
  s.horizontalVelocityEnuMps = {glm::dot(hv, f.e), glm::dot(hv, f.n), glm::dot(hv, f.u)};
  s.breakingFoam = r.hvel.w;
  return s;
}
}  // namespace

void WaveField::paperPatchAt(double phi0, double lam0, double rho0, double z0, double tS, kd::WvOctave* octaves,
                             kd::WvPaper& paper) const {
  // Paper 002, eq. 4-5: h(lambda cos(beta), beta), scaled to metres by the
  // mean radius. Per octave the lattice coordinate at the origin, reduced
  // here in double (cell + fraction), for lambda0 and across the seam.
  const double cp = std::cos(phi0);
  const double lamW = lam0 >= 0.0 ? lam0 - kTwoPi : lam0 + kTwoPi;
  const double x = kMeanRadiusM * lam0 * cp, xW = kMeanRadiusM * lamW * cp, y = kMeanRadiusM * phi0;
  for (const auto& o : octaves_) {
    const double f = o.frequencyPerM;
    const glm::dvec3 q(x * f + o.velocity.x * tS, y * f + o.velocity.y * tS, xW * f + o.velocity.x * tS);
    const glm::dvec3 fl = glm::floor(q);
    const glm::ivec3 c = wrapCells(fl);
    kd::WvOctave w;
    // f R as a float: the CPU's double kernel and the GPU scale the
    // offsets by the same number (at the query's own point the offset is 0).
    w.row0 = glm::dvec4(roundToFloat(f * kMeanRadiusM), 0.0, 0.0, o.amplitudeM);
    w.row1 = glm::dvec4(0.0, 0.0, 0.0, double(o.seed));
    w.row2 = glm::dvec4(0.0);
    w.fracO = glm::dvec4(finiteFrac(q.x, fl.x), finiteFrac(q.y, fl.y), finiteFrac(q.z, fl.z), finiteFrac(q.y, fl.y));
    w.cellO = glm::ivec4(c.x, c.y, c.z, c.y);
    w.vel = glm::dvec4(o.velocity, 0.0);
    *octaves++ = w;
  }
  paper.horiz = glm::dvec4(std::cos(lam0), std::sin(lam0), rho0, z0);
  paper.angles = glm::dvec4(phi0, lam0, lamW, lam0 >= 0.0 ? kPi - lam0 : -kPi - lam0);
  paper.trig = glm::dvec4(std::sin(phi0), cp, 0.0, 0.0);
}

WaveSample WaveField::samplePaper(double latDeg, double lonDeg, double tS) const {
  // The kernel at the point itself (d = 0), as the GPU evaluates it at offsets.
  double lonW = std::fmod(lonDeg, 360.0);
  if (lonW >= 180.0) lonW -= 360.0;
  if (lonW < -180.0) lonW += 360.0;
  const Located loc = locate(latDeg, lonDeg);
  std::array<kd::WvOctave, kMaxOctaves> oc;  // no allocation per query
  kd::WvPaper paper;
  paperPatchAt(deg2rad(latDeg), deg2rad(lonW), std::hypot(loc.p.x, loc.p.y), loc.p.z, tS, oc.data(), paper);
  kd::Kernel k{oc.data(), nullptr};
  return toEnu(k.wv_paperNoise(0, int(octaves_.size()), glm::dvec3(0.0), paper), Enu{loc.f.e, loc.f.n, loc.f.u});
}

WaveSample WaveField::sample(double latDeg, double lonDeg, double tS, double depthM) const {
  if (model_ == Model::NoisePaper) return samplePaper(latDeg, lonDeg, tS);
  const Located loc = locate(latDeg, lonDeg);
  const glm::dvec3 p = loc.p;
  const Enu f{loc.f.e, loc.f.n, loc.f.u};
  const kd::WvFrame frame = makeFrame(p);
  if (model_ == Model::Noise) {
    std::array<kd::WvOctave, kMaxOctaves> oc;
    for (std::size_t i = 0; i < octaves_.size(); ++i) oc[i] = octaveAt(octaves_[i], p, tS);
    kd::Kernel k{oc.data(), nullptr};
    return toEnu(k.wv_solidNoise(0, int(octaves_.size()), glm::dvec3(0.0), frame), f);
  }
  if (model_ == Model::Fft) {
    std::vector<kd::WvFftPlane> planes;
    fftPlanesAt(p, planes);
    const auto tables = fft_->tablesAt(tS);
    kd::Kernel k{nullptr, nullptr, planes.data(), tables->data()};
    return toEnu(k.wv_fft(0, FftOcean::kPlanes, FftOcean::kCascades, glm::dvec3(0.0), frame), f);
  }
  std::array<kd::WvWave, kMaxComponents> wv;
  const glm::dvec3 radial(frame.radial);
  for (std::size_t i = 0; i < components_.size(); ++i) wv[i] = waveAt(components_[i], radial, tS);
  kd::Kernel k{nullptr, wv.data(), nullptr, nullptr, coast_ ? coast_->texels().data() : nullptr};
  const kd::WvCoast co = coast_ ? coast_->at(p) : kd::WvCoast{};
  return toEnu(k.wv_gerstnerCoast(0, int(components_.size()), glm::dvec3(0.0), frame, depthM, co), f);
}

WaveField::BreakingMean WaveField::breakingFoamMean(double latDeg, double lonDeg, double tS, double depthM) const {
  if (model_ != Model::Gerstner || !coast_) return {};
  const Located loc = locate(latDeg, lonDeg);
  const kd::WvFrame frame = makeFrame(loc.p);
  std::array<kd::WvWave, kMaxComponents> wv;
  const glm::dvec3 radial(frame.radial);
  for (std::size_t i = 0; i < components_.size(); ++i) wv[i] = waveAt(components_[i], radial, tS);
  kd::Kernel k{nullptr, wv.data(), nullptr, nullptr, coast_->texels().data()};
  const glm::dvec4 m =
      k.wv_breakingFoamMean(0, int(components_.size()), glm::dvec3(0.0), frame, depthM, coast_->at(loc.p)).m;
  return {m.x, m.y};
}

SurfacePoint WaveField::surfaceAt(double latDeg, double lonDeg, double tS, double depthM) const {
  SurfacePoint sp;
  if (model_ != Model::Gerstner && model_ != Model::Fft) {
    const WaveSample s = sample(latDeg, lonDeg, tS, depthM);
    sp.heightM = s.displacementEnuM.z;
    sp.normalEnu = s.normalEnu;
    sp.verticalVelocityMps = s.verticalVelocityMps;
    return sp;
  }
  const Located loc = locate(latDeg, lonDeg);
  const glm::dvec3 p = loc.p;
  const Enu f{loc.f.e, loc.f.n, loc.f.u};
  const kd::WvFrame frame = makeFrame(p);
  std::array<kd::WvWave, kMaxComponents> wv;
  std::vector<kd::WvFftPlane> planes;
  std::shared_ptr<const std::vector<glm::dvec4>> tables;
  const glm::dvec3 radial(frame.radial);
  glm::dvec3 dir0(0.0);  // Gerstner: the Jacobian's frame axis (wv_tangent1)
  if (model_ == Model::Fft) {
    fftPlanesAt(p, planes);
    tables = fft_->tablesAt(tS);
  } else {
    for (std::size_t i = 0; i < components_.size(); ++i) wv[i] = waveAt(components_[i], radial, tS);
    dir0 = glm::dvec3(wv[0].dirO);
  }
  kd::Kernel k{nullptr, wv.data(), planes.data(), tables ? tables->data() : nullptr,
               coast_ ? coast_->texels().data() : nullptr};
  const int n = int(components_.size());
  const kd::WvCoast co = coast_ && model_ == Model::Gerstner ? coast_->at(p) : kd::WvCoast{};
  auto eval = [&](const glm::dvec3& dd) {
    return model_ == Model::Fft ? k.wv_fft(0, FftOcean::kPlanes, FftOcean::kCascades, dd, frame)
                                : k.wv_gerstnerCoast(0, n, dd, frame, depthM, co);
  };
  // Find the rest point x (offset d in P's tangent plane) whose particle sits
  // above P: F(d) = d + H(d) = 0. Newton steps with the kernel's Jacobian of
  // F (which ignores the slow taper and curvature terms: it only sets the
  // speed; convergence is checked on F itself). The kernel keeps the
  // Jacobian's eigenvalues >= 0.1, so F is one-to-one and the step is safe;
  // a step that does not shrink the miss falls back to the fixed-point step
  // d <- -H(d), a contraction.
  glm::dvec3 d(0.0);
  kd::WvResult r = eval(d);
  int it = 0;
  double lastMiss = 1e300;
  for (; it < 100; ++it) {
    const glm::dvec3 up = k.wv_upAt(frame, d);
    const glm::dvec3 hor = glm::dvec3(r.disp) - up * r.disp.w;
    glm::dvec3 miss = d + hor;
    miss -= glm::dot(miss, f.u) * f.u;
    const double missM = glm::length(miss);
    if (missM < kInversionToleranceM) break;
    if (missM < 0.5 * lastMiss) {
      const glm::dvec3 t1 = model_ == Model::Fft ? k.wv_fftTangent1(up) : k.wv_tangent1(dir0, up);
      const glm::dvec3 t2 = glm::cross(up, t1);
      const double mx = glm::dot(miss, t1), my = glm::dot(miss, t2);
      const double a11 = r.jac.x, a12 = r.jac.y, a22 = r.jac.z, det = r.jac.w;
      d -= t1 * ((a22 * mx - a12 * my) / det) + t2 * ((a11 * my - a12 * mx) / det);
    } else {
      d -= miss;
    }
    lastMiss = missM;
    r = eval(d);
  }
  const WaveSample s = toEnu(r, f);
  sp.heightM = r.disp.w;
  sp.normalEnu = s.normalEnu;
  // d(eta)/dt at fixed P = w - grad(eta) . v_h, grad(eta) = -n_h / n_u.
  const glm::dvec2 gradEta = -glm::dvec2(s.normalEnu.x, s.normalEnu.y) / s.normalEnu.z;
  sp.verticalVelocityMps =
      s.verticalVelocityMps - glm::dot(gradEta, glm::dvec2(s.horizontalVelocityEnuMps.x, s.horizontalVelocityEnuMps.y));
  sp.iterations = it;
  sp.restOffsetEnuM = {glm::dot(d, f.e), glm::dot(d, f.n), glm::dot(d, f.u)};
  return sp;
}

LocalSeaState WaveField::seaStateAt(double latDeg, double lonDeg, double depthM) const {
  LocalSeaState out;
  const Located loc = locate(latDeg, lonDeg);
  out.peakPeriodS = kTwoPi / omegaPeak_;
  // The depth that sets each model's phase: Gerstner and FFT take their wave
  // numbers from the reference depth, noise draws deep-water cells.
  const double phaseDepth = model_ == Model::Gerstner || model_ == Model::Fft ? sea_.referenceDepthM : kDeepWaterM;
  out.peakWavelengthM = kTwoPi / waveNumberExact(omegaPeak_, phaseDepth);
  glm::dvec3 travel = travelEcef_;
  if (model_ == Model::Gerstner) {
    const double depth = std::max(depthM, 0.05);  // as wv_gerstner
    const glm::dvec3 radial = glm::normalize(loc.p);
    kd::Kernel k{nullptr, nullptr, nullptr, nullptr, coast_ ? coast_->texels().data() : nullptr};
    const kd::WvCoast co = coast_ ? coast_->at(loc.p) : kd::WvCoast{};
    // Inside a coast field's grid the phase follows the local depth.
    const bool local = coast_ && co.cell.x >= 0 && co.cell.y >= 0 && co.cell.x < co.cell.z - 1 &&
                       co.cell.y < co.cell.z - 1;
    if (local) out.peakWavelengthM = kTwoPi / waveNumberExact(omegaPeak_, depth);
    double m0 = 0.0, sumAz = 0.0;
    travel = glm::dvec3(0.0);
    for (std::size_t i = 0; i < components_.size(); ++i) {
      const Component& c = components_[i];
      const kd::WvWave w = waveAt(c, radial, 0.0);
      const glm::dvec4 cf = co.cell.z > 0 ? k.wv_coastSample(co, int(i), glm::dvec3(0.0)) : glm::dvec4(0.0);
      // wv_gerstnerCoast's shoaling, refraction, taper and Miche cap at d = 0
      // (the arc from the source over |P| is sin(thetaO) there).
      const double az = k.wv_coastAmplitude(w, w.dirO.w, cf.w, depth, co.cell.z > 0).x;
      m0 += 0.5 * az * az;
      sumAz += az;
      glm::dvec3 dir = glm::dvec3(w.dirO);
      dir = dir * (1.0 - cf.z) + glm::cross(loc.f.u, dir) * cf.y;
      travel += (0.5 * az * az) * dir;
    }
    const double sB = k.wv_coastBreaking(depth, sumAz, 0.0, 0.0).x;  // wv_gerstner's breaking cap
    out.hsM = 4.0 * std::sqrt(m0) * sB;
  } else {
    out.hsM = hsM_;
  }
  const double te = glm::dot(travel, loc.f.e), tn = glm::dot(travel, loc.f.n);
  double from = std::atan2(te, tn) * (180.0 / kPi) + 180.0;
  from = std::fmod(from, 360.0);
  out.waveFromDeg = from < 0.0 ? from + 360.0 : from;
  return out;
}

void WaveField::surfaceBatch(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                             const double* depthM, std::size_t n, SurfacePoint* out) const {
  const batch::Points pts{latDeg, lonDeg, tS, timesPerPoint, depthM, n};
  if (n == 0) return;
  if (model_ == Model::Noise) {
    std::array<batch::NoiseOctave, kMaxOctaves> oc{};
    for (std::size_t i = 0; i < octaves_.size(); ++i) {
      const Octave& o = octaves_[i];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) oc[i].row[r][c] = o.row[r][c];
      for (int c = 0; c < 3; ++c) oc[i].vel[c] = o.velocity[c];
      oc[i].amplitudeM = o.amplitudeM;
      oc[i].seed = o.seed;
    }
    batch::noise(oc.data(), int(octaves_.size()), pts, out);
    return;
  }
  if (model_ == Model::Gerstner && !coast_) {  // the SIMD batch has no coast field: scalar below
    std::array<batch::GerstnerComponent, kMaxComponents> gc{};
    for (std::size_t i = 0; i < components_.size(); ++i) {
      const Component& c = components_[i];
      gc[i] = {{c.source.x, c.source.y, c.source.z}, c.omega, c.kRef, c.kRef * kMeanRadiusM, c.amplitudeM,
               c.phase0, c.choppiness};
    }
    batch::gerstner(gc.data(), int(components_.size()), pts, out);
    return;
  }
  if (model_ == Model::Fft) {
    // The plane constants of fftPlanesAt itself (at the origin, where the
    // texel coordinate is the plane's offset: cell + fraction).
    std::vector<kd::WvFftPlane> at0;
    fftPlanesAt(glm::dvec3(0.0), at0);
    std::array<batch::FftPlane, FftOcean::kPlanes * FftOcean::kCascades> pl{};
    for (std::size_t k = 0; k < pl.size(); ++k) {
      const kd::WvFftPlane& e = at0[k];
      pl[k] = {{e.uAxis.x, e.uAxis.y, e.uAxis.z}, {e.vAxis.x, e.vAxis.y, e.vAxis.z}, e.cell.x + e.uAxis.w,
               e.cell.y + e.vAxis.w, e.axis.w, e.cell.z};
    }
    // One table set per time: runs of points at the same time.
    for (std::size_t i0 = 0; i0 < n;) {
      const double t = timesPerPoint ? tS[i0] : tS[0];
      std::size_t i1 = i0 + 1;
      while (i1 < n && (!timesPerPoint || tS[i1] == t)) ++i1;
      const auto tables = fft_->tablesAt(t);
      const batch::Points run{latDeg + i0, lonDeg + i0, &t, false, nullptr, i1 - i0};
      batch::fft(pl.data(), tables->data(), run, out + i0);
      i0 = i1;
    }
    return;
  }
  for (std::size_t i = 0; i < n; ++i)
    out[i] = surfaceAt(latDeg[i], lonDeg[i], timesPerPoint ? tS[i] : tS[0], depthM ? depthM[i] : kDeepWaterM);
}

namespace {
// The integral over ln k from kMin to 1e4 rad/m of Elfouhaily's curvature
// spectrum B(k) times k^-power (0: slope variance, 2: height variance).
double elfouhailyMoment(const SeaState& sea, double kMinRadPerM, int power) {
  // Elfouhaily, Chapron, Katsaros & Vandemark (1997), JGR 102(C7), eq. 30-33,
  // 38-41, 44: curvature spectrum B(k) = k^3 S(k) = B_l + B_h, so the slope
  // variance is the integral of B over ln k. Wind at 10 m from the sea
  // state's 19.5 m (PM's reference height, U10 = U19.5 / 1.026).
  const double u10 = std::max(sea.windSpeedMps / 1.026, 0.1);
  constexpr double kM = 370.0, cM = 0.23, omegaC = 0.84;  // capillary peak; inverse wave age (fully developed)
  const double kP = kG * (omegaC / u10) * (omegaC / u10), cP = std::sqrt(kG / kP);
  const double uStar = std::sqrt((0.81 + 0.065 * u10) * 1e-3) * u10;  // drag coefficient of Wu (1982)
  const double alphaM = 0.01 * (uStar <= cM ? 1.0 + std::log(uStar / cM) : 1.0 + 3.0 * std::log(uStar / cM));
  const double alphaP = 6e-3 * std::sqrt(omegaC);
  const double sigma = 0.08 * (1.0 + 4.0 / (omegaC * omegaC * omegaC)), gamma = 1.7;
  // Midpoint rule in ln k from max(kMin, 1e-4) to 1e4 rad/m (B falls as
  // exp(-(k/kM)^2/4) beyond the capillary peak): 0.1 % with 2000 steps.
  const double lo = std::log(std::max(kMinRadPerM, 1e-4)), hi = std::log(1e4);
  if (!(lo < hi)) return 0.0;
  const int n = 2000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double k = std::exp(lo + (hi - lo) * (i + 0.5) / n);
    const double c = std::sqrt(kG / k * (1.0 + (k / kM) * (k / kM)));
    const double lpm = std::exp(-1.25 * (kP / k) * (kP / k));
    const double g = std::sqrt(k / kP) - 1.0;
    const double jp = std::pow(gamma, std::exp(-g * g / (2.0 * sigma * sigma)));
    const double bl = 0.5 * alphaP * cP / c * lpm * jp * std::exp(-omegaC / std::sqrt(10.0) * g);
    const double bh = 0.5 * alphaM * cM / c * lpm * jp * std::exp(-0.25 * (k / kM - 1.0) * (k / kM - 1.0));
    sum += (bl + bh) * std::pow(k, -power);
  }
  return sum * (hi - lo) / n;
}
}  // namespace

double slopeVarianceAbove(const SeaState& sea, double kMinRadPerM) { return elfouhailyMoment(sea, kMinRadPerM, 0); }
double heightVarianceAbove(const SeaState& sea, double kMinRadPerM) { return elfouhailyMoment(sea, kMinRadPerM, 2); }

std::vector<DetailWave> detailWaves(const SeaState& sea, double kLowRadPerM, int octaves, int perOctave) {
  Rng rng{sea.seed * 0xD1B54A32D192ED03ULL + 11};
  const int n = octaves * perOctave;
  const Enu a = enuAt(sea.anchorLatDeg, sea.anchorLonDeg);
  const double travel = deg2rad(sea.windFromDeg + 180.0);
  // Cox & Munk's upwind share of the slopes (sea_shading.glsl's
  // coxMunkUpwindShare): 1 + D cos 2 phi has the share 1/2 + D/4.
  const double u10 = sea.windSpeedMps / 1.026, up = 3.16e-3 * u10, cross = 0.003 + 1.92e-3 * u10;
  const double spread = 4.0 * (up / (up + cross) - 0.5);
  const auto quantile = [&](double u) {  // F(phi) = 1/2 + (phi + D/2 sin 2 phi) / 2 pi on [-pi, pi]
    double lo = -kPi, hi = kPi;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (0.5 + (mid + 0.5 * spread * std::sin(2.0 * mid)) / kTwoPi < u ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  std::vector<DetailWave> w(static_cast<std::size_t>(n));
  std::vector<double> var(static_cast<std::size_t>(n));
  double total = 0.0;
  for (int j = 0; j < n; ++j) {
    const double k0 = kLowRadPerM * std::exp2(double(j) / perOctave), k1 = k0 * std::exp2(1.0 / perOctave);
    var[std::size_t(j)] = std::max(slopeVarianceAbove(sea, k0) - slopeVarianceAbove(sea, k1), 0.0);
    total += var[std::size_t(j)];
    DetailWave& d = w[std::size_t(j)];
    d.k = k0 * std::pow(k1 / k0, rng.uniform());  // not commensurate
    d.omega = std::sqrt(kG * d.k * (1.0 + (d.k / 370.0) * (d.k / 370.0)));  // capillary term (Elfouhaily's k_m)
    d.slopeAmplitude = std::sqrt(2.0 * var[std::size_t(j)]);
    d.phase0 = rng.uniform() * kTwoPi;
  }
  // The Gerstner rule: strata as wide as each wave's slope share, in
  // golden-ratio order.
  const double u0 = rng.uniform();
  std::vector<std::pair<double, int>> order;
  for (int j = 0; j < n; ++j) order.push_back({std::fmod(u0 + j * kInvGolden, 1.0), j});
  std::sort(order.begin(), order.end());
  double below = 0.0;
  for (const auto& [key, j] : order) {
    const double share = total > 0.0 ? var[std::size_t(j)] / total : 1.0 / n;
    const double b = travel + quantile(below + 0.5 * share);
    below += share;
    w[std::size_t(j)].source = -(a.e * std::sin(b) + a.n * std::cos(b));
  }
  return w;
}

std::vector<glm::dvec4> detailPatch(const std::vector<DetailWave>& waves, const glm::dvec3& originEcef, double tS) {
  std::vector<glm::dvec4> out;
  out.reserve(2 * waves.size());
  const glm::dvec3 radial = glm::normalize(originEcef);
  for (const DetailWave& d : waves) {
    // waveAt's great-circle phase and direction at O.
    WaveField::Component c{d.source, d.omega, d.k, 0.0, d.phase0, 0.0};
    const kd::WvWave wv = waveAt(c, radial, tS);
    out.push_back(glm::dvec4(glm::dvec3(wv.dirO) * d.k, d.slopeAmplitude));
    out.push_back(glm::dvec4(wv.phase.x, kTwoPi / d.k, 0.0, 0.0));
  }
  return out;
}

}  // namespace geocean::waves
