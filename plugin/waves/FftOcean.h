// The FFT ocean (paper 001, Tessendorf): spectrum synthesis on the CPU into
// plain periodic tables that both the query path and the shader read
// (shaders/waves.glsl, wv_fft). Internal to plugin/waves; users select it as
// Model::Fft of WaveField.
//
// Spectrum: the paper's Phillips spectrum P(k) ~ exp(-1/(kL)^2) / k^4 with
// L = U^2/g when the sea state has no fetch, JONSWAP (converted to wave
// numbers through the deep-water dispersion relation) when it has one; both
// with cos^2 spreading about the wind (waves against the wind suppressed, as
// in the paper). The amplitude is calibrated so that the synthesised sea has
// the sea state's Hs (Tessendorf's constant A is free; the other models are
// calibrated the same way). Each mode has the spectrum's amplitude and a
// random phase (instead of the paper's Gaussian amplitude draws) so that every
// realisation has that Hs, not only the ensemble. Modes move with the full
// dispersion relation at the sea state's reference depth.
//
// Two cascades with incommensurate periods (5.3 and 5.3/7.3 peak wavelengths)
// split the wave numbers at 4 k_peak, so the sum never repeats visibly.
//
// Thread safety: const methods may be called from any number of threads
// (the time cache is locked).
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace geocean::waves {

struct SeaState;

class FftOcean {
 public:
  static constexpr int kCascades = 2;
  static constexpr int kN = 128;          // texels per side of every cascade (power of 2)
  static constexpr int kPlanes = 3;       // triplanar: one plane per ECEF axis
  static constexpr int kTexelParts = 2;   // WR4 per texel (see WvFftPlane)

  // hsM: the sea state's significant wave height; peakWavelengthM its deep-water
  // peak wavelength; travelEcef the unit wave travel direction at the anchor.
  FftOcean(const SeaState& sea, double hsM, double peakWavelengthM, const glm::dvec3& travelEcef);

  // Tables at time tS: kCascades * kN * kN * kTexelParts texels, cascade-major,
  // then row (v) major. Built by 2 x 4 inverse FFTs (KissFFT, double) and
  // cached for the most recent times.
  std::shared_ptr<const std::vector<glm::dvec4>> tablesAt(double tS) const;

  double lengthM(int cascade) const { return cascades_[cascade].lengthM; }
  // Horizontal scale of the choppy displacement (paper's lambda), <= 1.
  double choppiness() const { return lambda_; }
  // Bounds on |vertical| / |horizontal| displacement (sum of amplitudes).
  double maxVerticalM() const { return sumAmp_; }
  double maxHorizontalM() const { return lambda_ * sumAmp_; }

  // Plane p's tile axes (unit ECEF) and its offset (texels) that decorrelates
  // the three planes.
  glm::dvec3 uAxis(int p) const { return u_[p]; }
  glm::dvec3 vAxis(int p) const { return v_[p]; }
  glm::dvec3 planeAxis(int p) const;
  double offsetTexels(int p, int axis) const { return offset_[p][axis]; }

 private:
  struct Mode {
    int ix, iy;       // grid index of +k (the -k index is its negation mod N)
    double kx, ky;    // rad/m in tile coordinates
    double amp;       // m
    double omega;     // rad/s
    double phase0;    // rad
  };
  struct Cascade {
    double lengthM;
    std::vector<Mode> modes;
  };
  std::vector<glm::dvec4> build(double tS) const;

  Cascade cascades_[kCascades];
  double lambda_ = 1.0, sumAmp_ = 0.0;
  glm::dvec3 u_[kPlanes], v_[kPlanes];
  double offset_[kPlanes][2];

  struct Cache {
    std::mutex mutex;
    std::vector<std::pair<double, std::shared_ptr<const std::vector<glm::dvec4>>>> entries;  // most recent last
  };
  std::shared_ptr<Cache> cache_ = std::make_shared<Cache>();
};

}  // namespace geocean::waves
