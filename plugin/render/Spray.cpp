#include "plugin/render/Spray.h"

#include "globe/geo/Ellipsoid.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geocean::ocean_render {

Spray::Spray() : program_(gl::GlProgram::graphics("spray.vert", "spray.frag", {"WV_MODEL 1", "WV_COAST 1"})) {
  glCreateVertexArrays(1, &vao_);  // no attributes: gl_VertexID is the site
}

Spray::~Spray() {
  if (vao_) glDeleteVertexArrays(1, &vao_);
}

void Spray::draw(const camera::Camera& cam, const glm::dvec3& originEcef, double latDeg, double lonDeg, double timeS,
                 int waveCount, const glm::vec4& elevationGeo, const glm::dvec3& sunEcef) const {
  // Metres per degree at the nadir (finite differences, double), and the
  // lattice's steps in degrees fixed per whole degree of latitude so the
  // sites stay on the ground as the eye moves.
  auto perDeg = [](double lat, double lon, double dLat, double dLon) {
    const glm::dvec3 a = geo::toEcef({lat - 0.5 * dLat, lon - 0.5 * dLon, 0.0});
    const glm::dvec3 b = geo::toEcef({lat + 0.5 * dLat, lon + 0.5 * dLon, 0.0});
    return glm::length(b - a) / (dLat + dLon);
  };
  const double latRef = std::round(latDeg);
  // A whole number of sites round the parallel: the lattice (and spray.vert's
  // seed, its index modulo lonSites) is the same on both sides of 180 deg.
  const int lonSites = int(std::max(1L, std::lround(360.0 * perDeg(latRef, 0.0, 0.0, 1e-3) / kSpacingM)));
  const double stepLon = 360.0 / lonSites;
  const double stepLat = kSpacingM / perDeg(latRef, 0.0, 1e-3, 0.0);
  const double mLon = perDeg(latDeg, lonDeg, 0.0, 1e-3), mLat = perDeg(latDeg, lonDeg, 1e-3, 0.0);
  const geo::EnuFrame enu = geo::enuFrame({latDeg, lonDeg, 0.0});
  const glm::dvec3 east = enu.east, north = enu.north;
  const double uLon = lonDeg / stepLon, uLat = latDeg / stepLat;
  const double iLon = std::floor(uLon), iLat = std::floor(uLat);
  program_.use();
  const glm::vec3 eyeMinusO(cam.eyeEcef() - originEcef), eastF(east), northF(north), sun(sunEcef);
  glUniformMatrix4fv(program_.uniform("uViewProj"), 1, GL_FALSE, &cam.gpu().viewProj[0][0]);
  glUniform3fv(program_.uniform("uEyeMinusOrigin"), 1, &eyeMinusO[0]);
  glUniform1i(program_.uniform("uWaveCount"), waveCount);
  glUniform3fv(program_.uniform("uSunDir"), 1, &sun[0]);
  // 3600 s is a whole number of spray.vert's periods (1 s).
  glUniform1f(program_.uniform("uTimeS"), float(std::fmod(timeS, 3600.0)));
  glUniform1i(program_.uniform("uSprayN"), kSites);
  glUniform1i(program_.uniform("uSprayLonSites"), lonSites);
  glUniform1f(program_.uniform("uEyeAltM"), float(geo::fromEcef(cam.eyeEcef()).heightM));
  // Reduced here: GLSL's % is undefined for negative operands.
  const long long baseLon = (static_cast<long long>(iLon) - kSites / 2) % lonSites;
  glUniform2i(program_.uniform("uSprayBase"), int(baseLon < 0 ? baseLon + lonSites : baseLon), int(iLat) - kSites / 2);
  glUniform2f(program_.uniform("uSprayFrac"), float(uLon - iLon), float(uLat - iLat));
  glUniform2f(program_.uniform("uSprayCellM"), float(stepLon * mLon), float(stepLat * mLat));
  // The nadir's elevation texture coordinates in double, its longitude
  // within 180 deg of the raster's centre (raster::lonNear's rule; the
  // texture repeats in longitude).
  const glm::dvec4 geoD(elevationGeo);
  const double lonR = lonDeg + 360.0 * std::round((geoD.x + 0.5 * geoD.z - lonDeg) / 360.0);
  glUniform2f(program_.uniform("uSprayCellUv"), float(stepLon / geoD.z), float(stepLat / geoD.w));
  glUniform2f(program_.uniform("uOriginUv"), float((lonR - geoD.x) / geoD.z), float((latDeg - geoD.y) / geoD.w));
  glUniform3fv(program_.uniform("uEast"), 1, &eastF[0]);
  glUniform3fv(program_.uniform("uNorth"), 1, &northF[0]);
  const double pxPerRad = cam.heightPx() / (2.0 * std::tan(0.5 * cam.vfovDeg() * std::numbers::pi / 180.0));
  glUniform1f(program_.uniform("uPxPerRad"), float(pxPerRad));
  // Over the sea, blended, behind what is nearer, writing no depth and
  // only the colour attachment (the host's data target keeps the sea's).
  GLboolean depthMask = GL_TRUE, dataMask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
  glGetBooleani_v(GL_COLOR_WRITEMASK, 1, dataMask);
  const GLboolean blend = glIsEnabled(GL_BLEND), pointSize = glIsEnabled(GL_PROGRAM_POINT_SIZE);
  glDepthMask(GL_FALSE);
  glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunci(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_POINTS, 0, kSites * kSites);
  glDepthMask(depthMask);
  glColorMaski(1, dataMask[0], dataMask[1], dataMask[2], dataMask[3]);
  if (!blend) glDisable(GL_BLEND);
  if (!pointSize) glDisable(GL_PROGRAM_POINT_SIZE);
}

}  // namespace geocean::ocean_render
