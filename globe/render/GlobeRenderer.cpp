#include "globe/render/GlobeRenderer.h"

#include "globe/geo/Ellipsoid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <vector>

namespace geocean::render {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
double cpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}
}  // namespace

GlobeRenderer::GlobeRenderer(std::shared_ptr<const WorldTextures> world, TerrainOptions terrain)
    : world_(std::move(world)), terrain_(*world_, terrain) {
  sky_ = gl::GlProgram::graphics("sky.vert", "sky.frag");
  glCreateVertexArrays(1, &emptyVao_);
}

GlobeRenderer::~GlobeRenderer() {
  glDeleteVertexArrays(1, &emptyVao_);
  if (shadowFbo_) glDeleteFramebuffers(1, &shadowFbo_);
  if (shadowDepth_) glDeleteTextures(1, &shadowDepth_);
}

bool shadowView(const camera::Camera& cam, const glm::dvec3& sunEcef, ShadowView& out) {
  const glm::dvec3 up = geo::surfaceNormal(cam.latDeg(), cam.lonDeg());
  const glm::dvec3 sun = glm::normalize(sunEcef);
  const double sinSun = glm::dot(sun, up), h = cam.heightM();
  if (sinSun <= 0.0 || h >= kShadowReachMaxM) return false;
  const double reach = std::clamp(kShadowReachPerHeight * std::max(h, 0.0), kShadowReachMinM, kShadowReachMaxM);
  // The sea the view sees within the reach, on the tangent plane at the
  // nadir (relative to the eye): the nadir and where the rays through the
  // screen's corners and edge midpoints meet the plane, or their points at
  // the reach brought down onto it.
  std::vector<glm::dvec3> pts{-h * up};
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      const glm::dvec3 r = glm::normalize(cam.rayThroughNdc(i, j));
      const double down = -glm::dot(r, up);
      const double t = down > 0.0 ? std::min(h / down, reach) : reach;
      const glm::dvec3 p = t * r;
      pts.push_back(p - (glm::dot(p, up) + h) * up);
    }
  // The light's axes: z towards the sun, x level.
  glm::dvec3 lx = glm::cross(sun, up);
  lx = glm::dot(lx, lx) > 1e-12 ? glm::normalize(lx) : glm::normalize(glm::cross(sun, glm::dvec3(0.0, 0.0, 1.0)));
  const glm::dvec3 ly = glm::cross(sun, lx);
  glm::dvec3 lo(1e30), hi(-1e30);
  for (const glm::dvec3& p : pts) {
    const glm::dvec3 q(glm::dot(p, lx), glm::dot(p, ly), glm::dot(p, sun));
    lo = glm::min(lo, q), hi = glm::max(hi, q);
  }
  // 5 % margins across (the reach's arc bulges past the chords between the
  // rays' points); in depth from 200 m under the sea (troughs, hulls' keels)
  // up to the highest terrain (9 km) towards the sun.
  const glm::dvec2 pad = 0.05 * glm::dvec2(hi - lo) + 10.0;
  lo.x -= pad.x, hi.x += pad.x, lo.y -= pad.y, hi.y += pad.y;
  lo.z -= 200.0, hi.z += 9000.0;
  glm::dmat4 rot(1.0);
  for (int i = 0; i < 3; ++i) rot[i][0] = lx[i], rot[i][1] = ly[i], rot[i][2] = sun[i];
  glm::dmat4 ortho(1.0);
  ortho[0][0] = 2.0 / (hi.x - lo.x), ortho[3][0] = -(hi.x + lo.x) / (hi.x - lo.x);
  ortho[1][1] = 2.0 / (hi.y - lo.y), ortho[3][1] = -(hi.y + lo.y) / (hi.y - lo.y);
  ortho[2][2] = 1.0 / (hi.z - lo.z), ortho[3][2] = -lo.z / (hi.z - lo.z);
  out.matrix = ortho * rot;
  out.reachM = reach;
  // The region casters may stand in: the covered sea widened towards the
  // sun by a 1 km high caster's shadow (at most 20 km).
  const double cosSun = std::sqrt(std::max(0.0, 1.0 - sinSun * sinSun));
  const double widen = std::min(1000.0 * cosSun / std::max(sinSun, 1e-3), 20000.0) + 100.0;
  double lat0 = 90.0, lat1 = -90.0, lon0 = 1e9, lon1 = -1e9;
  const glm::dvec3 sunLevel = glm::length(sun - sinSun * up) > 1e-9 ? glm::normalize(sun - sinSun * up) : glm::dvec3(0.0);
  for (const glm::dvec3& p : pts)
    for (double w : {0.0, widen}) {
      const geo::Geodetic g = geo::fromEcef(cam.eyeEcef() + p + w * sunLevel);
      double lon = g.lonDeg;
      if (lon - cam.lonDeg() > 180.0) lon -= 360.0;
      if (lon - cam.lonDeg() < -180.0) lon += 360.0;
      lat0 = std::min(lat0, g.latDeg), lat1 = std::max(lat1, g.latDeg);
      lon0 = std::min(lon0, lon), lon1 = std::max(lon1, lon);
    }
  out.region[0] = lat0, out.region[1] = lat1, out.region[2] = lon0, out.region[3] = lon1;
  return true;
}

void GlobeRenderer::makeShadowMap(const camera::Camera& cam, const camera::Lighting& light, const Layer* waterLayer,
                                  LayerInputs& in, FrameTimes& t) {
  ShadowView sv;
  if (!shadowView(cam, light.sunEcef, sv)) return;
  // Nothing can cast onto the sea in view: no scene object and open water
  // all over the region (the layer's own answer, as the terrain asks it).
  if (objects_.empty() && waterLayer &&
      waterLayer->coversOpaquely(sv.region[0], sv.region[1], sv.region[2], sv.region[3], 1.0))
    return;
  const auto ts = Clock::now();
  const double cs = cpuMs();
  if (!shadowDepth_) {
    glCreateTextures(GL_TEXTURE_2D, 1, &shadowDepth_);
    glTextureStorage2D(shadowDepth_, 1, GL_DEPTH_COMPONENT32F, kShadowMapSize, kShadowMapSize);
    glTextureParameteri(shadowDepth_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(shadowDepth_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(shadowDepth_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(shadowDepth_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glCreateFramebuffers(1, &shadowFbo_);
    glNamedFramebufferTexture(shadowFbo_, GL_DEPTH_ATTACHMENT, shadowDepth_, 0);
    glNamedFramebufferDrawBuffer(shadowFbo_, GL_NONE);
    glNamedFramebufferReadBuffer(shadowFbo_, GL_NONE);
  }
  GLint target = 0, viewport[4] = {};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  glGetIntegerv(GL_VIEWPORT, viewport);
  glBindFramebuffer(GL_FRAMEBUFFER, shadowFbo_);
  glViewport(0, 0, kShadowMapSize, kShadowMapSize);
  glClearDepth(0.0);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDisable(GL_CULL_FACE);
  const glm::mat4 m(sv.matrix);
  terrain_.drawDepth(m, cam, waterLayer, sv.region);
  for (const auto& o : objects_) o->drawDepth(m, cam.eyeEcef());
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  in.shadowDepth = shadowDepth_;
  in.shadowSize = kShadowMapSize;
  in.shadowMatrix = sv.matrix;
  in.shadowOriginEcef = cam.eyeEcef();
  in.shadowReachM = sv.reachM;
  t.shadowDrawn = true;
  if (settingsTimed_) glFinish();
  t.shadowMs = msSince(ts);
  t.shadowCpuMs = cpuMs() - cs;
}

double GlobeRenderer::altitudeAboveSurfaceM(const camera::ViewPose& pose) const {
  const double water = world_->waterAt(pose.latDeg, pose.lonDeg);
  const double ground = water > 0.5 ? 0.0
                                    : std::max(0.0, double(world_->elevationAt(pose.latDeg, pose.lonDeg))) *
                                          terrain_.options().exaggeration;
  return pose.altM - ground;
}

camera::Camera GlobeRenderer::camera(const camera::ViewPose& pose) const {
  return camera::Camera::fromView(pose, altitudeAboveSurfaceM(pose));
}

void GlobeRenderer::drawScene(const camera::Camera& cam, const camera::Lighting& light, const FrameSettings& settings,
                              FrameTimes& t, const Layer* waterLayer, SeaShading sea,
                              const camera::Camera* mirroredFrom) {
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glClearDepth(0.0);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  // Sky first, over the whole screen, without depth: what the terrain and
  // the ocean leave uncovered, or cover only in part (the ocean's
  // anti-aliased shoreline, faded by the coverage's mipmap at the horizon,
  // over land the terrain does not draw there), blends with the sky, not
  // with the clear colour (black dots along the horizon from 2 m).
  auto ts = Clock::now();
  double cs = cpuMs();
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  if (!settings.bare) {
    sky_.use();
    const glm::vec3 f(cam.forward()), r(cam.right()), u(cam.up()), sun(light.sunEcef),
        eyeDir(glm::normalize(cam.eyeEcef()));
    const double tanY = std::tan(0.5 * cam.vfovDeg() * 3.14159265358979323846 / 180.0);
    glUniform3fv(sky_.uniform("uForward"), 1, &f[0]);
    glUniform3fv(sky_.uniform("uRight"), 1, &r[0]);
    glUniform3fv(sky_.uniform("uUp"), 1, &u[0]);
    glUniform2f(sky_.uniform("uTanHalf"), float(tanY * cam.widthPx() / cam.heightPx()), float(tanY));
    glUniform3fv(sky_.uniform("uSunDir"), 1, &sun[0]);
    glUniform3fv(sky_.uniform("uEyeDir"), 1, &eyeDir[0]);
    glUniform1f(sky_.uniform("uEyeRadiusM"), float(glm::length(cam.eyeEcef())));
    glBindVertexArray(emptyVao_);
    // The sky writes no data attachment (tests read the ocean's there).
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  glDepthMask(GL_TRUE);
  if (settings.timed) glFinish();
  t.skyMs += msSince(ts);
  t.skyCpuMs += cpuMs() - cs;

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  ts = Clock::now();
  cs = cpuMs();
  glDisable(GL_CULL_FACE);
  t.terrain = mirroredFrom ? terrain_.drawMirrored(cam, *mirroredFrom, light)
                           : terrain_.draw(cam, light, settings.bare, sea, waterLayer);
  for (const auto& o : objects_) o->draw(cam, light, settings.bare, mirroredFrom);
  if (settings.timed) glFinish();
  t.terrainMs += msSince(ts);
  t.terrainCpuMs += cpuMs() - cs;
}

void GlobeRenderer::makeLayerInputs(const camera::Camera& cam, const camera::Lighting& light,
                                    const FrameSettings& settings, unsigned wants, LayerInputs& in,
                                    FrameTimes& t) {
  const int w = cam.widthPx(), h = cam.heightPx();
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  if (wants & kLayerWantsSceneCopy) {
    sceneCopy_.ensure(w, h);
    // Colour attachment 0 and depth of whatever the host draws into.
    glNamedFramebufferReadBuffer(GLuint(target), target == 0 ? GL_BACK : GL_COLOR_ATTACHMENT0);
    glBlitNamedFramebuffer(GLuint(target), sceneCopy_.fbo(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBlitNamedFramebuffer(GLuint(target), sceneCopy_.fbo(), 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    in.sceneColor = sceneCopy_.color();
    in.sceneDepth = sceneCopy_.depth();
  }
  if (wants & kLayerWantsReflection) {
    // The eye mirrored in the sea-level plane under it sees what the sea
    // reflects. It is a proper camera (right = -mirror(right)), so its image
    // is the mirror's flipped left-right: layers project mirrored points
    // with its matrices rather than reuse screen positions.
    const glm::dvec3 n = geo::surfaceNormal(cam.latDeg(), cam.lonDeg());
    const auto mirror = [&](const glm::dvec3& v) { return v - 2.0 * glm::dot(v, n) * n; };
    const glm::dvec3 eye = cam.eyeEcef() - 2.0 * cam.heightM() * n;
    int rw = w, rh = h;
    if (settings.reflectionSize > 0) {
      // The same field of view at another resolution (layers project with
      // this camera's own matrices, so its size is all they need).
      const double scale = double(settings.reflectionSize) / double(std::max(w, h));
      rw = std::max(1, int(std::lround(w * scale)));
      rh = std::max(1, int(std::lround(h * scale)));
    }
    // Reused while younger than reflectionEvery frames and of the same size.
    if (reflectionCamera_ && ++reflectionAge_ < std::max(settings.reflectionEvery, 1) &&
        rw == reflectionCamera_->widthPx() && rh == reflectionCamera_->heightPx() &&
        settings.reflectionEvery == reflectionEvery_) {
      in.reflectionCamera = *reflectionCamera_;
      in.reflectionColor = reflection_.color();
      return;
    }
    in.reflectionCamera = camera::Camera::fromEcef(eye, mirror(cam.forward()), mirror(cam.up()), cam.vfovDeg(), rw, rh,
                                                   cam.heightM());
    reflectionCamera_ = in.reflectionCamera;
    reflectionAge_ = 0, reflectionEvery_ = settings.reflectionEvery;
    t.reflectionDrawn = true;
    reflection_.ensure(rw, rh);
    // At the viewport's size the map is read about 1:1 (nearest, as it
    // always was); resized, it is resampled: bilinear, not blocks.
    const GLint filter = settings.reflectionSize > 0 ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(reflection_.color(), GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(reflection_.color(), GL_TEXTURE_MAG_FILTER, filter);
    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);
    glBindFramebuffer(GL_FRAMEBUFFER, reflection_.fbo());
    glViewport(0, 0, rw, rh);
    FrameTimes scratch;
    const auto ts = Clock::now();
    const double cs = cpuMs();
    drawScene(in.reflectionCamera, light, settings, scratch, nullptr, SeaShading::None, &cam);
    if (settings.timed) glFinish();
    t.reflectionMs = msSince(ts);
    t.reflectionCpuMs = cpuMs() - cs;
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    in.reflectionColor = reflection_.color();
  }
}

FrameTimes GlobeRenderer::render(const camera::ViewPose& pose, const FrameSettings& settings) {
  FrameTimes t;
  const auto t0 = Clock::now();
  const double c0 = cpuMs();
  const camera::Camera cam = camera(pose);
  const camera::Lighting light{glm::normalize(settings.sunEcef), settings.timeS};
  for (const auto& o : objects_) o->update(settings.timeS);

  // The terrain shades water as distant sea where the wave grid does not
  // draw (cells it skips as land can hold lakes and coast); open water that
  // a layer covers opaquely is left to it (TerrainOptions::skipOpenWater).
  const Layer* waterLayer = nullptr;
  unsigned wants = 0;
  for (const auto& l : layers_) {
    const LayerInfo info = l->info();
    if (info.opaqueWater && !waterLayer) waterLayer = l.get();
    wants |= info.wants;
  }
  drawScene(cam, light, settings, t, waterLayer, layers_.empty() ? SeaShading::DistantSea : SeaShading::UnderOcean);

  auto ts = Clock::now();
  double cs = cpuMs();
  LayerInputs inputs;
  inputs.refraction = settings.refraction;
  if (!settings.reflections || cam.heightM() >= kReflectionReachM) {
    wants &= ~kLayerWantsReflection;
    reflectionCamera_.reset();  // a map from before would be stale when the pass resumes
  }
  inputs.shadowModel = settings.shadowModel;
  inputs.sunModel = settings.sunModel;
  if (!settings.shadows) wants &= ~kLayerWantsShadowMap;
  settingsTimed_ = settings.timed;
  if ((wants & kLayerWantsShadowMap) && !settings.bare) makeShadowMap(cam, light, waterLayer, inputs, t);
  wants &= ~kLayerWantsShadowMap;
  if (wants && !settings.bare) makeLayerInputs(cam, light, settings, wants, inputs, t);
  for (auto& l : layers_) l->draw(cam, light, settings.bare, inputs);
  if (settings.timed) glFinish();
  t.layersMs = msSince(ts);
  t.layersCpuMs = cpuMs() - cs;
  glBindVertexArray(0);
  glUseProgram(0);
  if (settings.timed) glFinish();
  t.totalMs = msSince(t0);
  t.totalCpuMs = cpuMs() - c0;
  return t;
}

}  // namespace geocean::render
