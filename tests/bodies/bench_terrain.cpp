// Terrain collision figures (issue 14 item 3): 100 boxes (2 x 1 x 1 m, 8
// corner contact points) thrown at 50 m/s, 10-80 degrees down, onto a
// 512 x 512 height field (2 m cells) with dt = 1/30, 90 steps; the same
// scene and start states in plugin/bodies (TerrainContact) and in Bullet
// 3.24 (btHeightfieldTerrainShape with the same cell diagonal, btBoxShape;
// discrete, and with continuous collision detection). Bullet is used here
// only, never by the product. Penetration is measured for both against the
// same exact triangulated surface (HeightField::heightAt).
#include "plugin/bodies/Simulation.h"
#include "plugin/bodies/Terrain.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <glm/gtc/quaternion.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

using namespace geocean;
using namespace geocean::bodies;

namespace {
constexpr int kN = 512, kBodies = 100, kSteps = 90;
constexpr double kS = 2.0, kDt = 1.0 / 30;
const glm::dvec3 kHalf(1.0, 0.5, 0.5);

struct Start {
  glm::dvec3 p, v;
};

struct Figures {
  long steps = 0, penetrating = 0, penetrating1cm = 0;
  double maxDepth = 0, seconds = 0;
  int tunnelled = 0;
};

// One body-step's corners against the surface.
void measure(const HeightField& T, const std::vector<glm::dvec3>& cornersEnu, Figures& f) {
  bool below = false, below1cm = false;
  for (const auto& q : cornersEnu) {
    const double d = T.heightAt(q.x, q.y) - q.z;
    if (d > 1e-6) below = true;
    if (d > 0.01) below1cm = true;
    if (d > f.maxDepth) f.maxDepth = d;
  }
  ++f.steps;
  f.penetrating += below;
  f.penetrating1cm += below1cm;
}

void print(const char* name, const Figures& f, int bodies = kBodies) {
  std::printf("| %s | %.4f | %.4f | %.3f | %d / %d | %.2f |\n", name, double(f.penetrating) / f.steps,
              double(f.penetrating1cm) / f.steps, f.maxDepth, f.tunnelled,
              bodies, 1e6 * f.seconds / f.steps);
}

// bruteForce: the reference, every sweep against every triangle.
Figures runOurs(const std::shared_ptr<HeightField>& T, const std::vector<Start>& starts, bool bruteForce = false) {
  Simulation sim({.stepS = kDt});
  std::vector<glm::dvec3> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back(c & 1 ? kHalf.x : -kHalf.x, c & 2 ? kHalf.y : -kHalf.y, c & 4 ? kHalf.z : -kHalf.z);
  auto contact = std::make_shared<TerrainContact>(T, corners);
  contact->setBruteForce(bruteForce);
  std::vector<BodyId> ids;
  for (const auto& s0 : starts) {
    BodyState s;
    s.positionEcef = T->frame().originEcef + T->frame().toEcef(s0.p);
    s.velocityEcef = T->frame().toEcef(s0.v);
    s.orientation = glm::quat_cast(T->frame().rotation());
    ids.push_back(sim.addBody(MassProperties::box(1000.0, 2.0 * kHalf), s));
    sim.addBodyConstraint(ids.back(), contact);
  }
  Figures f;
  std::vector<glm::dvec3> q(8);
  for (int k = 0; k < kSteps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.step();
    f.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (BodyId id : ids) {
      const BodyState& s = sim.body(id).state;
      for (int c = 0; c < 8; ++c) q[c] = T->toPatch(s.positionEcef + s.bodyToEcef(corners[c]));
      measure(*T, q, f);
    }
  }
  for (BodyId id : ids) {
    const glm::dvec3 c = T->toPatch(sim.body(id).state.positionEcef);
    if (c.z < T->heightAt(c.x, c.y) - 0.5) ++f.tunnelled;  // centre under the surface by more than the half-height
  }
  return f;
}

Figures runBullet(const HeightField& T, const std::vector<double>& heights, const std::vector<Start>& starts, bool ccd) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, btScalar(-9.80)));
  double lo = 1e300, hi = -1e300;
  for (double h : heights) lo = std::min(lo, h), hi = std::max(hi, h);
  std::vector<float> hf(heights.begin(), heights.end());
  // flipQuadEdges: cells split along (i, j)-(i+1, j+1), as HeightField does.
  btHeightfieldTerrainShape ground(kN, kN, hf.data(), btScalar(lo), btScalar(hi), 2, true);
  ground.setLocalScaling(btVector3(btScalar(kS), btScalar(kS), 1));
  btTransform gt;
  gt.setIdentity();
  gt.setOrigin(btVector3(btScalar((kN - 1) * kS / 2), btScalar((kN - 1) * kS / 2), btScalar((lo + hi) / 2)));
  btRigidBody groundBody(0, nullptr, &ground);
  groundBody.setWorldTransform(gt);
  world.addRigidBody(&groundBody);
  btBoxShape box(btVector3(btScalar(kHalf.x), btScalar(kHalf.y), btScalar(kHalf.z)));
  btVector3 inertia;
  box.calculateLocalInertia(1000, inertia);
  std::vector<std::unique_ptr<btDefaultMotionState>> motion;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  for (const auto& s0 : starts) {
    btTransform t;
    t.setIdentity();
    t.setOrigin(btVector3(btScalar(s0.p.x), btScalar(s0.p.y), btScalar(s0.p.z)));
    motion.push_back(std::make_unique<btDefaultMotionState>(t));
    bodies.push_back(std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(1000, motion.back().get(), &box, inertia)));
    bodies.back()->setLinearVelocity(btVector3(btScalar(s0.v.x), btScalar(s0.v.y), btScalar(s0.v.z)));
    if (ccd) {
      bodies.back()->setCcdMotionThreshold(btScalar(0.5));
      bodies.back()->setCcdSweptSphereRadius(btScalar(0.4));
    }
    world.addRigidBody(bodies.back().get());
  }
  Figures f;
  std::vector<glm::dvec3> q(8);
  for (int k = 0; k < kSteps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    world.stepSimulation(btScalar(kDt), 0);
    f.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (auto& b : bodies) {
      const btTransform& t = b->getWorldTransform();
      for (int c = 0; c < 8; ++c) {
        const btVector3 p = t * btVector3(btScalar(c & 1 ? kHalf.x : -kHalf.x), btScalar(c & 2 ? kHalf.y : -kHalf.y),
                                          btScalar(c & 4 ? kHalf.z : -kHalf.z));
        q[c] = {p.x(), p.y(), p.z()};
      }
      measure(T, q, f);
    }
  }
  for (auto& b : bodies) {
    const btVector3 c = b->getWorldTransform().getOrigin();
    if (c.z() < T.heightAt(c.x(), c.y()) - 0.5) ++f.tunnelled;
  }
  for (auto& b : bodies) world.removeRigidBody(b.get());
  world.removeRigidBody(&groundBody);
  return f;
}
}  // namespace

int main() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  std::vector<double> h(std::size_t(kN) * kN);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i)
      h[std::size_t(j) * kN + i] = 20 * std::sin(i / 37.0) * std::cos(j / 23.0) + 5 * std::sin(i / 7.0 + j / 11.0) + jitter(rng);
  auto T = std::make_shared<HeightField>(geo::Geodetic{46.5, 8.0, 0.0}, kN, kN, kS, h);
  std::uniform_real_distribution<double> pos(150.0, kN * kS - 150.0), ang(0.0, 2 * M_PI), dip(0.17, 1.4);
  std::vector<Start> starts;
  for (int b = 0; b < kBodies; ++b) {
    const double x = pos(rng), y = pos(rng), az = ang(rng), el = dip(rng);
    starts.push_back({{x, y, T->heightAt(x, y) + 3.0},
                      50.0 * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el))});
  }
  std::printf("| %d boxes, 50 m/s, dt 1/30, %d steps | penetration rate (> 1 um) | (> 1 cm) | max depth (m) | tunnelled | us per body-step |\n"
              "|---|---|---|---|---|---|\n", kBodies, kSteps);
  print("plugin/bodies TerrainContact (swept cell walk)", runOurs(T, starts));
  // The reference tests all 524,288 triangles per sweep (~1,000x the
  // walk's work): on the first 10 bodies, beside the walk on the same 10.
  const std::vector<Start> ten(starts.begin(), starts.begin() + 10);
  print("the same, first 10 bodies", runOurs(T, ten), int(ten.size()));
  print("brute force (every triangle per sweep), first 10 bodies", runOurs(T, ten, true), int(ten.size()));
  print("Bullet 3.24, discrete", runBullet(*T, h, starts, false));
  print("Bullet 3.24, CCD (swept sphere 0.4 m)", runBullet(*T, h, starts, true));
}
