// Screen and ray picking through Embree 3: one scene holds the sea (a user
// geometry for the WGS84 ellipsoid, present where the classifier says
// ocean) and an instance of the terrain scene (globe/terrain: the elevation
// raster as a triangle mesh), so a pick returns the first hit on terrain or sea.
//
// Embree works in single precision: at Earth scale that alone is metres of
// error. The scene is built relative to a local origin (the camera or the
// first ray), and every hit is refined in double: sea hits by
// geo::intersectEllipsoid (within 1 mm of the exact root, grazing rays and
// origins inside the ellipsoid included), terrain hits by a double
// ray/triangle test on the triangle Embree found.
// Thread-safety: pick/pickBatch are const and may run concurrently.
#pragma once

#include "globe/raster/Raster.h"
#include "globe/terrain/TerrainMesh.h"
#include "plugin/landsea/LandSea.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace geocean::pick {

enum class HitKind : std::uint8_t { None, Sea, Terrain };

struct PickResult {
  bool hit = false;
  HitKind kind = HitKind::None;
  double latDeg = 0.0, lonDeg = 0.0, heightM = 0.0;  // geodetic position of the hit
  double distanceM = 0.0;                             // from the ray origin
  glm::dvec3 pointEcef{0.0};
  ocean::Surface surface = ocean::Surface::Ocean;  // sea: Ocean; terrain: Land or Lake
};

// ECEF origin and a direction of any length > 0.
using PickRay = terrain::Ray;

class Picker {
 public:
  // elevation: terrain raster in metres (nullptr: sea only). classifier:
  // where the sea surface exists (nullptr: everywhere) and lake vs land for
  // terrain hits. localOriginEcef: where float precision is best.
  // Throws std::runtime_error with Embree's message if the device or scene fails.
  Picker(std::shared_ptr<const raster::Raster> elevation, ocean::SurfaceClassifier classifier,
         const glm::dvec3& localOriginEcef);
  // For a few known rays (a CLI pick): the terrain mesh holds only the
  // raster cells these rays pass over while within the raster's height
  // range (plus one cell around; terrain::cellsAlong), built from the same
  // vertices and triangles as the whole-raster scene, so these rays get the
  // same answers at a fraction of the build time (the world's 1.2 M
  // triangles take ~1 s). Other rays may miss terrain. Falls back to the
  // whole raster if the rays cross too many cells.
  Picker(std::shared_ptr<const raster::Raster> elevation, ocean::SurfaceClassifier classifier,
         const glm::dvec3& localOriginEcef, const std::vector<PickRay>& onlyAlong);
  ~Picker();
  Picker(const Picker&) = delete;
  Picker& operator=(const Picker&) = delete;

  // Rays with a zero or non-finite direction or origin return hit = false.
  PickResult pick(const PickRay& ray) const;
  // Packets of 16 (rtcIntersect16) over TBB threads.
  void pickBatch(const PickRay* rays, std::size_t n, PickResult* out) const;

  std::size_t terrainTriangles() const;

 private:
  Picker(std::shared_ptr<const raster::Raster> elevation, ocean::SurfaceClassifier classifier,
         const glm::dvec3& localOriginEcef, const std::vector<PickRay>* onlyAlong);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace geocean::pick
