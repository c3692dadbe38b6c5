// Inertia tensors of the shape constructors against a midpoint-rule
// quadrature of I = integral rho (|p|^2 E - p p^T) dV over the solid (not
// against the formulas themselves).
#include "plugin/bodies/RigidBody.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

using namespace geocean::bodies;

namespace {

// Accumulates dm * (|p|^2 E - p p^T) over the solid's cells.
struct Quadrature {
  glm::dmat3 I{0.0};
  double mass = 0.0;
  void add(const glm::dvec3& p, double dm) {
    mass += dm;
    const double r2 = glm::dot(p, p);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) I[c][r] += dm * ((r == c ? r2 : 0.0) - p[r] * p[c]);
  }
};

// Midpoint rule in each coordinate: relative error about 1/n^2 for these
// quadratic integrands (a cell of width h misses h^3/12 of integral x^2).
Quadrature boxQuadrature(double m, glm::dvec3 size, int n) {
  Quadrature q;
  const glm::dvec3 h = size / double(n);
  const double dm = m / (double(n) * n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        q.add(glm::dvec3((i + 0.5) * h.x, (j + 0.5) * h.y, (k + 0.5) * h.z) - size * 0.5, dm);
  return q;
}

// Tube r1 <= r <= r2 along x in polar coordinates (r dr dtheta dx).
Quadrature tubeQuadrature(double m, double r1, double r2, double len, int n) {
  Quadrature q;
  const double dr = (r2 - r1) / n, dth = 2.0 * std::numbers::pi / n, dx = len / n;
  const double volume = std::numbers::pi * (r2 * r2 - r1 * r1) * len;
  for (int i = 0; i < n; ++i) {
    const double r = r1 + (i + 0.5) * dr;
    for (int j = 0; j < n; ++j) {
      const double th = (j + 0.5) * dth;
      for (int k = 0; k < n; ++k) {
        const double x = -0.5 * len + (k + 0.5) * dx;
        q.add({x, r * std::cos(th), r * std::sin(th)}, m / volume * r * dr * dth * dx);
      }
    }
  }
  return q;
}

void expectTensorNear(const glm::dmat3& ours, const glm::dmat3& ref, double relTol) {
  const double scale = ref[0][0] + ref[1][1] + ref[2][2];
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(ours[c][r], ref[c][r], relTol * scale) << "[" << r << "][" << c << "]";
}

}  // namespace

TEST(BodyInertia, BoxMatchesQuadrature) {
  const int n = 64;
  const glm::dvec3 size(2.0, 5.0, 1.5);
  const auto box = MassProperties::box(800.0, size);
  const auto q = boxQuadrature(800.0, size, n);
  EXPECT_DOUBLE_EQ(box.massKg(), 800.0);
  EXPECT_NEAR(q.mass, 800.0, 1e-9);
  expectTensorNear(box.inertiaBody(), q.I, 1.0 / (n * n));
}

TEST(BodyInertia, SolidAndHollowCylindersMatchQuadrature) {
  const int n = 160;
  // Polar midpoint rule: O(1/n^2) in r, theta and x; 2/n^2 covers the sum.
  const double tol = 2.0 / (n * n);
  const auto solid = MassProperties::solidCylinder(500.0, 0.8, 6.0, Axis::X);
  expectTensorNear(solid.inertiaBody(), tubeQuadrature(500.0, 0.0, 0.8, 6.0, n).I, tol);
  const auto tube = MassProperties::hollowCylinder(500.0, 0.6, 0.8, 6.0, Axis::X);
  expectTensorNear(tube.inertiaBody(), tubeQuadrature(500.0, 0.6, 0.8, 6.0, n).I, tol);
  // A thin shell is heavier off-axis than a solid of the same mass.
  EXPECT_GT(tube.inertiaBody()[0][0], solid.inertiaBody()[0][0]);
}

TEST(BodyInertia, AxisChoicePermutesTheTensor) {
  const auto x = MassProperties::hollowCylinder(10.0, 0.5, 1.0, 4.0, Axis::X).inertiaBody();
  const auto y = MassProperties::hollowCylinder(10.0, 0.5, 1.0, 4.0, Axis::Y).inertiaBody();
  const auto z = MassProperties::hollowCylinder(10.0, 0.5, 1.0, 4.0, Axis::Z).inertiaBody();
  EXPECT_EQ(x[0][0], y[1][1]);
  EXPECT_EQ(x[0][0], z[2][2]);
  EXPECT_EQ(x[1][1], y[0][0]);
  EXPECT_EQ(x[2][2], z[0][0]);
}

TEST(BodyInertia, IsotropicKeepsTraceAndMass) {
  const auto tube = MassProperties::hollowCylinder(2000.0, 1.5, 2.0, 12.0);
  const auto iso = MassProperties::isotropicFrom(tube);
  const glm::dmat3& I = tube.inertiaBody();
  const glm::dmat3& J = iso.inertiaBody();
  EXPECT_EQ(iso.massKg(), tube.massKg());
  EXPECT_NEAR(J[0][0] + J[1][1] + J[2][2], I[0][0] + I[1][1] + I[2][2], 1e-9 * I[0][0]);
  EXPECT_EQ(J[0][0], J[1][1]);
  EXPECT_EQ(J[1][1], J[2][2]);
  EXPECT_EQ(J[0][1], 0.0);
}

TEST(BodyInertia, InverseIsTheInverse) {
  glm::dmat3 I(0.0);
  I[0][0] = 4.0, I[1][1] = 5.0, I[2][2] = 6.0;
  I[0][1] = I[1][0] = 0.5;
  I[2][1] = I[1][2] = -0.3;
  const MassProperties m(3.0, I);
  const glm::dmat3 e = m.inertiaBody() * m.inverseInertiaBody();
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(e[c][r], r == c ? 1.0 : 0.0, 1e-14);
  EXPECT_DOUBLE_EQ(m.inverseMass(), 1.0 / 3.0);
}
