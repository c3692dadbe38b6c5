#include "globe/render/GlobeRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

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
  sky_ = GlProgram::graphics("sky.vert", "sky.frag");
  glCreateVertexArrays(1, &emptyVao_);
}

double GlobeRenderer::altitudeAboveSurfaceM(const ViewPose& pose) const {
  const double water = world_->waterAt(pose.latDeg, pose.lonDeg);
  const double ground = water > 0.5 ? 0.0
                                    : std::max(0.0, double(world_->elevationAt(pose.latDeg, pose.lonDeg))) *
                                          terrain_.options().exaggeration;
  return pose.altM - ground;
}

ViewMatrices GlobeRenderer::matrices(const ViewPose& pose) const {
  return viewMatrices(pose, altitudeAboveSurfaceM(pose));
}

FrameTimes GlobeRenderer::render(const ViewPose& pose, const FrameSettings& settings) {
  FrameTimes t;
  const auto t0 = Clock::now();
  const double c0 = cpuMs();
  const ViewMatrices vm = matrices(pose);
  const Lighting light{glm::normalize(settings.sunEcef), settings.timeS};

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
    const glm::vec3 f(vm.forward), r(vm.right), u(vm.up), sun(light.sunEcef), eyeDir(glm::normalize(vm.eyeEcef));
    const double tanY = std::tan(0.5 * pose.fovYDeg * 3.14159265358979323846 / 180.0);
    glUniform3fv(sky_.uniform("uForward"), 1, &f[0]);
    glUniform3fv(sky_.uniform("uRight"), 1, &r[0]);
    glUniform3fv(sky_.uniform("uUp"), 1, &u[0]);
    glUniform2f(sky_.uniform("uTanHalf"), float(tanY * pose.width / pose.height), float(tanY));
    glUniform3fv(sky_.uniform("uSunDir"), 1, &sun[0]);
    glUniform3fv(sky_.uniform("uEyeDir"), 1, &eyeDir[0]);
    glUniform1f(sky_.uniform("uEyeRadiusM"), float(glm::length(vm.eyeEcef)));
    glBindVertexArray(emptyVao_);
    // The sky writes no data attachment (tests read the ocean's there).
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  glDepthMask(GL_TRUE);
  if (settings.timed) glFinish();
  t.skyMs = msSince(ts);
  t.skyCpuMs = cpuMs() - cs;

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  ts = Clock::now();
  cs = cpuMs();
  glDisable(GL_CULL_FACE);
  // The terrain shades water as distant sea where the wave grid does not
  // draw (cells it skips as land can hold lakes and coast); open water that
  // the ocean layer will cover can get only depth (TerrainOptions::seaProxy).
  t.terrain = terrain_.draw(vm, pose, light, settings.bare,
                            layers_.empty() ? SeaShading::DistantSea : SeaShading::UnderOcean);
  if (settings.timed) glFinish();
  t.terrainMs = msSince(ts);
  t.terrainCpuMs = cpuMs() - cs;

  ts = Clock::now();
  cs = cpuMs();
  for (auto& l : layers_) l->draw(vm, pose, light, settings.bare);
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
