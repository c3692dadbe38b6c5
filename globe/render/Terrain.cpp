#include "globe/render/Terrain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geocean::render {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr int kEdge = TerrainRenderer::kGrid + 2;  // with the skirt ring
constexpr int kVertsPerTile = kEdge * kEdge;
constexpr int kFloatsPerVertex = 9;  // local xyz, normal xyz, lon, lat, skirt
// Flat tiles (Key::flat): from this level on, every kFlatStep-th grid line
// (8 x 8 cells: level 9's are level 7's 32 x 32).
constexpr int kFlatLevel = 9;
constexpr int kFlatStep = 4;
static_assert((TerrainRenderer::kGrid - 1) % kFlatStep == 0 &&
              (TerrainRenderer::kGrid - 1) / kFlatStep << (kFlatLevel - 7) == TerrainRenderer::kGrid - 1);
// Highest and lowest terrain on Earth (Everest 8849 m, Challenger Deep 10935 m), with margin.
constexpr double kMaxTerrainM = 9000.0;
constexpr double kMinTerrainM = -11000.0;
// Texels the water/elevation filters read past a terrain tile's edge in
// its pyramid level (the B-spline's 2 and a skirt's).
constexpr double kReach = 3.0;

// The pyramid level a terrain tile `cellsAcross` level-0 texels wide asks
// for: the finest whose 2 x 2 tiles hold it and the filters' reach.
int blockLevel(const raster::TilePyramid& pyr, double cellsAcross) {
  int want = 0;
  while (want < pyr.levels() - 1 && cellsAcross / double(1 << want) + 2.0 * kReach + 1.0 > pyr.tileSize()) ++want;
  return want;
}
}  // namespace

glm::dvec3 sunFromSubsolar(double latDeg, double lonDeg) { return geo::surfaceNormal(latDeg, lonDeg); }

glm::dvec3 sunFromLocal(double latDeg, double lonDeg, double azimuthDeg, double elevationDeg) {
  const geo::EnuFrame f = geo::enuFrame({latDeg, lonDeg, 0.0});
  const double az = azimuthDeg * kDeg, el = elevationDeg * kDeg;
  return glm::normalize(f.toEcef({std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)}));
}

std::string TerrainRenderer::imageryDefine() const {
  return "GEOCEAN_IMAGERY_LAYERS " + std::to_string(world_.imageryLayers());
}

TerrainRenderer::TerrainRenderer(const WorldTextures& world, TerrainOptions options)
    : world_(world), options_(options) {
  if (options_.poolTiles < 64) throw std::invalid_argument("terrain pool must hold at least 64 tiles");
  maxLevel_ = options_.maxLevel;
  double texelDeg = world_.finestShapeTexelDeg();
  for (int w = 0; w < world_.waterTileLayers(); ++w)  // the streamed masks' own texels
    texelDeg = std::min(texelDeg, std::abs(world_.waterTiles(w)->pyramid().source().transform().lonStepDeg));
  for (int e = 0; e < world_.elevationTileLayers(); ++e)  // the streamed reliefs'
    texelDeg = std::min(texelDeg, std::abs(world_.elevationTiles(e)->pyramid().source().transform().lonStepDeg));
  while (maxLevel_ > 0 && texelDeg > 0.0 && 90.0 / double(1 << (maxLevel_ - 1)) / (kGrid - 1) <= texelDeg / 16.0)
    --maxLevel_;
  if (world_.waterTileLayers() == 1 && world_.waterTiles()->pyramid().source().transform().global)
    fineWater_ = std::make_unique<world::TileWaterIndex>(world_.waterTiles()->sharedPyramid());
  // Streamed water (WorldTextures::waterTiles): the same programs reading the tile pool.
  const auto with = [&](std::vector<std::string> d) {
    d.push_back(imageryDefine());
    if (world_.waterTiles()) d.push_back("GEOCEAN_WATER_TILES 1");
    if (world_.elevationTiles()) d.push_back("GEOCEAN_ELEVATION_TILES 1");
    // A regional pyramid falls through to the grid (geo_uv.glsl).
    if (world_.waterTiles() && !world_.waterTiles()->pyramid().source().transform().global)
      d.push_back("GEOCEAN_WATER_REGIONAL 1");
    if (world_.elevationTiles() && !world_.elevationTiles()->pyramid().source().transform().global)
      d.push_back("GEOCEAN_ELEVATION_REGIONAL 1");
    if (world_.waterTileLayers() > 1) d.push_back("GEOCEAN_WATER_TILES_LAYERS " + std::to_string(world_.waterTileLayers()));
    if (world_.elevationTileLayers() > 1)
      d.push_back("GEOCEAN_ELEVATION_TILES_LAYERS " + std::to_string(world_.elevationTileLayers()));
    return d;
  };
  // Under an ocean layer too: the ocean draws a streamed mask's coast from
  // the same pyramid (plugin/render/WaterPages), so the two agree.
  program_ = gl::GlProgram::graphics("terrain.vert", "terrain.frag", with({}));
  underOcean_ = gl::GlProgram::graphics("terrain.vert", "terrain.frag", with({"GEOCEAN_UNDER_OCEAN 1"}));
  seaProxy_ = gl::GlProgram::graphics("terrain.vert", "sea_proxy.frag");
  bare_ = gl::GlProgram::graphics("terrain.vert", "bare.frag", {"GEOCEAN_BARE 1"});
  depthDefines_ = with({"GEOCEAN_DEPTH_ONLY 1", "GEOCEAN_CLIP_SEA 1"});
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glNamedBufferStorage(vbo_, GLsizeiptr(options_.poolTiles) * kVertsPerTile * kFloatsPerVertex * sizeof(float),
                       nullptr, GL_DYNAMIC_STORAGE_BIT);
  std::vector<std::uint32_t> idx;
  for (int j = 0; j + 1 < kEdge; ++j)
    for (int i = 0; i + 1 < kEdge; ++i) {
      const std::uint32_t a = j * kEdge + i, b = a + 1, c = a + kEdge, d = c + 1;
      idx.insert(idx.end(), {a, c, b, b, c, d});
    }
  indexCount_ = GLsizei(idx.size());
  // Flat tiles (water throughout: -seaDrop on the ellipsoid) at level >=
  // kFlatLevel: every kFlatStep-th grid line and the skirt ring. Their
  // cells are no larger than level 7's (2.4 km), where open water already
  // stops (refines), and the chord sag over them is <= 0.12 m.
  std::vector<int> lines = {0};
  for (int g = 0; g < kGrid; g += kFlatStep) lines.push_back(g + 1);
  lines.push_back(kEdge - 1);
  for (std::size_t j = 0; j + 1 < lines.size(); ++j)
    for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
      const std::uint32_t a = lines[j] * kEdge + lines[i], b = lines[j] * kEdge + lines[i + 1],
                          c = lines[j + 1] * kEdge + lines[i], d = lines[j + 1] * kEdge + lines[i + 1];
      idx.insert(idx.end(), {a, c, b, b, c, d});
    }
  flatIndexCount_ = GLsizei(idx.size()) - indexCount_;
  glCreateBuffers(1, &ibo_);
  glNamedBufferStorage(ibo_, GLsizeiptr(idx.size() * sizeof(std::uint32_t)), idx.data(), 0);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, kFloatsPerVertex * sizeof(float));
  glVertexArrayElementBuffer(vao_, ibo_);
  const int sizes[] = {3, 3, 2, 1};
  int offset = 0;
  for (int a = 0; a < 4; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, sizes[a], GL_FLOAT, GL_FALSE, offset * sizeof(float));
    glVertexArrayAttribBinding(vao_, a, 0);
    offset += sizes[a];
  }
  for (int s = options_.poolTiles - 1; s >= 0; --s) freeSlots_.push_back(s);
}

TerrainRenderer::~TerrainRenderer() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
}

void TerrainRenderer::tileRange(const Key& k, double& lat0, double& lat1, double& lon0, double& lon1) const {
  const double span = 90.0 / double(1 << k.level);
  lon0 = -180.0 + k.x * span;
  lon1 = lon0 + span;
  lat1 = 90.0 - k.y * span;
  lat0 = lat1 - span;
}

TerrainRenderer::Bounds TerrainRenderer::bounds(const Key& k) const {
  double lat0, lat1, lon0, lon1;
  tileRange(k, lat0, lat1, lon0, lon1);
  Bounds b;
  b.center = geo::toEcef({0.5 * (lat0 + lat1), 0.5 * (lon0 + lon1), 0.0});
  // Water throughout: every water texel the tile's bilinear samples reach
  // (one texel around it) is water, from the exact any-land index; 9 x 9
  // samples missed an island between them and capped its LOD at level 7.
  // Over a regional streamed mask the grid's index is the layers' below
  // it: the mask's own index must agree, over the reach of the level the
  // tile reads (whose texels past the mask's edge or at its nodata read the
  // grid at their centres: that far into the grid too).
  const world::WaterIndex& wi = world_.waterIndex();
  double gridMargin = 1.0;
  bool regional = false, regionalLand = false;
  // Each streamed layer's own index (several masks: any of them with land
  // within its reach keeps the tile refining).
  for (int w = 0; w < world_.waterTileLayers() && !regionalLand; ++w) {
    const world::WaterIndex* ri = world_.regionalWaterIndex(w);
    if (!ri) continue;
    const raster::TilePyramid& pyr = world_.waterTiles(w)->pyramid();
    const raster::GeoTransform& t = pyr.source().transform();
    const double cellDeg = std::max(std::abs(t.lonStepDeg), std::abs(t.latStepDeg));
    const double across = std::max((lon1 - lon0) / std::abs(t.lonStepDeg), (lat1 - lat0) / std::abs(t.latStepDeg));
    const double reachDeg = 2.0 * double(1 << blockLevel(pyr, across)) * cellDeg;
    const double shift = t.nearLon(0.5 * (lon0 + lon1)) - 0.5 * (lon0 + lon1);  // across 180: the layer's longitudes
    double x0 = ri->texelX(lon0 + shift - reachDeg), x1 = ri->texelX(lon1 + shift + reachDeg);
    double y0 = ri->texelY(lat0 - reachDeg), y1 = ri->texelY(lat1 + reachDeg);
    if (x0 > x1) std::swap(x0, x1);
    if (y0 > y1) std::swap(y0, y1);
    const bool inReach = x1 >= 0.0 && x0 <= ri->width() && y1 >= 0.0 && y0 <= ri->height();
    regional = regional || inReach;
    if (inReach) {  // clipped: the index is not global, nothing past its edge may wrap in
      const double xe = std::nextafter(double(ri->width()), 0.0), ye = std::nextafter(double(ri->height()), 0.0);
      regionalLand = !ri->allWater(std::clamp(x0, 0.0, xe), std::clamp(x1, 0.0, xe), std::clamp(y0, 0.0, ye),
                                   std::clamp(y1, 0.0, ye));
      gridMargin = std::max(gridMargin, 1.0 + reachDeg / std::min(wi.lonStepDeg(), wi.latStepDeg()));
    }
  }
  b.allWater = !regionalLand && wi.allWaterAround(lat0, lat1, lon0, lon1, gridMargin);
  if (!b.allWater && fineWater_) {
    // A global streamed mask is drawn from its tiles alone. The vertex
    // shader's ground is flat at -seaDrop wherever its bilinear reads four
    // water texels (water = max(bilinear, B-spline) = 1, and the B-spline's
    // then >= 25/36 shades as full sea), whatever the B-spline's other 12:
    // the bilinear's reach is enough. At continuous level position X it
    // reads texels floor(X - 0.5) and floor(X + 0.5) (0.05 more for the
    // shader's float position), whose mask cells are checked.
    const raster::TilePyramid& pyr = world_.waterTiles()->pyramid();
    const raster::GeoTransform& t = pyr.source().transform();
    const double across = std::max((lon1 - lon0) / std::abs(t.lonStepDeg), (lat1 - lat0) / std::abs(t.latStepDeg));
    const double s = double(1 << blockLevel(pyr, across));
    double x0, x1, y0, y1;
    if (flatWaterFromBilinear_) {
      const auto cells = [&](double a, double c, double& lo, double& hi) {  // level-0 texel coordinates
        lo = s * std::floor(std::min(a, c) / s - 0.55);
        hi = std::nextafter(s * (std::floor(std::max(a, c) / s + 0.55) + 1.0), -1e300);  // the last cell's inside
      };
      cells(fineWater_->texelX(lon0), fineWater_->texelX(lon1), x0, x1);
      cells(fineWater_->texelY(lat0), fineWater_->texelY(lat1), y0, y1);
    } else {  // before: two texels of the level around the tile
      const double reachDeg = 2.0 * s * std::max(std::abs(t.lonStepDeg), std::abs(t.latStepDeg));
      x0 = fineWater_->texelX(lon0 - reachDeg), x1 = fineWater_->texelX(lon1 + reachDeg);
      y0 = fineWater_->texelY(lat0 - reachDeg), y1 = fineWater_->texelY(lat1 + reachDeg);
    }
    b.allWater = fineWater_->cover(x0, x1, y0, y1) == world::TileWaterIndex::Cover::Water;
  }
  // Heights as the vertex shader makes them (land >= 0, water at -seaDrop),
  // from 9 x 9 samples; between samples the bilinear relief can rise further,
  // by at most the range seen plus a margin, and never above Everest.
  const double exag = std::max(1.0, options_.exaggeration);
  double hMin = 1e30, hMax = -1e30;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i) {
      const double lat = lat0 + (lat1 - lat0) * j / 8.0, lon = lon0 + (lon1 - lon0) * i / 8.0;
      const double w = world_.waterAt(lat, lon);
      const double land = std::max(0.0, double(world_.elevationAt(lat, lon))) * exag;
      const double h = w > 0.55 ? -options_.seaDropM : (w < 0.45 ? land : std::max(land, 0.0));
      // The vertex shader drops the ground from coverage 0.3 (B-spline), which
      // can reach past these bilinear samples: any water at all may go under.
      // A regional mask may put land or water where the grid has neither.
      hMin = std::min({hMin, h, w > 0.0 || regional ? -options_.seaDropM : h});
      hMax = std::max({hMax, h, regionalLand ? land : h});
    }
  const double margin = 0.5 * (hMax - hMin) + 50.0 * exag;
  const double hi = std::min(hMax + margin, kMaxTerrainM * exag);
  // Skirts hang below the lowest point.
  const double cellM = (lat1 - lat0) / (kGrid - 1) * kDeg * geo::kWgs84A;
  const double lo = std::max(hMin - margin - 0.35 * cellM * exag - 5.0, kMinTerrainM * exag);
  double r = 0.0;
  int n = 0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const double lat = lat0 + (lat1 - lat0) * j / 2.0, lon = lon0 + (lon1 - lon0) * i / 2.0;
      const glm::dvec3 top = geo::toEcef({lat, lon, hi});
      b.samples[n++] = top;
      r = std::max({r, glm::length(top - b.center), glm::length(geo::toEcef({lat, lon, lo}) - b.center)});
    }
  // The surface bulges between samples half a tile apart by R (1 - cos(span / 4)).
  const double span = (lat1 - lat0) * kDeg;
  b.bulgeM = geo::kWgs84A * (1.0 - std::cos(span / 4.0)) + 1.0;
  r += b.bulgeM;
  b.radius = r;
  return b;
}

void TerrainRenderer::select(const Key& k, const camera::Camera& cam, std::vector<Key>& out,
                             int depth) {
  const Bounds b = bounds(k);
  const glm::dvec3 rel = b.center - cam.eyeEcef();
  const double dist = glm::length(rel);
  // Horizon, in the space where the ellipsoid is the unit sphere (x, y / a,
  // z / b: straight lines stay straight): the occluder is the sphere of the
  // lowest opaque surface; a tile no higher than rTop is hidden if its
  // centre lies beyond the two tangent angles acos(rOcc/|E|) + acos(rOcc/rTop)
  // from the eye's direction by more than its angular radius. Lengths are
  // divided by b, which only enlarges them.
  const auto scaled = [](const glm::dvec3& p) {
    return glm::dvec3(p.x / geo::kWgs84A, p.y / geo::kWgs84A, p.z / geo::kWgs84B);
  };
  const glm::dvec3 eyeS = scaled(cam.eyeEcef());
  const double eyeR = glm::length(eyeS);
  const double rOcc = 1.0 - options_.occluderDepthM / geo::kWgs84B;
  if (eyeR > rOcc) {
    double rTop = 0.0;
    for (const glm::dvec3& s : b.samples) rTop = std::max(rTop, glm::length(scaled(s)));
    rTop += b.bulgeM / geo::kWgs84B;
    const glm::dvec3 cS = scaled(b.center);
    const double cR = glm::length(cS);
    const double limit = std::acos(std::min(1.0, rOcc / eyeR)) + std::acos(std::min(1.0, rOcc / std::max(rTop, rOcc)));
    const double ang = std::acos(std::clamp(glm::dot(cS, eyeS) / (cR * eyeR), -1.0, 1.0));
    const double angRadius = std::asin(std::min(1.0, b.radius / geo::kWgs84B / cR));
    if (ang - angRadius > limit) return;
  }
  // Frustum: side planes through the eye, and in front of it.
  const double z = glm::dot(rel, cam.forward());
  if (z < -b.radius) return;
  const double tanY = std::tan(0.5 * cam.vfovDeg() * kDeg), tanX = tanY * cam.widthPx() / cam.heightPx();
  const double x = glm::dot(rel, cam.right()), y = glm::dot(rel, cam.up());
  if (std::abs(x) - z * tanX > b.radius * std::sqrt(1.0 + tanX * tanX)) return;
  if (std::abs(y) - z * tanY > b.radius * std::sqrt(1.0 + tanY * tanY)) return;

  double lat0, lat1, lon0, lon1;
  tileRange(k, lat0, lat1, lon0, lon1);
  const double pxPerM = cam.heightPx() / (2.0 * tanY);
  // The ocean layer answers from its own stack (a regional mask over the
  // grid), which can call water what the host grid calls land.
  if (waterLayer_ && underOpenWater(lat0, lat1, lon0, lon1, b, dist, cam, pxPerM)) return;
  if (refines(k, b, cam, dist) && depth < 40) {
    for (int cy = 0; cy < 2; ++cy)
      for (int cx = 0; cx < 2; ++cx) select({k.level + 1, 2 * k.x + cx, 2 * k.y + cy}, cam, out, depth + 1);
    return;
  }
  out.push_back({k.level, k.x, k.y, coarseFlat_ && b.allWater && k.level >= kFlatLevel});
}

bool TerrainRenderer::refines(const Key& k, const Bounds& b, const camera::Camera& cam, double dist) const {
  double lat0, lat1, lon0, lon1;
  tileRange(k, lat0, lat1, lon0, lon1);
  const double pxPerM = cam.heightPx() / (2.0 * std::tan(0.5 * cam.vfovDeg() * kDeg));
  const double latEq = (lat0 <= 0.0 && lat1 >= 0.0) ? 0.0 : std::min(std::abs(lat0), std::abs(lat1));
  const double extentM = std::max((lat1 - lat0), (lon1 - lon0) * std::cos(latEq * kDeg)) * kDeg * geo::kWgs84A;
  const double nearest = std::max(dist - b.radius, cam.nearM());
  const double cellPx = extentM / (kGrid - 1) / nearest * pxPerM;
  // Open water is flat and hidden under the wave grid: level 7 cells (2.4 km)
  // already follow the ellipsoid within 0.12 m (chord sag s^2 / 8R), far
  // below the 30 m the water areas sit under the sea.
  const int maxLevel = b.allWater ? std::min(maxLevel_, 7) : maxLevel_;
  return k.level < maxLevel && cellPx > options_.pixelErrorPx;
}

void TerrainRenderer::selectCasters(const Key& k, const camera::Camera& cam, const double region[4],
                                    std::vector<Key>& out, int depth) {
  double lat0, lat1, lon0, lon1;
  tileRange(k, lat0, lat1, lon0, lon1);
  if (lat1 < region[0] || lat0 > region[1]) return;
  // The region's longitudes are unwrapped around the eye's (may pass +-180).
  bool meets = false;
  for (double shift : {-360.0, 0.0, 360.0}) meets = meets || (lon1 + shift >= region[2] && lon0 + shift <= region[3]);
  if (!meets) return;
  const Bounds b = bounds(k);
  if (b.allWater) return;  // nothing above the sea to cast
  const double dist = glm::length(b.center - cam.eyeEcef());
  if (waterLayer_) {
    const double pxPerM = cam.heightPx() / (2.0 * std::tan(0.5 * cam.vfovDeg() * kDeg));
    if (underOpenWater(lat0, lat1, lon0, lon1, b, dist, cam, pxPerM)) return;
  }
  if (refines(k, b, cam, dist) && depth < 40) {
    for (int cy = 0; cy < 2; ++cy)
      for (int cx = 0; cx < 2; ++cx)
        selectCasters({k.level + 1, 2 * k.x + cx, 2 * k.y + cy}, cam, region, out, depth + 1);
    return;
  }
  out.push_back(k);
}

bool TerrainRenderer::underOpenWater(double lat0, double lat1, double lon0, double lon1, const Bounds& b, double dist,
                                     const camera::Camera& cam, double pxPerM) const {
  // The layer decides from the footprint of a pixel at the tile's farthest
  // point, widened by the grazing angle there: cos = (eye height over the
  // tangent plane) / distance. Over the tile, the point moves by <= radius
  // and its normal turns by <= radius / 6.3e6 m (the ellipsoid's smallest
  // radius of curvature).
  const glm::dvec3 up = geo::surfaceNormal(0.5 * (lat0 + lat1), 0.5 * (lon0 + lon1));
  const double farM = dist + b.radius;
  const double cosView = (glm::dot(cam.eyeEcef() - b.center, up) - b.radius * (1.0 + 1.1 * dist / 6.3e6)) / farM;
  if (cosView < 0.05) return false;
  const double footprintM = farM / (pxPerM * cosView);
  return waterLayer_->coversOpaquely(lat0, lat1, lon0, lon1, footprintM);
}

const TerrainRenderer::Slot& TerrainRenderer::acquire(const Key& k, TerrainStats& stats) {
  auto it = cache_.find(k);
  if (it != cache_.end()) {
    lru_.splice(lru_.begin(), lru_, it->second.lru);
    return it->second;
  }
  if (freeSlots_.empty()) {  // evict the least recently used tile
    const Key old = lru_.back();
    lru_.pop_back();
    auto o = cache_.find(old);
    freeSlots_.push_back(o->second.index);
    cache_.erase(o);
  }
  const int index = freeSlots_.back();
  freeSlots_.pop_back();
  double lat0, lat1, lon0, lon1;
  tileRange(k, lat0, lat1, lon0, lon1);
  const glm::dvec3 center = geo::toEcef({0.5 * (lat0 + lat1), 0.5 * (lon0 + lon1), 0.0});
  std::vector<float> v(std::size_t(kVertsPerTile) * kFloatsPerVertex);
  for (int gj = 0; gj < kEdge; ++gj)
    for (int gi = 0; gi < kEdge; ++gi) {
      const int i = std::clamp(gi - 1, 0, kGrid - 1), j = std::clamp(gj - 1, 0, kGrid - 1);
      const bool skirt = gi != i + 1 || gj != j + 1;
      const double lat = lat1 - (lat1 - lat0) * j / (kGrid - 1);
      const double lon = lon0 + (lon1 - lon0) * i / (kGrid - 1);
      const glm::dvec3 p = geo::toEcef({lat, lon, 0.0}) - center;
      const glm::dvec3 n = geo::surfaceNormal(lat, lon);
      float* o = &v[(std::size_t(gj) * kEdge + gi) * kFloatsPerVertex];
      o[0] = float(p.x), o[1] = float(p.y), o[2] = float(p.z);
      o[3] = float(n.x), o[4] = float(n.y), o[5] = float(n.z);
      o[6] = float(lon), o[7] = float(lat), o[8] = skirt ? 1.0f : 0.0f;
    }
  glNamedBufferSubData(vbo_, GLintptr(index) * kVertsPerTile * kFloatsPerVertex * sizeof(float),
                       GLsizeiptr(v.size() * sizeof(float)), v.data());
  lru_.push_front(k);
  ++stats.tilesBuilt;
  return cache_.emplace(k, Slot{index, center, lru_.begin()}).first->second;
}

void TerrainRenderer::selectTiles(const camera::Camera& cam, std::vector<Key>& tiles, std::vector<const Slot*>& slots,
                                  TerrainStats& stats) {
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) select({0, x, y}, cam, tiles, 0);
  // More visible tiles than slots would thrash: keep the coarsest that fit.
  if (int(tiles.size()) > options_.poolTiles) tiles.resize(options_.poolTiles);
  slots.reserve(tiles.size());
  for (const Key& k : tiles) {
    slots.push_back(&acquire(k, stats));
    stats.maxLevel = std::max(stats.maxLevel, k.level);
    stats.tilesFlat += k.flat;
  }
}

void TerrainRenderer::drawTiles(const gl::GlProgram& prog, const camera::Camera& cam, const camera::Lighting& light,
                              SeaShading sea, double oceanCellPx, const std::vector<Key>& tiles,
                              const std::vector<const Slot*>& slots, const glm::mat4* viewProj) {
  prog.use();
  world_.bind();
  glUniformMatrix4fv(prog.uniform("uViewProj"), 1, GL_FALSE, viewProj ? &(*viewProj)[0][0] : &cam.gpu().viewProj[0][0]);
  glUniform4fv(prog.uniform("uImageryGeo"), 1, &world_.imageryGeo()[0]);
  // The layers' count is compiled in (imageryDefine); absent uniforms are -1, ignored.
  for (int i = 0; i < world_.imageryLayers(); ++i)
    glUniform4fv(prog.uniform(("uImageryLayerGeo[" + std::to_string(i) + "]").c_str()), 1,
                 &world_.imageryLayerGeo(i)[0]);
  glUniform4fv(prog.uniform("uElevationGeo"), 1, &world_.elevationGeo()[0]);
  glUniform4fv(prog.uniform("uWaterGeo"), 1, &world_.waterGeo()[0]);
  glUniform1f(prog.uniform("uExaggeration"), float(options_.exaggeration));
  glUniform1f(prog.uniform("uSeaDropM"), float(options_.seaDropM));
  const glm::vec3 sun(light.sunEcef);
  glUniform3fv(prog.uniform("uSunDir"), 1, &sun[0]);
  // The eye's distance from the Earth's centre, for the atmosphere.
  glUniform1f(prog.uniform("uEyeRadiusM"), float(glm::length(cam.eyeEcef())));
  glUniform1i(prog.uniform("uSeaShading"), sea == SeaShading::None ? 0 : 1);
  glUniform1f(prog.uniform("uOceanCellPx"), float(oceanCellPx));
  glUniform1f(prog.uniform("uOceanCellRadians"),
              float(2.0 * std::tan(0.5 * cam.vfovDeg() * kDeg) / cam.heightPx() * oceanCellPx));
  const GLint locOffset = prog.uniform("uTileOffset"), locSkirt = prog.uniform("uSkirtM");
  gl::TilePool* pool = world_.waterTiles();
  const bool streamed = pool && prog.uniform("uWaterSlots") >= 0;
  if (streamed) glBindTextureUnit(5, pool->texture());
  // Streamed masks under the first (GEOCEAN_WATER_TILES_LAYERS): pools on units 15 + k,
  // uniforms uWaterB*[k - 1]; reliefs likewise below.
  const int waterLayers = streamed ? world_.waterTileLayers() : 0;
  static const char* const kBelow[] = {"", "[0]", "[1]", "[2]"};
  for (int w = 1; w < waterLayers; ++w) glBindTextureUnit(GLuint(15 + w), world_.waterTiles(w)->texture());
  gl::TilePool* elevPool = world_.elevationTiles();
  const bool elevStreamed = elevPool && prog.uniform("uElevSlots") >= 0;
  if (elevStreamed) glBindTextureUnit(4, elevPool->texture());
  // Streamed reliefs under the first (GEOCEAN_ELEVATION_TILES_LAYERS): pools on units 18 + k.
  const int elevLayers = elevStreamed ? world_.elevationTileLayers() : 0;
  for (int e = 1; e < elevLayers; ++e) glBindTextureUnit(GLuint(18 + e), world_.elevationTiles(e)->texture());
  glBindVertexArray(vao_);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const Key& k = tiles[i];
    if (streamed) bindWaterBlock(&prog, k);
    for (int w = 1; w < waterLayers; ++w) bindBlock(&prog, *world_.waterTiles(w), k, "uWaterB", kBelow[w]);
    if (elevStreamed) bindBlock(&prog, *elevPool, k, "uElev");
    for (int e = 1; e < elevLayers; ++e) bindBlock(&prog, *world_.elevationTiles(e), k, "uElevB", kBelow[e]);
    const glm::vec3 off(slots[i]->centerEcef - cam.eyeEcef());  // double difference, then float
    glUniform3fv(locOffset, 1, &off[0]);
    // Skirts hang deeper than the largest height error between levels
    // (a third of a cell: slopes up to 1:3) and the curvature sag of a cell.
    const double cellM = 90.0 / double(1 << k.level) / (kGrid - 1) * kDeg * geo::kWgs84A;
    glUniform1f(locSkirt, float(std::max(5.0, 0.35 * cellM * std::max(1.0, options_.exaggeration))));
    if (k.flat)
      glDrawElementsBaseVertex(GL_TRIANGLES, flatIndexCount_, GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(std::uintptr_t(indexCount_) * sizeof(std::uint32_t)),
                               slots[i]->index * kVertsPerTile);
    else
      glDrawElementsBaseVertex(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr, slots[i]->index * kVertsPerTile);
  }
}

bool TerrainRenderer::bindWaterBlock(const gl::GlProgram* prog, const Key& k) {
  return bindBlock(prog, *world_.waterTiles(), k, "uWater");
}

bool TerrainRenderer::bindBlock(const gl::GlProgram* prog, gl::TilePool& pool, const Key& k, const char* prefix,
                                const char* index) {
  // The finest pyramid level whose 2 x 2 tiles hold this terrain tile and
  // the filter's reach (3 texels: the B-spline's 2 and a skirt's), and are
  // resident; the finest such level is asked for. The terrain tile's cells
  // are at most pixelErrorPx pixels (its screen-space error), and 252
  // texels over its 32 cells make a texel about a pixel: the texture's level
  // follows the view.
  const raster::TilePyramid& pyr = pool.pyramid();
  const raster::GeoTransform& t0 = pyr.source().transform();
  const bool wrap = t0.global;
  const int T = pyr.tileSize(), top = pyr.levels() - 1;
  double lat0, lat1, lon0, lon1;
  tileRange(k, lat0, lat1, lon0, lon1);
  const double shift = t0.nearLon(0.5 * (lon0 + lon1)) - 0.5 * (lon0 + lon1);  // a regional layer across 180
  lon0 += shift, lon1 += shift;
  const double x0 = (lon0 - t0.originLonDeg) / t0.lonStepDeg, x1 = (lon1 - t0.originLonDeg) / t0.lonStepDeg;
  const double ya = (lat0 - t0.originLatDeg) / t0.latStepDeg, yb = (lat1 - t0.originLatDeg) / t0.latStepDeg;
  const double y0 = std::min(ya, yb), y1 = std::max(ya, yb);
  if (!wrap) {
    // A regional layer: a terrain tile clear of it by the filter's reach at
    // the coarsest level draws the grid alone (slots -1, geo_uv.glsl), so
    // nothing is asked for and every level agrees with the grid there.
    const double m = kReach * double(1 << top);
    if (x1 + m < 0.0 || x0 - m > pyr.levelWidth(0) || y1 + m < 0.0 || y0 - m > pyr.levelHeight(0)) {
      if (prog) glUniform4i(prog->uniform((std::string(prefix) + "Slots" + index).c_str()), -1, -1, -1, -1);
      return true;
    }
  }
  const int want = blockLevel(pyr, std::max(x1 - x0, y1 - y0));
  int slots[4] = {0, 0, 0, 0};
  int level = top, bx = 0, by = 0;
  for (int l = want; l <= top; ++l) {
    const double s = double(1 << l);
    const int W = pyr.levelWidth(l), H = pyr.levelHeight(l), nx = pyr.tilesX(l), ny = pyr.tilesY(l);
    double ax = x0 / s - kReach, bxx = x1 / s + kReach;
    if (!wrap) ax = std::clamp(ax, 0.0, W - 1.0), bxx = std::clamp(bxx, 0.0, W - 1.0);
    const double ay = std::clamp(y0 / s - kReach, 0.0, H - 1.0), byy = std::clamp(y1 / s + kReach, 0.0, H - 1.0);
    const int tx0 = int(std::floor(ax / T)), tx1 = int(std::floor(bxx / T));
    const int ty0 = int(std::floor(ay / T)), ty1 = int(std::floor(byy / T));
    if (l < top && (tx1 - tx0 > 1 || ty1 - ty0 > 1)) continue;
    const auto wrapX = [&](int x) { return wrap ? ((x % nx) + nx) % nx : std::clamp(x, 0, nx - 1); };
    const int cx[2] = {wrapX(tx0), wrapX(tx1)}, cy[2] = {std::clamp(ty0, 0, ny - 1), std::clamp(ty1, 0, ny - 1)};
    bool all = true;
    for (int q = 0; q < 4; ++q) {
      const raster::TileId id{l, cx[q & 1], cy[q >> 1]};
      slots[q] = pool.residentSlot(id);
      if (slots[q] < 0) {
        all = false;
        if (l == want) pool.request(id);
      }
    }
    if (!all && l < top) continue;
    level = l;
    bx = cx[0];
    by = cy[0];
    break;
  }
  if (!prog) return level == want;
  const double s = double(1 << level);
  const std::string p(prefix), i(index);
  glUniform4i(prog->uniform((p + "Slots" + i).c_str()), slots[0], slots[1], slots[2], slots[3]);
  glUniform4i(prog->uniform((p + "Block" + i).c_str()), bx, by, pyr.tilesX(level), T);
  glUniform3i(prog->uniform((p + "Level" + i).c_str()), pyr.levelWidth(level), pyr.levelHeight(level), wrap ? 1 : 0);
  glUniform4f(prog->uniform((p + "LevelGeo" + i).c_str()), float(t0.originLonDeg), float(t0.originLatDeg),
              float(t0.lonStepDeg * s), float(t0.latStepDeg * s));
  return level == want;
}

TerrainStats TerrainRenderer::drawMirrored(const camera::Camera& mirrored, const camera::Camera& selectFrom,
                                           const camera::Lighting& light) {
  if (mirrored_.id() == 0) {  // compiled on the first reflection a layer asks for
    // Clipped by the streamed water too: a regional layer's grid below knows
    // none of its islands (the whole island was clipped, none reflected).
    std::vector<std::string> d = {"GEOCEAN_CLIP_SEA 1", "GEOCEAN_NO_SEA_SHADING 1", imageryDefine()};
    if (const gl::TilePool* w = world_.waterTiles()) {
      d.push_back("GEOCEAN_WATER_TILES 1");
      if (!w->pyramid().source().transform().global) d.push_back("GEOCEAN_WATER_REGIONAL 1");
    }
    if (world_.waterTileLayers() > 1) d.push_back("GEOCEAN_WATER_TILES_LAYERS " + std::to_string(world_.waterTileLayers()));
    if (const gl::TilePool* e = world_.elevationTiles()) {
      d.push_back("GEOCEAN_ELEVATION_TILES 1");
      if (!e->pyramid().source().transform().global) d.push_back("GEOCEAN_ELEVATION_REGIONAL 1");
    }
    if (world_.elevationTileLayers() > 1)
      d.push_back("GEOCEAN_ELEVATION_TILES_LAYERS " + std::to_string(world_.elevationTileLayers()));
    mirrored_ = gl::GlProgram::graphics("terrain.vert", "terrain.frag", d);
  }
  TerrainStats stats;
  std::vector<Key> tiles;
  std::vector<const Slot*> slots;
  waterLayer_ = nullptr;
  // The real eye chooses the tiles: the mirrored one is under the sea, where
  // the horizon test would hide everything.
  selectTiles(selectFrom, tiles, slots, stats);
  // Flat water tiles lie seaDropM under the sea throughout: clipped whole.
  if (options_.seaDropM > 0.5) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < tiles.size(); ++i)
      if (!tiles[i].flat) tiles[kept] = tiles[i], slots[kept++] = slots[i];
    tiles.resize(kept), slots.resize(kept);
  }
  glEnable(GL_CLIP_DISTANCE0);
  drawTiles(mirrored_, mirrored, light, SeaShading::None, 0.0, tiles, slots);
  glDisable(GL_CLIP_DISTANCE0);
  stats.tilesDrawn = int(tiles.size());
  glBindVertexArray(0);
  return stats;
}

TerrainStats TerrainRenderer::drawDepth(const glm::mat4& viewProj, const camera::Camera& selectFrom,
                                        const Layer* waterLayer, const double region[4]) {
  TerrainStats stats;
  std::vector<Key> tiles;
  std::vector<const Slot*> slots;
  if (depth_.id() == 0)  // compiled on the first shadow map a layer asks for
    depth_ = gl::GlProgram::graphics("terrain.vert", "bare.frag", depthDefines_);
  waterLayer_ = options_.skipOpenWater && waterLayer && waterLayer->info().opaqueWater ? waterLayer : nullptr;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) selectCasters({0, x, y}, selectFrom, region, tiles, 0);
  // As selectTiles: never more than the pool holds (the coarsest first).
  if (int(tiles.size()) > options_.poolTiles) tiles.resize(options_.poolTiles);
  // Only the tiles whose bounding sphere (corners at sea level, 9 km of
  // relief) meets the map's box (the region's lat/lon box is wider).
  const glm::dmat4 m(viewProj);
  const double sx = glm::length(glm::dvec3(m[0][0], m[1][0], m[2][0])), sy = glm::length(glm::dvec3(m[0][1], m[1][1], m[2][1]));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    double lat0, lat1, lon0, lon1;
    tileRange(tiles[i], lat0, lat1, lon0, lon1);
    const glm::dvec3 c = geo::toEcef({0.5 * (lat0 + lat1), 0.5 * (lon0 + lon1), 0.0});
    double r = 0.0;
    for (double la : {lat0, lat1})
      for (double lo : {lon0, lon1}) r = std::max(r, glm::length(geo::toEcef({la, lo, 0.0}) - c));
    r += 9000.0;
    const glm::dvec4 q = m * glm::dvec4(c - selectFrom.eyeEcef(), 1.0);
    if (std::abs(q.x) > 1.0 + r * sx || std::abs(q.y) > 1.0 + r * sy) continue;
    tiles[kept++] = tiles[i];
  }
  tiles.resize(kept);
  slots.reserve(kept);
  for (const Key& k : tiles) slots.push_back(&acquire(k, stats));
  // The casters at the relief's and the mask's level a view of them would
  // draw (those behind the eye are not the view's: not asked for yet).
  waitForBlocks(tiles, true, true);
  // Only what stands above the sea casts onto it (water areas 30 m under it, skirts).
  glEnable(GL_CLIP_DISTANCE0);
  drawTiles(depth_, selectFrom, camera::Lighting{}, SeaShading::None, 0.0, tiles, slots, &viewProj);
  glDisable(GL_CLIP_DISTANCE0);
  stats.tilesDrawn = int(tiles.size());
  glBindVertexArray(0);
  return stats;
}

void TerrainRenderer::waitForBlocks(const std::vector<Key>& tiles, bool water, bool elevation) {
  if (!options_.waitForTiles) return;
  // A picture, not an interactive view: wait for the tiles these terrain
  // tiles ask for (bounded: a view needing more than the pool holds draws what fits).
  if (water && world_.waterTiles()) {
    for (int round = 0; round < 64; ++round) {
      bool complete = true;
      for (const Key& k : tiles)
        for (int w = 0; w < world_.waterTileLayers(); ++w)
          complete = bindBlock(nullptr, *world_.waterTiles(w), k, "") && complete;
      if (complete) break;
      for (int w = 0; w < world_.waterTileLayers(); ++w) world_.waterTiles(w)->waitIdle();
      for (int w = 0; w < world_.waterTileLayers(); ++w) world_.waterTiles(w)->endFrame();
    }
  }
  if (world_.elevationTiles() && elevation) {
    for (int round = 0; round < 64; ++round) {
      bool complete = true;
      for (const Key& k : tiles)
        for (int e = 0; e < world_.elevationTileLayers(); ++e)
          complete = bindBlock(nullptr, *world_.elevationTiles(e), k, "") && complete;
      if (complete) break;
      for (int e = 0; e < world_.elevationTileLayers(); ++e) world_.elevationTiles(e)->waitIdle();
      for (int e = 0; e < world_.elevationTileLayers(); ++e) world_.elevationTiles(e)->endFrame();
    }
  }
}

TerrainStats TerrainRenderer::draw(const camera::Camera& cam, const camera::Lighting& light, bool bare,
                                   SeaShading sea, const Layer* waterLayer) {
  TerrainStats stats;
  std::vector<Key> tiles;
  waterLayer_ = sea == SeaShading::UnderOcean && options_.skipOpenWater && waterLayer && waterLayer->info().opaqueWater
                    ? waterLayer
                    : nullptr;
  const double oceanCellPx = waterLayer ? waterLayer->info().cellPx : 0.0;
  std::vector<const Slot*> slots;
  selectTiles(cam, tiles, slots, stats);
  const auto pass = [&](const gl::GlProgram& prog) { drawTiles(prog, cam, light, sea, oceanCellPx, tiles, slots); };
  const gl::GlProgram& colour =
      bare ? bare_ : sea == SeaShading::UnderOcean && (!options_.seaProxy || world_.waterTiles()) ? underOcean_ : program_;
  waitForBlocks(tiles, &colour == &program_ || &colour == &underOcean_, !bare);
  // Not with a streamed mask: the proxy's cut is the single water texture's.
  if (!bare && sea == SeaShading::UnderOcean && options_.seaProxy && !world_.waterTiles()) {
    // Depth only, where the ocean layer will cover the pixel: the same
    // surface pulled a few float-depth units towards the eye (reversed Z),
    // so the colour pass fails GL_GREATER there before shading, while the
    // ocean, 30 m higher, passes.
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, 16.0f);
    pass(seaProxy_);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  pass(colour);
  // Finished tile loads go up after the frame's draws (they never wait).
  for (int w = 0; w < world_.waterTileLayers(); ++w) world_.waterTiles(w)->endFrame();
  for (int e = 0; e < world_.elevationTileLayers(); ++e) world_.elevationTiles(e)->endFrame();
  stats.tilesDrawn = int(tiles.size());
  glBindVertexArray(0);
  return stats;
}

}  // namespace geocean::render
