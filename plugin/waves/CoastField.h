// The near-shore phase field of a Gerstner sea (issue 15, paper 003): over a
// region of interest, each component's phase from the full dispersion
// relation at the local depth, w^2 = g k tanh(k h) (frequency conserved),
// accumulated along its path, its direction turned by refraction and its
// height scaled by the refraction coefficient Kr (shoaling Ks and breaking
// stay in the kernel, which has the local depth).
//
// Built once on the CPU in double from the water depth around a centre: per
// component the eikonal |grad S| = k(h(x)) is solved on an N x N grid of
// the tangent plane (first-order Godunov fast sweeping, Zhao 2005) from the
// plane wave k_ref s0 . x on the deep inflow edges; the direction is
// grad S / |grad S| (Snell's law follows: over straight contours the along-
// shore wave number k sin(theta) is conserved), the ray-tube spreading
// q = ln(b / b0) from s . grad q = div s (the same sweeps), Kr = exp(-q/2).
// Stored per node: S - k_ref s0 . x (bounded by the region's size times
// k - k_ref, so float keeps the GPU within 1 mm), sin and 1 - cos of the
// turning angle and Kr - 1; exactly 0 where the component does not feel the
// bottom, and blended to 0 over the outer `margin` nodes so the phase has
// no jump at the region's edge. The shared kernel (wv_gerstnerCoast,
// shaders/waves.glsl) samples it bilinearly, the same on CPU and GPU.
//
// Limits: rays that enter through a shallow inflow edge start as the plane
// wave there (choose a region whose up-wave edges are deep); first arrivals
// only (no crossing seas behind a shoal); no diffraction.
#pragma once

#include "plugin/waves/WaveKernel.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <functional>
#include <string>
#include <vector>

namespace geocean::waves {

class WaveField;

class CoastField {
 public:
  struct Region {
    double latDeg = 0.0, lonDeg = 0.0;  // centre (geodetic)
    double cellM = 50.0;                // node spacing
    int nodes = 201;                    // N: nodes per side (odd: the centre is a node)
    int margin = 8;                     // edge nodes blended to 0
  };
  // depthAt(eastM, northM): water depth (m; <= 0 on land) at the offset from
  // the centre in its tangent plane. The field needs model Gerstner. On bad
  // input returns an empty field and sets `error` naming the field and value.
  // The refraction coefficient's clamp: amplitudes scale by at most this
  // over the deep-water ones before the breaking and Miche caps, which only lower them.
  static constexpr double kMaxKr = 4.0, kMinKr = 0.25;
  static CoastField build(const WaveField& field, const Region& region,
                          const std::function<double(double eastM, double northM)>& depthAt, std::string& error);

  bool empty() const { return n_ == 0; }
  const Region& region() const { return region_; }
  int components() const { return components_; }

  // The struct for a patch at origin O (ECEF): double (CPU) and float (GPU).
  kd::WvCoast at(const glm::dvec3& originEcef) const;
  kf::WvCoast gpuAt(const glm::dvec3& originEcef) const;
  // Per component, per node (row-major, y then x): for wvCoastTexels[].
  const std::vector<glm::dvec4>& texels() const { return texels_; }
  std::vector<glm::vec4> gpuTexels() const;

  // The grid's frame: centre (ECEF) and unit east / north there.
  const glm::dvec3& centreEcef() const { return centre_; }
  const glm::dvec3& east() const { return east_; }
  const glm::dvec3& north() const { return north_; }

 private:
  Region region_;
  int n_ = 0, components_ = 0;
  glm::dvec3 centre_{0.0}, east_{0.0}, north_{0.0};
  glm::dvec3 eAxis_{0.0}, nAxis_{0.0};  // east / north per cell, rounded to float
  std::vector<glm::dvec4> texels_;
};

}  // namespace geocean::waves
