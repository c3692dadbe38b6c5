// The ocean as one C++ object: rasters (mask, elevation, mask encoding),
// the sea state, and every query. The C ABI (plugin/capi), the CLI
// (`geocean query`, `pick`, `demo`) and future bindings use this and
// nothing deeper of the plugin.
//
//   geocean::ocean::Ocean ocean;
//   ocean.setDefaultWorld(geocean::ocean::Ocean::defaultWorldDir());
//   ocean.setSeaState(geocean::waves::Model::Gerstner, sea);
//   const auto snap = ocean.current();          // one consistent state
//   snap->querySurface(points, outputs);         // on all cores (TBB)
//
// Thread safety: setters may run on any thread; they are serialised and
// publish a new immutable Snapshot. current() and every Snapshot query may
// run on any number of threads at once, also while a setter runs: a query
// sees the whole state before or after the setter, never a mix.
#pragma once

#include "globe/raster/Raster.h"
#include "globe/world/LayerStack.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/waves/CoastField.h"
#include "plugin/waves/SeaQuery.h"
#include "plugin/waves/WaveField.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <stdexcept>
#include <string>
#include <vector>

namespace geocean::ocean {

using world::LayerKind;
using world::RasterLayer;

// A query whose prerequisite is missing; `missing` says which, so a binding
// can name its own setter in the message.
class NotReady : public std::logic_error {
 public:
  enum class Missing { Rasters, Elevation, SeaState };
  explicit NotReady(Missing m);
  Missing missing;
};

// The points of a query: `count` latitudes and longitudes (degrees, WGS84)
// and times in seconds: one per point when timePerPoint, else timeS[0] for
// all. timeS may be null when no sea-surface output is asked for.
struct Points {
  const double* latDeg = nullptr;
  const double* lonDeg = nullptr;
  std::size_t count = 0;
  const double* timeS = nullptr;
  bool timePerPoint = false;
};

// What querySurface writes; every array may be null (then it is not
// computed unless another output needs it). Sea fields are NaN where the
// point is not ocean (land, lakes).
struct SurfaceOutputs {
  Surface* surface = nullptr;                 // count; written as bytes (memcpy), so uint8_t storage is fine
  float* elevationM = nullptr;                // count; terrain (m), NaN without elevation data
  double* heightM = nullptr;                  // count; sea surface above the ellipsoid exactly above the point
  double* normalEnu = nullptr;                // 3 x count; unit normal, east-north-up at the point
  double* verticalVelocityMps = nullptr;      // count; d(height)/dt at the fixed point
  double* horizontalVelocityEnMps = nullptr;  // 2 x count (east, north): velocity of the water particle now
                                              // at the surface above the point
  // The sea state at the point (waves::WaveField::seaStateAt at the query's
  // water depth): significant wave height (m), peak period (s), peak
  // wavelength (m) and the direction waves come FROM (degrees clockwise
  // from north). count each.
  double* hsM = nullptr;
  double* peakPeriodS = nullptr;
  double* peakWavelengthM = nullptr;
  double* waveFromDeg = nullptr;
  bool wantsSeaState() const { return hsM || peakPeriodS || peakWavelengthM || waveFromDeg; }
  bool wantsSea() const {
    return heightM || normalEnu || verticalVelocityMps || horizontalVelocityEnMps || wantsSeaState();
  }
};

// Classes for a batch of points, as the picker and the screen grid take them.
using Classifier = SurfaceClassifier;

// Everything a query reads, immutable once published. The renderer (the
// ABI's draw half) reads the members and compares snapshot pointers.
struct Snapshot {
  // The base rasters (the bundled world, or what setMask/setElevation/
  // setRasters gave), underneath every layer; maskEncoding is the base mask's.
  std::shared_ptr<const raster::Raster> baseMask, baseElevation;
  MaskEncoding maskEncoding;
  // The user's layers over the base (issue 12), as added.
  std::vector<RasterLayer> layers;
  // What the draw half builds the ocean's grids from: without layers the
  // base rasters; with layers the stack's drawingMask/drawingElevation
  // (globe/world/LayerStack.h), resampled through landSea.
  std::shared_ptr<const raster::Raster> mask, elevation;
  // Without layers a LandSea over the base; with layers a LayeredLandSea
  // (the first layer with data answers). Null without rasters.
  std::shared_ptr<const LandSea> landSea;
  std::shared_ptr<const waves::WaveField> waves;  // null without a sea state
  std::shared_ptr<const waves::SeaQuery> sea;     // the query path over landSea and waves
  waves::Model model = waves::Model::Noise;       // what `waves` was made from
  waves::SeaState seaState;
  // The near-shore region (Ocean::setCoastRegion): with a Gerstner sea
  // state and rasters, `waves` carries a coast field built from this
  // snapshot's water depth there (waves::CoastField), so queries take
  // depth-dependent phase and refraction inside it.
  std::optional<waves::CoastField::Region> coastRegion;
  // The coarse phase around it (waves::OuterPhase) when the region has no
  // deep inflow: built on the fixed lattice, kept by the follow builds
  // while their regions lie inside it (so they read the same phase), reset
  // when the rasters or the sea state change.
  std::shared_ptr<const waves::OuterPhase> coastOuter;

  // Nearest-cell class. Calling thread only. Throws NotReady without rasters.
  void classify(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const;
  // Terrain elevation (m, bilinear; NaN where no data). Calling thread only.
  // Throws NotReady without an elevation raster.
  void elevationAt(const double* latDeg, const double* lonDeg, std::size_t n, float* out) const;
  // Class, elevation and the sea surface in one pass, on all cores (TBB).
  // Without rasters every point is deep ocean (elevation NaN). Water depth
  // (Gerstner) is -elevation, at least 1 m where the mask says ocean.
  // Throws NotReady when a sea output is asked for without a sea state,
  // std::invalid_argument when its times are missing, not finite or outside
  // -1e12 .. 1e12 s (waves::kMaxTimeS; the message names the index).
  void querySurface(const Points& points, const SurfaceOutputs& out) const;
  // The same answers on the calling thread only (no TBB): for callers that
  // parallelise themselves over small batches (plugin/bodies, per body).
  void querySurfaceOnThisThread(const Points& points, const SurfaceOutputs& out) const;
  // Significant wave height (m) of the sea state's spectrum. Throws NotReady.
  double significantWaveHeightM() const;
  // For the picker: the classes of this snapshot (empty without rasters:
  // sea everywhere). Keeps the land/sea alive.
  Classifier classifier() const;

 private:
  void queryRange(const Points& p, std::size_t begin, std::size_t end, const SurfaceOutputs& out) const;
};

class Ocean {
 public:
  Ocean();
  ~Ocean();  // waits for a coast build in flight (followCoastRegion)
  Ocean(const Ocean&) = delete;
  Ocean& operator=(const Ocean&) = delete;

  // The default world's directory: $GEOCEAN_DATA if set, else what
  // `installedDir` returns if it is non-empty (the plugin looks beside its
  // installed library), else raster::dataDir() (beside the executable).
  static std::string defaultWorldDir(const std::function<std::string()>& installedDir = {});
  // The 5' mask and the 20' relief from `dir` (see defaultWorldDir), both
  // in one new snapshot. Throws raster::RasterError naming the file.
  void setDefaultWorld(const std::string& dir, const raster::OpenOptions& options = {});

  // Rasters from files (raster::OpenOptions: georeferencing, few lookups)
  // or already in memory (raster::Raster::fromPixels). A setter that throws
  // leaves the previous state.
  void setMaskFile(const std::string& path, const raster::OpenOptions& options = {});
  void setElevationFile(const std::string& path, const raster::OpenOptions& options = {});
  void setMask(std::shared_ptr<const raster::Raster> mask);
  void setElevation(std::shared_ptr<const raster::Raster> elevation);
  // Both at once (either may be null), one land/sea build.
  void setRasters(std::shared_ptr<const raster::Raster> mask, std::shared_ptr<const raster::Raster> elevation);
  void clearRasters();
  // The base mask's encoding (each layer has its own).
  void setMaskEncoding(const MaskEncoding& encoding);

  // Layers over the base rasters: at each point the first layer with data
  // answers, by higher priority, then finer cell, then order of adding; the
  // base rasters answer last (world::kDefaultWorldPriority). Masks classify
  // by their encoding, elevation layers by sign (below 0 m ocean), so a
  // user's relief finer than every mask decides land and sea there. Nodata
  // is per raster (raster::OpenOptions::nodata or the file's GDAL_NODATA).
  // Throws std::invalid_argument for a null raster, a priority at or below
  // kDefaultWorldPriority, or a layer of the same kind and path already in
  // the stack; the File forms raster::RasterError naming the file.
  void addMaskLayer(std::shared_ptr<const raster::Raster> mask, int priority = 0, const MaskEncoding& encoding = {});
  void addElevationLayer(std::shared_ptr<const raster::Raster> elevation, int priority = 0);
  void addMaskLayerFile(const std::string& path, int priority = 0, const MaskEncoding& encoding = {},
                        const raster::OpenOptions& options = {});
  void addElevationLayerFile(const std::string& path, int priority = 0, const raster::OpenOptions& options = {});
  // Removes the layers whose raster path (raster::Raster::path) is `path`;
  // returns how many (0: nothing changed).
  std::size_t removeLayer(const std::string& path);
  void clearLayers();

  // Builds the wave field; throws std::invalid_argument naming the field and
  // value of a bad sea state.
  void setSeaState(waves::Model model, const waves::SeaState& sea);
  void clearSeaState();
  // The region of interest of the near-shore phase field (Gerstner only;
  // rebuilt from the current rasters' depth whenever they or the sea state
  // change). Throws std::invalid_argument naming a bad field and value.
  void setCoastRegion(const waves::CoastField::Region& region);
  void clearCoastRegion();
  // The coast region follows a moving camera (issue 15 item 1). Call once
  // per frame with the camera's nadir, before the frame's queries and draw;
  // never waits for a build. When the nadir is outside the middle half of
  // the current region (more than a quarter of its size from the centre
  // along east or north), a region of the same size centred on the nadir
  // is built on a worker thread from the current snapshot; the old region
  // serves queries and drawing until then. A later call publishes the
  // finished build as one new snapshot (field and queries together), unless
  // any setter changed the snapshot meanwhile (then it is dropped and the
  // next call starts over). Hysteresis: the new centre is the nadir, so it
  // must move another quarter of the size before the next build.
  enum class CoastFollow {
    Off,       // no region, or no Gerstner sea or rasters: nothing to follow
    Inside,    // the nadir is in the middle half: nothing to do
    Started,   // a build started on the worker
    Building,  // a build is in flight: the old region stays
    Swapped,   // a finished build was published by this call
  };
  CoastFollow followCoastRegion(double nadirLatDeg, double nadirLonDeg);
  // Blocks until no build is in flight (tests, shutdown); the result waits
  // for the next followCoastRegion.
  void waitForCoastBuild();
  // How many follow builds were published (tests, the HUD).
  int coastSwaps() const;
  // Tests: run by the worker before it builds (e.g. to hold it there).
  void setCoastBuildHook(std::function<void()> hook);

  std::shared_ptr<const Snapshot> current() const;

 private:
  // Applies `edit` to a copy of the current snapshot, rebuilds what it
  // changed (land/sea only when rasters or encoding did) and publishes it.
  void update(const std::function<void(Snapshot&)>& edit);

  mutable std::mutex mutex_;  // guards snapshot_ (the pointer, not its contents)
  std::mutex editMutex_;      // serialises setters so no edit is lost
  std::shared_ptr<const Snapshot> snapshot_;

  // followCoastRegion's worker and its result (guarded by followMutex_).
  mutable std::mutex followMutex_;
  std::condition_variable followDone_;
  std::thread worker_;
  bool building_ = false;
  int swaps_ = 0;
  std::shared_ptr<const Snapshot> ready_, readyFrom_;  // the build and the snapshot it was made from
  std::function<void()> buildHook_;
};

}  // namespace geocean::ocean
