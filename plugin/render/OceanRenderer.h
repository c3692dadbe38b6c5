// The ocean layer: the screen-subdivision LOD grid (plugin/grid) rebuilt
// every frame from the camera, displaced in the vertex shader by the shared
// wave kernel (shaders/waves.glsl through plugin/waves' GPU patch), shaded
// with the sky's Fresnel reflection, depth colour, sun glint and foam, and
// cut at the shoreline by the water coverage (anti-aliased). Far away the
// octaves that would alias are dropped and become roughness.
#pragma once

#include "globe/camera/Camera.h"
#include "globe/gl/GlProgram.h"
#include "globe/world/TileWaterIndex.h"
#include "globe/world/WorldGrids.h"
#include "plugin/grid/ScreenGrid.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/render/Spray.h"
#include "plugin/render/ElevationPages.h"
#include "plugin/render/WaterPages.h"
#include "plugin/waves/WaveField.h"

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace geocean::ocean_render {

struct OceanOptions {
  double cellPx = 8.0;  // grid vertex spacing on screen
  waves::Model model = waves::Model::Noise;
  waves::SeaState sea;
  // The near-shore phase field (Gerstner; ocean::Snapshot's waves carry it
  // after Ocean::setCoastRegion): drawn with wv_gerstnerCoast, so the
  // picture is the query's surface there. Null: the shaders as without it.
  std::shared_ptr<const waves::CoastField> coast;
  // The coast field's island table for the picture built on the GPU
  // (plugin/render/CoastIslandsGpu) at the first draw; false: the CPU's.
  bool gpuIslandTable = true;
  // A wave field to draw (the façade snapshot's, so the FFT tables are built
  // once for query and drawing): model, sea and coast are then its own.
  // Null: made here from model, sea and coast.
  std::shared_ptr<const waves::WaveField> waves;
  // Open water (WaterIndex) and cells far smaller than a water texel with
  // shader variants that skip the per-pixel coverage (partitionCells).
  bool cheapCoverage = true;
  // With cheapCoverage over one global streamed mask: the coastal cells whose
  // every fragment reads its pages minified take a variant that fetches
  // only the bilinear's 2 x 2 texels (partitionCells, ScreenCull::minified).
  bool minifiedCoverage = true;
  // Leave out grid cells that no wave can bring on screen (offscreenSides):
  // the clamp rectangle spans up to 4 screens a side near the sea.
  bool cullOffscreen = true;
  // Far open water (waves faded into roughness) shaded per vertex.
  bool farVertexShading = true;
  // Issue 15 item 4, with a coast field: the breaking foam's distance bands
  // (shaders/coast_bands.glsl); false: the kernel's per-vertex foam at every
  // distance, as before (compiled out; bench_coast_frame's reference).
  bool coastBands = true;
  // Issue 15 item 4, with the bands: paper 003's coarser mesh in the middle
  // band (grid::coarseIndices): blocks of 2 x 2 grid cells drawn as one
  // where the cell along the view is at least kMiddleMeshFromR of the
  // breaking sea's longest wavelength (middleWavelengthM), the water
  // kMiddleMeshMinDepth of it deep and the waves not yet faded
  // (kMiddleMeshMaxFar). The normal there is the fragment's (ocean.frag's
  // GEOCEAN_FRAGMENT_NORMAL, on with the bands on either mesh), so the
  // larger cells do not soften the sea. Saves 1-6 % of the ocean pass on
  // llvmpipe (bench_coast_frame --split, docs/PERFORMANCE.md).
  bool coarseMiddle = true;
  // A streamed mask's coverage (world::waterPyramid of
  // world::streamedMaskLayer, the host terrain's pyramid): the shoreline is
  // drawn from its tiles (WaterPages.h), so the query's coverage rule on the
  // mask's own cells is what is drawn. Null: the water grid's texture.
  // A global mask's open water still takes the cheap variants and
  // coversOpaquely answers, when the world's water grid is a level of this
  // pyramid (oceanWorld makes it so; waterIndexFollowsTiles): its texels
  // are means of the mask's, 1 only where every mask cell under them is
  // water; cells much smaller than a mask cell read the pages per vertex.
  // A regional mask's cells all take the
  // per-pixel coverage, and coversOpaquely is false.
  std::shared_ptr<const raster::TilePyramid> waterTiles;
  // Streamed masks under waterTiles, in answer order (oceanWaterTileLayers):
  // the first with data at a point is drawn (WaterPages.h).
  std::vector<std::shared_ptr<const raster::TilePyramid>> waterTilesBelow;
  // The streamed reliefs in answer order (oceanElevationTileLayers, the
  // host terrain's): the water depth (the Gerstner depth, refraction's
  // bottom, the shore foam) is read from their tiles per vertex by the
  // query's rule (ElevationPages.h), the elevation grid past them. Empty:
  // the elevation grid alone.
  std::vector<std::shared_ptr<const raster::TilePyramid>> elevationTiles;
  // False: a streamed mask's cells all per pixel and coversOpaquely false
  // (the shortcuts' reference in tests). Either way a global mask's grid
  // cells are classed from the level (nearWaterClassifier).
  bool streamedIndex = true;
  // Gerstner and FFT whitecaps from the Jacobian's folds per fragment
  // (shaders/foam.glsl), their decaying trail interpolated between the
  // time samples; off, these models take the height-quantile crests.
  bool jacobianFoam = true;
  // The detail normal layer (issue 13 item 2, waves::detailWaves): the
  // spectrum's waves shorter than the model draws, per fragment down to 2
  // pixels, taken from the roughness.
  bool detailNormals = true;
  // Light through thin crests (ocean_shading.glsl, crestSubsurface).
  bool subsurface = true;
  // The noise sea's per-pixel shading deferred to one pass over a G-buffer
  // the grid writes (ocean.frag), on the tiles with sea: the same picture,
  // shaded once a pixel instead of ~1.9x on llvmpipe (docs/PERFORMANCE.md).
  // Used where octaves are drawn per pixel and the host's target allows it
  // (gBufferFor), else forward.
  bool deferred = true;
  // The noise sea's per-pixel programs without the octave loop for a view
  // where no pixel is under this x 1 / pixelOctaveEndPx of the longest
  // octave (OceanRenderer::draw states the bound; 1.05 its margin): the
  // same picture bit for bit.
  // Tests set another margin (infinity: always the loop).
  double noPixelOctaveMargin = 1.05;
  // The noise sea's per-pixel octaves end at a footprint of this many
  // pixels (noise_bands.glsl's noisePixelWeight: whole from twice it); the
  // shorter ones are roughness, their slope variance in the BRDF's (the
  // sea's energy and the glitter's spread kept). 2 is Nyquist; 4 leaves
  // the even pixels what is drawn, for reducedRate (~15x closer to full
  // rate at its tolerance, but a softer sea and fainter far foam than 2:
  // docs/PERFORMANCE.md, tenth pass).
  double pixelOctaveEndPx = 2.0;
  // Reduced-rate shading of the deferred pass (ocean_resolve.frag): the
  // even pixels (2i, 2j) shaded exactly, at a quarter of the pixels; a pixel
  // between them their mean where the sea is opaque at all and their
  // colours agree within reducedRateTolerance per channel (display units);
  // the 4 x 2 pixel groups (llvmpipe's 8 lanes) where a pixel's do not are
  // shaded again at full rate. Off by default: this sea has detail down to
  // 2 pixels (its per-pixel octaves, foam flecks, glitter), which a half-rate
  // lattice cannot hold, so the picture moves beyond the goldens' bounds:
  // docs/PERFORMANCE.md, ninth pass, gives its cost and quality by tolerance.
  // With pixelOctaveEndPx 4 (tenth pass) the default flight is 1.60-1.75x
  // the frame before the optics (full rate, 2 px: 2.24-2.34x), short of
  // issue 13's 1.5x, so neither is the default.
  bool reducedRate = false;
  double reducedRateTolerance = 16.0 / 255.0;
  // With reduced rate the deferred path is also taken where no octave is
  // drawn per pixel, for an eye below this: the default flight's ocean CPU
  // ms against forward (least of 2 draws), 42 km -30, 141 km -14, 444 km
  // 0 to +5, 3,169 km +9 (the G-buffer's fixed cost).
  double reducedRateDeferBelowM = 2.0e5;
};

// Reorders a grid frame's compacted cell indices (6 per cell) into three
// runs: cells that need the per-pixel shoreline coverage, cells small
// enough to interpolate it from their vertices, and cells over open water
// (no shoreline can reach any of their fragments), the last of them where
// the waves have faded (ScreenCull::farFootprintM) so it is shaded per vertex.
struct CellGroups {
  std::size_t sharp = 0, smooth = 0, open = 0, farOpen = 0;  // index counts, in this order
  // The last `minified` indices of the sharp run: cells whose every
  // fragment reads the streamed mask's pages minified (ScreenCull::minified).
  std::size_t minified = 0;
};
// The view, for leaving out cells that stay off screen.
struct ScreenCull {
  glm::dvec3 forward{0.0}, right{0.0}, up{0.0};
  double tanX = 1.0, tanY = 1.0;  // half-angle tangents of the view
  double cellRadians = 0.0;       // a grid cell's size on screen, radians
  double maxDisplacementM = 0.0;  // the wave field's bound
  // With these, vertices near the eye are tested at their displaced place
  // (fields that move the sea only vertically).
  const waves::WaveField* waves = nullptr;
  double timeS = 0.0;
  // Grid footprint (|eye-relative| x cellRadians) from which ocean.vert's
  // distance fade is complete; 0: no far group.
  double farFootprintM = 0.0;
  // Noise (shaders/noise_bands.glsl): farFootprintM is a pixel's footprint
  // along the view (the cell's over cellPx and the sine of the view's
  // elevation angle), as the fragments' pixel filter measures it.
  bool farAlongView = false;
  // And no nearer than this (the planar reflection's reach: per pixel).
  double farMinDistM = 0.0;
  // Bodies' foam (wake.glsl, per fragment): eye-relative centre and reach
  // (m); cells within reach stay out of the per-vertex far group.
  std::vector<glm::dvec4> wakeReach;
  // Sharp cells whose every fragment's texels per pixel of the `fine`
  // mask (geo_uv.glsl waterPagesAuto's length(fwidth)) is at least 1 go to
  // the sharp run's end (CellGroups::minified): from the vertices' screen
  // positions (forward/right/up, tanY, cellRadians) and level-0 texels.
  bool minified = false;
};
// Per grid vertex, the screen sides it stays beyond (bits 1 left, 2 right,
// 4 bottom, 8 top) under any wave displacement.
std::vector<std::uint8_t> offscreenSides(const grid::GridFrame& f, const ScreenCull& view);
// With `cull`, drops cells that stay off screen; with `group`, sorts the
// rest. pagedTexels > 0: the coverage is a streamed mask's (WaterPages),
// this many of its finest texels per water-index texel: the smooth run's
// bound is in those texels and the open-water margin covers its footprint,
// up to twice the mipmap's. fine (a global streamed mask's own texels):
// cells the grid's index does not find all water are asked again at the
// mask's resolution: all water goes to the open groups, all land is dropped
// (its fragments would all discard), the rest keeps the coverage.
CellGroups partitionCells(const grid::GridFrame& f, const world::WaterIndex& wi, double cellPx, const ScreenCull& view,
                          bool cull, bool group, std::vector<std::uint32_t>& idx, double pagedTexels = 0.0,
                          world::TileWaterIndex* fine = nullptr);

// What the host gives a draw beyond the camera (the host/layer contract's
// inputs) and the optics switches.
struct OceanInputs {
  // The sky and terrain seen by the eye mirrored in the tangent plane at
  // its nadir (0: none, the sky BRDF alone), drawn with reflectionCamera.
  GLuint reflectionColor = 0;
  std::optional<camera::Camera> reflectionCamera;
  bool refraction = true;  // the bottom through the water (Snell, Beer-Lambert)
  // The host's sun depth map (0: no shadows; render::LayerInputs' fields):
  // reversed DEPTH32F, shadowMatrix from positions relative to
  // shadowOriginEcef to clip space, the sea within shadowReachM of the eye.
  GLuint shadowDepth = 0;
  int shadowSize = 0;
  glm::dmat4 shadowMatrix{1.0};
  glm::dvec3 shadowOriginEcef{0.0};
  double shadowReachM = 0.0;
  // In shadow: false, the sun's direct light removed (the sky's stays);
  // true, paper 001's darkening of the pixel by 0.5.
  bool shadowPaper = false;
  // The sun's specular: paper 001's Phong term (eq. 19) instead of the
  // microfacet glitter; exponent 0: from the slopes not drawn (1 / 2 mss).
  bool sunPhong = false;
  double phongExponent = 0.0;
};

// A floating body at the waterline, for the foam it makes on the sea
// (shaders/wake.glsl): the plugin's bodies (plugin/capi) give these each draw.
struct Wake {
  glm::dvec3 centreEcef{0.0};    // the hull's centre at the waterline
  glm::dvec3 bowEcef{0.0};       // the bow's direction (unit; its horizontal part is used)
  glm::dvec3 velocityEcef{0.0};  // through the water (m/s; its horizontal part is used)
  double halfLengthM = 0.0, halfBeamM = 0.0;
};

// Draws into the current context's bound framebuffer; the host decides
// when (plugin/capi's geocean_draw, or a test's layer).
class OceanRenderer {
 public:
  // world: the ocean's elevation and water grids (its own textures are made
  // from them); landSea: classifier for land cells (nullptr: all sea).
  // Throws on a bad sea state (the message names the field) or a shader error.
  OceanRenderer(std::shared_ptr<const world::WorldGrids> world, std::shared_ptr<const ocean::LandSea> landSea,
                OceanOptions options = {});
  ~OceanRenderer();
  // Without the context of its GL objects: the destructor then makes no GL
  // call (the context owns the names) and frees only the CPU side.
  void abandonGl();
  OceanRenderer(const OceanRenderer&) = delete;
  OceanRenderer& operator=(const OceanRenderer&) = delete;

  void draw(const camera::Camera& cam, const camera::Lighting& light, bool bare);
  // For the next draws (kept until changed).
  void setInputs(OceanInputs inputs) { inputs_ = std::move(inputs); }
  const OceanInputs& inputs() const { return inputs_; }
  // The bodies on the sea for the next draws (kept until changed): the
  // kMaxWakes nearest the eye that move fast enough to foam are drawn.
  void setWakes(std::vector<Wake> wakes) { wakes_ = std::move(wakes); }
  static constexpr int kMaxWakes = 16;  // wake.glsl's GEOCEAN_MAX_WAKES
  // Where wake.glsl's foam sets in (smoothstep edges): the bow wave breaks
  // from a length Froude number U / sqrt(g L) of 0.2, fully by 0.35; the
  // stern's turbulent wake foams from 0.5 m/s through the water, fully by 3.
  static constexpr double kWakeBreakingFroude[2] = {0.2, 0.35};
  static constexpr double kWakeStirredMps[2] = {0.5, 3.0};
  // The wake's foam decays as exp(-age / kWakeDecayS): the upper end of
  // Callaghan et al. (2012)'s 0.5-8 s for whitecaps, as the propeller and
  // the hull keep stirring the wake and the bow wave's divergent crests go
  // on spilling along the arms while they are steep. It reaches a + 4
  // kWakeDecayS U + b from the body's centre (a, b its half length and beam).
  static constexpr double kWakeDecayS = 8.0;
  // The host/layer contract: whether every pixel over the rectangle is
  // drawn opaque for pixels of this footprint (metres), and the cell size.
  bool coversOpaquely(double lat0Deg, double lat1Deg, double lon0Deg, double lon1Deg, double pixelFootprintM) const;
  double cellPx() const { return options_.cellPx; }

  const waves::WaveField& waves() const { return *waves_; }
  // Draws `waves` from now on if it is the drawn field with another coast
  // region (Ocean::followCoastRegion's swap): only the coast texels are
  // uploaded (the CPU-built island table: a GPU build would stall this
  // frame), no program or grid is made. False (nothing changed) for any
  // other field: make a new renderer then.
  bool swapCoast(std::shared_ptr<const waves::WaveField> waves);
  const grid::GridFrame& lastFrame() const { return frame_; }
  // Draw the eye-relative surface position into colour attachment 1 (tests).
  void setWriteData(bool on) { writeData_ = on; }
  // Tests: the data target holds the drawn water depth (vDepthM) in x, w 2
  // where the sea drew (ocean.frag), instead of positions.
  void setWriteDepthData(bool on) { writeDepthData_ = on; }
  void setCheapCoverage(bool on) { options_.cheapCoverage = on; }
  void setMinifiedCoverage(bool on) { options_.minifiedCoverage = on; }
  void setCullOffscreen(bool on) { options_.cullOffscreen = on; }
  void setFarVertexShading(bool on) { options_.farVertexShading = on; }
  // Issue 15 item 4: the breaking foam's distance bands (shaders/coast_bands.glsl),
  // or one band everywhere (tests compare them).
  // MiddleTextureOnly, FarMeanOnly: the two ends of the middle -> far fade
  // (the middle band's texture, the far band's mean) everywhere.
  enum class CoastBands { ByDistance = 0, NearOnly = 1, FarOnly = 2, MiddleTextureOnly = 3, FarMeanOnly = 4 };
  void setCoastBands(CoastBands mode) { coastBands_ = mode; }
  // Issue 15 item 4: the near band's breaking spray (Spray.h); on with the
  // bands (Gerstner with a coast field), off for tests.
  void setSpray(bool on) { sprayOn_ = on; }
  // Issue 15 item 4: the middle band's coarser mesh (OceanOptions::
  // coarseMiddle), its blocks of `cells` x `cells` grid cells: 2 by
  // default, 1 none; 4 and 8 for tests (a mesh too coarse for the waves).
  void setMiddleMeshBlock(int cells) { middleBlock_ = cells; }
  // Issue 15 item 4: with the bands, the normal is the kernel's per
  // fragment (the whitecaps' present sample) until the waves fade (vFar),
  // on either mesh; false draws the vertices' interpolated normal, as
  // before (tests: what the coarse mesh did to the sea without it).
  void setFragmentNormal(bool on) { fragmentNormal_ = on; }
  // A vertex joins a coarse block where the grid cell's footprint along the
  // view (ocean.vert's, coast_bands.glsl's) is at least this times
  // middleWavelengthM: the middle band is whole there (r > 1/3), so the
  // foam is the fragments' texture and no vertex's.
  static constexpr double kMiddleMeshFromR = 0.5;
  // And where the relief's water is at least this times middleWavelengthM
  // deep (k h >= pi for that wavelength: no breaking, no shoaling of it).
  static constexpr double kMiddleMeshMinDepth = 0.5;
  // And where ocean.vert's vFar (the waves' fade by footprint) is below
  // this at every vertex of the block: ocean.frag's whitecaps, and so the
  // fragment's normal, are evaluated there (they fade out by vFar 0.75);
  // beyond, the normal is the vertices' and the far cells stay fine.
  static constexpr double kMiddleMeshMaxFar = 0.75;
  // The longest the breaking sea's amplitude-weighted wavelength gets
  // (wv_breakingFoamMean's lambda) over water depths 0.05 m to deep, without
  // refraction: where a cell exceeds a share of it, it exceeds that share
  // of the local lambda, which shoaling only shortens. 0 without the bands
  // or without OceanOptions::coarseMiddle.
  double middleWavelengthM() const { return middleWavelengthM_; }
  // Coarse blocks in the last draw (grid::coarseIndices).
  std::size_t lastCoarseBlocks() const { return coarseBlocks_; }
  // Single pictures: each draw first waits (bounded) for the streamed
  // tiles its view asks for, instead of drawing their ancestors.
  void setCompleteTiles(bool on) { completeTiles_ = on; }
  // The screen grid's projector: Direct (default) or paper 000's ISPG,
  // drawable for comparison (--grid ispg).
  void setGridMode(grid::GridMode mode);
  const WaterPages* waterPages() const { return pages_.get(); }
  const ElevationPages* elevationPages() const { return elevPages_.get(); }
  // The shading's sea statistics: mean square slope of the spectrum's waves
  // not drawn (ocean.vert's uMssAbove), and the whitecaps' crest height.
  const std::vector<float>& mssAbove() const { return mssAbove_; }
  // With c noise octaves drawn (Gerstner, FFT: all entries alike).
  double foamHeightM(int octavesDrawn = 16) const { return foamHeightM_[std::size_t(octavesDrawn)]; }
  // Monahan & O'Muircheartaigh (1980): whitecap cover W = 3.84e-6 U10^3.41.
  static double whitecapCover(double windSpeedMps);
  // Gerstner and FFT whitecaps (shaders/foam.glsl): foam where the Jacobian
  // determinant of the choppy map is below foamJacobian() (calibrated so
  // the foam-covered fraction of the sea is W), staying with the water
  // particle and decaying as exp(-age / kFoamDecayS), sampled at the present
  // and kFoamTimes - 1 earlier times on a kFoamStepS grid. 0: no such foam.
  static constexpr double kFoamDecayS = 2.0;  // Callaghan et al. 2012: 0.5-8 s
  // 0.5 s: a short component's fold lasts a fraction of its 1.5-3 s period,
  // so coarser steps leave the trail as separate copies of the fold.
  static constexpr double kFoamStepS = 0.5;
  static constexpr int kFoamTimes = 6;
  // Points a step where foam.glsl also takes the interpolated foam (FOAM_SUB).
  static constexpr int kFoamSub = 4;
  // Foam counted as sea covered (Monahan's W is bright foam in photographs):
  // over the navy water (red 27/255) under full foam's 221/255, the tone
  // curve puts red 170 (SeaOptics' foam pixel) at 0.40 foam.
  static constexpr double kFoamCounted = 0.40;
  double foamJacobian() const { return foamJacobian_; }
  double foamJacobianSoft() const { return foamJacobianSoft_; }  // its smoothstep's half width
  // Calibrates foamJacobian() around a place (draw() does it at its nadir,
  // again after moving kFoamCalibrationM; 0 before).
  void calibrateJacobianFoam(double latDeg, double lonDeg);
  static constexpr double kFoamCalibrationM = 100000.0;  // recalibrated when the nadir moves this far
  // The sample times for a frame at tS: tS, then the grid's past times.
  static std::array<double, kFoamTimes> foamTimes(double tS);
  // The foam (0..1) foam.glsl draws for a particle whose Jacobian
  // determinants at foamTimes(tS) are det (ages: tS - foamTimes).
  double foamOf(const double* det, const double* ageS) const;
  bool jacobianFoam() const {
    return options_.jacobianFoam && (options_.model == waves::Model::Gerstner || options_.model == waves::Model::Fft);
  }
  // CPU time of the last draw's grid build (ScreenGrid::build + index
  // compaction), wall ms: the part of the ocean pass that is not GL.
  double lastGridMs() const { return gridMs_; }
  // Whether the last draw shaded through the G-buffer (OceanOptions::deferred).
  bool lastDrawDeferred() const { return lastDeferred_; }
  // The last draw's cell groups (index counts; tests).
  const CellGroups& lastGroups() const { return lastGroups_; }
  // The last draw's per-pixel programs had no octave loop (OceanOptions::noPixelOctaveMargin).
  bool lastDrawWithoutPixelOctaves() const { return lastNoPixelOctaves_; }
  // The last deferred draw's share of its tiles' 4 x 2 groups shaded again
  // at full rate (OceanOptions::reducedRate; 1 when full rate throughout).
  double lastFullRateShare() const { return lastFullRateShare_; }

 private:
  std::shared_ptr<const world::WorldGrids> world_;
  GLuint elevationTex_ = 0, waterTex_ = 0;
  GLuint reliefFloorTex_ = 0;  // OceanWorld's reliefUnderMaskWater on the elevation grid (ocean.vert)
  OceanOptions options_;
  double maxDisplacementM_ = 0.0;  // the grid's and the cull's bound on wave displacement
  std::shared_ptr<const waves::WaveField> waves_;
  std::unique_ptr<grid::ScreenGrid> grid_;
  grid::GridFrame frame_;
  waves::GpuPatch patch_;
  gl::GlProgram farShaded_, bare_;
  // The per-pixel programs (coast cut, smooth coast, open water) by what a
  // draw needs: [1] the bodies' foam (wake.glsl's GEOCEAN_WAKES), [2] no
  // planar reflection (GEOCEAN_NO_REFLECTION), [4] no refraction
  // (GEOCEAN_NO_REFRACTION), [8] paper 001's Phong sun (GEOCEAN_SUN_PHONG),
  // [16] the noise sea with no octave per pixel (GEOCEAN_NO_PIXEL_OCTAVES);
  // [0] made with the renderer, the others at their first draw. llvmpipe
  // runs both sides of a branch on a uniform and a loop's body once even
  // for no iteration, so a term not drawn still cost every pixel
  // (docs/PERFORMANCE.md).
  // The noise sea's deferred programs beside them: the grid's G-buffer
  // writers (g*) and the shading over the tiles with sea (shade).
  struct PixelPrograms {
    gl::GlProgram sharp, smooth, open, gSharp, gSmooth, gOpen, shade, coarse;
    gl::GlProgram sharpMin, gSharpMin;  // GEOCEAN_WATER_PAGES_MINIFIED (CellGroups::minified)
  };
  gl::GlProgram resolve_;  // ocean_resolve.frag (OceanOptions::reducedRate)
  PixelPrograms pixel_[32];
  std::vector<std::string> sharpDefines_, smoothDefines_, openDefines_, sharpMinDefines_;
  const PixelPrograms& pixelPrograms(bool wakes, bool reflection, bool refraction, bool sunPhong,
                                     bool noPixelOctaves);
  // The G-buffer for a host target and viewport, made or resized, with the
  // host's depth attached (the draw detaches it after the grid's pass);
  // false (draw forward) for a target whose depth it cannot attach: the
  // default framebuffer, a depth other than a single-sample
  // DEPTH_COMPONENT32F renderbuffer or 2D texture, the scissor test on or
  // depth writes off.
  bool gBufferFor(GLint hostFbo, const GLint* viewport);
  void releaseGBuffer();  // its framebuffer and textures (the tile VAO/VBO stay)
  static constexpr int kGTargets = 3;   // ocean.frag's outG0..outG2
  static constexpr int kGTilePx = 8;    // ocean.frag's uGTiles
  GLuint gFbo_ = 0, gTex_[kGTargets] = {}, gTiles_ = 0, gVao_ = 0, gVbo_ = 0;
  int gWidth_ = 0, gHeight_ = 0;
  // Reduced rate: the coarse pass's target (a texel per 2 x 2 pixels, one
  // more column and row: the resolve reads past the last even pixel) and
  // the resolve's marks of the 4 x 2 groups to shade at full rate.
  static constexpr int kFullRateW = 4, kFullRateH = 2;
  GLuint gCoarseFbo_ = 0, gCoarse_ = 0, gFull_ = 0;
  int gCoarseW_ = 0, gCoarseH_ = 0;
  double lastFullRateShare_ = 1.0;
  std::vector<std::uint8_t> gFullMask_;
  std::vector<float> gFullRects_;
  bool lastDeferred_ = false;
  CellGroups lastGroups_;
  bool lastNoPixelOctaves_ = false;
  std::size_t gVboBytes_ = 0;
  std::vector<std::uint8_t> gTileMask_;
  std::vector<float> gRects_;
  std::vector<std::uint32_t> stripBucket_, stripStart_, stripIdx_;  // stripOrder's scratch (no allocation a frame)
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0, ssbo_[5] = {0, 0, 0, 0, 0};  // octaves, waves, frame, FFT planes | coast, FFT | coast texels
  std::size_t vboBytes_ = 0, iboBytes_ = 0;
  std::vector<float> octaveWavelengthM_;
  std::vector<float> mssAbove_;
  // ocean.frag's octave data as buffer textures (noise_bands.glsl's NOISE_OCTAVE_TEXELS).
  GLuint octaveBandBuf_ = 0, octaveBandTex_ = 0, octaveTexelTex_ = 0;
  std::vector<waves::DetailWave> detail_;  // the detail normal layer (ocean.frag): Gerstner, FFT
  // Noise: the detail layer is the same noise continued below the model's
  // finest octave (octaves n..11 of a 12-octave field, scaled to continue
  // the model's amplitudes), appended to the octave buffer for the fragments.
  std::optional<waves::WaveField> noiseDetail_;
  double noiseDetailScale_ = 1.0;
  int noiseDetailOctaves_ = 0;
  std::vector<float> octaveHeightVar_;  // the model octaves' crest-field variance (noise foam, noise_bands.glsl)
  double crestM_ = 0.0;                 // the crest field's level exceeded on W of the sea (noise)
  std::vector<float> foamHeightM_;
  double foamSoftM_ = 0.0, whitecap_ = 0.0;
  double windMps_ = 0.0, windFromRad_ = 0.0;
  double foamJacobian_ = 0.0, foamJacobianSoft_ = 0.0;
  waves::GpuPatch pastPatch_;
  glm::dvec3 foamCalibratedAt_{0.0};  // the origin: never a nadir, so the first draw calibrates
  OceanInputs inputs_;
  std::vector<Wake> wakes_;
  bool writeData_ = false, writeDepthData_ = false;
  CoastBands coastBands_ = CoastBands::ByDistance;  // issue 15 item 4
  std::unique_ptr<Spray> spray_;                    // issue 15 item 4: null without the bands
  bool sprayOn_ = true;
  int middleBlock_ = 2;               // issue 15 item 4: the middle band's mesh (setMiddleMeshBlock)
  bool fragmentNormal_ = true;        // issue 15 item 4: ocean.frag's uFragmentNormal
  double middleWavelengthM_ = 0.0;    // 0: no coarse mesh (no bands, or off)
  std::size_t coarseBlocks_ = 0;
  std::vector<std::uint8_t> coarseVertex_;
  bool glAbandoned_ = false;
  GLuint shadowSampler_ = 0;  // the shadow map's comparison and filter, whatever the host's texture says
  std::unique_ptr<WaterPages> pages_;
  std::unique_ptr<ElevationPages> elevPages_;
  // The world's water index is the streamed pyramid's (waterIndexFollowsTiles):
  // open water and coversOpaquely as without pages.
  bool pagesIndexed_ = false;
  std::unique_ptr<world::TileWaterIndex> fineWater_;  // a global streamed mask's (partitionCells)
  double pagedTexels_ = 0.0;  // the pyramid's level-0 texels per water-grid texel (partitionCells)
  bool completeTiles_ = false;
  double gridMs_ = 0.0;
};

// The default world's classifier (5' mask + ETOPO) for the grid.
std::shared_ptr<const ocean::LandSea> defaultLandSea();

}  // namespace geocean::ocean_render
