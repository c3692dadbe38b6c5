// Forces of the water on floating bodies.
//
// HullForce (the default): the hull mesh is clipped against the sea surface
// every step and the water pressure is integrated over each submerged
// triangle:
//   * depth d of every vertex below the sea surface exactly above it (the
//     SeaSurface's height at the vertex's latitude and longitude minus the
//     vertex's height above the ellipsoid);
//   * each triangle is clipped where d, linear along its edges, is 0;
//   * pressure p = rho g (d - eta (1 - e^{-k d})), eta the surface height
//     above still water (height 0): hydrostatic under a flat sea, and with
//     waves the linear (Airy) deep-water pressure p = rho g (-z + eta e^{k z})
//     with Wheeler's stretching (the decay counted from the instantaneous
//     surface, so p = 0 on it): the Froude-Krylov pressure of the waves
//     (Dean & Dalrymple, Water Wave Mechanics, 1991, sec. 4.4; Wheeler,
//     J. Petroleum Technology 22, 1970). k is SeaSurface::decayWaveNumberPerM.
//   * force -(integral of p n dA) and its moment, exact for p linear over the
//     triangle (integral p r dA = A/12 (sum p_i r_i + sum p_i sum r_i)); with
//     hydrostatic pressure the closed clipped hull plus the zero-pressure
//     waterplane give exactly rho g V_submerged (divergence theorem).
//   * added mass in heave, a33 = 1/2 C_A rho pi/4 B^2 L for a box or boat of
//     waterplane length L and beam B <= L (half of the flat rectangular plate
//     in infinite fluid, the infinite-frequency limit of a floating body;
//     C_A from DNV-RP-C205 (2010) table A-2), a33 = 4/3 rho R^3 for the
//     vertical cylinder (half of Newman's disc, 8/3 rho R^3, Marine
//     Hydrodynamics table 4.3); scaled by (A_wp / A_wp,full)^{3/2} as the
//     waterplane A_wp shrinks. It enters the integrator's mass matrix
//     (Wrench::addAddedMass) and, as in Morison's equation, a33 times the
//     water's vertical acceleration at the keel (backward difference over
//     one step of the surface's vertical velocity, decayed by e^{-k d_keel})
//     is a force: the
//     long-wave diffraction term, which makes the heave follow long swell.
//   * added mass in surge, sway, roll, pitch and yaw: half of that of the
//     double body (the submerged hull and its mirror image in the
//     waterplane) in unbounded fluid, the double body taken as the
//     ellipsoid of semi-axes L/2, B/2 and the mean draft T = V / A_wp (L, B
//     the hull's extents scaled by sqrt(A_wp / A_wp,full) as a33 is):
//     Lamb's coefficients of the ellipsoid (Lamb, Hydrodynamics, 6th ed.
//     1932, sec. 114-115, 373; Lamb, The inertia-coefficients of an
//     ellipsoid moving in fluid, ARC R&M 623, 1918), from Carlson's R_D.
//     The double body moving as one is the rigid-wall free surface
//     (d phi/dz = 0, the manoeuvring limit) for surge, sway and yaw, and
//     phi = 0 (the high-frequency limit, as a33) for roll and pitch. The
//     rotational terms act about the centre of mass (the coupling of sway
//     and roll, surge and pitch through the height of the centre of mass
//     above the waterplane is not modelled), and so does the water's
//     horizontal acceleration on a11, a22 (the long-wave diffraction term,
//     as in heave; linear theory at the surface: du/dt = -g grad eta, taken
//     at the centre one step earlier and decayed to half the keel's depth).
//     Not modelled: the added mass's velocity terms (Kirchhoff's equations:
//     the Munk moment (a22 - a11) u v), off-diagonal terms, frequency
//     dependence and wave radiation damping (the damping is below).
//   * the sea under the hull: with a sea that states its shortest
//     wavelength lambda_min (SeaSurface::shortestWavelengthM; OceanSea:
//     Gerstner), the surface is queried on a grid in the horizontal plane,
//     aligned with the hull's heading, over its footprint, spacing at most
//     lambda_min / seaGridPointsPerWavelength, height and slope at each
//     node, and interpolated to the vertices by bicubic Hermite (the twist
//     from central differences of the slopes): error O((k h)^4) of each
//     component, against O((k h)^2) for bilinear heights. When the grid
//     would have as many nodes as the hull has vertices, or a node has no
//     sea (a coast), every vertex is queried instead. Measured against
//     every vertex (boat of 20 m, 123 vertices, Gerstner at 10 m/s,
//     lambda_min 5.7 m, 2.5 per wavelength: 40 nodes; 400 poses): force
//     error rms 2.2e-4, max 9.3e-4 of the weight, torque rms 5e-5, max
//     1.7e-4 of weight x length (test BodyWaves.SeaGrid...).
//   * drag per submerged triangle on the velocity relative to the water
//     (orbital velocity from the surface at the centre, decayed e^{-k d}):
//     pressure drag -1/2 rho (C_D / 2) |v_n| v_n A n on every face, the
//     advancing faces' stagnation and the retreating faces' base suction
//     sharing C_D = 1 (Hoerner, Fluid-Dynamic Drag, 1965, ch. 3: a flat plate
//     normal to the flow 1.17, bluff bodies ~1; counting only advancing
//     faces would rectify a heaving asymmetric hull's oscillation into
//     thrust), and skin friction 1/2 rho C_f |v_t| v_t A with the ITTC-1957
//     line C_f = 0.075 / (log10 Re - 2)^2 (Blasius 1.328 / sqrt(Re) below
//     Re = 5e5), Re = |v| L / nu.
//   * wave-radiation damping, linear, as fractions of critical damping of
//     the current hydrostatic stiffness: heave zeta 0.1 on the velocity
//     relative to the water, c = 2 zeta sqrt((m + a33) rho g A_wp); roll
//     zeta 0.05 and pitch 0.1 on the body's rates, c = 2 zeta sqrt((I + a44)
//     rho g V GM) (a55 for pitch) with GM = z_B + I_wp / V about the centre of mass (I_wp of the
//     clipped waterplane, from the wetted surface: the closed hull's
//     integral of y^2 n_up dA is 0); none while GM <= 0. Typical ship values
//     at resonance (Journee & Massie, Offshore Hydromechanics, 2001, ch. 6:
//     heave and pitch strongly damped by radiation, roll lightly).
//
// ContactPointForce: paper 000 sec. 2.1, eq. 3-4 (one option): n points
// fixed in the body, each carrying 1/n of the volume over a vertical column;
// buoyancy rho g V_i f_i along the local up (f_i the column's submerged
// fraction from the sea height at the point), drag on the point's velocity
// relative to the water (the orbital velocity at the centre decayed to the
// point's depth, ContactPointOptions), torque from the same points (eq. 4). Gravity acts at
// the centre of mass (Simulation). Use with MassProperties::isotropicFrom of
// the hollow-cylinder proxy (eq. 2). As in the paper: no added mass and no
// damping but the drag.
//
// Thrust: the engine force F_e along the hull's x axis at the centre of mass.
// Repulsion: F_c between bodies (paper eq. 3-4), springs on the overlap of
// spheres fixed in the bodies.
//
// All models are const and keep no state across steps (Repulsion places
// the step's bodies once in beginStep): they may be evaluated for
// different bodies on different threads at once.
#pragma once

#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Sea.h"
#include "plugin/bodies/Simulation.h"

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace geocean::bodies {

struct WaterProperties {
  // ITTC Recommended Procedure 7.5-02-01-03 (2011), sea water at 15 C,
  // salinity 35 g/kg: 1025.9 kg/m^3, 1.1892e-6 m^2/s (1025 is the usual round figure).
  double densityKgM3 = 1025.0;
  double kinematicViscosityM2ps = 1.1892e-6;
};

struct HullForceOptions {
  WaterProperties water;
  double pressureDragCoefficient = 1.0;  // on faces advancing into the water (Hoerner)
  bool skinFriction = true;              // ITTC-1957
  bool addedMass = true;                 // a33 and the other five modes (see above)
  double heaveDampingRatio = 0.1;        // radiation damping, fractions of critical (see above)
  double rollDampingRatio = 0.05;
  double pitchDampingRatio = 0.1;
  // Sea grid nodes per shortest wavelength (see above); 0: query every vertex.
  double seaGridPointsPerWavelength = 2.5;
};

// What the water does to one body at one instant (tests, tools, the CLI).
struct HullEvaluation {
  Wrench wrench;                     // everything HullForce adds (no gravity)
  double submergedVolumeM3 = 0.0;    // of the clipped hull (exact on a flat sea)
  double waterplaneAreaM2 = 0.0;     // -(sum of n_up dA) over the wetted surface
  glm::dvec3 buoyancyCentreEnu{0.0}; // centre of the clipped volume, ENU offset from the centre of mass
  double keelDepthM = 0.0;           // lowest vertex below the sea surface at the centre of mass (<0: above)
  double seaHeightM = 0.0;           // sea surface above the ellipsoid at the centre (NaN: no sea)
  double heaveAddedMassKg = 0.0;     // a33 used this step
  glm::dvec3 addedMassKg{0.0};       // a11, a22, a33 this step (body axes)
  glm::dvec3 addedInertiaKgM2{0.0};  // a44, a55, a66 this step (about the body axes)
  glm::dvec2 metacentricHeightM{0.0};  // GM transverse (roll, about body x) and longitudinal (pitch)
  int seaGridNodes = 0;              // nodes of the sea grid this step (0: every vertex queried)
};

class HullForce final : public ForceModel {
 public:
  HullForce(std::shared_ptr<const HullMesh> hull, std::shared_ptr<const SeaSurface> sea, HullForceOptions options = {});

  void accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const override;
  HullEvaluation evaluate(const BodyState& state, const MassProperties& mass, const StepContext& ctx) const;

  // a33 at the full waterplane (kg) and the waterplane area it belongs to (m^2).
  double fullHeaveAddedMassKg() const { return a33Full_; }
  double fullWaterplaneAreaM2() const { return awpFull_; }
  const HullMesh& hull() const { return *hull_; }
  const HullForceOptions& options() const { return options_; }

 private:
  std::shared_ptr<const HullMesh> hull_;
  std::shared_ptr<const SeaSurface> sea_;
  HullForceOptions options_;
  double a33Full_ = 0.0, awpFull_ = 0.0, lengthM_ = 0.0, beamM_ = 0.0, depthM_ = 0.0;
};

// C_A of a flat rectangular plate of aspect ratio b/a >= 1 (DNV-RP-C205
// table A-2, linear between its rows; 1 - 0.53 a/b beyond b/a = 10, which
// meets the table's 0.947 at 10 and its limit 1).
double rectangularPlateAddedMassCoefficient(double aspect);

// Added mass of an ellipsoid of semi-axes a (along x), b (y), c (z)
// translating along and turning about its axes in unbounded fluid of density
// rho (Lamb 1932 sec. 114-115): with alpha0 = abc int_0^inf dl / ((a^2 + l) D),
// D = sqrt((a^2 + l)(b^2 + l)(c^2 + l)) (= 2/3 abc R_D(b^2, c^2, a^2)) and
// beta0, gamma0 alike, m_f = 4/3 pi rho abc: along x alpha0 / (2 - alpha0) m_f,
// about x m_f / 5 (b^2 - c^2)^2 (gamma0 - beta0) / (2 (b^2 - c^2) + (b^2 + c^2)
// (beta0 - gamma0)), and the others by permutation.
struct EllipsoidAddedMass {
  glm::dvec3 massKg{0.0};       // translating along x, y, z
  glm::dvec3 inertiaKgM2{0.0};  // turning about x, y, z
};
EllipsoidAddedMass ellipsoidAddedMass(double a, double b, double c, double rho);
// Carlson's symmetric elliptic integral R_D(x, y, z) (Carlson, Numerical
// Algorithms 10, 1995), x, y >= 0 (not both 0), z > 0.
double carlsonRD(double x, double y, double z);

struct ContactPointOptions {
  WaterProperties water;
  double dragCoefficient = 1.0;  // quadratic, on each point's share of the waterplane (Hoerner)
  // The water's velocity for the drag: false (default), the surface's at the
  // centre of mass decayed e^{-k d} to each point's depth, as HullForce
  // does (one velocity query per body-step: the façade evaluates horizontal
  // velocities point by point on the scalar kernel, 8 of them cost ~2.5x
  // the rest of the step); true, the surface's above each point.
  bool waterVelocityAtEachPoint = false;
};

class ContactPointForce final : public ForceModel {
 public:
  // pointsBody: the contact points (body axes, about the centre of mass);
  // volumeM3: the displacement when every column is fully under; columnHeightM:
  // the vertical extent of each point's column, centred on the point;
  // waterplaneAreaM2: shared among the points for the drag.
  ContactPointForce(std::vector<glm::dvec3> pointsBody, double volumeM3, double columnHeightM,
                    double waterplaneAreaM2, std::shared_ptr<const SeaSurface> sea, ContactPointOptions options = {});
  // Paper 000's hull proxy: a hollow cylinder of length L and outer radius R
  // along x, with nx x 2 points on its horizontal mid-plane (the proxy's
  // displacement pi R^2 L over columns of height 2R).
  static std::shared_ptr<ContactPointForce> hollowCylinderProxy(double lengthM, double outerRadiusM, int nx,
                                                                std::shared_ptr<const SeaSurface> sea,
                                                                ContactPointOptions options = {});

  // The water's velocity at every centre of mass of this model's bodies,
  // and the sea at all their points, in one sea query each (a SIMD batch
  // fills its vectors; per body a 1-point query would cost a whole vector);
  // accumulate uses them for the same state and time.
  void beginStep(const Simulation& sim) const override;
  void accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const override;
  const std::vector<glm::dvec3>& points() const { return points_; }

 private:
  std::vector<glm::dvec3> points_;
  double volume_, column_, area_;
  std::shared_ptr<const SeaSurface> sea_;
  ContactPointOptions options_;
  // This step's centres (beginStep, one thread; read by accumulate).
  struct Centre {
    BodyId id;
    glm::dvec3 positionEcef;
  };
  mutable std::vector<Centre> centres_;  // ids ascending
  mutable std::vector<SeaSample> centreSea_;
  mutable double centreTimeS_ = 0.0;
  // And every body's points in one query too (a body's 8 points are 2
  // AVX2 vectors: per body the query's set-up cost more than its kernel):
  // points_.size() per centre, their sea and their heights above the ellipsoid.
  mutable std::vector<SeaSample> pointSea_;
  mutable std::vector<double> pointLat_, pointLon_, pointH_, pointT_;
};

// Engine force along the body's x axis (bow) at the centre of mass (N).
class Thrust final : public ForceModel {
 public:
  explicit Thrust(double newtons);
  void accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const override;

 private:
  double newtons_;
};

// Repulsion between bodies (paper 000 eq. 3-4, F_c_i and its torque):
// each body carries spheres fixed in it (body axes, about the centre of
// mass); two spheres of different bodies that overlap push apart along the
// line of their centres, stiffness N per m of overlap, each force acting at
// its sphere's centre (a torque, as eq. 4). The pair's forces are equal and
// opposite on one line, computed from the same differences (bit for bit):
// the pair's linear and angular momentum are conserved to rounding. A body
// without spheres of its own has one of defaultRadiusM at its centre of
// mass. The spheres of a step are placed in a hash grid by beginStep (cells
// of the largest body's diameter), so a step costs O(bodies), not O(n^2).
struct RepulsionSphere {
  glm::dvec3 centreBody{0.0};  // m, body axes about the centre of mass
  double radiusM = 0.0;
};

class Repulsion final : public ForceModel {
 public:
  Repulsion(const Simulation& sim, double defaultRadiusM, double stiffnessNpm);
  // Replaces body `id`'s spheres (radii finite and > 0, centres finite).
  // Not during a step.
  void setSpheres(BodyId id, std::vector<RepulsionSphere> spheres);
  void forgetBody(BodyId id);
  // A row of spheres along the hull's x axis covering its footprint:
  // ceil(L / B) spheres of radius B / 2 (L length, B beam of the bounding
  // box), centres on the box's centre line from bow to stern.
  static std::vector<RepulsionSphere> spheresAlongHull(const HullMesh& hull);
  double stiffnessNpm() const { return stiffness_; }

  void beginStep(const Simulation& sim) const override;
  void accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const override;

 private:
  struct Placed {
    BodyId id;
    glm::dvec3 positionEcef;
    double boundM;          // bounding radius about the centre of mass
    std::size_t first, n;   // its spheres in offsets_ / radii_
  };
  const std::vector<RepulsionSphere>& spheresOf(BodyId id) const;

  const Simulation* sim_;
  double radius_, stiffness_;
  std::vector<RepulsionSphere> defaultSpheres_;
  std::unordered_map<BodyId, std::vector<RepulsionSphere>> spheres_;
  // This step's placement (beginStep, one thread; read by accumulate).
  mutable std::vector<Placed> placed_;  // in body order (ids ascending)
  mutable std::vector<glm::dvec3> offsets_;  // sphere centres - centre of mass, ECEF
  mutable std::vector<double> radii_;
  mutable std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
  mutable double cellM_ = 1.0;
  mutable std::int64_t step_ = -1;
};

// Geodetic coordinates of ENU offsets from the step's centre of mass, to
// second order in |offset| / R (latitude and longitude to first order,
// the height with the ellipsoid's curvature): over 100 m the height is
// within 1e-8 m and the horizontal position within 1 mm of GeographicLib
// (tests/bodies). Above 89 degrees of latitude it calls GeographicLib.
void offsetsToGeodetic(const StepContext& ctx, const glm::dvec3* offsetsEnu, std::size_t n, double* latDeg,
                       double* lonDeg, double* heightM);

}  // namespace geocean::bodies
