// Hull meshes against closed forms: volume and inertia of the box and the
// cylinder (textbook tables), mesh validation, and the tangent-plane
// geodetic offsets against GeographicLib.
#include "plugin/bodies/Hull.h"
#include "plugin/bodies/Hydro.h"
#include "plugin/bodies/Simulation.h"
#include "tests/bodies/BodiesTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

using namespace geocean;
using namespace geocean::bodies;

namespace {
double relErr(double a, double b) { return std::abs(a - b) / std::abs(b); }
}  // namespace

TEST(BodyHull, BoxMassPropertiesAreTheTextbookBox) {
  const glm::dvec3 size(4.0, 2.0, 1.5);
  for (int facets : {1, 4}) {
    const HullMesh h = HullMesh::box(size, facets);
    EXPECT_EQ(h.triangleCount(), std::size_t(12 * facets * facets));
    EXPECT_LT(relErr(h.volumeM3(), 12.0), 1e-14);
    EXPECT_LT(glm::length(h.designCentroid()), 1e-14);
    const MassProperties m = h.massProperties(500.0);
    const MassProperties ref = MassProperties::box(6000.0, size);
    EXPECT_LT(relErr(m.massKg(), 6000.0), 1e-14);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(m.inertiaBody()[i][j], ref.inertiaBody()[i][j], 1e-12 * ref.inertiaBody()[0][0]);
  }
}

TEST(BodyHull, CylinderHasTheTrueVolumeAndInertiaConverges) {
  const double r = 1.5, h = 4.0, rho = 300.0;
  const double V = std::numbers::pi * r * r * h;
  const MassProperties ref = MassProperties::solidCylinder(rho * V, r, h, Axis::Z);
  double errPrev = 0.0;
  for (int n : {24, 48}) {
    const HullMesh c = HullMesh::cylinder(r, h, n);
    EXPECT_LT(relErr(c.volumeM3(), V), 1e-13) << n;
    const MassProperties m = c.massProperties(rho);
    const double err = relErr(m.inertiaBody()[2][2], ref.inertiaBody()[2][2]);
    EXPECT_LT(err, 3.0 / (n * n)) << n;  // polygon vs circle
    EXPECT_LT(relErr(m.inertiaBody()[0][0], ref.inertiaBody()[0][0]), 3.0 / (n * n)) << n;
    if (errPrev > 0.0) {
      // The area-matched radius cancels the 1/n^2 term: doubling n divides
      // the error by 16 (fourth order).
      EXPECT_NEAR(errPrev / err, 16.0, 1.0);
    }
    errPrev = err;
  }
}

TEST(BodyHull, BoatIsClosedBuoyantAndWiderThanDeep) {
  const HullMesh b = HullMesh::boat(20.0);
  EXPECT_EQ(b.triangleCount(), 242u);
  const glm::dvec3 ext = b.maxCorner() - b.minCorner();
  EXPECT_NEAR(ext.x, 20.0, 1e-12);
  EXPECT_NEAR(ext.y, 20.0 / 3.5, 1e-12);
  EXPECT_NEAR(ext.z, 2.5, 1e-12);
  // Between a wedge and the bounding box.
  EXPECT_GT(b.volumeM3(), 0.3 * ext.x * ext.y * ext.z);
  EXPECT_LT(b.volumeM3(), 0.8 * ext.x * ext.y * ext.z);
}

TEST(BodyHull, RejectsOpenMeshesInwardWindingAndBadSizes) {
  const HullMesh box = HullMesh::box({1, 1, 1}, 1);
  auto v = box.vertices();
  auto idx = box.indices();
  auto open = idx;
  open.resize(open.size() - 3);
  EXPECT_THROW(HullMesh::fromTriangles(v, open), std::invalid_argument);
  auto inward = idx;
  for (std::size_t k = 0; k < inward.size(); k += 3) std::swap(inward[k + 1], inward[k + 2]);
  try {
    HullMesh::fromTriangles(v, inward);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("hull volume"), std::string::npos) << e.what();
  }
  auto bad = idx;
  bad[0] = 99;
  EXPECT_THROW(HullMesh::fromTriangles(v, bad), std::invalid_argument);
  try {
    HullMesh::box({-1, 1, 1});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("box length = -1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(HullMesh::cylinder(std::nan(""), 1), std::invalid_argument);
  EXPECT_THROW(HullMesh::boat(0.0), std::invalid_argument);
  EXPECT_THROW(box.massProperties(-5.0), std::invalid_argument);
}

TEST(BodyHull, TangentOffsetsToGeodeticMatchGeographicLib) {
  Simulation sim;
  for (double lat : {0.0, 45.0, -63.0, 80.0, 88.9, 89.9}) {
    const geo::Geodetic p{lat, 179.95, 3.0};
    BodyState s = test::stateAt(p);
    const StepContext ctx = sim.context(s);
    std::vector<glm::dvec3> off;
    for (double e : {-100.0, 0.0, 70.0})
      for (double n : {-100.0, 0.0, 60.0})
        for (double u : {-5.0, 0.0, 4.0}) off.emplace_back(e, n, u);
    std::vector<double> la(off.size()), lo(off.size()), h(off.size());
    offsetsToGeodetic(ctx, off.data(), off.size(), la.data(), lo.data(), h.data());
    for (std::size_t i = 0; i < off.size(); ++i) {
      const geo::Geodetic g = geo::fromEcef(ctx.enu.originEcef + ctx.enu.toEcef(off[i]));
      EXPECT_NEAR(h[i], g.heightM, 1e-8) << lat << " " << i;
      const double dn = (la[i] - g.latDeg) * std::numbers::pi / 180.0 * 6.37e6;
      const double dl = geo::wrapLonDeg(lo[i] - g.lonDeg);
      const double de = dl * std::numbers::pi / 180.0 * 6.39e6 * std::cos(g.latDeg * std::numbers::pi / 180.0);
      EXPECT_LT(std::hypot(dn, de), 1e-3) << lat << " " << i;
    }
  }
}

TEST(BodyHull, VolumeBelowAPlaneAndTheRestingWaterline) {
  // Box: linear in the plane's height; cylinder: pi r^2 times the depth.
  const HullMesh box = HullMesh::box({4.0, 2.0, 3.0});
  EXPECT_NEAR(box.volumeBelow(0.0), 12.0, 1e-12);
  EXPECT_NEAR(box.volumeBelow(-1.0), 4.0, 1e-12);
  EXPECT_NEAR(box.restingWaterlineZ(0.25), -0.75, 1e-9);  // draft 0.25 H, centre 0.75 m above
  const HullMesh cyl = HullMesh::cylinder(1.0, 2.0);
  EXPECT_NEAR(cyl.volumeBelow(0.3), std::numbers::pi * 1.3, 1e-12);
  EXPECT_THROW(box.restingWaterlineZ(1.2), std::invalid_argument);
}
