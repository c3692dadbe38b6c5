// What the hydrodynamic forces read of the sea: the surface height above the
// WGS84 ellipsoid at (lat, lon, t), and the water's velocity there. The
// product reads it from the ocean façade (OceanSea.h: the very surface the
// renderer draws and `geocean query` prints); tests also use closed-form seas.
#pragma once

#include <glm/vec2.hpp>

#include <cstddef>
#include <limits>

namespace geocean::bodies {

struct SeaSample {
  // Sea surface above the ellipsoid exactly above the point (m); NaN where
  // there is no sea (land, lakes): no water pressure there.
  double heightM = std::numeric_limits<double>::quiet_NaN();
  double verticalVelocityMps = 0.0;  // d(height)/dt at the fixed point
  glm::dvec2 horizontalVelocityEnMps{0.0};  // water particle at the surface, east/north
  glm::dvec2 slopeEn{0.0};  // d(height)/d(east, north): sampleSlopes only
};

class SeaSurface {
 public:
  virtual ~SeaSurface() = default;
  // out[i] at (latDeg[i], lonDeg[i]) and time tS[i]; the velocities only
  // when `velocities` (else they may be left 0). Must be callable from any
  // number of threads at once.
  virtual void sample(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n,
                      bool velocities, SeaSample* out) const = 0;
  // The wave number k (rad/m) that sets how the waves' pressure and orbital
  // velocity decay under the surface, e^{-k d} at depth d (linear deep-water
  // theory). 0: hydrostatic under the local surface (long-wave limit).
  virtual double decayWaveNumberPerM() const = 0;
  // The height, d(height)/dt and the slope at each point (horizontal
  // velocities left 0): what HullForce's sea grid reads (Hydro.h), and the
  // centre one step earlier (the water's acceleration) on any sea.
  virtual void sampleSlopes(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n,
                            SeaSample* out) const = 0;
  // The shortest wavelength (m) the surface carries: it sets the spacing of
  // the sea grid under a hull. 0: not known, or the surface is not smooth
  // between queries (coasts, land): every hull vertex is queried. Infinity:
  // a constant surface.
  virtual double shortestWavelengthM() const { return 0.0; }
};

// Still water at a constant height above the ellipsoid (default 0).
class FlatSea final : public SeaSurface {
 public:
  explicit FlatSea(double heightM = 0.0) : heightM_(heightM) {}
  void sample(const double*, const double*, const double*, std::size_t n, bool, SeaSample* out) const override {
    for (std::size_t i = 0; i < n; ++i) out[i] = SeaSample{heightM_, 0.0, {0.0, 0.0}};
  }
  double decayWaveNumberPerM() const override { return 0.0; }
  void sampleSlopes(const double*, const double*, const double*, std::size_t n, SeaSample* out) const override {
    for (std::size_t i = 0; i < n; ++i) out[i] = SeaSample{heightM_, 0.0, {0.0, 0.0}, {0.0, 0.0}};
  }
  double shortestWavelengthM() const override { return std::numeric_limits<double>::infinity(); }

 private:
  double heightM_;
};

}  // namespace geocean::bodies
