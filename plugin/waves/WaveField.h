// The sea surface as one deterministic function of geodetic (lat, lon) and
// simulation time t (seconds, never a frame count), for the CPU query path
// and, through the same source (shaders/waves.glsl), for the GPU.
//
// Thread safety: a WaveField is immutable after creation; all const methods
// may be called from any number of threads at once.
//
// Contract with the renderer (GPU path):
//   1. Per frame and per patch (a tile, or the camera's ground point), call
//      gpuPatch(originEcef, tS, patch). It computes in double everything that
//      is large at Earth scale at the origin O (noise lattice cells and their
//      fractions, wave phases reduced mod 2 pi) and returns float structs with
//      the exact std430 layout of shaders/waves_types.glsl.
//   2. Upload patch.octaves to an SSBO declared `buffer { WvOctave wvOctaves[]; }`
//      and patch.waves to `buffer { WvWave wvWaves[]; }`, and patch.frame as a
//      uniform block / SSBO member of type WvFrame.
//   3. In the shader: #include "waves_types.glsl", declare those buffers,
//      #include "waves.glsl", and for a vertex at ECEF position P on the
//      ellipsoid call, with d = P - O as float (metres, ECEF axes):
//        model kNoise:    WvResult r = wv_solidNoise(0, patch.octaveCount, d, frame);
//        model kGerstner: WvResult r = wv_gerstner(0, patch.waveCount, d, frame, depthM);
//        model kNoisePaper: WvResult r = wv_paperNoise(0, patch.octaveCount, d, patch.paper);
//          (after #include "waves_paper.glsl"; P on the ellipsoid)
//      (depthM: water depth at the vertex in metres, e.g. from a depth texture;
//      1e30 for deep water). Displaced position = P + r.disp.xyz; normal =
//      r.normal.xyz (ECEF). Accuracy: within 1 mm of the CPU for |d| up to
//      ~20 km (tests/waves/test_gpu_parity.cpp); beyond that the float error
//      grows in proportion to |d| (still far below a pixel for a camera-
//      relative origin).
//   The grid engineer's clamp spheres: maxVerticalM() / maxHorizontalM().
#pragma once

#include "plugin/waves/WaveKernel.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geocean::waves {

class FftOcean;
class CoastField;

enum class Model : std::uint8_t {
  Noise,       // "noise": solid fractal noise on the 3D surface point (the default)
  NoisePaper,  // "noise-paper": paper 002, 2D fractal noise at (lon*cos(lat), lat), with its seam at 180 deg
  Gerstner,    // "gerstner": paper 003, trochoidal waves from the sea spectrum
  Fft,         // "fft": paper 001, Tessendorf's FFT ocean (2 cascades, choppy), triplanar on the ellipsoid
};
const char* toString(Model m);
std::optional<Model> parseModel(std::string_view name);  // the CLI names above

inline constexpr double kDeepWaterM = 1e30;  // depth meaning "deep water"
inline constexpr double kMinReferenceDepthM = 0.01;  // SeaState::referenceDepthM below this is refused

// One sea-state description for all models.
struct SeaState {
  // Wind speed (m/s) at 19.5 m, the reference height of Pierson-Moskowitz
  // (about 1.026 x the 10 m wind).
  double windSpeedMps = 10.0;
  // Direction the wind blows FROM, degrees clockwise from north; the waves
  // travel towards windFromDeg + 180. It holds exactly at the anchor; far
  // from it Gerstner waves follow great circles, as swell does.
  double windFromDeg = 270.0;
  // Fetch (m): 0 = fully developed sea (Pierson-Moskowitz), > 0 = JONSWAP.
  double fetchM = 0.0;
  std::uint32_t seed = 1;
  double anchorLatDeg = 0.0, anchorLonDeg = 0.0;
  // Depth (m) that sets the Gerstner wave numbers through the dispersion
  // relation (the local depth passed to sample() sets amplitude and orbits).
  double referenceDepthM = kDeepWaterM;
  int gerstnerComponents = 16;  // 1..64
  int noiseOctaves = 8;         // 1..12

  // Wind speed for a Beaufort number 0..12 (middle of the class, WMO, at
  // 10 m, converted to 19.5 m). Returns nullopt outside 0..12.
  static std::optional<SeaState> fromBeaufort(int beaufort);
};

// A model evaluated at a rest point, in the east-north-up frame of that point.
struct WaveSample {
  glm::dvec3 displacementEnuM{0.0};     // horizontal (e, n) and vertical (u)
  glm::dvec3 normalEnu{0.0, 0.0, 1.0};  // unit normal of the displaced surface
  double verticalVelocityMps = 0.0;     // of the water particle
  glm::dvec3 horizontalVelocityEnuMps{0.0};
  double breakingFoam = 0.0;            // 0 .. 1 (wv_breakingFoam; Gerstner with a coast field)
};

// The surface exactly above a point (horizontal displacement inverted).
struct SurfacePoint {
  double heightM = 0.0;                 // above the ellipsoid
  glm::dvec3 normalEnu{0.0, 0.0, 1.0};
  double verticalVelocityMps = 0.0;     // d(height)/dt at this fixed point
  int iterations = 0;                   // of the horizontal inversion
  glm::dvec3 restOffsetEnuM{0.0};       // rest point of the particle now above, from the point
};

// The sea state at a point, as wave models and buoys report it (linear
// theory statistics of the field the model draws; no time dependence).
struct LocalSeaState {
  double hsM = 0.0;              // significant wave height, 4 sqrt(m0) of the local amplitudes
  double peakPeriodS = 0.0;      // 2 pi / omega_p of the spectrum (frequency is conserved)
  double peakWavelengthM = 0.0;  // of the peak frequency at the depth that sets the model's phase
  double waveFromDeg = 0.0;      // mean direction the waves come FROM, clockwise from north, [0, 360)
};

// Float data for one GPU patch (see the contract above).
struct GpuPatch {
  kf::WvFrame frame{};
  std::vector<kf::WvOctave> octaves;
  std::vector<kf::WvWave> waves;
  // Model Fft: 3 planes x fftCascades entries for `buffer { WvFftPlane
  // wvFftPlanes[]; }` and the tables at tS for `buffer { vec4
  // wvFftTexels[]; }`; call wv_fft(0, 3, fftCascades, d, frame) after
  // `#define WV_FFT 1` (see shaders/waves.glsl).
  std::vector<kf::WvFftPlane> fftPlanes;
  std::vector<glm::vec4> fftTexels;
  int fftCascades = 0;
  // Model Gerstner with a coast field (WaveField::setCoast): call
  // wv_gerstnerCoast(0, waveCount, d, frame, depthM, coast) after `#define
  // WV_COAST 1` with `buffer { vec4 wvCoastTexels[]; }` holding
  // coastField()->gpuTexels() (uploaded once per field, not per patch).
  // coast.cell.z == 0 without a field.
  kf::WvCoast coast{};
  // Model NoisePaper: the origin as wv_paperNoise takes it (shaders/waves_paper.glsl).
  kf::WvPaper paper{};
};

class WaveField {
 public:
  // Validates the sea state; on bad input returns nullopt and sets `error`
  // naming the field and the value.
  static std::optional<WaveField> create(Model model, const SeaState& sea, std::string& error);

  Model model() const { return model_; }
  const SeaState& seaState() const { return sea_; }

  // The model at the rest point (latDeg, lonDeg) at time tS; depthM is the
  // local water depth (m, positive; kDeepWaterM for deep water).
  WaveSample sample(double latDeg, double lonDeg, double tS, double depthM = kDeepWaterM) const;

  // Gerstner with a coast field: the breaking foam at the rest point
  // averaged over the waves' phases (wv_breakingFoamMean, what the
  // renderer's far distance band draws), and the amplitude-weighted local
  // wavelength (m) that band is measured against; 0, 0 otherwise.
  struct BreakingMean {
    double foam = 0.0, wavelengthM = 0.0;
  };
  BreakingMean breakingFoamMean(double latDeg, double lonDeg, double tS, double depthM = kDeepWaterM) const;

  // The displaced surface exactly above (latDeg, lonDeg): the horizontal
  // displacement is inverted by Newton iteration to within 0.01 mm.
  SurfacePoint surfaceAt(double latDeg, double lonDeg, double tS, double depthM = kDeepWaterM) const;

  // The batch form of surfaceAt: out[i] for (latDeg[i], lonDeg[i]) at time
  // tS[i] (tS[0] for every point when timesPerPoint is false) and depth
  // depthM[i] (deep water everywhere when depthM is null). Models noise,
  // Gerstner and FFT run a SIMD path (Highway, 2-8 points per vector,
  // dispatched to the CPU's widest vectors) that agrees with surfaceAt to
  // within the inversion tolerance (tests/waves/test_batch.cpp); noise-paper
  // loops over surfaceAt. Runs on the calling thread.
  void surfaceBatch(const double* latDeg, const double* lonDeg, const double* tS, bool timesPerPoint,
                    const double* depthM, std::size_t n, SurfacePoint* out) const;

  // The sea state at (latDeg, lonDeg) with local water depth depthM.
  // Gerstner: Hs from the components' local amplitudes (shoaling, great-
  // circle taper, breaking cap as wv_gerstner applies them), direction the
  // energy-weighted mean of the components' local directions. Noise and FFT
  // have no depth terms: the spectrum's Hs and the drift direction.
  LocalSeaState seaStateAt(double latDeg, double lonDeg, double depthM = kDeepWaterM) const;

  // Significant wave height (m) of the sea state's spectrum, 4 sqrt(m0).
  double spectrumHsM() const { return hsM_; }
  // Peak wavelength (m) in deep water.
  double peakWavelengthM() const { return peakWavelengthM_; }
  // Bounds (m) on |vertical| and |horizontal| displacement at any point,
  // time and depth: for clamp spheres.
  double maxVerticalM() const { return maxVerticalM_; }
  double maxHorizontalM() const { return maxHorizontalM_; }
  double maxDisplacementM() const { return maxVerticalM_ + maxHorizontalM_; }

  // GPU patch data for origin O (ECEF, m) at time tS. NoisePaper: an origin
  // within 6 um (1e-12 rad) of the 180 degree seam is taken on its west
  // side (-180, as the query wraps longitudes).
  void gpuPatch(const glm::dvec3& originEcef, double tS, GpuPatch& out) const;

  // Double-precision patch data (what the CPU path evaluates; tests use it).
  struct CpuPatch {
    kd::WvFrame frame{};
    std::vector<kd::WvOctave> octaves;
    std::vector<kd::WvWave> waves;
    std::vector<kd::WvFftPlane> fftPlanes;
    std::shared_ptr<const std::vector<glm::dvec4>> fftTexels;
    kd::WvCoast coast{};
    const glm::dvec4* coastTexels = nullptr;
    kd::WvPaper paper{};
  };
  void cpuPatch(const glm::dvec3& originEcef, double tS, CpuPatch& out) const;

  // Evaluate a patch at offset d (ECEF, m) from its origin: the double twin
  // of the shader call.
  kd::WvResult evaluate(const CpuPatch& patch, const glm::dvec3& d, double depthM) const;
  // The choppy map's Jacobian determinant that whitecaps fold on
  // (shaders/foam.glsl): Gerstner, evaluate()'s jac.w; FFT, wv_fftFold
  // (continuous across texels, unlike wv_fft's); noise: 1 (no fold).
  double foldJacobian(const CpuPatch& patch, const glm::dvec3& d, double depthM) const;

  // The near-shore phase field (model Gerstner; see CoastField.h): every
  // query, sample and patch of this field then takes depth-dependent phase,
  // refraction and Kr inside the field's region (deep water unchanged bit
  // for bit). Null clears it. Not thread-safe against concurrent queries:
  // set it before sharing the field.
  void setCoast(std::shared_ptr<const CoastField> coast);
  const CoastField* coastField() const { return coast_.get(); }
  const std::shared_ptr<const CoastField>& coastFieldShared() const { return coast_; }

  // The FFT ocean's synthesis (model Fft; null otherwise).
  const FftOcean* fftOcean() const { return fft_.get(); }

  // Internal spectral data, public for tests.
  struct Octave {
    glm::dvec3 row[3];     // M rows, lattice units per metre (float-exact)
    double frequencyPerM;  // lattice units per metre
    double amplitudeM;
    std::uint32_t seed;
    glm::dvec3 velocity;   // lattice units per second
  };
  struct Component {
    glm::dvec3 source;     // unit ECEF direction of the great-circle source
    double omega;          // rad/s
    double kRef;           // rad/m at the reference depth
    double amplitudeM;     // deep water
    double phase0;         // rad
    double choppiness;     // 0..1
  };
  const std::vector<Octave>& octaves() const { return octaves_; }
  const std::vector<Component>& components() const { return components_; }

 private:
  WaveField() = default;
  void buildNoise();
  void buildGerstner();
  void buildBounds();
  WaveSample samplePaper(double latDeg, double lonDeg, double tS) const;
  // The paper model's patch at the origin (phi0, lambda0 in [-pi, pi)) with
  // distance rho0 from the polar axis and z0 (m): octaves_.size() octaves
  // into `octaves`, the origin into `paper`.
  void paperPatchAt(double phi0, double lam0, double rho0, double z0, double tS, kd::WvOctave* octaves,
                    kd::WvPaper& paper) const;
  void fftPlanesAt(const glm::dvec3& originEcef, std::vector<kd::WvFftPlane>& out) const;

  Model model_ = Model::Noise;
  SeaState sea_;
  double hsM_ = 0.0, peakWavelengthM_ = 0.0, omegaPeak_ = 0.0;
  double maxVerticalM_ = 0.0, maxHorizontalM_ = 0.0;
  std::vector<Octave> octaves_;
  std::vector<Component> components_;
  std::shared_ptr<const FftOcean> fft_;
  std::shared_ptr<const CoastField> coast_;
  glm::dvec3 travelEcef_{0.0};   // wave travel direction at the anchor (unit ECEF)
  glm::dvec2 travelEn_{0.0};     // same, east/north components
};

// Sea spectra (omega in rad/s, S in m^2 s).
double piersonMoskowitz(double omega, double windSpeedMps);
// Fetch (m) at which the JONSWAP sea is fully developed: its peak is
// Pierson-Moskowitz's. A longer fetch gives the same sea.
double fullyDevelopedFetchM(double windSpeedMps);
// JONSWAP for a fetch (m); gamma = 3.3.
double jonswap(double omega, double windSpeedMps, double fetchM);
// Peak angular frequency of the sea state's spectrum.
double peakOmega(const SeaState& sea);
// Mean square slope (both axes summed, deep water) of the sea state's waves
// with wave numbers above kMinRadPerM (0: all of them), for the renderer's
// microfacet roughness: what its grid leaves out. The spectrum is
// Elfouhaily et al. (1997)'s unified one for this wind, fully developed: its
// long-wave part has the peak of the Pierson-Moskowitz sea the models draw,
// its short-wave part the wind-driven gravity-capillary waves (2 mm - 1 m)
// the models do not; PM's own omega^-5 tail gives a slope variance that
// grows only with log U, where Cox & Munk (1954) measured 0.003 + 5.12e-3 U.
double slopeVarianceAbove(const SeaState& sea, double kMinRadPerM);

// The direction (radians from the wind's travel, -pi/2 .. pi/2) below which
// a share u of the cos^2 spreading's energy lies: the Gerstner components'
// directions are its quantiles (plugin/waves/README.md, the direction rule).
double cos2SpreadingQuantile(double u);

// The detail normal layer (issue 13 item 2): the spectrum's waves shorter
// than a model draws, as a shading normal only. `octaves` x `perOctave`
// plane waves on great circles (sources a quarter circumference up-wave of
// the anchor, as Gerstner's) with wave numbers from kLowRadPerM up, each
// carrying the slope variance of its log-k band of slopeVarianceAbove's
// spectrum (so the layer's total is slopeVarianceAbove(kLow) -
// slopeVarianceAbove(kLow 2^octaves)), directions by the Gerstner rule
// over Elfouhaily's short-wave spreading 1 + D cos 2 phi, D set so that the
// upwind share of the slopes is Cox & Munk's; gravity-capillary dispersion.
struct DetailWave {
  glm::dvec3 source;  // unit ECEF
  double k, omega, slopeAmplitude, phase0;  // rad/m, rad/s, a k, rad
};
std::vector<DetailWave> detailWaves(const SeaState& sea, double kLowRadPerM, int octaves = 8, int perOctave = 4);
// Per frame at the patch origin O and time t: wv_detailSlope's wvDetail
// (2 per wave, ordered longest first).
std::vector<glm::dvec4> detailPatch(const std::vector<DetailWave>& waves, const glm::dvec3& originEcef, double tS);
// Height variance (m^2) of slopeVarianceAbove's spectrum above kMinRadPerM:
// what a normal-only layer of those waves leaves out of the heights.
double heightVarianceAbove(const SeaState& sea, double kMinRadPerM);

// Full dispersion relation solved to machine precision (bisection + Newton);
// the reference the shared kernel's explicit form is tested against.
double waveNumberExact(double omega, double depthM);

}  // namespace geocean::waves
