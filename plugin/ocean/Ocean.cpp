#include "plugin/ocean/Ocean.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/geo/Parallel.h"
#include "globe/raster/World.h"
#include "plugin/landsea/LayeredLandSea.h"
#include "plugin/waves/TimeRange.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <utility>

namespace geocean::ocean {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* missingText(NotReady::Missing m) {
  switch (m) {
    case NotReady::Missing::Rasters: return "no mask or elevation raster";
    case NotReady::Missing::Elevation: return "no elevation raster";
    case NotReady::Missing::SeaState: return "no sea state";
  }
  return "not ready";
}

// Every time of a sea query finite and within waves::kMaxTimeS (the
// bindings check first, naming their own field; this is the façade's own
// guarantee for C++ callers).
void checkTimes(const Points& p) {
  for (std::size_t i = 0, n = p.timePerPoint ? p.count : 1; i < n; ++i) {
    if (waves::timeInRange(p.timeS[i])) continue;
    char b[40];
    const auto r = std::to_chars(b, b + sizeof b, p.timeS[i]);
    throw std::invalid_argument("sea-surface query: timeS[" + std::to_string(i) + "] " + std::string(b, r.ptr) +
                                (std::isfinite(p.timeS[i]) ? std::string(" s is outside ") + waves::kTimeRangeText
                                                           : std::string(" is not finite")));
  }
}

// The velocity (east, north) of the particle that is now at the surface
// above each point: the wave kernel's own analytic particle velocity
// (Gerstner: a omega per component; FFT: the dDx/dt, dDy/dt tables; the
// noise models move particles vertically only, so it is 0) evaluated at the
// particle's rest point, which the height's surface inversion found
// (restOffsetEnuM). Ocean points only.
void horizontalVelocities(const waves::WaveField& field, const double* latDeg, const double* lonDeg,
                          const double* tS, const double* depthM, const glm::dvec3* restOffsetEnuM, std::size_t n,
                          double* outEn) {
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 off = restOffsetEnuM[i];
    double restLat = latDeg[i], restLon = lonDeg[i];
    if (off != glm::dvec3(0.0)) {
      const geo::EnuFrame f = geo::enuFrame({latDeg[i], lonDeg[i], 0.0});
      const geo::Geodetic rest = geo::fromEcef(f.originEcef + f.toEcef(off));
      restLat = rest.latDeg;
      restLon = rest.lonDeg;
    }
    const glm::dvec3 v = field.sample(restLat, restLon, tS[i], depthM[i]).horizontalVelocityEnuMps;
    outEn[2 * i] = v.x;
    outEn[2 * i + 1] = v.y;
  }
}

}  // namespace

NotReady::NotReady(Missing m) : std::logic_error(missingText(m)), missing(m) {}

// ---- Snapshot ---------------------------------------------------------------

void Snapshot::classify(const double* latDeg, const double* lonDeg, std::size_t n, Surface* out) const {
  if (!landSea) throw NotReady(NotReady::Missing::Rasters);
  landSea->classifyBatch(latDeg, lonDeg, n, out);
}

void Snapshot::elevationAt(const double* latDeg, const double* lonDeg, std::size_t n, float* out) const {
  if (!elevation) throw NotReady(NotReady::Missing::Elevation);
  landSea->elevationBatch(latDeg, lonDeg, n, out);
}

double Snapshot::significantWaveHeightM() const {
  if (!waves) throw NotReady(NotReady::Missing::SeaState);
  return waves->spectrumHsM();
}

Classifier Snapshot::classifier() const { return landSea ? classifierFor(landSea) : Classifier(); }

void Snapshot::querySurface(const Points& p, const SurfaceOutputs& out) const {
  if (out.wantsSea() && !sea) throw NotReady(NotReady::Missing::SeaState);
  if (p.count == 0) return;
  if (out.wantsSea() && !p.timeS) throw std::invalid_argument("sea-surface query: timeS is null");
  if (out.wantsSea()) checkTimes(p);
  // Blocks as `geocean query` had them: large enough that the per-block
  // set-up vanishes, small enough to balance 2..N cores on 10 k points.
  constexpr std::size_t kGrain = 4096;
  geo::parallelFor(tbb::blocked_range<std::size_t>(0, p.count, kGrain),
                   [&](const tbb::blocked_range<std::size_t>& r) { queryRange(p, r.begin(), r.end(), out); });
}

void Snapshot::querySurfaceOnThisThread(const Points& p, const SurfaceOutputs& out) const {
  if (out.wantsSea() && !sea) throw NotReady(NotReady::Missing::SeaState);
  if (p.count == 0) return;
  if (out.wantsSea() && !p.timeS) throw std::invalid_argument("sea-surface query: timeS is null");
  if (out.wantsSea()) checkTimes(p);
  queryRange(p, 0, p.count, out);
}

void Snapshot::queryRange(const Points& p, std::size_t begin, std::size_t end, const SurfaceOutputs& out) const {
  constexpr std::size_t kChunk = 256;
  std::array<Surface, kChunk> cls;
  std::array<float, kChunk> elev;
  std::array<waves::SeaQueryResult, kChunk> res;
  std::array<double, kChunk> oLat, oLon, oT, oDepth;
  std::array<std::size_t, kChunk> oIdx;
  std::array<glm::dvec3, kChunk> oRest;
  const bool wantSea = out.wantsSea();
  const bool wantElevation = out.elevationM || (wantSea && elevation);
  for (std::size_t i0 = begin; i0 < end; i0 += kChunk) {
    const std::size_t m = std::min(kChunk, end - i0);
    const double* lat = p.latDeg + i0;
    const double* lon = p.lonDeg + i0;
    Surface* c = cls.data();
    if (landSea)
      landSea->classifyBatch(lat, lon, m, c);
    else
      std::fill(c, c + m, Surface::Ocean);
    // Bytes, not Surface stores: a binding may hand uint8_t storage (the C ABI does).
    if (out.surface) std::memcpy(out.surface + i0, c, m * sizeof(Surface));
    float* e = out.elevationM ? out.elevationM + i0 : elev.data();
    if (wantElevation) {
      if (landSea)
        landSea->elevationBatch(lat, lon, m, e);
      else
        std::fill(e, e + m, std::numeric_limits<float>::quiet_NaN());
    }
    if (!wantSea) continue;
    const double* t = p.timePerPoint ? p.timeS + i0 : p.timeS;
    // Off the globe (|lat| > 90, |lon| > 360, NaN: a host may pass
    // anything): the class as classified, the sea NaN and never evaluated.
    // Near DBL_MAX degrees the radians overflow and the kernel saw a NaN
    // point (fuzz finding 7: UB converting its FFT cell to int).
    std::array<Surface, kChunk> onGlobe;
    bool offGlobe = false;
    for (std::size_t k = 0; k < m; ++k) {
      const bool on = std::abs(lat[k]) <= 90.0 && std::abs(lon[k]) <= 360.0;
      onGlobe[k] = on ? c[k] : Surface::Land;
      offGlobe |= !on;
    }
    sea->queryClassified(lat, lon, t, p.timePerPoint, m, offGlobe ? onGlobe.data() : c, wantElevation ? e : nullptr,
                         res.data());
    std::size_t nOcean = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = i0 + k;
      const waves::SeaQueryResult& r = res[k];
      const bool water = r.surface == Surface::Ocean;
      if (out.heightM) out.heightM[i] = r.seaHeightM;
      if (out.normalEnu) {
        out.normalEnu[3 * i] = water ? r.normalEnu.x : kNaN;
        out.normalEnu[3 * i + 1] = water ? r.normalEnu.y : kNaN;
        out.normalEnu[3 * i + 2] = water ? r.normalEnu.z : kNaN;
      }
      if (out.verticalVelocityMps) out.verticalVelocityMps[i] = water ? r.verticalVelocityMps : kNaN;
      if (out.wantsSeaState()) {
        waves::LocalSeaState st;
        st.hsM = st.peakPeriodS = st.peakWavelengthM = st.waveFromDeg = kNaN;
        if (water) st = sea->field().seaStateAt(lat[k], lon[k], r.depthM);
        if (out.hsM) out.hsM[i] = st.hsM;
        if (out.peakPeriodS) out.peakPeriodS[i] = st.peakPeriodS;
        if (out.peakWavelengthM) out.peakWavelengthM[i] = st.peakWavelengthM;
        if (out.waveFromDeg) out.waveFromDeg[i] = st.waveFromDeg;
      }
      if (out.horizontalVelocityEnMps) {
        out.horizontalVelocityEnMps[2 * i] = out.horizontalVelocityEnMps[2 * i + 1] = kNaN;
        if (water) {
          oLat[nOcean] = lat[k], oLon[nOcean] = lon[k], oT[nOcean] = p.timePerPoint ? t[k] : t[0];
          oDepth[nOcean] = r.depthM, oIdx[nOcean] = i, oRest[nOcean] = r.restOffsetEnuM;
          ++nOcean;
        }
      }
    }
    if (nOcean == 0) continue;
    std::array<double, 2 * kChunk> v;
    horizontalVelocities(sea->field(), oLat.data(), oLon.data(), oT.data(), oDepth.data(), oRest.data(), nOcean,
                         v.data());
    for (std::size_t k = 0; k < nOcean; ++k) {
      out.horizontalVelocityEnMps[2 * oIdx[k]] = v[2 * k];
      out.horizontalVelocityEnMps[2 * oIdx[k] + 1] = v[2 * k + 1];
    }
  }
}

// ---- Ocean ------------------------------------------------------------------

Ocean::Ocean() : snapshot_(std::make_shared<Snapshot>()) {}

Ocean::~Ocean() {
  if (worker_.joinable()) worker_.join();
}

std::string Ocean::defaultWorldDir(const std::function<std::string()>& installedDir) {
  if (const char* env = std::getenv("GEOCEAN_DATA"); env && *env) return env;
  if (installedDir)
    if (std::string d = installedDir(); !d.empty()) return d;
  return raster::dataDir();
}

void Ocean::setDefaultWorld(const std::string& dir, const raster::OpenOptions& options) {
  // The file names of raster::defaultWorld(), in `dir`.
  auto mask = raster::Raster::open(dir + "/landmask_5m.tif", options);
  auto elevation = raster::Raster::open(dir + "/etopo_20m.tif", options);
  setRasters(std::move(mask), std::move(elevation));
}

void Ocean::setMaskFile(const std::string& path, const raster::OpenOptions& options) {
  setMask(raster::Raster::open(path, options));
}

void Ocean::setElevationFile(const std::string& path, const raster::OpenOptions& options) {
  setElevation(raster::Raster::open(path, options));
}

void Ocean::setMask(std::shared_ptr<const raster::Raster> mask) {
  update([&](Snapshot& s) { s.baseMask = std::move(mask); });
}

void Ocean::setElevation(std::shared_ptr<const raster::Raster> elevation) {
  update([&](Snapshot& s) { s.baseElevation = std::move(elevation); });
}

void Ocean::setRasters(std::shared_ptr<const raster::Raster> mask, std::shared_ptr<const raster::Raster> elevation) {
  update([&](Snapshot& s) {
    s.baseMask = std::move(mask);
    s.baseElevation = std::move(elevation);
  });
}

namespace {
void addLayer(RasterLayer l, const std::function<void(const std::function<void(Snapshot&)>&)>& update) {
  const char* kind = world::toString(l.kind);
  if (!l.raster) throw std::invalid_argument(std::string(kind) + " layer: no raster");
  if (l.priority <= world::kDefaultWorldPriority)
    throw std::invalid_argument(l.raster->path() + ": " + kind + " layer priority " + std::to_string(l.priority) +
                                " is not above the default world's (" + std::to_string(world::kDefaultWorldPriority) +
                                ")");
  update([&](Snapshot& s) {
    for (const RasterLayer& o : s.layers)
      if (o.kind == l.kind && o.raster->path() == l.raster->path())
        throw std::invalid_argument(l.raster->path() + ": already a " + kind + " layer");
    s.layers.push_back(std::move(l));
  });
}
}  // namespace

void Ocean::addMaskLayer(std::shared_ptr<const raster::Raster> mask, int priority, const MaskEncoding& encoding) {
  addLayer({LayerKind::Mask, std::move(mask), encoding, priority}, [this](const auto& e) { update(e); });
}

void Ocean::addElevationLayer(std::shared_ptr<const raster::Raster> elevation, int priority) {
  addLayer({LayerKind::Elevation, std::move(elevation), {}, priority}, [this](const auto& e) { update(e); });
}

void Ocean::addMaskLayerFile(const std::string& path, int priority, const MaskEncoding& encoding,
                             const raster::OpenOptions& options) {
  addMaskLayer(raster::Raster::open(path, options), priority, encoding);
}

void Ocean::addElevationLayerFile(const std::string& path, int priority, const raster::OpenOptions& options) {
  addElevationLayer(raster::Raster::open(path, options), priority);
}

std::size_t Ocean::removeLayer(const std::string& path) {
  std::size_t removed = 0;
  update([&](Snapshot& s) {
    const auto before = s.layers.size();
    std::erase_if(s.layers, [&](const RasterLayer& l) { return l.raster->path() == path; });
    removed = before - s.layers.size();
  });
  return removed;
}

void Ocean::clearLayers() {
  update([](Snapshot& s) { s.layers.clear(); });
}

void Ocean::clearRasters() { setRasters(nullptr, nullptr); }

void Ocean::setMaskEncoding(const MaskEncoding& encoding) {
  update([&](Snapshot& s) { s.maskEncoding = encoding; });
}

void Ocean::setSeaState(waves::Model model, const waves::SeaState& sea) {
  std::string error;
  auto field = waves::WaveField::create(model, sea, error);
  if (!field) throw std::invalid_argument(error);
  auto shared = std::make_shared<const waves::WaveField>(std::move(*field));
  update([&](Snapshot& s) {
    s.waves = std::move(shared);
    s.model = model;
    s.seaState = sea;
  });
}

void Ocean::setCoastRegion(const waves::CoastField::Region& region) {
  // Validate now (a 1-component deep sea), so a bad region throws here.
  std::string error;
  waves::SeaState probe;
  probe.gerstnerComponents = 1;
  const auto w = waves::WaveField::create(waves::Model::Gerstner, probe, error);
  if (waves::CoastField::build(*w, region, [](double, double) { return 1e4; }, error).empty())
    throw std::invalid_argument(error);
  update([&](Snapshot& s) { s.coastRegion = region; });
}

void Ocean::clearCoastRegion() {
  update([](Snapshot& s) { s.coastRegion.reset(); });
}

void Ocean::clearSeaState() {
  update([](Snapshot& s) { s.waves.reset(); });
}

std::shared_ptr<const Snapshot> Ocean::current() const {
  std::lock_guard lock(mutex_);
  return snapshot_;
}

namespace {
// The coast field from a snapshot's water depth over a region (as the
// query's: -elevation where the mask says ocean, 0 on land). Throws
// std::invalid_argument naming a bad region.
// The water depth (m) at (east, north) of the tangent plane at (latDeg,
// lonDeg), as the query's: -elevation where the mask says ocean, 0 on land.
std::function<double(double, double)> depthAbout(const std::shared_ptr<const LandSea>& ls, double latDeg,
                                                 double lonDeg) {
  const geo::EnuFrame f = geo::enuFrame({latDeg, lonDeg, 0.0});
  return [ls, f](double e, double n) {
    const geo::Geodetic g = geo::fromEcef(f.originEcef + f.east * e + f.north * n);
    Surface c;
    ls->classifyBatch(&g.latDeg, &g.lonDeg, 1, &c);
    if (c != Surface::Ocean) return 0.0;
    float el = std::numeric_limits<float>::quiet_NaN();
    ls->elevationBatch(&g.latDeg, &g.lonDeg, 1, &el);
    return std::isnan(el) ? waves::kDeepWaterM : std::max(-double(el), 1.0);
  };
}

// The coast field from a snapshot's water depth over a region. `outer`:
// the outer phase to read if a component has no deep inflow; kept if it
// covers the region, else (re)built at the lattice point nearest the
// region's centre. Throws std::invalid_argument naming a bad region.
std::shared_ptr<const waves::CoastField> buildCoastField(const Snapshot& s, const waves::CoastField::Region& r,
                                                         std::shared_ptr<const waves::OuterPhase>& outer) {
  auto outerFor = [&]() -> const waves::OuterPhase* {
    const double halfM = 0.5 * r.cellM * (r.nodes - 1);
    if (outer && outer->covers(geo::toEcef({r.latDeg, r.lonDeg, 0.0}), halfM)) return outer.get();
    double lat = 0.0, lon = 0.0;
    waves::OuterPhase::latticePoint(r.latDeg, r.lonDeg, lat, lon);
    std::string error;
    auto built = std::make_shared<const waves::OuterPhase>(
        waves::OuterPhase::build(*s.waves, lat, lon, depthAbout(s.landSea, lat, lon), error));
    outer = built->empty() ? nullptr : std::move(built);
    return outer.get();
  };
  std::string error;
  auto coast = std::make_shared<const waves::CoastField>(
      waves::CoastField::build(*s.waves, r, depthAbout(s.landSea, r.latDeg, r.lonDeg), error, outerFor));
  if (coast->empty()) throw std::invalid_argument(error);
  return coast;
}
}  // namespace

void Ocean::update(const std::function<void(Snapshot&)>& edit) {
  std::lock_guard editLock(editMutex_);
  const std::shared_ptr<const Snapshot> prev = current();
  auto next = std::make_shared<Snapshot>(*prev);
  edit(*next);
  auto sameLayers = [](const std::vector<RasterLayer>& a, const std::vector<RasterLayer>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const RasterLayer& x, const RasterLayer& y) {
      return x.kind == y.kind && x.raster == y.raster && x.priority == y.priority &&
             x.encoding.classOf == y.encoding.classOf;
    });
  };
  const bool rastersChanged = next->baseMask != prev->baseMask || next->baseElevation != prev->baseElevation ||
                              next->maskEncoding.classOf != prev->maskEncoding.classOf ||
                              !sameLayers(next->layers, prev->layers);
  if (rastersChanged && next->layers.empty()) {
    next->mask = next->baseMask;
    next->elevation = next->baseElevation;
    next->landSea = next->mask || next->elevation
                        ? std::make_shared<const LandSea>(next->mask, next->elevation, next->maskEncoding)
                        : nullptr;
  } else if (rastersChanged) {
    std::vector<RasterLayer> all = next->layers;
    if (next->baseMask)
      all.push_back({LayerKind::Mask, next->baseMask, next->maskEncoding, world::kDefaultWorldPriority});
    if (next->baseElevation)
      all.push_back({LayerKind::Elevation, next->baseElevation, {}, world::kDefaultWorldPriority});
    auto layered = std::make_shared<const LayeredLandSea>(std::move(all));
    next->mask = layered->stack().drawingMask();
    next->elevation = layered->stack().drawingElevation();
    next->landSea = std::move(layered);
  }
  const bool coastChanged = !(next->coastRegion.has_value() == prev->coastRegion.has_value() &&
                              (!next->coastRegion || (next->coastRegion->latDeg == prev->coastRegion->latDeg &&
                                                      next->coastRegion->lonDeg == prev->coastRegion->lonDeg &&
                                                      next->coastRegion->cellM == prev->coastRegion->cellM &&
                                                      next->coastRegion->nodes == prev->coastRegion->nodes &&
                                                      next->coastRegion->margin == prev->coastRegion->margin &&
                                                      next->coastRegion->islandRadiusM ==
                                                          prev->coastRegion->islandRadiusM &&
                                                      next->coastRegion->breaking == prev->coastRegion->breaking)));
  if (rastersChanged || next->waves != prev->waves) next->coastOuter.reset();  // another depth or sea
  if (next->waves && next->model == waves::Model::Gerstner &&
      (rastersChanged || coastChanged || next->waves != prev->waves)) {
    std::shared_ptr<const waves::CoastField> coast;
    if (next->coastRegion && next->landSea) coast = buildCoastField(*next, *next->coastRegion, next->coastOuter);
    if (coast || next->waves->coastField()) {
      auto copy = std::make_shared<waves::WaveField>(*next->waves);
      copy->setCoast(coast);
      next->waves = std::move(copy);
    }
  }
  if (rastersChanged || next->waves != prev->waves)
    next->sea = next->waves ? std::make_shared<const waves::SeaQuery>(*next->waves, next->landSea) : nullptr;
  std::lock_guard lock(mutex_);
  snapshot_ = std::move(next);
}

Ocean::CoastFollow Ocean::followCoastRegion(double nadirLatDeg, double nadirLonDeg) {
  std::unique_lock follow(followMutex_);
  bool swapped = false;
  if (ready_) {
    // Publish the finished build if nothing changed since it started (the
    // lock order is followMutex_ then editMutex_, as nowhere else takes both).
    std::lock_guard edit(editMutex_);
    if (current() == readyFrom_) {
      std::lock_guard lock(mutex_);
      snapshot_ = std::move(ready_);
      ++swaps_;
      swapped = true;
    }
    ready_.reset();
    readyFrom_.reset();
  }
  if (building_) return CoastFollow::Building;
  const std::shared_ptr<const Snapshot> snap = current();
  if (!snap->coastRegion || !snap->waves || snap->model != waves::Model::Gerstner || !snap->landSea ||
      !snap->waves->coastField())
    return CoastFollow::Off;
  // The nadir in the region's tangent plane (the grid's own frame).
  const waves::CoastField& field = *snap->waves->coastField();
  const glm::dvec3 p = geo::toEcef({nadirLatDeg, nadirLonDeg, 0.0}) - field.centreEcef();
  const waves::CoastField::Region region = *snap->coastRegion;
  const double quarter = 0.25 * region.cellM * (region.nodes - 1);
  if (std::abs(glm::dot(p, field.east())) <= quarter && std::abs(glm::dot(p, field.north())) <= quarter)
    return swapped ? CoastFollow::Swapped : CoastFollow::Inside;
  if (worker_.joinable()) worker_.join();  // finished: building_ was false
  waves::CoastField::Region next = region;
  next.latDeg = nadirLatDeg;
  next.lonDeg = nadirLonDeg;
  building_ = true;
  worker_ = std::thread([this, snap, next, hook = buildHook_] {
    std::shared_ptr<const Snapshot> built;
    try {
      if (hook) hook();
      auto s = std::make_shared<Snapshot>(*snap);
      s->coastRegion = next;
      auto copy = std::make_shared<waves::WaveField>(*snap->waves);
      copy->setCoast(buildCoastField(*snap, next, s->coastOuter));
      s->waves = std::move(copy);
      s->sea = std::make_shared<const waves::SeaQuery>(*s->waves, s->landSea);
      built = std::move(s);
    } catch (const std::exception&) {
      // The nadir's region is as valid as the old one (same size, finite
      // place); a failure (out of memory) leaves the old region in use.
    }
    std::lock_guard lock(followMutex_);
    ready_ = std::move(built);
    readyFrom_ = ready_ ? snap : nullptr;
    building_ = false;
    followDone_.notify_all();
  });
  return swapped ? CoastFollow::Swapped : CoastFollow::Started;
}

void Ocean::waitForCoastBuild() {
  std::unique_lock lock(followMutex_);
  followDone_.wait(lock, [&] { return !building_; });
}

int Ocean::coastSwaps() const {
  std::lock_guard lock(followMutex_);
  return swaps_;
}

void Ocean::setCoastBuildHook(std::function<void()> hook) {
  std::lock_guard lock(followMutex_);
  buildHook_ = std::move(hook);
}

}  // namespace geocean::ocean
