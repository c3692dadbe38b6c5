// Rigid-body state and mass properties, all in double.
// Frames: ECEF (WGS84, metres) for position, linear velocity, forces and
// torques; the body frame (x forward/bow, y port, z up, origin at the centre
// of mass) for the inertia tensor and the angular velocity.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace geocean::bodies {

enum class Axis { X, Y, Z };  // body axis a cylinder's axis lies along

// Mass and the inertia tensor about the centre of mass in body axes (kg, kg m^2).
// Every constructor validates: mass finite and > 0; the tensor finite,
// symmetric and positive definite; else std::invalid_argument naming the field.
class MassProperties {
 public:
  MassProperties(double massKg, const glm::dmat3& inertiaBody);

  // Homogeneous solids; formulas from the textbook tables of moments of
  // inertia (e.g. Meriam & Kraige, Engineering Mechanics: Dynamics, app. D).
  // Box with full edge lengths size.x, size.y, size.z:
  //   Ixx = m (sy^2 + sz^2) / 12, and cyclically.
  static MassProperties box(double massKg, const glm::dvec3& sizeM);
  // Solid cylinder of radius r and length L along `axis`:
  //   I_axis = m r^2 / 2, I_perp = m (3 r^2 + L^2) / 12.
  static MassProperties solidCylinder(double massKg, double radiusM, double lengthM, Axis axis = Axis::X);
  // Thick-walled tube (paper 000 sec. 2.1's hull proxy), radii r1 < r2:
  //   I_axis = m (r1^2 + r2^2) / 2, I_perp = m (3 (r1^2 + r2^2) + L^2) / 12.
  static MassProperties hollowCylinder(double massKg, double innerRadiusM, double outerRadiusM,
                                       double lengthM, Axis axis = Axis::X);
  // Paper 000 eq. 2 takes the inertia as a scalar I_pe times the identity; it
  // does not say which scalar, we take the mean principal moment trace(I)/3.
  static MassProperties isotropicFrom(const MassProperties& shape);

  double massKg() const { return mass_; }
  double inverseMass() const { return inverseMass_; }
  const glm::dmat3& inertiaBody() const { return inertia_; }
  const glm::dmat3& inverseInertiaBody() const { return inverseInertia_; }

 private:
  double mass_, inverseMass_;
  glm::dmat3 inertia_, inverseInertia_;
};

// Kinematic state. orientation is a unit glm::dquat (Hamilton, constructed
// (w, x, y, z)) rotating body vectors into ECEF: v_ecef = orientation * v_body.
struct BodyState {
  glm::dvec3 positionEcef{0.0};              // centre of mass, m
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // body -> ECEF
  glm::dvec3 velocityEcef{0.0};              // m/s, relative to the ECEF axes
  glm::dvec3 angularVelocityBody{0.0};       // rad/s, body axes

  glm::dvec3 angularVelocityEcef() const { return orientation * angularVelocityBody; }
  // Velocity of a material point at `offsetEcef` from the centre of mass.
  glm::dvec3 pointVelocityEcef(const glm::dvec3& offsetEcef) const {
    return velocityEcef + glm::cross(angularVelocityEcef(), offsetEcef);
  }
  glm::dvec3 bodyToEcef(const glm::dvec3& vBody) const { return orientation * vBody; }
  glm::dvec3 ecefToBody(const glm::dvec3& vEcef) const { return glm::conjugate(orientation) * vEcef; }
};

// Throws std::invalid_argument unless every field is finite and the
// orientation is a unit quaternion to 1e-9 (bodies are renormalised every step).
void validate(const BodyState& s);

// Angular momentum about the centre of mass in ECEF (kg m^2/s) and the
// rotational kinetic energy (J).
glm::dvec3 angularMomentumEcef(const BodyState& s, const MassProperties& m);
double rotationalEnergy(const BodyState& s, const MassProperties& m);

// Force and torque about the centre of mass, accumulated in ECEF (N, N m).
// Offsets are point - centre of mass in ECEF axes: pass offsets rather than
// absolute points where you have them (an ECEF point carries only ~1 nm of
// resolution at Earth radius, offsets keep full precision).
class Wrench {
 public:
  void addForce(const glm::dvec3& forceEcef) { force_ += forceEcef; }
  void addForceAtOffset(const glm::dvec3& forceEcef, const glm::dvec3& offsetEcef) {
    force_ += forceEcef;
    torque_ += glm::cross(offsetEcef, forceEcef);
  }
  void addForceAtPoint(const glm::dvec3& forceEcef, const glm::dvec3& pointEcef, const glm::dvec3& comEcef) {
    addForceAtOffset(forceEcef, pointEcef - comEcef);
  }
  void addTorque(const glm::dvec3& torqueEcef) { torque_ += torqueEcef; }
  // Added (hydrodynamic) mass along the body axes (kg) and added moments of
  // inertia about them (kg m^2), diagonal in body axes: the integrator solves
  // (M + A) a = F + M g. Each must be >= 0 (Simulation checks).
  void addAddedMass(const glm::dvec3& massBodyKg, const glm::dvec3& inertiaBodyKgM2) {
    addedMass_ += massBodyKg;
    addedInertia_ += inertiaBodyKgM2;
  }
  const glm::dvec3& force() const { return force_; }
  const glm::dvec3& torque() const { return torque_; }
  const glm::dvec3& addedMassBody() const { return addedMass_; }
  const glm::dvec3& addedInertiaBody() const { return addedInertia_; }

 private:
  glm::dvec3 force_{0.0}, torque_{0.0}, addedMass_{0.0}, addedInertia_{0.0};
};

// For drawing between fixed steps: position along the step, orientation by
// slerp; alpha in [0, 1] from Simulation::alpha().
BodyState interpolate(const BodyState& a, const BodyState& b, double alpha);

}  // namespace geocean::bodies
