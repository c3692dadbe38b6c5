// The sea of the ocean façade (plugin/ocean): the surface the renderer draws
// and `geocean query` prints, for the bodies' forces. Target
// geocean_bodies_ocean (geocean_bodies itself stays free of the waves).
#pragma once

#include "plugin/bodies/Sea.h"
#include "plugin/bodies/Terrain.h"
#include "plugin/ocean/Ocean.h"

#include <memory>

namespace geocean::bodies {

class OceanSea final : public SeaSurface {
 public:
  // Reads one immutable snapshot (a later setter on the Ocean is not seen:
  // make a new OceanSea from ocean.current()). Without a sea state the sea is
  // flat at height 0 where the snapshot says ocean (everywhere without
  // rasters); land and lakes have no sea (NaN) either way.
  explicit OceanSea(std::shared_ptr<const ocean::Snapshot> snapshot);
  void sample(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n, bool velocities,
              SeaSample* out) const override;
  // 2 pi / the spectrum's peak wavelength (0 without waves): the decay of
  // the dominant waves' pressure; shorter components decay faster than this
  // in reality, so their pressure at depth is overestimated.
  double decayWaveNumberPerM() const override { return k_; }
  // Heights, vertical velocities and slopes (from the façade's normals).
  void sampleSlopes(const double* latDeg, const double* lonDeg, const double* tS, std::size_t n,
                    SeaSample* out) const override;
  // Gerstner: 2 pi / the largest component wave number (its phase is set
  // at the reference depth; the local depth changes only amplitudes and
  // orbits). 0 (every vertex queried) for the other models, without waves
  // (the coastline is the only detail: a grid would blur it) and with a
  // coast field (refraction shortens the waves over the shelf).
  double shortestWavelengthM() const override { return shortest_; }
  const ocean::Snapshot& snapshot() const { return *snap_; }

 private:
  std::shared_ptr<const ocean::Snapshot> snap_;
  double k_ = 0.0, shortest_ = 0.0;
};

// A terrain patch for TerrainContact from the snapshot's elevation (the
// layer stack: the first layer with data answers, bilinear), n x n vertices
// spacingM apart in the ENU frame at `southWest` (height 0): each vertex is
// the ground at the latitude and longitude of the ENU point, placed at its
// height in the patch frame (the ellipsoid's drop, 2 cm at 500 m, is kept;
// the horizontal shift of a point z above the tangent plane is
// z * distance / R, under 1 mm for 10 m at 500 m). Throws
// std::invalid_argument without an elevation, or where it has no data.
std::shared_ptr<HeightField> terrainPatch(const ocean::Snapshot& snapshot, const geo::Geodetic& southWest, int n,
                                          double spacingM);

// Terrain contact that follows a body (geocean float and the C ABI's
// bodies): a patch of the snapshot's elevation 400 m square at 2 m cells
// centred on the body. The caller re-centres it (a new contact) once
// nearPatchEdge says the body is within 100 m of the edge, checking at
// least every simulated second: a body faster than 100 m/s could leave the
// patch between checks. Throws as terrainPatch does.
std::shared_ptr<TerrainContact> terrainContactAround(const ocean::Snapshot& snapshot, const BodyState& state,
                                                     std::vector<glm::dvec3> contactPointsBody,
                                                     double frictionCoefficient);
bool nearPatchEdge(const TerrainContact& contact, const BodyState& state);
// Wet sand on a hull (TerrainContact's note, Engineering ToolBox 0.4-0.6).
constexpr double kWetSandFriction = 0.5;

}  // namespace geocean::bodies
