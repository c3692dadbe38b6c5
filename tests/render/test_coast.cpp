// Coasts (issue 12 item 4): the query follows what is drawn, and the drawn
// coastline is crisp.
// - The coverage rule is one function: the GPU's textureBSplineGather
//   (shaders/geo_uv.glsl) and the CPU's world::coverageClassAt give the same
//   coverage on a 3" GSHHG mask texture.
// - Frames near coasts (Tarifa, Gibraltar) are drawn; every pixel away from
//   the shoreline's anti-aliased pixels is picked (the ocean's own surface
//   position where it drew, the sea-level point of the pixel's ray where it
//   did not) and `geocean query` at that point must say water with a sea
//   height where the ocean drew and land without one where it did not:
//   with the default world (the 5' mask drawn cell for cell) and with the
//   3" Strait of Gibraltar mask made by `geocean mask` (drawn at its own
//   cells: the ocean's grids made from it directly, as the streamed tiles
//   of item 2 will give the product).
// - From 500 m the drawn coastline lies within one pixel plus a quarter
//   mask cell of the mask's coverage-0.5 isoline.
// With the 3" mask the host's terrain draws the same cells as its water
// (the default imagery and relief otherwise). The frames are written next
// to the test's temp files for looking at.
#include "RenderFixture.h"

#include "globe/geo/Ellipsoid.h"
#include "globe/gl/Framebuffer.h"
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/Raster.h"
#include "globe/raster/World.h"
#include "globe/render/Session.h"
#include "globe/world/LayerStack.h"
#include "globe/world/TileWaterIndex.h"
#include "globe/world/WaterPyramid.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/landsea/LayeredLandSea.h"
#include "plugin/ocean/Ocean.h"
#include "plugin/render/OceanWorld.h"
#include "shaders/Shaders.h"
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace geocean::render::test {
namespace {

namespace fs = std::filesystem;
using camera::ViewPose;
const std::string kExe = GEOCEAN_EXE;
constexpr double kDeg = M_PI / 180.0;
constexpr double kCellDeg = 3.0 / 3600.0;  // the 3" mask

// The 3" mask of the strait, built once by `geocean mask` (GMT, seconds).
const std::string& gibraltarMask() {
  static const std::string path = [] {
    // Per process: ctest runs each Coast test as its own process, in parallel.
    const std::string p = ::testing::TempDir() + "/coast_gibraltar_3s." + std::to_string(::getpid()) + ".tif";
    fs::remove(p);
    const auto r = geocean::test::run(kExe + " mask --quiet --region -6/-5/35.75/36.25 --resolution 3s --out " + p);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return p;
  }();
  return path;
}

// The renderer tests' session (default world, its ocean) and, in its
// context, the 3" world: the host's and the ocean's grids with the mask's
// own cells as the water layer (the default imagery and relief).
struct Scene {
  GlobeRenderer* defaultRenderer = nullptr;
  ocean_render::OceanRenderer* defaultOcean = nullptr;
  std::shared_ptr<const raster::Raster> mask;
  std::shared_ptr<const ocean::LandSea> fineLandSea;
  std::shared_ptr<WorldTextures> fineWorld;
  std::unique_ptr<GlobeRenderer> fineRenderer;
  std::shared_ptr<ocean_render::OceanRenderer> fineOcean;
};

Scene& scene() {
  static Scene s = [] {
    Scene c;
    c.defaultRenderer = session().renderer.get();
    c.defaultOcean = &sessionOcean();
    c.mask = raster::Raster::open(gibraltarMask());
    const auto etopo = raster::Raster::open(raster::defaultWorld().elevation);
    c.fineLandSea = std::make_shared<const ocean::LandSea>(c.mask, etopo);
    world::WorldData d = world::loadDefaultWorld();
    d.water = world::waterLayerOf(*c.mask);
    c.fineWorld = std::make_shared<WorldTextures>(d);
    c.fineRenderer = std::make_unique<GlobeRenderer>(c.fineWorld);
    c.fineOcean = std::make_shared<ocean_render::OceanRenderer>(c.fineWorld->grids(), c.fineLandSea);
    c.fineRenderer->addLayer(std::make_shared<DirectOceanLayer>(c.fineOcean));
    return c;
  }();
  return s;
}

// The ocean's side as plugin/capi's draw builds it for `--mask FILE` over
// the default world: the façade's snapshot, its streamed water tiles and
// grids (oceanWaterTiles/oceanWorld).
struct FacadeOcean {
  std::shared_ptr<const ocean::Snapshot> snap;
  ocean_render::OceanOptions options;
  std::shared_ptr<const world::WorldGrids> grids;
};
FacadeOcean facadeOcean(const std::vector<std::string>& paths, world::LayerKind kind = world::LayerKind::Mask) {
  ocean::Ocean o;
  o.setDefaultWorld(ocean::Ocean::defaultWorldDir());
  for (const std::string& path : paths)
    if (kind == world::LayerKind::Elevation) o.addElevationLayerFile(path);
    else o.addMaskLayerFile(path);
  FacadeOcean f;
  f.snap = o.current();
  f.options.waterTiles = ocean_render::oceanWaterTiles(f.snap->landSea.get(), f.snap->mask);
  f.grids = ocean_render::oceanWorld(f.snap->mask, f.snap->elevation, f.snap->landSea.get(), f.snap->maskEncoding,
                                     f.options.waterTiles.get());
  f.options.elevationTiles = ocean_render::oceanElevationTileLayers(f.snap->landSea.get(), f.snap->elevation);
  return f;
}

FacadeOcean facadeOcean(const std::string& path, world::LayerKind kind = world::LayerKind::Mask) {
  return facadeOcean(std::vector<std::string>{path}, kind);
}

// The bundled 1.25' mask as a layer over the default world, built the way
// the product builds it (issue 12): the host's world by
// world::loadLayeredWorld (its terrain streams the mask's tiles), the
// ocean's grids, land/sea and streamed tiles from the façade's snapshot by
// oceanWorld/oceanWaterTiles, as plugin/capi's draw does. The control is
// the same stack drawn from the 5' water grids alone on both sides (no
// tiles), as before the ocean streamed.
// The reference (refRenderer, refOcean) draws the same streamed mask
// without the open-water index: every ocean cell per pixel, the terrain
// under all the sea.
struct Streamed {
  std::shared_ptr<WorldTextures> world, gridWorld;
  std::unique_ptr<GlobeRenderer> renderer, gridRenderer, refRenderer;
  std::shared_ptr<ocean_render::OceanRenderer> ocean, gridOcean, refOcean;
};

Streamed& streamed() {
  static Streamed s = [] {
    session();  // the GL context (scene() would build the 3" Gibraltar world too)
    Streamed c;
    // A cache of this test's own (the pyramid is built once per process).
    const std::string cache = ::testing::TempDir() + "/coast_tiles." + std::to_string(::getpid());
    ::setenv("GEOCEAN_TILE_CACHE", cache.c_str(), 1);
    const std::string fine = raster::defaultWorld().maskFine;
    world::WorldData d = world::loadLayeredWorld({{world::LayerKind::Mask, fine, "", 0}}, true);
    EXPECT_TRUE(d.waterSource) << "the 1.25' mask should be streamed";
    TerrainOptions t;
    t.waitForTiles = true;  // as geocean render
    c.world = std::make_shared<WorldTextures>(d);
    c.renderer = std::make_unique<GlobeRenderer>(c.world, t);
    d.waterSource = nullptr;
    c.gridWorld = std::make_shared<WorldTextures>(d);
    c.gridRenderer = std::make_unique<GlobeRenderer>(c.gridWorld, t);
    const FacadeOcean f = facadeOcean(fine);
    ocean_render::OceanOptions oo = f.options;
    const auto& grids = f.grids;
    const auto& snap = f.snap;
    EXPECT_TRUE(oo.waterTiles) << "the ocean should stream the 1.25' mask";
    c.ocean = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
    c.ocean->setCompleteTiles(true);
    c.gridOcean = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea);
    c.renderer->addLayer(std::make_shared<DirectOceanLayer>(c.ocean));
    c.gridRenderer->addLayer(std::make_shared<DirectOceanLayer>(c.gridOcean));
    oo.streamedIndex = false;
    c.refOcean = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
    c.refOcean->setCompleteTiles(true);
    c.refRenderer = std::make_unique<GlobeRenderer>(c.world, t);
    c.refRenderer->terrain().setSkipOpenWater(false);
    c.refRenderer->addLayer(std::make_shared<DirectOceanLayer>(c.refOcean));
    return c;
  }();
  return s;
}

// A regional mask (regional(): the 3" Strait of Gibraltar mask) as a
// layer over the default world, built as `geocean render --mask
// gibraltar_3s.tif` builds it (issue 12): the host's world by
// world::loadLayeredWorld (its terrain streams the mask's tiles over the
// stack's 5' grid), the ocean's from the façade's snapshot by
// oceanWorld/oceanWaterTiles as plugin/capi's draw does, both waiting for
// their tiles as the CLI's single pictures do.
struct Regional {
  std::shared_ptr<WorldTextures> world;
  std::unique_ptr<GlobeRenderer> renderer;
  std::shared_ptr<ocean_render::OceanRenderer> ocean;
  std::shared_ptr<const ocean::LandSea> landSea;  // the façade's layered land/sea
};

// kind Elevation: a relief finer than every mask, whose 0 m line is the coast.
// Several paths: layers of one kind at one priority (the stack orders them).
Regional makeRegional(const std::vector<std::string>& paths, world::LayerKind kind = world::LayerKind::Mask) {
  session();  // the GL context (scene() would build the 3" Gibraltar world too)
  Regional c;
  const std::string cache = ::testing::TempDir() + "/coast_regional_tiles." + std::to_string(::getpid());
  ::setenv("GEOCEAN_TILE_CACHE", cache.c_str(), 1);
  std::vector<world::LayerSource> sources;
  for (const std::string& path : paths) sources.push_back({kind, path, "", 0});
  world::WorldData d = world::loadLayeredWorld(sources, true);
  EXPECT_EQ(d.waterFromRelief, kind == world::LayerKind::Elevation);
  EXPECT_TRUE(d.waterSource) << "the regional 3\" mask should be streamed";
  TerrainOptions t;
  t.waitForTiles = true;  // as geocean render
  c.world = std::make_shared<WorldTextures>(d);
  c.renderer = std::make_unique<GlobeRenderer>(c.world, t);
  const FacadeOcean f = facadeOcean(paths, kind);
  const auto& snap = f.snap;
  EXPECT_TRUE(f.options.waterTiles) << "the ocean should stream the regional 3\" mask";
  c.ocean = std::make_shared<ocean_render::OceanRenderer>(f.grids, snap->landSea, f.options);
  c.ocean->setCompleteTiles(true);
  c.renderer->addLayer(std::make_shared<DirectOceanLayer>(c.ocean));
  c.landSea = snap->landSea;
  return c;
}

Regional makeRegional(const std::string& path, world::LayerKind kind = world::LayerKind::Mask) {
  return makeRegional(std::vector<std::string>{path}, kind);
}

Regional& regional() {
  static Regional s = makeRegional(gibraltarMask());
  return s;
}

// The coast tests' light: time 0, the sun at azimuth 135 degrees, 50
// degrees above the horizon at the camera's nadir.
FrameSettings coastLight(const ViewPose& p) {
  FrameSettings fs;
  fs.timeS = 0.0;
  fs.sunEcef = sunForView(p, 135.0, 50.0);
  return fs;
}

struct Frame {
  ViewPose pose;
  camera::Camera cam = camera::Camera::fromView(ViewPose{});
  std::vector<float> data;  // eye-relative ocean position, w = 1 where the ocean drew
  gl::Image image;
  std::vector<std::uint8_t> ocean;  // 1 where the ocean drew (see render)
  std::vector<float> depth;         // reversed Z (near / distance), top row first; 0: nothing drawn
  TerrainStats terrain;             // the host terrain's tiles
  bool drawn(int x, int y) const { return ocean[std::size_t(y) * pose.width + x] != 0; }
};

Frame render(const ViewPose& p, GlobeRenderer& renderer, ocean_render::OceanRenderer* ocean, const std::string& name);

Frame render(const ViewPose& p, bool fine, const std::string& name) {
  Scene& s = scene();
  return render(p, fine ? *s.fineRenderer : *s.defaultRenderer, fine ? s.fineOcean.get() : s.defaultOcean, name);
}

Frame render(const ViewPose& p, GlobeRenderer& renderer, ocean_render::OceanRenderer* ocean, const std::string& name) {
  ocean->setWriteData(true);
  gl::Framebuffer fb(p.width, p.height, true);
  fb.bind();
  const FrameTimes t = renderer.render(p, coastLight(p));
  Frame f;
  f.pose = p;
  f.terrain = t.terrain;
  f.cam = renderer.camera(p);
  f.data = fb.readData();
  f.image = fb.readColor();
  {
    std::vector<float> raw(std::size_t(p.width) * p.height);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
    glReadPixels(0, 0, p.width, p.height, GL_DEPTH_COMPONENT, GL_FLOAT, raw.data());
    f.depth.resize(raw.size());
    for (int y = 0; y < p.height; ++y)  // GL's first row is the bottom one
      std::copy_n(&raw[std::size_t(p.height - 1 - y) * p.width], p.width, &f.depth[std::size_t(y) * p.width]);
  }
  ocean->setWriteData(false);
  // The ocean drew a pixel where its data target holds a surface point
  // that projects back into that pixel (the clear colour and the sky's
  // and terrain's colour reach that target too: w = 1, xyz a colour).
  f.ocean.assign(std::size_t(p.width) * p.height, 0);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const float* q = &f.data[(std::size_t(y) * p.width + x) * 4];
      if (q[3] != 1.0f) continue;
      const glm::dvec3 rel(q[0], q[1], q[2]);
      if (glm::length(rel) < f.cam.nearM()) continue;
      const auto ndc = f.cam.projectEyeRelative(rel);
      if (!ndc) continue;
      const double px = (ndc->x * 0.5 + 0.5) * p.width, py = (0.5 - ndc->y * 0.5) * p.height;
      f.ocean[std::size_t(y) * p.width + x] = std::abs(px - (x + 0.5)) < 1.0 && std::abs(py - (y + 0.5)) < 1.0;
    }
  const std::string out = ::testing::TempDir() + "/coast_" + name + ".png";
  gl::writePng(out, f.image);
  std::printf("%s: %s\n", name.c_str(), out.c_str());
  return f;
}

// The ground point of a pixel: where the ocean drew, its surface; else
// where the pixel's ray meets sea level. False for sky.
bool groundPoint(const Frame& f, int x, int y, geo::Geodetic& g) {
  const float* q = &f.data[(std::size_t(y) * f.pose.width + x) * 4];
  if (f.drawn(x, y)) {
    g = geo::fromEcef(f.cam.eyeEcef() + glm::dvec3(q[0], q[1], q[2]));
    return true;
  }
  const glm::dvec3 dir = f.cam.pixelRay(x + 0.5, y + 0.5);
  const geo::RayHit h = geo::intersectEllipsoid(f.cam.eyeEcef(), dir);
  if (!h.hit) return false;
  g = geo::fromEcef(f.cam.eyeEcef() + h.tFirst() * dir);
  return true;
}

// The drawn surface at a pixel (the nearest, from the depth buffer:
// reversed Z with an infinite far plane, depth = near / distance along the
// view axis, Camera::gpu()). False where nothing was drawn.
bool surfacePoint(const Frame& f, int x, int y, geo::Geodetic& g) {
  const float d = f.depth[std::size_t(y) * f.pose.width + x];
  if (!(d > 0.0f)) return false;
  const glm::dvec2 ndc = f.cam.pixelToNdc(x + 0.5, y + 0.5);
  g = geo::fromEcef(f.cam.eyeEcef() + (f.cam.nearM() / double(d)) * f.cam.rayThroughNdc(ndc.x, ndc.y));
  return true;
}

// Away from the anti-aliased shoreline: no pixel within 2 px drawn
// otherwise (the ocean's alpha ramps over +-0.75 px of coverage 0.5, and
// its data target is written wherever alpha > 0).
bool awayFromShore(const Frame& f, int x, int y) {
  const bool d = f.drawn(x, y);
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const int xx = x + dx, yy = y + dy;
      if (xx < 0 || yy < 0 || xx >= f.pose.width || yy >= f.pose.height) return false;
      if (f.drawn(xx, yy) != d) return false;
    }
  return true;
}

ViewPose pose(double lat, double lon, double alt, double heading, double pitch) {
  ViewPose p;
  p.latDeg = lat, p.lonDeg = lon, p.altM = alt, p.headingDeg = heading, p.pitchDeg = pitch;
  p.width = 320, p.height = 240;
  p.fovYDeg = 45.0;
  return p;
}

struct QueryRow {
  std::string surface;
  bool hasSeaHeight = false;
};

std::vector<QueryRow> query(const std::vector<geo::Geodetic>& pts, const std::string& extra) {
  std::ostringstream csv;
  csv.precision(12);
  for (const auto& g : pts) csv << g.latDeg << ',' << g.lonDeg << '\n';
  const auto r = geocean::test::run(kExe + " query --points - --time 0" + extra, csv.str());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::vector<QueryRow> rows;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    if (f.size() < 6) continue;
    rows.push_back({f[2], f[5] != "null" && !f[5].empty()});
  }
  return rows;
}

// Every non-shore pixel's ground point through `geocean query` (with
// `extra` layers): water with a sea height where the ocean drew, land
// without one where it did not. Returns the pixels checked.
// keep (optional): only the ground points it accepts are checked.
int queryMismatches(const Frame& f, const std::string& extra, int& water, int& land, bool expectNone,
                    const std::function<bool(const geo::Geodetic&)>& keep = {});

void expectQueryFollowsPicture(const Frame& f, const std::string& extra, int& water, int& land,
                               const std::function<bool(const geo::Geodetic&)>& keep = {}) {
  queryMismatches(f, extra, water, land, true, keep);
}

// The pixels whose query disagrees with the picture (failures only with expectNone).
int queryMismatches(const Frame& f, const std::string& extra, int& water, int& land, bool expectNone,
                    const std::function<bool(const geo::Geodetic&)>& keep) {
  std::vector<geo::Geodetic> pts;
  std::vector<std::pair<int, int>> where;
  for (int y = 0; y < f.pose.height; y += 2)
    for (int x = 0; x < f.pose.width; x += 2) {
      geo::Geodetic g;
      if (!awayFromShore(f, x, y) || !groundPoint(f, x, y, g) || (keep && !keep(g))) continue;
      pts.push_back(g);
      where.emplace_back(x, y);
    }
  const auto rows = query(pts, extra);
  EXPECT_EQ(rows.size(), pts.size());
  if (rows.size() != pts.size()) return -1;
  int bad = 0;
  water = land = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bool drawn = f.drawn(where[i].first, where[i].second);
    (drawn ? water : land)++;
    const bool wet = rows[i].surface != "land";
    if (wet != drawn || rows[i].hasSeaHeight != drawn) {
      if (++bad <= 10 && expectNone)
        ADD_FAILURE() << "pixel " << where[i].first << "," << where[i].second << " drawn "
                      << (drawn ? "water" : "land") << ", query at " << pts[i].latDeg << "," << pts[i].lonDeg
                      << " says " << rows[i].surface << (rows[i].hasSeaHeight ? " with" : " without")
                      << " a sea height";
    }
  }
  if (expectNone) {
    EXPECT_EQ(bad, 0) << "of " << rows.size() << " pixels";
  }
  return bad;
}

TEST(Coast, CpuCoverageIsTheShadersBSpline) {
  Scene& s = scene();
  // A 256 x 128 window of the 3" mask round Tarifa, as a float texture.
  const int w = 256, h = 128, x0 = 380, y0 = 220;
  const world::MaskEncoding enc;
  std::vector<float> tex(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) tex[std::size_t(y) * w + x] = enc.isWater(s.mask->pixel(x0 + x, y0 + y)) ? 1.0f : 0.0f;
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, GL_R32F, w, h);
  glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RED, GL_FLOAT, tex.data());
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> ux(2.0f, w - 2.0f), uy(2.0f, h - 2.0f);
  constexpr int n = 32768;
  std::vector<float> pts(2 * n);
  for (int i = 0; i < n; ++i) pts[2 * i] = ux(rng), pts[2 * i + 1] = uy(rng);
  const std::string src = std::string("#version 450 core\n") + shaders::find("geo_uv.glsl")->text + R"(
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D uTex;
layout(std430, binding = 0) readonly buffer P { vec2 p[]; };
layout(std430, binding = 1) writeonly buffer C { float c[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  c[i] = textureBSplineGather(uTex, p[i] / vec2(textureSize(uTex, 0)));
}
)";
  GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
  const char* cs = src.c_str();
  glShaderSource(sh, 1, &cs, nullptr);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  char log[4096] = {};
  glGetShaderInfoLog(sh, sizeof log, nullptr, log);
  ASSERT_TRUE(ok) << log;
  GLuint prog = glCreateProgram();
  glAttachShader(prog, sh);
  glLinkProgram(prog);
  GLuint buf[2];
  glCreateBuffers(2, buf);
  glNamedBufferStorage(buf[0], GLsizeiptr(pts.size() * sizeof(float)), pts.data(), 0);
  glNamedBufferStorage(buf[1], GLsizeiptr(n * sizeof(float)), nullptr, GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buf[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buf[1]);
  glBindTextureUnit(0, t);
  glUseProgram(prog);
  glDispatchCompute(n / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> gpu(n);
  glGetNamedBufferSubData(buf[1], 0, GLsizeiptr(n * sizeof(float)), gpu.data());
  glDeleteProgram(prog);
  glDeleteShader(sh);
  glDeleteBuffers(2, buf);
  glDeleteTextures(1, &t);
  double worst = 0.0;
  int coastal = 0;
  for (int i = 0; i < n; ++i) {
    const world::CoverageClass c = world::coverageClassAt(pts[2 * i], pts[2 * i + 1], [&](int cx, int cy) {
      return tex[std::size_t(std::clamp(cy, 0, h - 1)) * w + std::clamp(cx, 0, w - 1)] > 0.5f ? world::Surface::Ocean
                                                                                            : world::Surface::Land;
    });
    worst = std::max(worst, double(std::abs(c.coverage - gpu[i])));
    coastal += c.coverage > 0.0f && c.coverage < 1.0f;
  }
  std::printf("GPU vs CPU coverage: worst %.2e over %d points (%d on the coast)\n", worst, n, coastal);
  EXPECT_GT(coastal, 800);
  // Both sum 16 float products of the same weights (textureGather returns
  // the texels exactly): a few float ulps of 1.
  EXPECT_LT(worst, 1e-5);
}

// The default world: the ocean draws the bundled 5' mask cell for cell.
TEST(Coast, QueryFollowsThePictureOnTheDefaultWorld) {
  int water = 0, land = 0;
  for (const auto& [name, p] :
       {std::pair{std::string("tarifa_5km"), pose(36.05, -5.62, 5000.0, 150.0, -50.0)},
        std::pair{std::string("gibraltar_20km"), pose(36.0, -5.45, 20000.0, 0.0, -70.0)}}) {
    const Frame f = render(p, false, name);
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, "", w, l);
    std::printf("%s: %d water, %d land pixels agree\n", name.c_str(), w, l);
    water += w, land += l;
  }
  EXPECT_GT(water, 2000);
  EXPECT_GT(land, 2000);
}

// The 3" mask (geocean mask) as a layer: `geocean query --mask` follows the
// ocean drawn from that mask's cells.
TEST(Coast, QueryFollowsThePictureWithThe3sGibraltarMask) {
  int water = 0, land = 0;
  for (const auto& [name, p] :
       {std::pair{std::string("tarifa_500m"), pose(36.012, -5.600, 500.0, 230.0, -45.0)},
        std::pair{std::string("tarifa_5km"), pose(36.05, -5.62, 5000.0, 150.0, -50.0)},
        std::pair{std::string("gibraltar_5km"), pose(36.10, -5.37, 5000.0, 20.0, -55.0)}}) {
    const Frame f = render(p, true, "3s_" + name);
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, " --mask " + gibraltarMask(), w, l);
    std::printf("3s %s: %d water, %d land pixels agree\n", name.c_str(), w, l);
    water += w, land += l;
  }
  EXPECT_GT(water, 2000);
  EXPECT_GT(land, 2000);
}

// A global mask finer than the water grid (the bundled 1.25' one) as a
// layer: the ocean draws its coverage from the mask's streamed tiles, so
// `geocean query --mask` follows the picture at every pixel away from the
// shoreline. Drawn from the 5' water grids alone (the control), the same
// views disagree.
TEST(Coast, QueryFollowsThePictureWithAStreamedGlobalMask) {
  Streamed& s = streamed();
  const std::string extra = " --mask " + raster::defaultWorld().maskFine;
  int water = 0, land = 0, controlBad = 0;
  for (const auto& [name, p] :
       {std::pair{std::string("tarifa_5km"), pose(36.05, -5.62, 5000.0, 150.0, -50.0)},
        std::pair{std::string("gibraltar_5km"), pose(36.10, -5.37, 5000.0, 20.0, -55.0)},
        std::pair{std::string("gibraltar_20km"), pose(36.0, -5.45, 20000.0, 0.0, -70.0)}}) {
    const Frame f = render(p, *s.renderer, s.ocean.get(), "streamed_" + name);
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, extra, w, l);
    const Frame g = render(p, *s.gridRenderer, s.gridOcean.get(), "streamed_control_" + name);
    int gw = 0, gl = 0;
    const int bad = queryMismatches(g, extra, gw, gl, false);
    std::printf("1.25' %s: %d water, %d land pixels agree; drawn from the grids: %d of %d disagree\n", name.c_str(),
                w, l, bad, gw + gl);
    water += w, land += l, controlBad += bad;
  }
  EXPECT_GT(water, 2000);
  EXPECT_GT(land, 2000);
  EXPECT_GT(controlBad, 100) << "the control (the grids' water) should disagree with the 1.25' query";
  const gl::TilePool& pool = s.ocean->waterPages()->pool();
  std::printf("ocean tile pool: %d resident, %llu uploads\n", pool.stats().resident,
              (unsigned long long)pool.stats().uploads);
  EXPECT_GT(pool.stats().uploads, 0u);
}

// A streamed global mask's shortcuts (issue 12 item 6: open water from
// the pyramid level that is the ocean's water grid, cheap shader variants
// there, the terrain left out under it) must not change the picture: each view drawn with them and
// by the reference without any (Streamed::refRenderer), as
// Render.ShortcutsDoNotChangeTheImage does for the default world. Views
// with the 1.25' mask's smallest islands (two cells near 37.01 N 26.44 E,
// inside grid texels that are mostly water) and coasts from orbit to 2 m;
// an open-water cell over a mask cell of land loses the island, a margin
// short of the paged footprint changes pixels at the limb from orbit (26
// with the mipmap's margin).
TEST(Coast, AStreamedMasksShortcutsDoNotChangeTheImage) {
  Streamed& s = streamed();
  const std::pair<const char*, ViewPose> views[] = {
      {"earth_20000km", pose(0.0, -150.0, 2.0e7, 0.0, -90.0)},
      {"aegean_300km", pose(37.5, 25.0, 3.0e5, 0.0, -90.0)},
      {"islet_30km", pose(37.01, 26.44, 3.0e4, 0.0, -90.0)},
      {"islet_oblique_8km", pose(36.95, 26.44, 8000.0, 0.0, -20.0)},
      {"gibraltar_50km", pose(36.0, -5.45, 5.0e4, 270.0, -50.0)},
      {"coast_300m", pose(35.95, -5.5, 300.0, 330.0, -8.0)},
      {"strait_2m", pose(36.0, -5.6, 2.0, 250.0, -3.0)},
  };
  std::size_t minified = 0;
  for (const auto& [name, p] : views) {
    s.ocean->setFarVertexShading(false);
    const Frame exact = render(p, *s.renderer, s.ocean.get(), std::string("shortcuts_") + name);
    // The coastal cells read minified (CellGroups::minified) fetch the
    // bilinear's texels alone: the same bits as the full paged variant.
    if (const std::size_t m = s.ocean->lastGroups().minified; m > 0) {
      s.ocean->setMinifiedCoverage(false);
      const Frame full = render(p, *s.renderer, s.ocean.get(), std::string("no_minified_") + name);
      s.ocean->setMinifiedCoverage(true);
      EXPECT_EQ(s.ocean->lastGroups().minified, 0u);
      const ImageDiff md = compare(full.image, exact.image);
      std::printf("1.25' %s: %zu of %zu sharp cells minified; without them: max %d\n", name, m / 6,
                  s.ocean->lastGroups().sharp / 6, md.max);
      EXPECT_EQ(md.max, 0) << name;
      minified += m;
    }
    s.refOcean->setCheapCoverage(false);
    s.refOcean->setCullOffscreen(false);
    s.refOcean->setFarVertexShading(false);
    const Frame full = render(p, *s.refRenderer, s.refOcean.get(), std::string("reference_") + name);
    s.ocean->setFarVertexShading(true);
    const Frame fast = render(p, *s.renderer, s.ocean.get(), std::string("far_per_vertex_") + name);
    const ImageDiff d = compare(full.image, exact.image), f = compare(exact.image, fast.image);
    int drawn = 0;
    for (const std::uint8_t o : exact.ocean) drawn += o;
    std::printf("1.25' %s: %d ocean pixels; shortcuts: mean %.4f, max %d, over 16: %.5f; far per vertex: mean %.4f, "
                "max %d\n",
                name, drawn, d.mean, d.max, d.fractionOver16, f.mean, f.max);
    // The bounds of Render.ShortcutsDoNotChangeTheImage: the same bits
    // where the ocean is opaque, one unit of blending at the coast; far
    // open water shaded per vertex a few units.
    EXPECT_LE(d.mean, 0.01) << name;
    EXPECT_EQ(d.fractionOver16, 0.0) << name;
    EXPECT_LE(f.mean, 0.1) << name;
    EXPECT_LE(f.max, 24) << name;
  }
  s.ocean->setFarVertexShading(true);
  EXPECT_GT(minified, 0u) << "no view drew minified cells";

  // The host's terrain over the sea 5 km off the coast (west of Cabo da
  // Roca), looking out to sea from 3 km: the grid's index sees the coast's
  // land within its reach, so the sea's tiles refined to the mask's texel
  // (level 12 here; flat at the sea's drop all the same). At the mask's own
  // cells they are water throughout and stop at the first level that is
  // (10 here, 19 tiles for 27), as the grid's open water stops at 7.
  constexpr double kLat = 38.78, kLon = -9.56;
  ASSERT_FALSE(s.world->waterIndex().allWaterAround(kLat - 0.02, kLat + 0.02, kLon - 0.02, kLon + 0.02, 1.0))
      << "the grid's index should see the coast";
  world::TileWaterIndex fine(s.world->waterTiles()->sharedPyramid());
  ASSERT_EQ(fine.cover(fine.texelX(kLon - 0.03), fine.texelX(kLon + 0.03), fine.texelY(kLat - 0.03), fine.texelY(kLat + 0.03)),
            world::TileWaterIndex::Cover::Water)
      << "the mask's cells should be sea";
  const ViewPose p = pose(kLat, kLon, 3000.0, 270.0, -20.0);
  gl::Framebuffer fb(p.width, p.height, true);
  fb.bind();
  const auto t = s.renderer->render(p, coastLight(p));
  std::printf("terrain off the coast: %d tiles, max level %d\n", t.terrain.tilesDrawn, t.terrain.maxLevel);
  EXPECT_GT(t.terrain.tilesDrawn, 0);
  EXPECT_LE(t.terrain.maxLevel, 11);

  // Near the shore from 2 - 300 m: terrain tiles whose vertex bilinear
  // reads only water texels are flat at the sea's drop (as the B-spline's
  // whole reach was asked before), so they stop at the open water's level:
  // fewer tiles, the same bits. And such tiles at level >= 9 are drawn
  // with 8 x 8 cells (no larger than level 7's, where open water stops):
  // the ocean covers them but at its anti-aliased coast and the horizon,
  // where the per-vertex haze and sea colour are interpolated over coarser
  // cells; bound: that of the shortcuts above (the same bits where the
  // ocean is opaque, a unit or so beside).
  const std::pair<const char*, ViewPose> shore[] = {
      {"coast_300m", pose(35.95, -5.5, 300.0, 330.0, -8.0)},
      {"tarifa_30m", pose(35.985, -5.6, 30.0, 0.0, -4.0)},  // the shore 2 - 4 km north
      {"strait_2m", pose(36.0, -5.6, 2.0, 250.0, -3.0)},
  };
  int before = 0, after = 0, flat = 0;
  for (const auto& [name, view] : shore) {
    s.renderer->terrain().setFlatWaterFromBilinear(false);
    s.renderer->terrain().setCoarseFlatTiles(false);
    const Frame old = render(view, *s.renderer, s.ocean.get(), std::string("bspline_reach_") + name);
    s.renderer->terrain().setFlatWaterFromBilinear(true);
    const Frame reach = render(view, *s.renderer, s.ocean.get(), std::string("bilinear_reach_") + name);
    s.renderer->terrain().setCoarseFlatTiles(true);
    const Frame now = render(view, *s.renderer, s.ocean.get(), std::string("coarse_flat_") + name);
    const ImageDiff d = compare(old.image, reach.image), c = compare(reach.image, now.image);
    std::printf("1.25' %s: terrain tiles %d (B-spline's reach) -> %d (bilinear's): max %d; %d of them coarse: "
                "mean %.5f, max %d\n",
                name, old.terrain.tilesDrawn, reach.terrain.tilesDrawn, d.max, now.terrain.tilesFlat, c.mean, c.max);
    EXPECT_EQ(d.max, 0) << name;
    EXPECT_EQ(old.terrain.tilesFlat, 0);
    EXPECT_EQ(now.terrain.tilesDrawn, reach.terrain.tilesDrawn);
    EXPECT_LE(c.mean, 0.01) << name;
    EXPECT_EQ(c.fractionOver16, 0.0) << name;
    before += old.terrain.tilesDrawn, after += reach.terrain.tilesDrawn, flat += now.terrain.tilesFlat;
  }
  EXPECT_GT(flat, 0) << "no tile drawn coarse";
  EXPECT_LT(after, before) << "no tile stopped earlier";
}

// Pixels of a frame whose drawn class differs from the side of the 3"
// mask's coverage-0.5 isoline their ground point is on, and of those the
// ones farther from the isoline than one pixel's ground footprint plus a
// quarter mask cell (searched on 8 circles of 32 points within that
// radius); worst: the largest distance found within it, metres.
struct Crispness {
  int pixels = 0, coastline = 0, offSide = 0, beyond = 0;
  double worstM = 0.0;
};
Crispness crispness(const Frame& f) {
  Scene& s = scene();
  const double cellM = kCellDeg * kDeg * geo::kWgs84B;
  Crispness c;
  for (int y = 1; y + 1 < f.pose.height; ++y)
    for (int x = 1; x + 1 < f.pose.width; ++x) {
      geo::Geodetic g, gx, gy;
      if (!groundPoint(f, x, y, g) || !groundPoint(f, x + 1, y, gx) || !groundPoint(f, x, y + 1, gy)) continue;
      const bool drawn = f.drawn(x, y);
      c.coastline += drawn != f.drawn(x + 1, y);
      ++c.pixels;
      const bool wet = s.fineLandSea->classify(g.latDeg, g.lonDeg) != world::Surface::Land;
      if (wet == drawn) continue;
      ++c.offSide;
      auto metres = [&](const geo::Geodetic& a) { return glm::length(geo::toEcef(a) - geo::toEcef(g)); };
      const double r = std::max(metres(gx), metres(gy)) + 0.25 * cellM;
      double at = -1.0;
      for (int k = 1; k <= 8 && at < 0; ++k)
        for (int a = 0; a < 32 && at < 0; ++a) {
          const double rr = r * k / 8.0, t = a * M_PI / 16.0;
          const double la = g.latDeg + rr * std::cos(t) / (kDeg * geo::kWgs84A);
          const double lo = g.lonDeg + rr * std::sin(t) / (kDeg * geo::kWgs84A * std::cos(g.latDeg * kDeg));
          if ((s.fineLandSea->classify(la, lo) != world::Surface::Land) == drawn) at = rr;
        }
      if (at < 0) ++c.beyond;
      else c.worstM = std::max(c.worstM, at);
    }
  return c;
}

// The same from 500 m on the product path: the regional 3" mask streamed
// on both sides over the default world (Regional), so the picture's
// coastline is the mask's own isoline, not its 5' resample.
TEST(Coast, CoastlineFrom500mLiesWithinAPixelAndAQuarterCellOfTheIsolineWithTheMaskStreamed) {
  Regional& r = regional();
  int coastline = 0;
  for (const auto& [name, p] : {std::pair{std::string("tarifa_500m_down"), pose(36.0095, -5.6044, 500.0, 0.0, -90.0)},
                                std::pair{std::string("tarifa_500m"), pose(36.012, -5.600, 500.0, 230.0, -45.0)}}) {
    const Crispness c = crispness(render(p, *r.renderer, r.ocean.get(), "regional_crisp_" + name));
    std::printf("streamed %s: %d pixels, %d on the drawn coastline, %d on the other side of the isoline, %d beyond "
                "the tolerance, worst %.2f m\n",
                name.c_str(), c.pixels, c.coastline, c.offSide, c.beyond, c.worstM);
    EXPECT_EQ(c.beyond, 0) << name;
    coastline += c.coastline;
  }
  EXPECT_GT(coastline, 300);
  EXPECT_GT(r.ocean->waterPages()->pool().stats().uploads, 0u);
  ASSERT_TRUE(r.world->waterTiles());
  EXPECT_GT(r.world->waterTiles()->stats().uploads, 0u);
}

// The product path's query follows its picture (geocean query --mask, the
// same stack) inside the region, and across its edges: near Cape Trafalgar
// (the region's west edge, -6, runs through it) and on the Moroccan
// Atlantic coast (its south edge, 35.75, crosses it), where outside the
// region the default world's 5' coast answers and is drawn. Views where the
// 3" texels are magnified (under a pixel: at most 10 km up here): minified,
// the picture is the mipmap's bilinear coverage, not the query's B-spline
// (from 20 km one pixel of 18086 on a sub-pixel creek disagreed).
TEST(Coast, QueryFollowsThePictureWithTheRegionalMaskStreamed) {
  Regional& r = regional();
  int water = 0, land = 0;
  for (const auto& [name, p] :
       {std::pair{std::string("tarifa_5km"), pose(36.05, -5.62, 5000.0, 150.0, -50.0)},
        std::pair{std::string("gibraltar_5km"), pose(36.10, -5.37, 5000.0, 20.0, -55.0)},
        std::pair{std::string("trafalgar_10km"), pose(36.18, -6.0, 10000.0, 0.0, -80.0)},
        std::pair{std::string("morocco_10km"), pose(35.75, -5.95, 10000.0, 0.0, -80.0)}}) {
    const Frame f = render(p, *r.renderer, r.ocean.get(), "regional_" + name);
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, " --mask " + gibraltarMask(), w, l);
    std::printf("regional %s: %d water, %d land pixels agree\n", name.c_str(), w, l);
    water += w, land += l;
  }
  EXPECT_GT(water, 4000);
  EXPECT_GT(land, 4000);
}

// No seam at the region's edge: away from it (by the B-spline's reach, two
// 3" texels, plus a pixel's footprint) the streamed picture draws water
// exactly where the default world's does outside the region, and where the
// 3" mask's coverage rule says inside it (within a pixel plus a quarter cell,
// as crispness() measures; counted, not required, near the coast).
TEST(Coast, OutsideTheRegionTheDefaultWorldsCoastIsDrawn) {
  Regional& r = regional();
  Scene& s = scene();
  for (const auto& [name, p] : {std::pair{std::string("trafalgar_20km"), pose(36.18, -6.0, 20000.0, 0.0, -80.0)},
                                std::pair{std::string("morocco_20km"), pose(35.75, -5.95, 20000.0, 0.0, -80.0)}}) {
    const Frame a = render(p, *r.renderer, r.ocean.get(), "regional_edge_" + name);
    const Frame b = render(p, *s.defaultRenderer, s.defaultOcean, "default_edge_" + name);
    int outside = 0, differ = 0, inside = 0;
    for (int y = 1; y + 1 < p.height; ++y)
      for (int x = 1; x + 1 < p.width; ++x) {
        geo::Geodetic g, gx;
        if (!groundPoint(a, x, y, g) || !groundPoint(a, x + 1, y, gx)) continue;
        // Margin: two 3" texels (the filter's reach) and a pixel's footprint.
        const double m = 2.0 * kCellDeg + std::abs(gx.lonDeg - g.lonDeg) + std::abs(gx.latDeg - g.latDeg);
        const bool out = g.lonDeg < -6.0 - m || g.lonDeg > -5.0 + m || g.latDeg < 35.75 - m || g.latDeg > 36.25 + m;
        const bool in = g.lonDeg > -6.0 + m && g.lonDeg < -5.0 - m && g.latDeg > 35.75 + m && g.latDeg < 36.25 - m;
        if (in) ++inside;
        if (!out) continue;
        ++outside;
        differ += a.drawn(x, y) != b.drawn(x, y);
      }
    std::printf("%s: %d pixels outside the region, %d drawn otherwise than the default world; %d inside\n",
                name.c_str(), outside, differ, inside);
    EXPECT_GT(outside, 5000) << name;
    EXPECT_GT(inside, 5000) << name;
    EXPECT_EQ(differ, 0) << name;
  }
}

// From 500 m with the 3" mask the drawn coastline lies within one pixel
// plus a quarter mask cell of the mask's coverage-0.5 isoline. The same
// views drawn from the default 5' world's water (a control) are not.
TEST(Coast, CoastlineFrom500mLiesWithinAPixelAndAQuarterCellOfTheIsoline) {
  int coastline = 0;
  for (const auto& [name, p] : {std::pair{std::string("tarifa_500m_down"), pose(36.0095, -5.6044, 500.0, 0.0, -90.0)},
                                std::pair{std::string("tarifa_500m"), pose(36.012, -5.600, 500.0, 230.0, -45.0)}}) {
    const Crispness fine = crispness(render(p, true, "crisp_" + name));
    const Crispness coarse = crispness(render(p, false, "crisp_5m_" + name));
    std::printf("%s: %d pixels, %d on the drawn coastline, %d on the other side of the isoline, %d beyond "
                "the tolerance, worst %.2f m; drawn from 5': %d beyond\n",
                name.c_str(), fine.pixels, fine.coastline, fine.offSide, fine.beyond, fine.worstM, coarse.beyond);
    EXPECT_EQ(fine.beyond, 0) << name;
    EXPECT_GT(coarse.beyond, 1000) << name << ": the control (5' water) should miss the 3\" isoline";
    coastline += fine.coastline;
  }
  EXPECT_GT(coastline, 300);
}

// An island that only a regional mask has, in open sea where the 5' grid
// below it is water for hundreds of km: the host's terrain must refine it
// like any land. Its all-water rule once read only the grid below (the
// host's WaterIndex), capped the island's tile at level 7 (2.4 km cells,
// no vertex on an 800 m island) and drew it as the terrain's sunken sea
// where the ocean left its hole. 3" cells, 0 ocean and 1 land, over
// 36.0..36.3 N, 7.5..7.0 W (the Gulf of Cadiz, 80 km from any coast); the
// island a disc of 0.004 degrees radius at (36.15 N, 7.25 W).
TEST(Coast, TheTerrainRefinesAnIslandOnlyTheRegionalMaskHas) {
  constexpr double kIslandLat = 36.15, kIslandLon = -7.25, kRadiusDeg = 0.004;
  const std::string path = ::testing::TempDir() + "/coast_regional_island." + std::to_string(::getpid()) + ".tif";
  {
    const int w = 600, h = 360;
    std::vector<std::uint8_t> px(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double lat = 36.3 - (y + 0.5) * kCellDeg, lon = -7.5 + (x + 0.5) * kCellDeg;
        if (std::hypot(lat - kIslandLat, (lon - kIslandLon) * std::cos(kIslandLat * kDeg)) < kRadiusDeg)
          px[std::size_t(y) * w + x] = 1;
      }
    raster::GeoTiffWriteOptions wo;
    wo.transform = {-7.5, 36.3, kCellDeg, -kCellDeg, false};
    raster::writeGeoTiff(path, px.data(), w, h, 1, raster::SampleType::U8, wo);
  }
  Regional r = makeRegional(path);
  ASSERT_NE(r.world->regionalWaterIndex(), nullptr);
  // The grid below calls the whole tile round the island water.
  EXPECT_TRUE(r.world->waterIndex().allWaterAround(kIslandLat - 0.5, kIslandLat + 0.5, kIslandLon - 0.5,
                                                    kIslandLon + 0.5, 1.0));
  const ViewPose p = pose(kIslandLat, kIslandLon, 3000.0, 0.0, -90.0);
  gl::Framebuffer fb(p.width, p.height, true);
  fb.bind();
  const auto t = r.renderer->render(p, coastLight(p));
  gl::writePng(::testing::TempDir() + "/coast_regional_island.png", fb.readColor());
  std::printf("terrain: %d tiles, max level %d\n", t.terrain.tilesDrawn, t.terrain.maxLevel);
  // 3 km up the island's tile cells are over a thousand pixels: land
  // refines to level 10 and beyond, as Render.TerrainRefinesAnIslandBetween
  // ATilesSamples finds for an island of the grid itself.
  EXPECT_GT(t.terrain.maxLevel, 8);
  // The ocean draws the island as land (its hole) and the sea round it.
  const Frame f = render(p, *r.renderer, r.ocean.get(), "regional_island");
  EXPECT_FALSE(f.drawn(p.width / 2, p.height / 2));
  EXPECT_TRUE(f.drawn(10, 10));
  int w = 0, l = 0;
  expectQueryFollowsPicture(f, " --mask " + path, w, l);
  std::printf("regional island: %d water, %d land pixels agree\n", w, l);
  EXPECT_GT(l, 100);
  fs::remove(path);
}

// A regional mask across the antimeridian is one piece (raster::lonNear):
// the query, the ocean's pages and the host's terrain tiles read -179.9 as
// its 180.1. Taveuni (Fiji), 179.5 E .. 179.5 W, 3" GSHHG by `geocean mask`:
// the island straddles 180 and Qamea and Laucala lie west of it. Truth is
// the mask file's own cells, indexed here by hand (x from lon + 360 west of
// 180): every pixel away from the drawn shoreline whose ground point has
// one class over the 5 x 5 cells round it (beyond the B-spline's reach)
// must be drawn on that side; and `geocean query --mask` follows the
// picture there. On both sides of 180, counted apart. The control: the
// default world drawn at the same views (what the west half showed before,
// when both the query and the picture left it to the layers below).
TEST(Coast, ARegionalMaskAcrossTheAntimeridianDrawsAndAnswersOnBothSides) {
  const std::string path = ::testing::TempDir() + "/coast_taveuni_3s." + std::to_string(::getpid()) + ".tif";
  fs::remove(path);
  const auto made =
      geocean::test::run(kExe + " mask --quiet --region 179.5/180.5/-17.2/-16.5 --resolution 3s --out " + path);
  ASSERT_EQ(made.exitCode, 0) << made.err;
  const auto mask = raster::Raster::open(path);
  ASSERT_EQ(mask->width(), 1200);
  ASSERT_EQ(mask->height(), 840);
  const auto cellWater = [&](double lat, double lon, bool& uniform) {
    const int cx = int(std::floor(((lon < 0.0 ? lon + 360.0 : lon) - 179.5) / kCellDeg));
    const int cy = int(std::floor((-16.5 - lat) / kCellDeg));
    uniform = cx >= 2 && cy >= 2 && cx + 2 < 1200 && cy + 2 < 840;
    if (!uniform) return false;
    const float v = mask->pixel(cx, cy);  // 0 ocean, 1 land (lakes, 2, left out)
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) uniform = uniform && mask->pixel(cx + dx, cy + dy) == v;
    uniform = uniform && v <= 1.0f;
    return v == 0.0f;
  };
  Regional r = makeRegional(path);
  Scene& s = scene();
  int counted[2][2] = {{0, 0}, {0, 0}};  // [west of 180][water]
  int bad = 0, controlBad = 0;
  for (const auto& [name, p] : {std::pair{std::string("180_15km"), pose(-16.85, 180.0, 15000.0, 0.0, -85.0)},
                                std::pair{std::string("qamea_10km"), pose(-16.74, -179.82, 10000.0, 0.0, -90.0)},
                                std::pair{std::string("taveuni_8km"), pose(-16.93, 179.93, 8000.0, 40.0, -60.0)}}) {
    const Frame f = render(p, *r.renderer, r.ocean.get(), "antimeridian_" + name);
    const Frame c = render(p, *s.defaultRenderer, s.defaultOcean, "antimeridian_default_" + name);
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, " --mask " + path, w, l);
    for (int y = 0; y < p.height; y += 2)
      for (int x = 0; x < p.width; x += 2) {
        geo::Geodetic g;
        bool uniform = false;
        if (!awayFromShore(f, x, y) || !groundPoint(f, x, y, g)) continue;
        const bool water = cellWater(g.latDeg, g.lonDeg, uniform);
        if (!uniform) continue;
        counted[g.lonDeg < 0.0][water]++;
        if (f.drawn(x, y) != water && ++bad <= 10)
          ADD_FAILURE() << name << ": pixel " << x << "," << y << " at " << g.latDeg << "," << g.lonDeg << " drawn "
                        << (f.drawn(x, y) ? "water" : "land") << ", the mask says " << (water ? "water" : "land");
        controlBad += awayFromShore(c, x, y) && c.drawn(x, y) != water;
      }
    std::printf("%s: query and picture agree at %d water, %d land pixels\n", name.c_str(), w, l);
  }
  std::printf("against the mask's cells: west of 180 %d water %d land, east %d water %d land; %d wrong; "
              "the default world %d wrong\n",
              counted[1][1], counted[1][0], counted[0][1], counted[0][0], bad, controlBad);
  EXPECT_EQ(bad, 0);
  for (int west = 0; west < 2; ++west)
    for (int water = 0; water < 2; ++water)
      EXPECT_GT(counted[west][water], 500) << "west " << west << " water " << water;
  EXPECT_GT(controlBad, 200) << "the default world should differ from the 3\" mask here";
  fs::remove(path);
}

// A relief finer than every mask decides the coast (issue 12 item 1: its
// 0 m line is land's edge), and a regional one is streamed like a mask: its
// 0 m line drawn at its own cells on both sides (world::reliefWaterPyramid),
// not resampled on the 5' grid, which misses this island. A 3" F32 relief
// over 36.0..36.3 N, 7.5..7.0 W (the Gulf of Cadiz, 80 km from any coast):
// a sea floor at -60 m and a Gaussian island 300 exp(-(r/s)^2) - 60 m, s =
// 0.00315 degrees, whose coast is the circle r0 = s sqrt(ln 5) = 0.0040
// degrees (445 m north-south) round (36.15 N, 7.25 W). The truth is that
// circle: every pixel whose ground point is farther from it than its own
// footprint plus one 3" cell (the binary cells' B-spline puts the 0.5
// contour within half a cell of the cells' edge, and the edge within half a
// cell of the 0 m line) must be drawn on its side; and `geocean query
// --elevation` follows the picture at every pixel away from the shore.
// Looking straight down: no ray is shallower than 56 degrees, steeper than
// the island's flank (23 degrees at the coast), so no sea hides behind it.
void reliefIslandIsDrawnAndQueried(const double kIslandLat, const double kIslandLon, const std::string& tag) {
  constexpr double kS = 0.00315;
  const double r0 = kS * std::sqrt(std::log(300.0 / 60.0));
  const std::string path = ::testing::TempDir() + "/coast_" + tag + "." + std::to_string(::getpid()) + ".tif";
  const double cosLat = std::cos(kIslandLat * kDeg);
  const auto rDeg = [&](double lat, double lon) {
    return std::hypot(lat - kIslandLat, std::remainder(lon - kIslandLon, 360.0) * cosLat);
  };
  {
    const int w = 600, h = 360;
    std::vector<float> px(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double r = rDeg(kIslandLat + 0.15 - (y + 0.5) * kCellDeg, kIslandLon - 0.25 + (x + 0.5) * kCellDeg);
        px[std::size_t(y) * w + x] = float(300.0 * std::exp(-(r / kS) * (r / kS)) - 60.0);
      }
    raster::GeoTiffWriteOptions wo;
    wo.transform = {kIslandLon - 0.25, kIslandLat + 0.15, kCellDeg, -kCellDeg, false};
    raster::writeGeoTiff(path, px.data(), w, h, 1, raster::SampleType::F32, wo);
  }
  // The 5' grid below (the default world) is open sea round the island.
  {
    const world::WorldData d = world::loadLayeredWorld({{world::LayerKind::Elevation, path, "", 0}}, true);
    ASSERT_TRUE(d.waterSource) << "the relief's coast should be streamed";
    EXPECT_TRUE(d.waterFromRelief);
    EXPECT_EQ(d.waterSource->path(), path);
    const world::WorldGrids g(d.elevation, d.water);
    EXPECT_TRUE(g.waterIndex().allWaterAround(kIslandLat - 0.1, kIslandLat + 0.1, kIslandLon - 0.1, kIslandLon + 0.1, 1.0));
  }
  Regional r = makeRegional(path, world::LayerKind::Elevation);
  ASSERT_TRUE(r.world->waterTiles());
  ASSERT_NE(r.world->regionalWaterIndex(), nullptr);
  const double cellM = kCellDeg * kDeg * geo::kWgs84B;
  int water = 0, land = 0, checked = 0, wrong = 0, checkedWest = 0;
  const double eastLon = std::remainder(kIslandLon + r0 / cosLat, 360.0);  // the island's east coast
  for (const auto& [name, p] : {std::pair{tag + "_3km", pose(kIslandLat, kIslandLon, 3000.0, 0.0, -90.0)},
                                std::pair{tag + "_east_1200m", pose(kIslandLat, eastLon, 1200.0, 0.0, -90.0)}}) {
    const Frame f = render(p, *r.renderer, r.ocean.get(), name);
    for (int y = 0; y + 1 < p.height; ++y)
      for (int x = 0; x + 1 < p.width; ++x) {
        geo::Geodetic g, gx, gy;
        if (!groundPoint(f, x, y, g) || !groundPoint(f, x + 1, y, gx) || !groundPoint(f, x, y + 1, gy)) continue;
        auto metres = [&](const geo::Geodetic& a) { return glm::length(geo::toEcef(a) - geo::toEcef(g)); };
        const double marginM = std::max(metres(gx), metres(gy)) + cellM;
        const double offM = (rDeg(g.latDeg, g.lonDeg) - r0) * kDeg * geo::kWgs84B;
        if (std::abs(offM) <= marginM) continue;
        ++checked;
        checkedWest += g.lonDeg < -90.0;  // west of 180 (the island at 180)
        if (f.drawn(x, y) != (offM > 0.0) && ++wrong <= 10)
          ADD_FAILURE() << name << " pixel " << x << "," << y << " drawn " << (f.drawn(x, y) ? "water" : "land") << " "
                        << offM << " m from the 0 m circle";
      }
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, " --elevation " + path, w, l);
    std::printf("%s: %d water, %d land pixels agree with the query\n", name.c_str(), w, l);
    water += w, land += l;
  }
  std::printf("%s: %d pixels off the 0 m circle by more than a pixel and a cell (%d west of 180), %d drawn on the "
              "wrong side\n",
              tag.c_str(), checked, checkedWest, wrong);
  if (std::abs(kIslandLon) == 180.0) {
    EXPECT_GT(checkedWest, 20000) << "both sides of 180";
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(checked, 50000);
  EXPECT_GT(water, 2000);
  EXPECT_GT(land, 2000);
  fs::remove(path);
}

TEST(Coast, AReliefFinerThanEveryMaskDrawsItsOwnCoastStreamed) {
  reliefIslandIsDrawnAndQueried(36.15, -7.25, "relief_island");
}

// The same island on the antimeridian (21.5 S 180, the South Fiji Basin,
// open sea in the 5' grid): the relief's 3" cells over 179.75 E .. 179.75 W
// stream as one piece (its water pyramid on both sides, its elevation
// tiles on the host), half the island west of 180.
TEST(Coast, AReliefIslandOnTheAntimeridianIsDrawnAndQueriedOnBothSides) {
  reliefIslandIsDrawnAndQueried(-21.5, 180.0, "relief_island_180");
}

// The sea's water depth from a streamed relief (issues 12 and 15): a
// regional 1" shelf whose depth steps from 4 m to 40 m at one texel edge
// (a step the 5' grid cannot have: 144 x 144 texels over 0.04 deg, inside
// one 5' cell), seen straight down from 60 m, centred on the step. The
// drawn depth (ocean.vert's vDepthM, the data target's depth mode) at each
// sea pixel against the query's (-elevation at the drawn surface point,
// LayerStack::elevationBatch): where the 4 query texels round every grid
// vertex within reach are one depth (farther than a grid cell plus a texel
// from the step) exactly that depth (float: 1e-3 m); on the 1-texel ramp
// between the two texel centres within the linear interpolation's error
// over a grid cell of a piecewise linear function whose slope jumps by s =
// 36 m / 30.9 m: s x (cell diagonal) / 4, plus 0.05 m. Placed at 0 E and on
// the antimeridian (the raster spanning 179.98 E .. 179.98 W, the step at
// 180): the same pictures' depths pixel for pixel within 0.01 m (the eye-
// relative texel positions; float longitudes near 180 are 1.7 m apart, a
// 2 m depth error on the ramp). One test for both, one world with both
// shelves as two streamed reliefs.
struct ShelfDepth {
  std::vector<float> drawn;  // vDepthM, NaN where the sea did not draw
  std::vector<double> query;  // -elevation at the drawn surface point, NaN off the sea
  std::vector<int> kind;      // 0 off the sea, 1 flat (one depth within reach), 2 ramp
  int flat = 0, ramp = 0, flatWrong = 0, rampWrong = 0;
  double flatMaxErr = 0.0, rampMaxErr = 0.0, rampMaxBound = 0.0, rampRmsErr = 0.0;
  glm::dvec3 shallowRgb{0.0}, deepRgb{0.0};  // median colour of the flat pixels on each side
  int shallowN = 0, deepN = 0;
};

constexpr double kShelfCellDeg = 1.0 / 3600.0;  // 1"

std::string writeShelf(double lat0, double stepLon, const std::string& tag) {
  constexpr double kC = kShelfCellDeg;
  constexpr int kN = 144;
  const double originLon = stepLon - 72 * kC, originLat = lat0 + 72 * kC;
  const std::string path = ::testing::TempDir() + "/shelf_" + tag + "." + std::to_string(::getpid()) + ".tif";
  {
    std::vector<float> px(std::size_t(kN) * kN);
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) px[std::size_t(y) * kN + x] = x < 72 ? -4.0f : -40.0f;
    raster::GeoTiffWriteOptions wo;
    wo.transform = {originLon, originLat, kC, -kC, false};
    raster::writeGeoTiff(path, px.data(), kN, kN, 1, raster::SampleType::F32, wo);
  }
  return path;
}

ShelfDepth shelfDepth(Regional& r, double lat0, double stepLon, const std::string& tag) {
  constexpr double kC = kShelfCellDeg;
  ShelfDepth out;
  const ViewPose p = pose(lat0, std::remainder(stepLon, 360.0), 60.0, 0.0, -90.0);
  const Frame f = render(p, *r.renderer, r.ocean.get(), "shelf_" + tag);  // positions, colour
  r.ocean->setWriteDepthData(true);
  std::vector<float> data;
  {
    gl::Framebuffer fb(p.width, p.height, true);
    fb.bind();
    r.renderer->render(p, coastLight(p));
    data = fb.readData();
  }
  r.ocean->setWriteDepthData(false);
  const std::size_t n = std::size_t(p.width) * p.height;
  out.drawn.assign(n, NAN);
  out.query.assign(n, NAN);
  out.kind.assign(n, 0);
  const double cosLat = std::cos(lat0 * kDeg), texelM = kC * kDeg * geo::kWgs84A * cosLat;
  const double slope = 36.0 / texelM;
  std::array<std::vector<int>, 3> shallowC, deepC;
  for (int y = 0; y + 1 < p.height; ++y)
    for (int x = 0; x + 1 < p.width; ++x) {
      const std::size_t i = std::size_t(y) * p.width + x;
      if (!f.drawn(x, y) || data[4 * i + 3] != 2.0f || !awayFromShore(f, x, y)) continue;
      geo::Geodetic g, gx, gy;
      if (!groundPoint(f, x, y, g) || !groundPoint(f, x + 1, y, gx) || !groundPoint(f, x, y + 1, gy)) continue;
      const auto metres = [&](const geo::Geodetic& a) { return glm::length(geo::toEcef(a) - geo::toEcef(g)); };
      const double cellM = 8.0 * std::max(metres(gx), metres(gy));  // OceanOptions::cellPx
      float e = NAN;
      r.landSea->elevationBatch(&g.latDeg, &g.lonDeg, 1, &e);
      const double q = -double(e), d = double(data[4 * i]);
      out.drawn[i] = float(d), out.query[i] = q;
      // Metres east of the step (the texel edge); the ramp spans +-half a texel.
      const double eastM = std::remainder(g.lonDeg - stepLon, 360.0) * kDeg * geo::kWgs84A * cosLat;
      const double err = std::abs(d - q);
      if (std::abs(eastM) > 0.5 * texelM + cellM * std::sqrt(2.0)) {
        out.kind[i] = 1, ++out.flat;
        out.flatMaxErr = std::max(out.flatMaxErr, err);
        if (err > 1e-3 && ++out.flatWrong <= 5)
          ADD_FAILURE() << tag << " flat pixel " << x << "," << y << " drawn depth " << d << " m, query " << q << " m";
        const std::uint8_t* c = &f.image.rgba[4 * i];
        for (int k = 0; k < 3; ++k) (eastM < 0.0 ? shallowC : deepC)[k].push_back(c[k]);
        ++(eastM < 0.0 ? out.shallowN : out.deepN);
      } else {
        out.kind[i] = 2, ++out.ramp;
        const double bound = slope * cellM * std::sqrt(2.0) / 4.0 + 0.05;
        out.rampMaxErr = std::max(out.rampMaxErr, err);
        out.rampRmsErr += err * err;
        out.rampMaxBound = std::max(out.rampMaxBound, bound);
        if (err > bound && ++out.rampWrong <= 5)
          ADD_FAILURE() << tag << " ramp pixel " << x << "," << y << " drawn depth " << d << " m, query " << q
                        << " m, bound " << bound << " m";
      }
    }
  out.rampRmsErr = std::sqrt(out.rampRmsErr / std::max(out.ramp, 1));
  const auto median = [](std::vector<int>& v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return double(v[v.size() / 2]);
  };
  for (int k = 0; k < 3; ++k) out.shallowRgb[k] = median(shallowC[k]), out.deepRgb[k] = median(deepC[k]);
  std::printf("%s: %d flat px (max |drawn - query| %.2g m, %d wrong), %d ramp px (max %.3f m, bound <= %.3f m, %d "
              "wrong, rms %.3f m); median colour 4 m side %.1f %.1f %.1f (%d px), 40 m side %.1f %.1f %.1f (%d px)\n",
              tag.c_str(), out.flat, out.flatMaxErr, out.flatWrong, out.ramp, out.rampMaxErr, out.rampMaxBound,
              out.rampWrong, out.rampRmsErr, out.shallowRgb.r, out.shallowRgb.g, out.shallowRgb.b, out.shallowN, out.deepRgb.r,
              out.deepRgb.g, out.deepRgb.b, out.deepN);
  EXPECT_GT(out.flat, 20000) << tag;
  EXPECT_GT(out.ramp, 10000) << tag;
  EXPECT_GT(out.shallowN, 5000) << tag;
  EXPECT_GT(out.deepN, 5000) << tag;
  return out;
}

TEST(Coast, TheSeasDepthFollowsAStreamedShelfStepAtZeroAndOnTheAntimeridian) {
  // Both shelves in one stack (one world to build): two streamed reliefs,
  // each answering where the other has no data (GEOCEAN_ELEV_PAGES 2).
  const std::vector<std::string> paths = {writeShelf(-21.5, 0.0, "0e"), writeShelf(-21.5, 180.0, "180")};
  Regional r = makeRegional(paths, world::LayerKind::Elevation);
  ASSERT_TRUE(r.ocean->elevationPages()) << "the reliefs should stream";
  EXPECT_EQ(r.ocean->elevationPages()->layers(), 2);
  const ShelfDepth a = shelfDepth(r, -21.5, 0.0, "0e");
  const ShelfDepth b = shelfDepth(r, -21.5, 180.0, "180");
  for (const std::string& p : paths) fs::remove(p);
  // The same interpolation error on the ramp at 180 as at 0 E: the grid's
  // vertices lie alike on the relief (the waves, anchored to the Earth,
  // differ: drawn points move by their displacement, hence a margin).
  // Float longitudes (1.7 m apart near 180) gave 0.94 m there, 0.39 at 0 E.
  std::printf("ramp error 0 E: max %.3f rms %.3f m; 180: max %.3f rms %.3f m\n", a.rampMaxErr, a.rampRmsErr,
              b.rampMaxErr, b.rampRmsErr);
  EXPECT_LT(std::abs(b.rampMaxErr - a.rampMaxErr), 0.05);
  EXPECT_LT(std::abs(b.rampRmsErr - a.rampRmsErr), 0.1 * a.rampRmsErr);
  // The picture: refraction's bottom shows the 4 m shelf greener than the
  // 40 m side (both places alike; whitecaps differ, hence medians).
  for (const ShelfDepth* s : {&a, &b})
    EXPECT_GT(s->shallowRgb.g - s->deepRgb.g, 5.0) << "the 4 m side's bottom should show";
}

// The seabed seen through the sea has no step where the default world's
// 20' relief crosses 0 m inside the mask's sea (the quick-start flight's
// straight seam south of Tarifa: the relief's shallows, 9-23 m, met the
// coverage's 60 m floor along its 0 m line, straight across a 37 km cell).
// Straight down from 10 km over that line (36.025 N, 5.70 W; 33 m a pixel):
// between any two neighbouring sea pixels away from the shoreline the depth
// seen (the data target's depth mode) changes by at most 0.1 x the metres
// between their ground points: three times the steepest of what it is
// drawn from (the floor's 60 m over the 5' coverage's ramp of at least a
// 9 km texel, 0.007; the blend's 60 m over the relief's first 20 m, which
// take over 2 km here, 0.03; the relief itself, < 0.01). Without the blend
// the step was up to 60 m between neighbours (4 m over 35 m at this view's
// worst). Set-up check: the relief's 0 m line crosses the view (the drawn
// relief depth changes sign between neighbours at > 100 pairs).
TEST(Coast, TheSeabedSeenHasNoStepWhereTheCoarseReliefCrossesSeaLevelInTheSea) {
  auto& renderer = *session().renderer;
  auto& ocean = sessionOcean();
  const ViewPose p = pose(36.025, -5.70, 10000.0, 0.0, -90.0);
  const Frame f = render(p, renderer, &ocean, "relief_line");
  ocean.setWriteDepthData(true);
  std::vector<float> data;
  {
    gl::Framebuffer fb(p.width, p.height, true);
    fb.bind();
    renderer.render(p, coastLight(p));
    data = fb.readData();
  }
  ocean.setWriteDepthData(false);
  const auto sea = [&](int x, int y) {
    return f.drawn(x, y) && data[4 * (std::size_t(y) * p.width + x) + 3] == 2.0f && awayFromShore(f, x, y);
  };
  int pairs = 0, crossings = 0, steep = 0;
  double worst = 0.0;
  for (int y = 0; y + 1 < p.height; ++y)
    for (int x = 0; x + 1 < p.width; ++x) {
      if (!sea(x, y)) continue;
      geo::Geodetic g;
      ASSERT_TRUE(groundPoint(f, x, y, g));
      const std::size_t i = std::size_t(y) * p.width + x;
      for (const auto& [nx, ny] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
        if (!sea(nx, ny)) continue;
        geo::Geodetic h;
        ASSERT_TRUE(groundPoint(f, nx, ny, h));
        const std::size_t j = std::size_t(ny) * p.width + nx;
        const double metres = glm::length(geo::toEcef(g) - geo::toEcef(h));
        const double slope = std::abs(double(data[4 * i + 1]) - double(data[4 * j + 1])) / std::max(metres, 1e-3);
        ++pairs;
        crossings += (data[4 * i] > 0.0f) != (data[4 * j] > 0.0f);
        worst = std::max(worst, slope);
        if (slope > 0.1 && ++steep <= 5)
          ADD_FAILURE() << "pixels " << x << "," << y << " and " << nx << "," << ny << ": depth seen "
                        << data[4 * i + 1] << " and " << data[4 * j + 1] << " m, " << metres << " m apart";
      }
    }
  std::printf("%d neighbouring sea pairs, %d across the relief's 0 m line, steepest seen depth change %.4f\n", pairs,
              crossings, worst);
  EXPECT_GT(pairs, 50000);
  EXPECT_GT(crossings, 100) << "the relief's 0 m line should cross the view";
  EXPECT_EQ(steep, 0);
}

// Several streamed masks of a kind (issue 12 item 2): two overlapping
// regional masks over the default world, both streamed (the ocean's pages
// fall through them in answer order, world::streamedWaterLayers). In the
// Gulf of Cadiz (open sea in the 5' grid, as the island test's): A, 3" over
// 36.10..36.30 N, 7.40..7.10 W, with islands A1 in the overlap and A2 where
// only A has data, and a nodata square (255, declared) in the overlap; B, 6" over
// 36.00..36.20 N, 7.50..7.20 W, with B1 in the overlap (partly under A's
// water: not drawn there; drawn in A's nodata square) and B2 where only B
// has data. At the same priority the finer A answers first. Truth is the
// files' own cells, indexed here by hand: the answering layer at a point
// is A where A's nearest cell has data, else B where B's has, else the
// default world (open sea here); a pixel whose 5 x 5 cells round it in that
// layer all have that layer's data and one class (past the B-spline's
// reach of any other layer's texel) must be drawn that class. `geocean
// query` with both masks follows the picture at every pixel away from the
// drawn shoreline. Control: the first mask alone streamed (the pages before
// this chain), B from the 5' grid, loses B2.
TEST(Coast, TwoOverlappingRegionalMasksAreDrawnAndAnsweredAsTheStackSays) {
  struct Disc {
    double lat, lon, r;
  };
  struct Mask {
    std::string path;
    double lon0, lat0, cell;
    int w, h;
    std::vector<Disc> islands;
    double holeLat0 = 0, holeLat1 = 0, holeLon0 = 0, holeLon1 = 0;  // nodata
    std::vector<std::uint8_t> px;
    // -1 outside, 255 nodata, else the class value (0 ocean, 1 land).
    int cellAt(int cx, int cy) const {
      return cx < 0 || cy < 0 || cx >= w || cy >= h ? -1 : px[std::size_t(cy) * w + cx];
    }
    int cx(double lon) const { return int(std::floor((lon - lon0) / cell)); }
    int cy(double lat) const { return int(std::floor((lat0 - lat) / cell)); }
  };
  const double cosLat = std::cos(36.15 * kDeg);
  const std::string dir = ::testing::TempDir() + "/coast_two_masks." + std::to_string(::getpid());
  fs::create_directories(dir);
  Mask a{dir + "/a_3s.tif", -7.40, 36.30, kCellDeg, 360, 240, {{36.15, -7.30, 0.008}, {36.25, -7.15, 0.008}}, 0, 0, 0, 0, {}};
  a.holeLat0 = 36.11, a.holeLat1 = 36.14, a.holeLon0 = -7.27, a.holeLon1 = -7.23;
  Mask b{dir + "/b_6s.tif", -7.50, 36.20, 2.0 * kCellDeg, 180, 120, {{36.14, -7.26, 0.012}, {36.05, -7.42, 0.012}}, 0, 0, 0, 0, {}};
  for (Mask* m : {&a, &b}) {
    m->px.assign(std::size_t(m->w) * m->h, 0);
    for (int y = 0; y < m->h; ++y)
      for (int x = 0; x < m->w; ++x) {
        const double lat = m->lat0 - (y + 0.5) * m->cell, lon = m->lon0 + (x + 0.5) * m->cell;
        std::uint8_t& v = m->px[std::size_t(y) * m->w + x];
        for (const Disc& d : m->islands)
          if (std::hypot(lat - d.lat, (lon - d.lon) * cosLat) < d.r) v = 1;
        if (lat > m->holeLat0 && lat < m->holeLat1 && lon > m->holeLon0 && lon < m->holeLon1) v = 255;
      }
    raster::GeoTiffWriteOptions wo;
    wo.transform = {m->lon0, m->lat0, m->cell, -m->cell, false};
    if (m == &a) wo.nodata = 255.0;  // A's pools R32F (its nodata reaches the shader), B's R8
    raster::writeGeoTiff(m->path, m->px.data(), m->w, m->h, 1, raster::SampleType::U8, wo);
  }
  // The layer that answers at a point, by its nearest cell (0 A, 1 B, 2 the default world), and whether the
  // 5 x 5 cells round the point in it all have its data and one class (`cls`, 1 land).
  const auto truth = [&](double lat, double lon, int& cls) {
    int layer = 2;
    for (int k = 0; k < 2 && layer == 2; ++k) {
      const Mask& m = k == 0 ? a : b;
      const int c = m.cellAt(m.cx(lon), m.cy(lat));
      if (c >= 0 && c != 255) layer = k;
    }
    cls = 0;
    if (layer == 2) return std::pair{layer, false};
    const Mask& m = layer == 0 ? a : b;
    const int x = m.cx(lon), y = m.cy(lat);
    cls = m.cellAt(x, y);
    bool uniform = true;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) uniform = uniform && m.cellAt(x + dx, y + dy) == cls;
    // B answers near A only past A's filter reach (2 of A's cells and a margin).
    if (layer == 1)
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          const int c = a.cellAt(a.cx(lon) + dx, a.cy(lat) + dy);
          uniform = uniform && (c < 0 || c == 255);
        }
    return std::pair{layer, uniform};
  };

  session();  // the GL context (scene() would build the 3" Gibraltar world too)
  const std::string cache = dir + "/tiles";
  ::setenv("GEOCEAN_TILE_CACHE", cache.c_str(), 1);
  world::WorldData d = world::loadLayeredWorld({{world::LayerKind::Mask, b.path, "", 0}, {world::LayerKind::Mask, a.path, "", 0}}, true);
  ASSERT_TRUE(d.waterSource);
  EXPECT_EQ(d.waterSource->path(), a.path) << "the finer mask answers first";
  TerrainOptions t;
  t.waitForTiles = true;
  auto worldTex = std::make_shared<WorldTextures>(d);
  GlobeRenderer renderer(worldTex, t);
  ocean::Ocean o;
  o.setDefaultWorld(ocean::Ocean::defaultWorldDir());
  o.addMaskLayerFile(b.path);
  o.addMaskLayerFile(a.path);
  const auto snap = o.current();
  auto layers = ocean_render::oceanWaterTileLayers(snap->landSea.get(), snap->mask);
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0]->source().path(), a.path);
  EXPECT_EQ(layers[1]->source().path(), b.path);
  ocean_render::OceanOptions oo;
  oo.waterTiles = layers[0];
  oo.waterTilesBelow = {layers[1]};
  const auto grids = ocean_render::oceanWorld(snap->mask, snap->elevation, snap->landSea.get(), snap->maskEncoding,
                                              layers[0].get());
  auto ocean = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
  ocean->setCompleteTiles(true);
  renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
  // The control: A streamed alone, B and the world from the grid below A.
  ocean_render::OceanOptions one;
  one.waterTiles = layers[0];
  const auto* layered = dynamic_cast<const ocean::LayeredLandSea*>(snap->landSea.get());
  ASSERT_NE(layered, nullptr);
  const auto gridsOne = std::make_shared<const world::WorldGrids>(
      grids->elevation(), world::waterLayerBelow(layered->stack(), layers[0]->source()));
  auto oceanOne = std::make_shared<ocean_render::OceanRenderer>(gridsOne, snap->landSea, one);
  oceanOne->setCompleteTiles(true);
  GlobeRenderer rendererOne(worldTex, t);
  rendererOne.addLayer(std::make_shared<DirectOceanLayer>(oceanOne));

  const std::string extra = " --mask " + b.path + " --mask " + a.path;
  int counted[3][2] = {{0, 0}, {0, 0}, {0, 0}};  // [layer][land]
  int overlap = 0, inHole = 0, bad = 0, controlBad = 0, water = 0, land = 0;
  for (const auto& [name, p] : {std::pair{std::string("overlap_12km"), pose(36.15, -7.28, 12000.0, 0.0, -90.0)},
                                std::pair{std::string("b_only_15km"), pose(36.02, -7.42, 15000.0, 0.0, -90.0)},
                                std::pair{std::string("a_only_12km"), pose(36.24, -7.16, 12000.0, 0.0, -90.0)}}) {
    const Frame f = render(p, renderer, ocean.get(), "two_masks_" + name);
    const Frame c = render(p, rendererOne, oceanOne.get(), "two_masks_one_streamed_" + name);
    int w = 0, l = 0;
    expectQueryFollowsPicture(f, extra, w, l);
    water += w, land += l;
    for (int y = 0; y < p.height; y += 2)
      for (int x = 0; x < p.width; x += 2) {
        geo::Geodetic g;
        if (!awayFromShore(f, x, y) || !groundPoint(f, x, y, g)) continue;
        int cls = 0;
        const auto [layer, uniform] = truth(g.latDeg, g.lonDeg, cls);
        if (layer < 2 && !uniform) continue;
        counted[layer][cls]++;
        const int bc = b.cellAt(b.cx(g.lonDeg), b.cy(g.latDeg));
        overlap += layer == 0 && bc >= 0 && bc != 255;
        inHole += layer == 1 && a.cellAt(a.cx(g.lonDeg), a.cy(g.latDeg)) == 255;
        const bool wet = layer == 2 ? true : cls == 0;
        if (f.drawn(x, y) != wet && ++bad <= 10)
          ADD_FAILURE() << name << ": pixel " << x << "," << y << " at " << g.latDeg << "," << g.lonDeg << " drawn "
                        << (f.drawn(x, y) ? "water" : "land") << ", layer " << layer << " says "
                        << (wet ? "water" : "land");
        controlBad += awayFromShore(c, x, y) && c.drawn(x, y) != wet;
      }
    std::printf("%s: query and picture agree at %d water, %d land pixels\n", name.c_str(), w, l);
  }
  std::printf("against the files' cells: A %d water %d land (%d where B has data too), B %d water %d land (%d in A's "
              "nodata), the default world %d water; %d wrong; A alone streamed: %d wrong\n",
              counted[0][0], counted[0][1], overlap, counted[1][0], counted[1][1], inHole, counted[2][0], bad,
              controlBad);
  EXPECT_EQ(bad, 0);
  for (int layer = 0; layer < 2; ++layer)
    for (int cls = 0; cls < 2; ++cls) EXPECT_GT(counted[layer][cls], 300) << "layer " << layer << " class " << cls;
  EXPECT_GT(counted[2][0], 1000);
  EXPECT_GT(overlap, 1000);
  EXPECT_GT(inHole, 100);
  // 93 pixels (B2 and B1 from the 5' grid); more (over 300) while a lone
  // layer's nodata was drawn as land (gl::chainedWaterPool's R8 then).
  EXPECT_GT(controlBad, 50) << "B drawn from the 5' grid should lose its islands";
  EXPECT_GT(land, 1000);
  EXPECT_GT(water, 5000);
  // The host's terrain streams both too: B2 (only B has it) is the
  // terrain's land, as A1 (A's, drawn from A's tiles since one layer
  // streamed): inside both islands the terrain draws the same land
  // (imagery and relief alike: the default world's open sea here, 25 km
  // apart), where the ocean leaves its hole. With B left to the 5' grid (A
  // alone streamed, as before this chain) the terrain drew B2 as its
  // sunken sea. Mean colour of the centre 9 x 9 pixels, 3 km up, looking
  // down, the same sun over each view.
  ASSERT_EQ(worldTex->waterTileLayers(), 2);
  {
    world::WorldData first = d;
    first.waterSourcesBelow.clear(), first.waterEncodingsBelow.clear();
    first.water = world::waterLayerBelow(layered->stack(), layers[0]->source());
    GlobeRenderer alone(std::make_shared<WorldTextures>(first), t);
    alone.addLayer(std::make_shared<DirectOceanLayer>(ocean));
    const auto centre = [&](GlobeRenderer& r, double lat, double lon, const std::string& name) {
      const ViewPose p = pose(lat, lon, 3000.0, 0.0, -90.0);
      const Frame f = render(p, r, ocean.get(), name);
      EXPECT_FALSE(f.drawn(p.width / 2, p.height / 2)) << name << ": the island's centre is land";
      glm::dvec3 c(0.0);
      for (int y = -4; y <= 4; ++y)
        for (int x = -4; x <= 4; ++x)
          for (int ch = 0; ch < 3; ++ch)
            c[ch] += f.image.rgba[(std::size_t(p.height / 2 + y) * p.width + p.width / 2 + x) * 4 + ch] / 81.0;
      return c;
    };
    const glm::dvec3 a1 = centre(renderer, 36.15, -7.30, "two_masks_a1_3km");
    const glm::dvec3 b2 = centre(renderer, 36.05, -7.42, "two_masks_b2_3km");
    const glm::dvec3 b2Alone = centre(alone, 36.05, -7.42, "two_masks_b2_alone_3km");
    std::printf("terrain colour inside A1 %.1f %.1f %.1f, B2 %.1f %.1f %.1f, B2 with A alone streamed %.1f %.1f %.1f\n",
                a1.r, a1.g, a1.b, b2.r, b2.g, b2.b, b2Alone.r, b2Alone.g, b2Alone.b);
    // Land against land: the imagery's own variation over 25 km (a few
    // units, looked at); the sunken sea is 20-50 units darker in green and blue.
    const auto maxDiff = [](const glm::dvec3& u, const glm::dvec3& v) {
      return std::max({std::abs(u.r - v.r), std::abs(u.g - v.g), std::abs(u.b - v.b)});
    };
    EXPECT_LT(maxDiff(b2, a1), 8.0);
    EXPECT_GT(maxDiff(b2Alone, a1), 20.0) << "the control should draw B2 as the terrain's sea";
  }
  ASSERT_TRUE(ocean->waterPages());
  ASSERT_EQ(ocean->waterPages()->layers(), 2);
  EXPECT_GT(ocean->waterPages()->pool(1).stats().resident, 0);  // B: one tile, the pinned top
  fs::remove_all(dir);
}

// Several streamed reliefs (issue 12 item 2): the elevation's chain on the
// host's terrain and the coast their 0 m lines decide, on both sides. Two
// overlapping regional reliefs over the default world in the Gulf of Cadiz
// (open sea in the 5' grids), both finer than every mask: S, a 30" shelf
// over 35.90..36.35 N, 7.60..7.00 W, sea at -80 m with island S1 (36.0 N,
// 7.4167 W: only S has data there; a corner of the 5' grids' cells, whose
// centres are all sea) and S2 (36.085 N, 7.28 W, under I's
// nodata border); I, a 3" island over 36.06..36.26 N, 7.40..7.16 W, its
// outer 0.05 degrees nodata (declared), sea at -60 m round peak I1 (36.16 N,
// 7.28 W). At the same priority the finer I answers first. Truth is the
// files' own cells sampled here by the query's rule (raster::Raster::
// sampleBilinear: the nearest cell inside the layer, the bilinear mean of
// its 4 cells that have data): I where it has data, else S. From 14 km and
// 10 km, looking down:
// - `geocean query` with both reliefs follows the picture's land and sea at
//   every pixel away from the drawn shore; where the answering layer's 5 x 5
//   cells round a point all have one sign (and, for S, I has no cell within
//   3), the drawn class is that sign;
// - on such land the drawn terrain's height (the depth buffer's point) is
//   the truth's within the mesh's linear interpolation: 1 m + max(c^2 / 8,
//   cell c / 4) |h''|max, c the diagonal of a mesh cell of at most
//   TerrainOptions::pixelErrorPx (8) pixels, cell the layer's, |h''|max =
//   2 A / s^2 of its Gaussian hills (c^2/8: the smooth relief's; cell c/4: a
//   kink of the bilinear cells inside a mesh cell), where the answering
//   layer is the same a mesh cell around.
// Control: only the first relief streamed (its elevation and its water, as
// before this chain), S from the 5' grids: S1 drawn as the terrain's sea.
TEST(Coast, TwoOverlappingRegionalReliefsAreDrawnAndAnsweredAsTheStackSays) {
  struct Hill {
    double lat, lon, sDeg, peakM;  // peakM above the layer's sea floor
  };
  struct Relief {
    std::string path;
    double lon0, lat0, cell;
    int w, h;
    double floorM;
    std::vector<Hill> hills;
    double border = 0.0;  // nodata ring (degrees)
    std::vector<float> px;  // NaN: nodata
    double curvature() const {  // |h''|max, 1/m
      double c = 0.0;
      for (const Hill& hl : hills) c = std::max(c, 2.0 * hl.peakM / std::pow(hl.sDeg * 111320.0, 2.0));
      return c;
    }
    float cellAt(int x, int y) const { return x < 0 || y < 0 || x >= w || y >= h ? NAN : px[std::size_t(y) * w + x]; }
    int cx(double lon) const { return int(std::floor((lon - lon0) / cell)); }
    int cy(double lat) const { return int(std::floor((lat0 - lat) / cell)); }
    float sample(double lat, double lon) const {
      const double X = (lon - lon0) / cell, Y = (lat0 - lat) / cell;
      if (!(X >= 0.0 && X < w && Y >= 0.0 && Y < h)) return NAN;
      const double x = X - 0.5, y = std::clamp(Y - 0.5, 0.0, double(h - 1));
      const double fx = std::floor(x), fy = std::floor(y), wx = x - fx, wy = y - fy;
      const int x0 = std::clamp(int(fx), 0, w - 1), x1 = std::clamp(int(fx) + 1, 0, w - 1);
      const int y0 = int(fy), y1 = std::min(int(fy) + 1, h - 1);
      const double wt[4] = {(1 - wx) * (1 - wy), wx * (1 - wy), (1 - wx) * wy, wx * wy};
      const float v[4] = {cellAt(x0, y0), cellAt(x1, y0), cellAt(x0, y1), cellAt(x1, y1)};
      double s = 0.0, ws = 0.0;
      for (int i = 0; i < 4; ++i)
        if (!std::isnan(v[i])) s += wt[i] * v[i], ws += wt[i];
      return ws > 0.0 ? float(s / ws) : NAN;
    }
  };
  const double cosLat = std::cos(36.15 * kDeg);
  const std::string dir = ::testing::TempDir() + "/coast_two_reliefs." + std::to_string(::getpid());
  fs::create_directories(dir);
  Relief shelf{dir + "/s_30s.tif", -7.60, 36.35, 10.0 * kCellDeg, 72, 54, -80.0,
               {{36.0, -7.5 + 1.0 / 12.0, 0.035, 330.0}, {36.085, -7.28, 0.02, 400.0}}, 0.0, {}};
  Relief island{dir + "/i_3s.tif", -7.40, 36.26, kCellDeg, 288, 240, -60.0, {{36.16, -7.28, 0.012, 300.0}}, 0.05, {}};
  for (Relief* r : {&shelf, &island}) {
    r->px.assign(std::size_t(r->w) * r->h, 0.0f);
    std::vector<float> file(r->px.size());
    for (int y = 0; y < r->h; ++y)
      for (int x = 0; x < r->w; ++x) {
        const double lat = r->lat0 - (y + 0.5) * r->cell, lon = r->lon0 + (x + 0.5) * r->cell;
        double v = r->floorM;
        for (const Hill& hl : r->hills) {
          const double d = std::hypot(lat - hl.lat, (lon - hl.lon) * cosLat) / hl.sDeg;
          v += hl.peakM * std::exp(-d * d);
        }
        const bool nodata = std::min({x, y, r->w - 1 - x, r->h - 1 - y}) < int(std::lround(r->border / r->cell));
        r->px[std::size_t(y) * r->w + x] = nodata ? NAN : float(v);
        file[std::size_t(y) * r->w + x] = nodata ? -9999.0f : float(v);
      }
    raster::GeoTiffWriteOptions wo;
    wo.transform = {r->lon0, r->lat0, r->cell, -r->cell, false};
    if (r->border > 0.0) wo.nodata = -9999.0;
    raster::writeGeoTiff(r->path, file.data(), r->w, r->h, 1, raster::SampleType::F32, wo);
  }
  // The answering layer at a point (0 I, 1 S, 2 neither) and its elevation.
  const auto truth = [&](double lat, double lon, float& elev) {
    elev = island.sample(lat, lon);
    if (!std::isnan(elev)) return 0;
    elev = shelf.sample(lat, lon);
    return std::isnan(elev) ? 2 : 1;
  };
  // Its 5 x 5 cells round the point all of one sign (`land`) with data and,
  // for S, no cell of I within 3 (past I's filter reach).
  const auto uniform = [&](double lat, double lon, int layer, bool& land) {
    const Relief& r = layer == 0 ? island : shelf;
    const int x = r.cx(lon), y = r.cy(lat);
    land = r.cellAt(x, y) >= 0.0f;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const float c = r.cellAt(x + dx, y + dy);
        if (std::isnan(c) || (c >= 0.0f) != land) return false;
      }
    if (layer == 1)
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx)
          if (!std::isnan(island.cellAt(island.cx(lon) + dx, island.cy(lat) + dy))) return false;
    return true;
  };

  session();  // the GL context (scene() would build the 3" Gibraltar world too)
  const std::string cache = dir + "/tiles";
  ::setenv("GEOCEAN_TILE_CACHE", cache.c_str(), 1);
  world::WorldData d = world::loadLayeredWorld(
      {{world::LayerKind::Elevation, shelf.path, "", 0}, {world::LayerKind::Elevation, island.path, "", 0}}, true);
  ASSERT_TRUE(d.elevationTiles);
  EXPECT_EQ(d.elevationTiles->source().path(), island.path) << "the finer relief answers first";
  ASSERT_EQ(d.elevationTilesBelow.size(), 1u);
  EXPECT_EQ(d.elevationTilesBelow[0]->source().path(), shelf.path);
  ASSERT_TRUE(d.waterSource);
  EXPECT_TRUE(d.waterFromRelief);
  ASSERT_EQ(d.waterSourcesBelow.size(), 1u);
  EXPECT_EQ(d.waterSourcesBelow[0]->path(), shelf.path);
  EXPECT_TRUE(d.waterFromReliefBelow.at(0));
  TerrainOptions t;
  t.waitForTiles = true;
  GlobeRenderer renderer(std::make_shared<WorldTextures>(d), t);
  ocean::Ocean o;
  o.setDefaultWorld(ocean::Ocean::defaultWorldDir());
  o.addElevationLayerFile(shelf.path);
  o.addElevationLayerFile(island.path);
  const auto snap = o.current();
  const auto layers = ocean_render::oceanWaterTileLayers(snap->landSea.get(), snap->mask);
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0]->source().path(), island.path);
  EXPECT_EQ(layers[1]->source().path(), shelf.path);
  ocean_render::OceanOptions oo;
  oo.waterTiles = layers[0];
  oo.waterTilesBelow = {layers[1]};
  const auto grids = ocean_render::oceanWorld(snap->mask, snap->elevation, snap->landSea.get(), snap->maskEncoding,
                                              layers[0].get());
  auto ocean = std::make_shared<ocean_render::OceanRenderer>(grids, snap->landSea, oo);
  ocean->setCompleteTiles(true);
  renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
  // The control: I alone streamed on both sides (elevation and water), S
  // and the world from the grids below I.
  const auto* layered = dynamic_cast<const ocean::LayeredLandSea*>(snap->landSea.get());
  ASSERT_NE(layered, nullptr);
  world::WorldData first = d;
  first.elevationTilesBelow.clear();
  first.waterSourcesBelow.clear(), first.waterEncodingsBelow.clear(), first.waterFromReliefBelow.clear();
  first.water = world::waterLayerBelow(layered->stack(), layers[0]->source());
  GlobeRenderer rendererOne(std::make_shared<WorldTextures>(first), t);
  ocean_render::OceanOptions one;
  one.waterTiles = layers[0];
  auto oceanOne = std::make_shared<ocean_render::OceanRenderer>(
      std::make_shared<const world::WorldGrids>(grids->elevation(), first.water), snap->landSea, one);
  oceanOne->setCompleteTiles(true);
  rendererOne.addLayer(std::make_shared<DirectOceanLayer>(oceanOne));

  const std::string extra = " --elevation " + shelf.path + " --elevation " + island.path;
  int classes[2][2] = {{0, 0}, {0, 0}}, heights[2] = {0, 0};  // [layer][land], [layer]
  int badClass = 0, badHeight = 0, controlClass = 0, controlHeight = 0, water = 0, land = 0;
  double worst[2] = {0.0, 0.0}, worstControl = 0.0;
  for (const auto& [name, p] : {std::pair{std::string("i_14km"), pose(36.12, -7.28, 14000.0, 0.0, -90.0)},
                                std::pair{std::string("s1_10km"), pose(36.0, -7.5 + 1.0 / 12.0, 10000.0, 0.0, -90.0)}}) {
    const Frame f = render(p, renderer, ocean.get(), "two_reliefs_" + name);
    const Frame c = render(p, rendererOne, oceanOne.get(), "two_reliefs_one_streamed_" + name);
    int w = 0, l = 0;
    // Every pixel away from the drawn shore, I's data edge included: its
    // nodata cells and those past its edge take the layers below in the
    // query as in the picture (LandSea::reliefCoverage).
    expectQueryFollowsPicture(f, extra, w, l);
    std::printf("%s: query and picture agree at %d water, %d land pixels\n", name.c_str(), w, l);
    water += w, land += l;
    for (int y = 2; y + 2 < p.height; y += 2)
      for (int x = 2; x + 2 < p.width; x += 2) {
        geo::Geodetic g;
        if (!awayFromShore(f, x, y) || !groundPoint(f, x, y, g)) continue;
        float elev = 0.0f;
        const int layer = truth(g.latDeg, g.lonDeg, elev);
        bool isLand = false;
        if (layer == 2 || !uniform(g.latDeg, g.lonDeg, layer, isLand)) continue;
        classes[layer][isLand]++;
        if (f.drawn(x, y) == isLand && ++badClass <= 10)
          ADD_FAILURE() << name << ": pixel " << x << "," << y << " at " << g.latDeg << "," << g.lonDeg << " drawn "
                        << (f.drawn(x, y) ? "water" : "land") << ", layer " << layer << " says "
                        << (isLand ? "land" : "water");
        // The control's sea: the ocean, or the terrain's water areas (30 m
        // under the sea, TerrainOptions::seaDropM), which show where the
        // ocean's grid skips cells the query calls land.
        geo::Geodetic cg;
        const bool controlSea = c.drawn(x, y) || (surfacePoint(c, x, y, cg) && cg.heightM < -10.0);
        controlClass += awayFromShore(c, x, y) && controlSea == isLand;
        if (!isLand) continue;
        // The drawn terrain's height against the truth at its own point.
        geo::Geodetic s, sx, sy;
        if (!surfacePoint(f, x, y, s) || !surfacePoint(f, x + 1, y, sx) || !surfacePoint(f, x, y + 1, sy)) continue;
        const auto metres = [&](const geo::Geodetic& a) { return glm::length(geo::toEcef(a) - geo::toEcef(s)); };
        const double meshM = 8.0 * std::sqrt(2.0) * std::max(metres(sx), metres(sy));
        const Relief& r = layer == 0 ? island : shelf;
        const double cellM = r.cell * 111320.0 * cosLat;
        float at = 0.0f;
        if (truth(s.latDeg, s.lonDeg, at) != layer) continue;
        bool same = true;  // no other layer (a cliff at I's data edge) within a mesh cell
        for (int k = 0; k < 8 && same; ++k) {
          const double a = k * M_PI / 4.0, dDeg = meshM / 111320.0;
          float e2 = 0.0f;
          same = truth(s.latDeg + dDeg * std::sin(a), s.lonDeg + dDeg * std::cos(a) / cosLat, e2) == layer;
        }
        if (!same) continue;
        const double bound = 1.0 + std::max(meshM * meshM / 8.0, cellM * meshM / 4.0) * r.curvature();
        const double err = std::abs(s.heightM - double(at));
        heights[layer]++;
        worst[layer] = std::max(worst[layer], err / bound);
        if (err > bound && ++badHeight <= 10)
          ADD_FAILURE() << name << ": pixel " << x << "," << y << " at " << s.latDeg << "," << s.lonDeg
                        << " drawn at " << s.heightM << " m, layer " << layer << " says " << at << " m (bound "
                        << bound << " m)";
        geo::Geodetic cs;
        if (surfacePoint(c, x, y, cs)) {
          float atC = 0.0f;
          truth(cs.latDeg, cs.lonDeg, atC);
          const double e = std::abs(cs.heightM - double(atC));
          worstControl = std::max(worstControl, e / bound);
          controlHeight += e > bound;
        }
      }
  }
  std::printf("against the files' cells: I %d water %d land, S %d water %d land, %d drawn on the wrong side; "
              "heights on land: I %d, S %d pixels, worst %.2f and %.2f of the bound, %d beyond; I alone streamed: "
              "%d classes wrong, %d heights beyond the bound (worst %.1f of it)\n",
              classes[0][0], classes[0][1], classes[1][0], classes[1][1], badClass, heights[0], heights[1], worst[0],
              worst[1], badHeight, controlClass, controlHeight, worstControl);
  EXPECT_EQ(badClass, 0);
  EXPECT_EQ(badHeight, 0);
  for (int layer = 0; layer < 2; ++layer) {
    for (int cls = 0; cls < 2; ++cls) EXPECT_GT(classes[layer][cls], 200) << "layer " << layer << " class " << cls;
    EXPECT_GT(heights[layer], 200) << "layer " << layer;
  }
  EXPECT_GT(land, 1000);
  EXPECT_GT(water, 1000);
  EXPECT_GT(controlClass, 300) << "S from the 5' grid should lose its islands";
  EXPECT_GT(controlHeight, 300) << "S from the 5' grid should lose its relief";
  if (!HasFailure()) fs::remove_all(dir);  // else kept to look at
}

// Golden images of the strait with the 3" mask, looked at: Tarifa's shore
// from 500 m (looking south-west over the Isla de las Palomas causeway)
// and the Rock of Gibraltar from 5 km (looking north-north-east up the
// peninsula, the Bay of Algeciras to the left). Thresholds as the globe
// goldens' (test_render.cpp): another Mesa/LLVM build may round shading
// differently by under 2 of 255 on average, 0.5% of pixels visibly.
TEST(Coast, GoldenStraitOfGibraltarWithThe3sMask) {
  const Frame a = render(pose(36.012, -5.600, 500.0, 230.0, -45.0), true, "golden_500m");
  expectMatchesGolden(a.image, "gibraltar_3s_500m", 2.0, 0.005);
  const Frame b = render(pose(36.10, -5.37, 5000.0, 20.0, -55.0), true, "golden_5km");
  expectMatchesGolden(b.image, "gibraltar_3s_5km", 2.0, 0.005);
}

// The same views on the product path (Regional: the 3" mask streamed over
// the default world on both sides), looked at; thresholds as above.
TEST(Coast, GoldenStraitOfGibraltarWithThe3sMaskStreamed) {
  Regional& r = regional();
  const Frame a = render(pose(36.012, -5.600, 500.0, 230.0, -45.0), *r.renderer, r.ocean.get(), "golden_streamed_500m");
  expectMatchesGolden(a.image, "gibraltar_3s_streamed_500m", 2.0, 0.005);
  const Frame b = render(pose(36.10, -5.37, 5000.0, 20.0, -55.0), *r.renderer, r.ocean.get(), "golden_streamed_5km");
  expectMatchesGolden(b.image, "gibraltar_3s_streamed_5km", 2.0, 0.005);
}

}  // namespace
}  // namespace geocean::render::test
