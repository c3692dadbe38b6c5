#include "plugin/bodies/Hydro.h"

#include "plugin/bodies/Validate.h"

#include <glm/geometric.hpp>
#include <glm/gtc/type_precision.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <limits>
#include <stdexcept>

namespace geocean::bodies {

using detail::fail;
using detail::requireNonNegative;
using detail::requirePositive;

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

// Columns: the body's axes in the step's ENU frame.
glm::dmat3 bodyToEnu(const BodyState& s, const StepContext& ctx) {
  glm::dmat3 R;
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 axis(0.0);
    axis[k] = 1.0;
    R[k] = ctx.enu.toLocal(s.bodyToEcef(axis));
  }
  return R;
}

// ITTC-1957 model-ship correlation line; Blasius' laminar plate below 5e5.
double frictionCoefficient(double reynolds) {
  reynolds = std::max(reynolds, 1.0);
  if (reynolds < 5e5) return 1.328 / std::sqrt(reynolds);
  const double l = std::log10(reynolds) - 2.0;
  return 0.075 / (l * l);
}

struct Vtx {
  glm::dvec3 r;   // ENU offset from the centre of mass
  double d;       // depth below the local surface (> 0 wet)
  double p;       // pressure (Pa)
  double x, y;    // r along the body's x and y axes laid horizontal (the waterplane's moments)
};

// Per-thread scratch for the per-vertex arrays (no allocation per step).
struct Scratch {
  std::vector<glm::dvec3> off;
  std::vector<double> lat, lon, h, t;
  std::vector<SeaSample> sea;
  std::vector<Vtx> v;
  // The sea grid (HullForce): node offsets, their geodetic points and times,
  // samples, and the slopes and twist along the grid's axes.
  std::vector<glm::dvec3> gOff;
  std::vector<double> gLat, gLon, gH, gT, fx, fy, fxy;
  std::vector<SeaSample> gSea;
  void resize(std::size_t n) {
    off.resize(n), lat.resize(n), lon.resize(n), h.resize(n), t.resize(n), sea.resize(n), v.resize(n);
  }
  void resizeGrid(std::size_t n) {
    gOff.resize(n), gLat.resize(n), gLon.resize(n), gH.resize(n), gT.resize(n), gSea.resize(n);
    fx.resize(n), fy.resize(n), fxy.resize(n);
  }
};

// Cubic Hermite basis on [0, 1]: value at 0, slope at 0, value at 1, slope at 1.
inline void hermite(double t, double* b) {
  const double t2 = t * t, t3 = t2 * t;
  b[0] = 2 * t3 - 3 * t2 + 1, b[1] = t3 - 2 * t2 + t, b[2] = -2 * t3 + 3 * t2, b[3] = t3 - t2;
}

// The sea under the hull on a grid (Hydro.h): writes the surface height
// above every vertex to S.sea[i].heightM and the height and vertical
// velocity at the centre one step earlier to `previous` (one query with the
// nodes). Returns the node count, or 0 when the grid does not apply (the
// caller then queries every vertex).
int seaOnGrid(const SeaSurface& sea, const StepContext& ctx, const glm::dmat3& R, std::size_t n,
              double pointsPerWavelength, Scratch& S, SeaSample& previous) {
  const double lambda = sea.shortestWavelengthM();
  if (!(lambda > 0.0) || !(pointsPerWavelength > 0.0)) return 0;
  // Above 89 degrees the east-north axes turn across a hull's width (the
  // slopes' axes would need a frame per node): query every vertex.
  if (std::abs(ctx.geodetic.latDeg) > 89.0) return 0;
  // Grid axes: the hull's heading laid horizontal, and its left.
  glm::dvec3 ax(R[0].x, R[0].y, 0.0);
  if (glm::length(ax) < 1e-6) ax = glm::dvec3(-R[1].y, R[1].x, 0.0);  // bow straight up or down
  ax = glm::normalize(ax);
  const glm::dvec3 ay(-ax.y, ax.x, 0.0);
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = glm::dot(S.off[i], ax), y = glm::dot(S.off[i], ay);
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  const double spacing = lambda / pointsPerWavelength;
  const double cx = std::max(2.0, std::ceil((x1 - x0) / spacing) + 1.0);
  const double cy = std::max(2.0, std::ceil((y1 - y0) / spacing) + 1.0);
  if (!(cx * cy < double(n))) return 0;
  const int nx = int(cx), ny = int(cy), nodes = nx * ny;
  const double sx = x1 > x0 ? (x1 - x0) / (nx - 1) : 1.0, sy = y1 > y0 ? (y1 - y0) / (ny - 1) : 1.0;
  S.resizeGrid(std::size_t(nodes) + 1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) S.gOff[std::size_t(j) * nx + i] = (x0 + i * sx) * ax + (y0 + j * sy) * ay;
  offsetsToGeodetic(ctx, S.gOff.data(), std::size_t(nodes), S.gLat.data(), S.gLon.data(), S.gH.data());
  std::fill(S.gT.begin(), S.gT.begin() + nodes, ctx.timeS);
  // The centre one step earlier rides along (the water's acceleration).
  S.gLat[nodes] = ctx.geodetic.latDeg, S.gLon[nodes] = ctx.geodetic.lonDeg, S.gT[nodes] = ctx.timeS - ctx.stepS;
  sea.sampleSlopes(S.gLat.data(), S.gLon.data(), S.gT.data(), std::size_t(nodes) + 1, S.gSea.data());
  for (int k = 0; k < nodes; ++k) {
    const SeaSample& g = S.gSea[k];
    if (std::isnan(g.heightM)) return 0;  // a coast under the hull
    S.fx[k] = g.slopeEn.x * ax.x + g.slopeEn.y * ax.y;
    S.fy[k] = g.slopeEn.x * ay.x + g.slopeEn.y * ay.y;
  }
  previous = S.gSea[nodes];
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int ja = std::max(j - 1, 0), jb = std::min(j + 1, ny - 1), ia = std::max(i - 1, 0),
                ib = std::min(i + 1, nx - 1);
      S.fxy[std::size_t(j) * nx + i] =
          0.5 * ((S.fx[std::size_t(jb) * nx + i] - S.fx[std::size_t(ja) * nx + i]) / ((jb - ja) * sy) +
                 (S.fy[std::size_t(j) * nx + ib] - S.fy[std::size_t(j) * nx + ia]) / ((ib - ia) * sx));
    }
  for (std::size_t v = 0; v < n; ++v) {
    const double u = (glm::dot(S.off[v], ax) - x0) / sx, w = (glm::dot(S.off[v], ay) - y0) / sy;
    const int i = std::clamp(int(u), 0, nx - 2), j = std::clamp(int(w), 0, ny - 2);
    double bu[4], bw[4];
    hermite(std::clamp(u - i, 0.0, 1.0), bu);
    hermite(std::clamp(w - j, 0.0, 1.0), bw);
    double eta = 0.0;
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const std::size_t k = std::size_t(j + b) * nx + (i + a);
        const double vu = bu[2 * a], du = bu[2 * a + 1] * sx, vw = bw[2 * b], dw = bw[2 * b + 1] * sy;
        eta += S.gSea[k].heightM * vu * vw + S.fx[k] * du * vw + S.fy[k] * vu * dw + S.fxy[k] * du * dw;
      }
    S.sea[v].heightM = eta;
  }
  return nodes;
}

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

}  // namespace

void offsetsToGeodetic(const StepContext& ctx, const glm::dvec3* off, std::size_t n, double* latDeg, double* lonDeg,
                       double* heightM) {
  constexpr double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double phi = ctx.geodetic.latDeg / kDeg;
  const double s = std::sin(phi), c = std::cos(phi);
  if (std::abs(c) < 0.0174524) {  // above 89 degrees: tan(lat) > 57 feeds the neglected third order
    for (std::size_t i = 0; i < n; ++i) {
      const geo::Geodetic g = geo::fromEcef(ctx.enu.originEcef + ctx.enu.toEcef(off[i]));
      latDeg[i] = g.latDeg, lonDeg[i] = g.lonDeg, heightM[i] = g.heightM;
    }
    return;
  }
  const double w = std::sqrt(1.0 - e2 * s * s);
  const double Nh = a / w + ctx.geodetic.heightM, Mh = a * (1.0 - e2) / (w * w * w) + ctx.geodetic.heightM;
  const double tanPhi = s / c;
  for (std::size_t i = 0; i < n; ++i) {
    const double e = off[i].x, nn = off[i].y, u = off[i].z;
    // Second order: moving east along the tangent plane lowers the latitude
    // by e^2 tan(phi) / (2 N^2); moving north stretches the parallel.
    latDeg[i] = ctx.geodetic.latDeg + kDeg * (nn / Mh - e * e * tanPhi / (2.0 * Nh * Nh));
    lonDeg[i] = ctx.geodetic.lonDeg + kDeg * (e / (Nh * c)) * (1.0 + nn * tanPhi / Nh);
    heightM[i] = ctx.geodetic.heightM + u + 0.5 * (e * e / Nh + nn * nn / Mh);
  }
}

double rectangularPlateAddedMassCoefficient(double aspect) {
  // DNV-RP-C205 (2010) table A-2, rectangular plates: b/a, C_A.
  static constexpr std::array<std::array<double, 2>, 12> kTable{{{1.0, 0.579}, {1.25, 0.642}, {1.5, 0.704},
                                                                  {1.59, 0.719}, {2.0, 0.757}, {2.5, 0.801},
                                                                  {3.0, 0.830}, {4.0, 0.872}, {5.0, 0.897},
                                                                  {6.25, 0.917}, {8.0, 0.934}, {10.0, 0.947}}};
  if (!(aspect >= 1.0)) fail("plate aspect ratio b/a", aspect, "", "must be >= 1");
  if (aspect >= 10.0) return 1.0 - 0.53 / aspect;
  for (std::size_t i = 1; i < kTable.size(); ++i) {
    if (aspect <= kTable[i][0]) {
      const double u = (aspect - kTable[i - 1][0]) / (kTable[i][0] - kTable[i - 1][0]);
      return kTable[i - 1][1] + u * (kTable[i][1] - kTable[i - 1][1]);
    }
  }
  return 0.947;
}

double carlsonRD(double x, double y, double z) {
  if (!(x >= 0.0 && y >= 0.0 && x + y > 0.0 && z > 0.0) || !std::isfinite(x + y + z))
    throw std::invalid_argument("geocean::bodies: carlsonRD needs x, y >= 0 (not both 0) and z > 0");
  // Duplication until the arguments agree to 1e-4: the series' error is then
  // below 1e-4^6 / (3 (1 - 1e-4)^{3/2}), far under double rounding.
  constexpr double C1 = 3.0 / 14.0, C2 = 1.0 / 6.0, C3 = 9.0 / 22.0, C4 = 3.0 / 26.0, C5 = 0.25 * C3,
                   C6 = 1.5 * C4;
  double sum = 0.0, fac = 1.0, ave, dx, dy, dz;
  for (;;) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * (sy + sz) + sy * sz;
    sum += fac / (sz * (z + lambda));
    fac *= 0.25;
    x = 0.25 * (x + lambda), y = 0.25 * (y + lambda), z = 0.25 * (z + lambda);
    ave = 0.2 * (x + y + 3.0 * z);
    dx = (ave - x) / ave, dy = (ave - y) / ave, dz = (ave - z) / ave;
    if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) <= 1e-4) break;
  }
  const double ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - 6.0 * eb, ee = ed + ec + ec;
  const double series = 1.0 + ed * (-C1 + C5 * ed - C6 * dz * ee) + dz * (C2 * ee + dz * (-C3 * ec + dz * C4 * ea));
  return 3.0 * sum + fac * series / (ave * std::sqrt(ave));
}

EllipsoidAddedMass ellipsoidAddedMass(double a, double b, double c, double rho) {
  requirePositive("ellipsoid semi-axis a", a, "m");
  requirePositive("ellipsoid semi-axis b", b, "m");
  requirePositive("ellipsoid semi-axis c", c, "m");
  requirePositive("water density", rho, "kg/m^3");
  const double abc = a * b * c, a2 = a * a, b2 = b * b, c2 = c * c;
  // Lamb's alpha0, beta0, gamma0 (they sum to 2).
  const glm::dvec3 g0(2.0 / 3.0 * abc * carlsonRD(b2, c2, a2), 2.0 / 3.0 * abc * carlsonRD(c2, a2, b2),
                      2.0 / 3.0 * abc * carlsonRD(a2, b2, c2));
  const double mf = 4.0 / 3.0 * std::numbers::pi * rho * abc;
  const glm::dvec3 s2(a2, b2, c2);
  EllipsoidAddedMass out;
  for (int i = 0; i < 3; ++i) {
    out.massKg[i] = g0[i] / (2.0 - g0[i]) * mf;
    // About axis i: the other two, j and k (cyclic), as Lamb's about x with (b, c).
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double d = s2[j] - s2[k];
    // Axially symmetric about i: turning it moves no water.
    if (std::abs(d) <= 1e-12 * (s2[j] + s2[k])) continue;
    const double den = 2.0 * d + (s2[j] + s2[k]) * (g0[j] - g0[k]);
    out.inertiaKgM2[i] = mf / 5.0 * d * d * (g0[k] - g0[j]) / den;
  }
  return out;
}

// ---- HullForce ---------------------------------------------------------------

HullForce::HullForce(std::shared_ptr<const HullMesh> hull, std::shared_ptr<const SeaSurface> sea,
                     HullForceOptions options)
    : hull_(std::move(hull)), sea_(std::move(sea)), options_(options) {
  if (!hull_) throw std::invalid_argument("geocean::bodies: HullForce hull is null");
  if (!sea_) throw std::invalid_argument("geocean::bodies: HullForce sea is null");
  requirePositive("water density", options_.water.densityKgM3, "kg/m^3");
  requirePositive("water kinematic viscosity", options_.water.kinematicViscosityM2ps, "m^2/s");
  requireNonNegative("pressure drag coefficient", options_.pressureDragCoefficient, "");
  requireNonNegative("heave damping ratio", options_.heaveDampingRatio, "");
  requireNonNegative("roll damping ratio", options_.rollDampingRatio, "");
  requireNonNegative("pitch damping ratio", options_.pitchDampingRatio, "");
  requireNonNegative("sea grid points per wavelength", options_.seaGridPointsPerWavelength, "");
  const glm::dvec3 ext = hull_->maxCorner() - hull_->minCorner();
  lengthM_ = ext.x, beamM_ = ext.y, depthM_ = ext.z;
  const double rho = options_.water.densityKgM3;
  if (hull_->kind() == "cylinder") {
    const double R = std::sqrt(hull_->volumeM3() / (std::numbers::pi * ext.z));
    a33Full_ = 4.0 / 3.0 * rho * R * R * R;
    awpFull_ = std::numbers::pi * R * R;
  } else {
    const double a = std::min(ext.x, ext.y), b = std::max(ext.x, ext.y);
    a33Full_ = 0.5 * rectangularPlateAddedMassCoefficient(b / a) * rho * std::numbers::pi / 4.0 * a * a * b;
    awpFull_ = ext.x * ext.y;
  }
}

void HullForce::accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const {
  const HullEvaluation e = evaluate(body.state, body.mass, ctx);
  wrench.addForce(e.wrench.force());
  wrench.addTorque(e.wrench.torque());
  wrench.addAddedMass(e.wrench.addedMassBody(), e.wrench.addedInertiaBody());
}

HullEvaluation HullForce::evaluate(const BodyState& state, const MassProperties& mass, const StepContext& ctx) const {
  HullEvaluation out;
  const auto& verts = hull_->vertices();
  const auto& idx = hull_->indices();
  const std::size_t n = verts.size();
  Scratch& S = scratch();
  S.resize(std::max<std::size_t>(n, 3));
  const glm::dmat3 R = bodyToEnu(state, ctx);
  for (std::size_t i = 0; i < n; ++i) S.off[i] = R * verts[i];
  offsetsToGeodetic(ctx, S.off.data(), n, S.lat.data(), S.lon.data(), S.h.data());

  // The centre: the surface and the water's velocity at t, and its vertical
  // velocity one step earlier for the acceleration (a backward difference,
  // lagging by dt/2: 0.5 % of a radian for a 12 s swell at 60 Hz; at the
  // previous step's time, which the FFT model still has in its cache).
  const double probe = ctx.stepS;
  std::array<double, 2> cLat{}, cLon{}, cT{ctx.timeS, ctx.timeS - probe};
  cLat.fill(ctx.geodetic.latDeg), cLon.fill(ctx.geodetic.lonDeg);
  std::array<SeaSample, 2> c;
  out.seaGridNodes = seaOnGrid(*sea_, ctx, R, n, options_.seaGridPointsPerWavelength, S, c[1]);
  if (out.seaGridNodes > 0) {
    sea_->sample(cLat.data(), cLon.data(), cT.data(), 1, true, c.data());
  } else {
    std::fill(S.t.begin(), S.t.begin() + n, ctx.timeS);
    sea_->sample(S.lat.data(), S.lon.data(), S.t.data(), n, false, S.sea.data());
    sea_->sample(cLat.data(), cLon.data(), cT.data(), 1, true, c.data());
    // One step earlier with the slope (the water's horizontal acceleration),
    // as the grid's query has it.
    sea_->sampleSlopes(&cLat[1], &cLon[1], &cT[1], 1, &c[1]);
  }
  out.seaHeightM = c[0].heightM;

  const double rho = options_.water.densityKgM3, g = ctx.gravityMps2, rhoG = rho * g;
  const double k = sea_->decayWaveNumberPerM();
  // The body's x and y axes laid horizontal (for the waterplane's moments).
  auto horizontal = [](glm::dvec3 v) {
    v.z = 0.0;
    const double l = glm::length(v);
    return l > 1e-9 ? v / l : glm::dvec3(0.0);
  };
  glm::dvec3 hx = horizontal(R[0]), hy = horizontal(R[1]);
  if (hx == glm::dvec3(0.0)) hx = glm::normalize(glm::cross(hy, glm::dvec3(0, 0, 1)));
  if (hy == glm::dvec3(0.0)) hy = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), hx));
  bool anyWet = false;
  double lowest = ctx.geodetic.heightM;
  for (std::size_t i = 0; i < n; ++i) {
    const double eta = S.sea[i].heightM;
    lowest = std::min(lowest, S.h[i]);
    const double d = std::isnan(eta) ? -1e300 : eta - S.h[i];
    double p = 0.0;
    if (d > 0.0) {
      anyWet = true;
      p = k > 0.0 ? rhoG * (d - eta * (1.0 - std::exp(-k * d))) : rhoG * d;
      p = std::max(p, 0.0);
    }
    S.v[i] = Vtx{S.off[i], d, p, glm::dot(S.off[i], hx), glm::dot(S.off[i], hy)};
  }
  out.keelDepthM = std::isnan(c[0].heightM) ? std::numeric_limits<double>::quiet_NaN() : c[0].heightM - lowest;
  if (!anyWet) return out;

  const glm::dvec3 vCom = ctx.enu.toLocal(state.velocityEcef);
  const glm::dvec3 wEnu = ctx.enu.toLocal(state.angularVelocityEcef());
  const glm::dvec3 vWater0 = std::isnan(c[0].heightM)
                                 ? glm::dvec3(0.0)
                                 : glm::dvec3(c[0].horizontalVelocityEnMps, c[0].verticalVelocityMps);
  const double relSpeed = glm::length(vCom - vWater0);
  const double cf = options_.skinFriction ? frictionCoefficient(relSpeed * lengthM_ /
                                                                 options_.water.kinematicViscosityM2ps)
                                          : 0.0;
  const double cd = options_.pressureDragCoefficient;

  glm::dvec3 F(0.0), T(0.0), volMoment(0.0);
  double vol = 0.0, areaUp = 0.0, wpX = 0.0, wpY = 0.0, wpXX = 0.0, wpYY = 0.0;
  auto integrate = [&](const Vtx& a, const Vtx& b, const Vtx& cc) __attribute__((always_inline)) {
    const glm::dvec3 Sv = 0.5 * glm::cross(b.r - a.r, cc.r - a.r);  // area x outward normal
    const double P = a.p + b.p + cc.p;
    const glm::dvec3 sr = a.r + b.r + cc.r;
    F -= (P / 3.0) * Sv;
    T -= glm::cross((a.p * a.r + b.p * b.r + cc.p * cc.r + P * sr) / 12.0, Sv);
    const double D = a.d + b.d + cc.d;
    vol -= D / 3.0 * Sv.z;
    volMoment -= (a.d * a.r + b.d * b.r + cc.d * cc.r + D * sr) / 12.0 * Sv.z;
    areaUp += Sv.z;
    // Second moments of the waterplane, -integral of (offset along the
    // body's horizontal axes)^2 n_up dA: int f^2 = A/6 (sum f_i^2 + sum f_i f_j).
    const double xa = a.x, xb = b.x, xc = cc.x, ya = a.y, yb = b.y, yc = cc.y;
    wpX += Sv.z * (xa + xb + xc) / 3.0, wpY += Sv.z * (ya + yb + yc) / 3.0;
    wpXX += Sv.z * (xa * xa + xb * xb + xc * xc + xa * xb + xb * xc + xc * xa) / 6.0;
    wpYY += Sv.z * (ya * ya + yb * yb + yc * yc + ya * yb + yb * yc + yc * ya) / 6.0;
    // Drag on the velocity relative to the water at the centroid.
    const double A = glm::length(Sv);
    if (A <= 0.0) return;
    const glm::dvec3 nrm = Sv / A, rc = sr / 3.0;
    const glm::dvec3 vRel = vCom + glm::cross(wEnu, rc) - vWater0 * std::exp(-k * (D / 3.0));
    const double vn = glm::dot(vRel, nrm);
    glm::dvec3 fd = -0.25 * rho * cd * std::abs(vn) * vn * A * nrm;
    const glm::dvec3 vt = vRel - vn * nrm;
    fd -= 0.5 * rho * cf * glm::length(vt) * A * vt;
    F += fd;
    T += glm::cross(rc, fd);
  };
  for (std::size_t t = 0; t < idx.size(); t += 3) {
    const Vtx* tri[3] = {&S.v[idx[t]], &S.v[idx[t + 1]], &S.v[idx[t + 2]]};
    const int wet = (tri[0]->d > 0.0) + (tri[1]->d > 0.0) + (tri[2]->d > 0.0);
    if (wet == 0) continue;
    if (wet == 3) {
      integrate(*tri[0], *tri[1], *tri[2]);
      continue;
    }
    // Clip (Sutherland-Hodgman) at d = 0, where the pressure is 0 too.
    std::array<Vtx, 4> poly;
    int m = 0;
    for (int e = 0; e < 3; ++e) {
      const Vtx &p = *tri[e], &q = *tri[(e + 1) % 3];
      if (p.d > 0.0) poly[m++] = p;
      if ((p.d > 0.0) != (q.d > 0.0)) {
        const double s = p.d / (p.d - q.d);
        poly[m++] = Vtx{p.r + s * (q.r - p.r), 0.0, 0.0, p.x + s * (q.x - p.x), p.y + s * (q.y - p.y)};
      }
    }
    for (int j = 1; j + 1 < m; ++j) integrate(poly[0], poly[j], poly[j + 1]);
  }
  out.submergedVolumeM3 = vol;
  out.waterplaneAreaM2 = -areaUp;
  if (vol > 0.0) {
    out.buoyancyCentreEnu = volMoment / vol;
  }

  const double awp = out.waterplaneAreaM2;
  double a33 = 0.0;
  glm::dvec3 addedRot(0.0);
  if (options_.addedMass && awp > 0.0) {
    const double frac = std::min(1.0, awp / awpFull_);
    a33 = a33Full_ * frac * std::sqrt(frac);
    out.heaveAddedMassKg = a33;
    // The other modes from the double body's ellipsoid (see Hydro.h).
    const double shrink = std::sqrt(frac), draft = std::min(vol / awp, depthM_);
    EllipsoidAddedMass e{};
    if (draft > 0.0) e = ellipsoidAddedMass(0.5 * lengthM_ * shrink, 0.5 * beamM_ * shrink, draft, rho);
    const glm::dvec3 am(0.5 * e.massKg.x, 0.5 * e.massKg.y, a33);
    addedRot = 0.5 * e.inertiaKgM2;
    out.addedMassKg = am, out.addedInertiaKgM2 = addedRot;
    out.wrench.addAddedMass(am, addedRot);
    // Morison / G.I. Taylor long-wave term: the added mass times the
    // water's acceleration, vertical at the keel, horizontal at half its depth.
    if (!std::isnan(c[0].heightM) && !std::isnan(c[1].heightM)) {
      const double keel = std::max(out.keelDepthM, 0.0);
      const double aw = (c[0].verticalVelocityMps - c[1].verticalVelocityMps) / probe * std::exp(-k * keel);
      const glm::dvec2 ah = -g * std::exp(-0.5 * k * keel) * c[1].slopeEn;
      const glm::dvec3 accel(ah, aw);
      for (int i = 0; i < 3; ++i) F += am[i] * glm::dot(R[i], accel) * R[i];
    }
  }
  // Radiation damping (linear, fractions of critical).
  if (awp > 0.0 && vol > 0.0) {
    // A hull across a coast can have its centre over land: no surface there
    // (keelDepthM NaN, and std::max(NaN, 0) is NaN), so the water is still
    // (vWater0 = 0) and its decay with depth is not needed; 0 * exp(NaN) was NaN.
    const double vzWater =
        std::isnan(c[0].heightM) ? 0.0 : vWater0.z * std::exp(-k * std::max(out.keelDepthM, 0.0));
    const double vzRel = vCom.z - vzWater;
    F.z -= 2.0 * options_.heaveDampingRatio * std::sqrt((mass.massKg() + a33) * rhoG * awp) * vzRel;
    // GM about the centre of mass: z_B + I_wp / V, I_wp about the waterplane's centroid.
    const double Ixx = -(wpYY - wpY * wpY / -areaUp), Iyy = -(wpXX - wpX * wpX / -areaUp);
    const double zB = out.buoyancyCentreEnu.z;
    out.metacentricHeightM = {zB + Ixx / vol, zB + Iyy / vol};
    const glm::dvec3 wBody = state.angularVelocityBody;
    const glm::dmat3& I = mass.inertiaBody();
    glm::dvec3 tauBody(0.0);
    if (out.metacentricHeightM.x > 0.0)
      tauBody.x = -2.0 * options_.rollDampingRatio *
                  std::sqrt((I[0][0] + addedRot.x) * rhoG * vol * out.metacentricHeightM.x) * wBody.x;
    if (out.metacentricHeightM.y > 0.0)
      tauBody.y = -2.0 * options_.pitchDampingRatio *
                  std::sqrt((I[1][1] + addedRot.y) * rhoG * vol * out.metacentricHeightM.y) * wBody.y;
    T += R * tauBody;
  }
  out.wrench.addForce(ctx.enu.toEcef(F));
  out.wrench.addTorque(ctx.enu.toEcef(T));
  return out;
}

// ---- ContactPointForce -------------------------------------------------------

ContactPointForce::ContactPointForce(std::vector<glm::dvec3> pointsBody, double volumeM3, double columnHeightM,
                                     double waterplaneAreaM2, std::shared_ptr<const SeaSurface> sea,
                                     ContactPointOptions options)
    : points_(std::move(pointsBody)),
      volume_(volumeM3),
      column_(columnHeightM),
      area_(waterplaneAreaM2),
      sea_(std::move(sea)),
      options_(options) {
  if (points_.empty()) fail("contact point count", 0.0, "", "must be > 0");
  for (std::size_t i = 0; i < points_.size(); ++i)
    detail::requireFinite("contact point " + std::to_string(i), points_[i], "m");
  requirePositive("contact point volume", volume_, "m^3");
  requirePositive("contact point column height", column_, "m");
  requirePositive("contact point waterplane area", area_, "m^2");
  requirePositive("water density", options_.water.densityKgM3, "kg/m^3");
  requireNonNegative("contact point drag coefficient", options_.dragCoefficient, "");
  if (!sea_) throw std::invalid_argument("geocean::bodies: ContactPointForce sea is null");
}

std::shared_ptr<ContactPointForce> ContactPointForce::hollowCylinderProxy(double lengthM, double outerRadiusM, int nx,
                                                                          std::shared_ptr<const SeaSurface> sea,
                                                                          ContactPointOptions options) {
  requirePositive("proxy length", lengthM, "m");
  requirePositive("proxy outer radius", outerRadiusM, "m");
  if (nx < 1 || nx > 256) fail("proxy points along the length", nx, "", "must be 1..256");
  std::vector<glm::dvec3> pts;
  for (int j = 0; j < nx; ++j)
    for (double side : {-0.5, 0.5})
      pts.emplace_back(lengthM * ((j + 0.5) / nx - 0.5), side * outerRadiusM, 0.0);
  return std::make_shared<ContactPointForce>(std::move(pts), std::numbers::pi * outerRadiusM * outerRadiusM * lengthM,
                                             2.0 * outerRadiusM, 2.0 * outerRadiusM * lengthM, std::move(sea),
                                             options);
}

void ContactPointForce::accumulate(const Body& body, const StepContext& ctx, Wrench& wrench) const {
  const std::size_t n = points_.size();
  Scratch& S = scratch();
  S.resize(n);
  const glm::dmat3 R = bodyToEnu(body.state, ctx);
  for (std::size_t i = 0; i < n; ++i) S.off[i] = R * points_[i];
  const bool each = options_.waterVelocityAtEachPoint;
  // beginStep's queries when they were for this state and time.
  const SeaSample* sea = nullptr;
  SeaSample centre{};
  if (!each) {
    const auto it = std::lower_bound(centres_.begin(), centres_.end(), body.id,
                                     [](const Centre& c, BodyId v) { return c.id < v; });
    if (it != centres_.end() && it->id == body.id && it->positionEcef == body.state.positionEcef &&
        centreTimeS_ == ctx.timeS) {
      const std::size_t j = std::size_t(it - centres_.begin());
      centre = centreSea_[j];
      sea = &pointSea_[j * n];
      std::copy_n(&pointH_[j * n], n, S.h.begin());
    }
  }
  if (!sea) {
    offsetsToGeodetic(ctx, S.off.data(), n, S.lat.data(), S.lon.data(), S.h.data());
    std::fill(S.t.begin(), S.t.begin() + n, ctx.timeS);
    sea_->sample(S.lat.data(), S.lon.data(), S.t.data(), n, each, S.sea.data());
    sea = S.sea.data();
    if (!each) sea_->sample(&ctx.geodetic.latDeg, &ctx.geodetic.lonDeg, &ctx.timeS, 1, true, &centre);
  }
  const glm::dvec3 vCentre = std::isnan(centre.heightM)
                                 ? glm::dvec3(0.0)
                                 : glm::dvec3(centre.horizontalVelocityEnMps, centre.verticalVelocityMps);
  const double rho = options_.water.densityKgM3, k = sea_->decayWaveNumberPerM();
  const double vi = volume_ / n, ai = area_ / n;
  const glm::dvec3 vCom = ctx.enu.toLocal(body.state.velocityEcef);
  const glm::dvec3 wEnu = ctx.enu.toLocal(body.state.angularVelocityEcef());
  glm::dvec3 F(0.0), T(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const SeaSample& s = sea[i];
    if (std::isnan(s.heightM)) continue;
    const double d = s.heightM - S.h[i];
    const double frac = std::clamp(d / column_ + 0.5, 0.0, 1.0);
    if (frac <= 0.0) continue;
    glm::dvec3 f(0.0, 0.0, rho * ctx.gravityMps2 * vi * frac);  // Fn_i
    const glm::dvec3 vSurface = each ? glm::dvec3(s.horizontalVelocityEnMps, s.verticalVelocityMps) : vCentre;
    const glm::dvec3 vWater = vSurface * std::exp(-k * std::max(d, 0.0));
    const glm::dvec3 vRel = vCom + glm::cross(wEnu, S.off[i]) - vWater;
    f -= 0.5 * rho * options_.dragCoefficient * ai * frac * glm::length(vRel) * vRel;  // Fd_i
    F += f;
    T += glm::cross(S.off[i], f);  // eq. 4
  }
  wrench.addForce(ctx.enu.toEcef(F));
  wrench.addTorque(ctx.enu.toEcef(T));
}

void ContactPointForce::beginStep(const Simulation& sim) const {
  centres_.clear();
  centreSea_.clear();
  if (options_.waterVelocityAtEachPoint) return;
  const std::size_t n = points_.size();
  std::vector<double> lat, lon, t;
  pointLat_.clear(), pointLon_.clear(), pointH_.clear();
  std::vector<glm::dvec3> off(n);
  for (const Body& b : sim.bodies()) {
    bool mine = false;
    for (const auto& m : b.forces) mine |= m.get() == this;
    if (!mine) continue;
    // As Simulation::context computes it for accumulate: the same centre and points.
    const StepContext ctx = sim.context(b.state);
    centres_.push_back({b.id, b.state.positionEcef});
    lat.push_back(ctx.geodetic.latDeg), lon.push_back(ctx.geodetic.lonDeg);
    const glm::dmat3 R = bodyToEnu(b.state, ctx);
    for (std::size_t i = 0; i < n; ++i) off[i] = R * points_[i];
    const std::size_t k = pointLat_.size();
    pointLat_.resize(k + n), pointLon_.resize(k + n), pointH_.resize(k + n);
    offsetsToGeodetic(ctx, off.data(), n, &pointLat_[k], &pointLon_[k], &pointH_[k]);
  }
  centreTimeS_ = sim.time();
  t.assign(lat.size(), centreTimeS_);
  centreSea_.resize(lat.size());
  sea_->sample(lat.data(), lon.data(), t.data(), lat.size(), true, centreSea_.data());
  pointT_.assign(pointLat_.size(), centreTimeS_);
  pointSea_.resize(pointLat_.size());
  sea_->sample(pointLat_.data(), pointLon_.data(), pointT_.data(), pointLat_.size(), false, pointSea_.data());
}

// ---- Thrust, Repulsion -----------------------------------------------------------

Thrust::Thrust(double newtons) : newtons_(newtons) { detail::requireFinite("thrust", newtons, "N"); }

void Thrust::accumulate(const Body& body, const StepContext&, Wrench& wrench) const {
  wrench.addForce(newtons_ * body.state.bodyToEcef(glm::dvec3(1.0, 0.0, 0.0)));
}

Repulsion::Repulsion(const Simulation& sim, double defaultRadiusM, double stiffnessNpm)
    : sim_(&sim), radius_(defaultRadiusM), stiffness_(stiffnessNpm) {
  requirePositive("repulsion radius", defaultRadiusM, "m");
  requirePositive("repulsion stiffness", stiffnessNpm, "N/m");
  defaultSpheres_ = {RepulsionSphere{glm::dvec3(0.0), radius_}};
}

void Repulsion::setSpheres(BodyId id, std::vector<RepulsionSphere> spheres) {
  if (spheres.empty()) fail("repulsion sphere count of body " + std::to_string(id), 0.0, "", "must be > 0");
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    detail::requireFinite("repulsion sphere " + std::to_string(i) + " centre", spheres[i].centreBody, "m");
    requirePositive("repulsion sphere " + std::to_string(i) + " radius", spheres[i].radiusM, "m");
  }
  spheres_[id] = std::move(spheres);
}

void Repulsion::forgetBody(BodyId id) { spheres_.erase(id); }

std::vector<RepulsionSphere> Repulsion::spheresAlongHull(const HullMesh& hull) {
  const glm::dvec3 lo = hull.minCorner(), hi = hull.maxCorner(), mid = 0.5 * (lo + hi);
  const double L = hi.x - lo.x, B = hi.y - lo.y, r = 0.5 * std::min(L, B);
  const int n = std::max(1, int(std::ceil(L / (2.0 * r) - 1e-9)));
  std::vector<RepulsionSphere> out;
  for (int j = 0; j < n; ++j) {
    // Centres from lo.x + r to hi.x - r: the row spans the length.
    const double x = n == 1 ? mid.x : lo.x + r + (L - 2.0 * r) * j / (n - 1);
    out.push_back({glm::dvec3(x, mid.y, mid.z), r});
  }
  return out;
}

const std::vector<RepulsionSphere>& Repulsion::spheresOf(BodyId id) const {
  const auto it = spheres_.find(id);
  return it == spheres_.end() ? defaultSpheres_ : it->second;
}

namespace {
glm::i64vec3 cellOf(const glm::dvec3& p, double cell) {
  return {std::int64_t(std::floor(p.x / cell)), std::int64_t(std::floor(p.y / cell)), std::int64_t(std::floor(p.z / cell))};
}
// 21 bits a coordinate: cells of >= 1 m over +-6.4e6 m wrap, which only
// adds candidates (the bound test rejects them), never loses one.
std::uint64_t cellKey(const glm::i64vec3& c) {
  return (std::uint64_t(c.x) & 0x1fffffu) | ((std::uint64_t(c.y) & 0x1fffffu) << 21) |
         ((std::uint64_t(c.z) & 0x1fffffu) << 42);
}
}  // namespace

void Repulsion::beginStep(const Simulation& sim) const {
  const auto& all = sim.bodies();
  placed_.clear();
  offsets_.clear();
  radii_.clear();
  cells_.clear();
  double maxBound = 0.0;
  for (const Body& b : all) {
    const auto& sp = spheresOf(b.id);
    Placed p{b.id, b.state.positionEcef, 0.0, offsets_.size(), sp.size()};
    for (const RepulsionSphere& s : sp) {
      offsets_.push_back(b.state.bodyToEcef(s.centreBody));
      radii_.push_back(s.radiusM);
      p.boundM = std::max(p.boundM, glm::length(s.centreBody) + s.radiusM);
    }
    maxBound = std::max(maxBound, p.boundM);
    placed_.push_back(p);
  }
  // Two bodies that can touch are closer than 2 maxBound: in neighbouring cells.
  cellM_ = std::max(2.0 * maxBound, 1.0);
  for (std::size_t i = 0; i < placed_.size(); ++i) cells_[cellKey(cellOf(placed_[i].positionEcef, cellM_))].push_back(std::uint32_t(i));
  step_ = sim.stepCount();
}

void Repulsion::accumulate(const Body& body, const StepContext&, Wrench& wrench) const {
  if (step_ != sim_->stepCount() || placed_.size() != sim_->bodies().size())
    throw std::logic_error("geocean::bodies: Repulsion::accumulate without beginStep (add it with addForceModel)");
  const auto it = std::lower_bound(placed_.begin(), placed_.end(), body.id,
                                   [](const Placed& p, BodyId v) { return p.id < v; });
  if (it == placed_.end() || it->id != body.id) return;
  const Placed& a = *it;
  const auto self = std::size_t(it - placed_.begin());
  const glm::i64vec3 home = cellOf(a.positionEcef, cellM_);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const auto cell = cells_.find(cellKey(home + glm::i64vec3(dx, dy, dz)));
        if (cell == cells_.end()) continue;
        for (const std::uint32_t j : cell->second) {
          if (j == self) continue;
          const Placed& b = placed_[j];
          // The difference of the centres first, in full precision; the
          // pair's other side computes exactly its negation.
          const glm::dvec3 ab = b.positionEcef - a.positionEcef;
          if (glm::dot(ab, ab) >= (a.boundM + b.boundM) * (a.boundM + b.boundM)) continue;
          for (std::size_t s = a.first; s < a.first + a.n; ++s)
            for (std::size_t t = b.first; t < b.first + b.n; ++t) {
              const glm::dvec3 d = ab + (offsets_[t] - offsets_[s]);
              const double dist = glm::length(d), overlap = radii_[s] + radii_[t] - dist;
              if (overlap <= 0.0 || dist <= 0.0) continue;
              wrench.addForceAtOffset(-stiffness_ * overlap / dist * d, offsets_[s]);
            }
        }
      }
}

}  // namespace geocean::bodies
