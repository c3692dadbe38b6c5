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
// Inflow edges: the deepest nodes carry the plane wave; the others the
// phase carried along the edge by Snell's law over the local contours (the
// wave number along them conserved from deep water) and the matching
// ray-tube spreading, so a region moved along a straight shore gives the
// same field in the overlap (Ocean::followCoastRegion).
// Each component is carried from its deeper side: one travelling toward
// deeper water (offshore: its outflow edges have more deep water than its
// inflow edges, land counting as none) is solved as the time-reversed wave (-s0) from its outflow edges,
// where the phase is the deep-water phase, and its phase negated (rays and
// ray tubes are reversible: same turning and Kr). Otherwise its rays,
// traced back, end on the shore, and its phase there is whatever first
// arrives from the region's own edges (two regions disagree). Near an
// island such a component's eikonal wraps around it on the up-wave side
// (the reversed wave's lee); the island table still shades the true lee.
// Where no inflow node is deep for a component, its phase comes from an
// OuterPhase (below) given to build(), the same for every region inside it.
// Limits: curved contours at a shallow inflow edge start approximately;
// without an outer phase (or outside its reach) a region with no deep
// inflow fixes the phase's constant at its own deepest edge node (a moved
// region shifts it); first arrivals only (no crossing seas behind a shoal).
//
// Islands (paper 003 sec. 3): the table (D_blo, theta_blo, D_obs, theta_def)
// per component and node from the same elevation (shaders/coast_islands.glsl,
// built on the CPU here and by plugin/render/CoastIslandsGpu on the GPU);
// D_obs scales the amplitude and theta_def turns the direction behind land
// (folded into the texels, so the kernel and its parity are unchanged); in
// a shadow they replace the eikonal's ray-tube Kr and turning, which have
// no meaning there (blended by the land's share of the Fresnel zones).
// The diffracted wave keeps the eikonal's phase (only its height and
// direction change, as in the paper); rebuilt with the field, i.e. when the
// wind direction changes.
//
// Curl and breaking (paper 003 eq. 5-6, in wv_gerstnerCoast): the beach
// slope tan(beta) = |grad h| per node (central differences over +-L0/4, the
// surf zone's scale, clamped to the grid), the Iribarren number
// xi = tan(beta) / sqrt(H0 / L0) with the sea's deep-water Hs and peak
// wavelength (Battjes 1974), and from it the breaker type: spilling below
// 0.4 (no curl), plunging 0.4 .. 2 (curl), surging above 2 (neither curl
// nor collapse). Stored as one more slab after the components' texels:
// (xi, curl weight, break weight, tan beta), the weights smoothed over
// xi 0.3 .. 0.5 and 1.8 .. 2.2 (no seam in the picture) and blended to 0
// over the margin like the rest.
#pragma once

#include "plugin/waves/WaveKernel.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <functional>
#include <string>
#include <vector>

namespace geocean::waves {

class WaveField;

// The outer phase (issue 15 item 1, a shelf with no deep water in reach):
// the same eikonal as CoastField's, solved coarsely (500 m cells, 200 km,
// land blocking) over the sea around a region, on a lattice fixed on the
// ellipsoid (the centre at whole multiples of kLatticeDeg in latitude and
// longitude), so every fine region that reads it reads the same phase. A
// fine region with no deep inflow node for a component takes that
// component's phase offset and ray-tube spreading from here at every node
// at least kMinDepthM deep inside an all-water coarse cell, and solves only
// the rest (the shore, shoals) from them: re-solving the whole region from
// its edges would add the coarse solve's first-order drift (measured up to
// 1.9 rad over 10 km at 500 m cells, half that at 250 m) from edges that
// move with the region. Before, the plane wave at the region's own deepest
// edge node fixed the phase, and two regions 2.8 km apart off the Dutch
// coast had unrelated phases.
// Offsets as the fine field's: the phase minus the grid's plane wave, i.e.
// the integral of k - k_ref along the rays from deep water (0 there), which
// the kernel adds to its own deep-water phase.
class OuterPhase {
 public:
  static constexpr double kLatticeDeg = 0.25, kCellM = 500.0;
  static constexpr int kNodes = 401;
  static constexpr double kMinDepthM = 10.0;
  // Fine regions read it while they lie this far inside its edges (their
  // inflow edges then take phases the coarse solve carried >= 10 km).
  static constexpr double kReachM = 10e3;
  // The lattice point nearest (latDeg, lonDeg).
  static void latticePoint(double latDeg, double lonDeg, double& latOut, double& lonOut);
  // depthAt(eastM, northM) as CoastField::build's, about the lattice point.
  static OuterPhase build(const WaveField& field, double latDeg, double lonDeg,
                          const std::function<double(double eastM, double northM)>& depthAt, std::string& error);
  bool empty() const { return n_ == 0; }
  double latDeg() const { return latDeg_; }
  double lonDeg() const { return lonDeg_; }
  // Whether a square of half-size halfM about centreEcef lies kReachM inside the grid.
  bool covers(const glm::dvec3& centreEcef, double halfM) const;
  // Component c at ECEF point p: (phase offset, ray-tube spreading
  // q = ln(b / b0)), bilinear; NaN unless the cell's four nodes are reached water.
  glm::dvec2 sample(int c, const glm::dvec3& p) const;
  int components() const { return components_; }
  // Whether component c was solved from its outflow edges (as CoastField::reversed).
  bool reversed(int c) const { return c >= 0 && c < int(reversed_.size()) && reversed_[std::size_t(c)]; }

 private:
  double latDeg_ = 0.0, lonDeg_ = 0.0;
  std::vector<char> reversed_;
  int n_ = 0, components_ = 0;
  glm::dvec3 centre_{0.0}, east_{0.0}, north_{0.0};
  std::vector<glm::dvec2> nodes_;  // per component and node: (offset, q); NaN: not reached
};

class CoastField {
 public:
  struct Region {
    double latDeg = 0.0, lonDeg = 0.0;  // centre (geodetic)
    double cellM = 50.0;                // node spacing
    int nodes = 201;                    // N: nodes per side (odd: the centre is a node)
    int margin = 8;                     // edge nodes blended to 0
    double islandRadiusM = 0.0;         // occlusion radius (<= 64 nodes); 0: 6 deep-water wavelengths of the longest
    bool breaking = true;               // curl and collapse (eq. 5-6); false: their weights 0 (the slab's xi stays)
  };
  // What the island table is built from (the same for CPU and GPU).
  struct IslandInputs {
    int nodes = 0, components = 0;
    double cellM = 0.0, radiusCells = 0.0;
    std::vector<double> elevation;    // per node (row-major), m; > 0: land
    std::vector<int> landSat;         // summed-area table of the land nodes, (nodes + 1)^2
    std::vector<glm::dvec4> travel;   // per component: travel direction (x east, y north), omega, 0
  };
  // The table on the CPU (threads over rows): component-major like texels();
  // `shadow` (if given): per entry, how far D_obs replaces the eikonal's Kr (0 .. 1).
  static std::vector<glm::dvec4> islandTable(const IslandInputs& in, std::vector<double>* shadow = nullptr);
  // depthAt(eastM, northM): water depth (m; <= 0 on land) at the offset from
  // the centre in its tangent plane. The field needs model Gerstner. On bad
  // input returns an empty field and sets `error` naming the field and value.
  // The refraction coefficient's clamp: amplitudes scale by at most this
  // over the deep-water ones before the breaking and Miche caps, which only lower them.
  static constexpr double kMaxKr = 4.0, kMinKr = 0.25;
  // outer (optional): asked for at most once, when a component has no deep
  // inflow node; its phase then fixes that component's inflow edges (null: as without).
  static CoastField build(const WaveField& field, const Region& region,
                          const std::function<double(double eastM, double northM)>& depthAt, std::string& error,
                          const std::function<const OuterPhase*()>& outer = {});
  // How many components took their inflow edges from an OuterPhase.
  int outerComponents() const { return outerComponents_; }

  enum class Breaker { Spilling, Plunging, Surging };
  // Battjes (1974)'s classes by the Iribarren number (bounds 0.4 and 2).
  static Breaker breakerType(double iribarren);
  static const char* breakerName(Breaker b);
  struct Beach {
    double tanBeta = 0.0, iribarren = 0.0;  // at the nearest node
    double curlWeight = 0.0, breakWeight = 0.0;
    Breaker type = Breaker::Spilling;
  };
  // The beach at (east, north) m from the centre; all 0 outside the grid.
  Beach beachAt(double eastM, double northM) const;

  bool empty() const { return n_ == 0; }
  // Whether component c was carried from its outflow edges (the time-reversed solve: it travels offshore).
  bool reversed(int c) const { return c >= 0 && c < int(reversed_.size()) && reversed_[std::size_t(c)]; }
  const Region& region() const { return region_; }
  int components() const { return components_; }

  // The struct for a patch at origin O (ECEF): double (CPU) and float (GPU).
  kd::WvCoast at(const glm::dvec3& originEcef) const;
  kf::WvCoast gpuAt(const glm::dvec3& originEcef) const;
  // Per component, per node (row-major, y then x), then the beach slab: for wvCoastTexels[].
  const std::vector<glm::dvec4>& texels() const { return texels_; }
  std::vector<glm::vec4> gpuTexels() const;
  // The island table (D_blo, theta_blo, D_obs, theta_def) the texels were folded with, and its inputs.
  const std::vector<glm::dvec4>& islands() const { return islands_; }
  const IslandInputs& islandInputs() const { return islandInputs_; }
  // The texels (as gpuTexels) folded with another build of the island
  // table and its shadow weights (component-major: the GPU's,
  // plugin/render/CoastIslandsGpu); empty if their sizes are not the field's.
  std::vector<glm::vec4> gpuTexelsWith(const std::vector<glm::vec4>& islands, const std::vector<float>& shadow) const;

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
  std::vector<char> reversed_;  // per component
  int outerComponents_ = 0;
  std::vector<glm::dvec4> islands_;
  std::vector<double> shadow_;
  IslandInputs islandInputs_;
  // Per component and node: the eikonal's phase offset, turning angle and
  // clamped Kr before the island table (NaN: not reached), for fold().
  std::vector<glm::dvec3> eikonal_;
  // The components' texels from eikonal_ and an island table (the beach slab untouched).
  void fold(const std::vector<glm::dvec4>& islands, const std::vector<double>& shadow,
            std::vector<glm::dvec4>& texels) const;
};

}  // namespace geocean::waves
