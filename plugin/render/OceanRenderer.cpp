#include "plugin/render/OceanRenderer.h"

#include "plugin/render/CoastIslandsGpu.h"
#include "plugin/waves/CoastField.h"
#include "plugin/waves/FftOcean.h"
#include "plugin/waves/WaveKernel.h"
#include "plugin/render/OceanWorld.h"

#include "globe/gl/Texture.h"

#include "globe/camera/Camera.h"
#include "globe/raster/World.h"
#include "shaders/Shaders.h"
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <cmath>
#include <stdexcept>

namespace geocean::ocean_render {

std::shared_ptr<const ocean::LandSea> defaultLandSea() {
  const auto files = raster::defaultWorld();
  return std::make_shared<ocean::LandSea>(raster::Raster::open(files.mask), raster::Raster::open(files.elevation));
}

OceanRenderer::OceanRenderer(std::shared_ptr<const world::WorldGrids> world,
                             std::shared_ptr<const ocean::LandSea> landSea, OceanOptions options)
    : world_(std::move(world)), options_(options) {
  // The ocean's own textures (the host may draw another world, or none).
  const auto& e = world_->elevation();
  elevationTex_ = gl::redGeoTexture(e.values.data(), e.channels, e.width, e.height, GL_R32F, false);
  const std::vector<float> reliefFloor = reliefUnderMaskWater(*world_);
  reliefFloorTex_ = gl::redGeoTexture(reliefFloor.data(), 1, e.width, e.height, GL_R8, false);
  const auto& w = world_->water();
  waterTex_ = gl::redGeoTexture(w.values.data(), w.channels, w.width, w.height, GL_R8, true);
  if (options_.waves) {
    // The caller's field (the façade snapshot's): its model and sea state rule.
    waves_ = options_.waves;
    options_.model = waves_->model(), options_.sea = waves_->seaState(), options_.coast = waves_->coastFieldShared();
  } else {
    std::string err;
    auto made = waves::WaveField::create(options_.model, options_.sea, err);
    if (!made) throw std::invalid_argument("sea state: " + err);
    made->setCoast(options_.coast);  // kept only for Gerstner
    waves_ = std::make_shared<const waves::WaveField>(std::move(*made));
  }
  const bool coast = waves_->coastField() != nullptr;
  grid::GridOptions go;
  go.cellPx = options_.cellPx;
  // WaveField's bound is the deep-water scan's; the coast field's Kr scales
  // amplitudes by up to kMaxKr (the caps only lower them).
  maxDisplacementM_ = waves_->maxDisplacementM() * (coast ? waves::CoastField::kMaxKr : 1.0);
  go.maxDisplacementM = maxDisplacementM_;
  // Cells are skipped only where the drawn shoreline cannot reach (the
  // fragment shader cuts the exact coastline); nearest-cell classes would
  // drop sea that the smooth shoreline shows as water.
  ocean::SurfaceClassifier classifier;
  const bool levelIsGrid = options_.waterTiles && waterIndexFollowsTiles(*world_, *options_.waterTiles);
  pagesIndexed_ = levelIsGrid && options_.streamedIndex;
  if (levelIsGrid)
    classifier = nearWaterClassifier(world_->water());
  else if (landSea)
    classifier = [ls = landSea](const double* lat, const double* lon, std::size_t n, ocean::Surface* out) {
      ls->classifyNearWaterBatch(lat, lon, n, out);
    };
  grid_ = std::make_unique<grid::ScreenGrid>(go, classifier);
  // WV_MODEL 4: paper 002's noise (shaders/waves_paper.glsl), as waves_eval.glsl numbers it.
  std::vector<std::string> model = {options_.model == waves::Model::Gerstner     ? "WV_MODEL 1"
                                    : options_.model == waves::Model::Fft        ? "WV_MODEL 2"
                                    : options_.model == waves::Model::NoisePaper ? "WV_MODEL 4"
                                                                                 : "WV_MODEL 0"};
  if (options_.model == waves::Model::Fft) model.push_back("WV_FFT 1");
  if (!options_.elevationTiles.empty()) {
    elevPages_ = std::make_unique<ElevationPages>(options_.elevationTiles);
    for (const std::string& d : elevPages_->defines()) model.push_back(d);
  }
  if (coast) model.push_back("WV_COAST 1");
  if (coast && !options_.coastBands) model.push_back("GEOCEAN_NO_COAST_BANDS 1");  // issue 15 item 4
  // Gerstner and FFT whitecaps per fragment from the Jacobian (foam.glsl);
  // the far per-vertex group has faded to the mean cover.
  std::vector<std::string> shaded = model;
  if (jacobianFoam()) {
    shaded.push_back("FOAM_TIMES " + std::to_string(kFoamTimes));
    shaded.push_back("FOAM_SUB " + std::to_string(kFoamSub));
    // Issue 15 item 4: with the bands, the normal per fragment from the
    // whitecaps' present sample (ocean.frag; uFragmentNormal), so the middle
    // band's coarse cells do not soften the sea.
    if (coast && options_.coastBands && options_.model == waves::Model::Gerstner)
      shaded.push_back("GEOCEAN_FRAGMENT_NORMAL 1");
  }
  if (options_.waterTiles) {
    pages_ = std::make_unique<WaterPages>(options_.waterTiles, gl::TilePoolOptions{}, options_.waterTilesBelow);
    pagedTexels_ = world_->water().lonStepDeg / options_.waterTiles->source().transform().lonStepDeg;
    // One global layer (its texels alone draw the coast): asked per cell.
    if (pagesIndexed_ && pages_->layers() == 1 && options_.waterTiles->source().transform().global)
      fineWater_ = std::make_unique<world::TileWaterIndex>(options_.waterTiles);
    auto paged = shaded;
    for (const std::string& d : pages_->defines()) paged.push_back(d);
    sharpDefines_ = paged;
    if (fineWater_) {
      sharpMinDefines_ = paged;
      sharpMinDefines_.push_back("GEOCEAN_WATER_PAGES_MINIFIED 1");
    }
  } else {
    sharpDefines_ = shaded;
  }
  {
    openDefines_ = shaded;
    openDefines_.push_back("GEOCEAN_OPEN_WATER 1");
    smoothDefines_ = shaded;
    smoothDefines_.push_back("GEOCEAN_VERTEX_COVERAGE 1");
    if (pages_) smoothDefines_.push_back("GEOCEAN_WATER_PAGES 1");  // read per vertex from the pages
    pixelPrograms(false, true, true, false, false);
    auto far = model;
    far.push_back("GEOCEAN_FAR_SHADED 1");
    farShaded_ = gl::GlProgram::graphics("ocean.vert", "ocean.frag", far);
  }
  model.push_back("GEOCEAN_BARE 1");
  bare_ = gl::GlProgram::graphics("ocean.vert", "bare.frag", model);
  // Issue 15 item 4 hook: the bands' breaking spray (Spray.h).
  if (coast && options_.coastBands && options_.model == waves::Model::Gerstner) spray_ = std::make_unique<Spray>();
  // Issue 15 item 4: the middle band's mesh is measured against lambda =
  // 2 pi sum az / sum az kP (wv_breakingFoamMean), at its largest over the
  // depths, each component's az and kP from the kernel's own
  // wv_coastAmplitude (shoaling, Miche's cap; no refraction, no taper).
  if (coast && options_.coastBands && options_.coarseMiddle && options_.model == waves::Model::Gerstner) {
    waves::WaveField::CpuPatch cp;
    waves_->cpuPatch(geo::toEcef({options_.sea.anchorLatDeg, options_.sea.anchorLonDeg, 0.0}), 0.0, cp);
    waves::kd::Kernel k;
    for (double depth = 0.05; depth < 2e4; depth *= 1.1) {
      double sumAz = 0.0, sumAzK = 0.0;
      for (const auto& wave : cp.waves) {
        const glm::dvec3 a = k.wv_coastAmplitude(wave, 1.0, 0.0, depth, true);
        sumAz += a.x, sumAzK += a.x * a.z;
      }
      if (sumAzK > 0.0) middleWavelengthM_ = std::max(middleWavelengthM_, 6.283185307179586 * sumAz / sumAzK);
    }
  }
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glCreateBuffers(1, &ibo_);
  glCreateBuffers(5, ssbo_);
  // The coast field's texels are the field's, not the frame's: uploaded once.
  if (coast) {
    // The island table built here on the GPU (paper 003: the GPU's table for
    // the picture, the CPU's for queries; WavesGpuParity bounds the two);
    // the CPU-built texels if the compute build fails.
    std::string islandError;
    std::vector<glm::vec4> texels;
    if (options_.gpuIslandTable) texels = coastTexelsGpuIslands(*waves_->coastField(), islandError);
    if (texels.empty()) {
      if (!islandError.empty()) std::fprintf(stderr, "geocean: %s; drawing the CPU-built table\n", islandError.c_str());
      texels = waves_->coastField()->gpuTexels();
    }
    glNamedBufferData(ssbo_[4], GLsizeiptr(texels.size() * sizeof(glm::vec4)), texels.data(), GL_STATIC_DRAW);
  }
  // GridVertex: vec3 eyeRel, uint class|flags << 8, dvec2 lat/lon (32 bytes).
  glEnableVertexArrayAttrib(vao_, 0);
  glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao_, 0, 0);
  glEnableVertexArrayAttrib(vao_, 1);
  glVertexArrayAttribIFormat(vao_, 1, 1, GL_UNSIGNED_INT, 12);
  glVertexArrayAttribBinding(vao_, 1, 0);
  glEnableVertexArrayAttrib(vao_, 2);
  glVertexArrayAttribLFormat(vao_, 2, 2, GL_DOUBLE, 16);
  glVertexArrayAttribBinding(vao_, 2, 0);
  // Noise: the detail layer continues the model's octaves down to octave
  // 12 (the kernel's most), the same rotations and seeds as a 12-octave
  // sea's and the amplitudes halving on from the model's finest: per-fragment
  // normals only (the query's heights have the model's octaves).
  std::vector<waves::WaveField::Octave> allOctaves = waves_->octaves();
  if (options_.model == waves::Model::Noise && options_.detailNormals && options_.sea.noiseOctaves < 12) {
    waves::SeaState s12 = options_.sea;
    s12.noiseOctaves = 12;
    std::string why;
    auto made = waves::WaveField::create(waves::Model::Noise, s12, why);
    if (made && !made->octaves().empty() && !allOctaves.empty()) {
      noiseDetailScale_ = allOctaves[0].amplitudeM / made->octaves()[0].amplitudeM;
      noiseDetailOctaves_ = 12 - int(allOctaves.size());
      for (std::size_t i = allOctaves.size(); i < made->octaves().size(); ++i) allOctaves.push_back(made->octaves()[i]);
      noiseDetail_.emplace(std::move(*made));
    }
  }
  // The model octaves' height variances (the noise's whitecaps: what the
  // pixel does not resolve widens the crest's edge). 0.27008: the 3D
  // gradient noise's standard deviation (WaveField.cpp kPerlin3Std).
  for (std::size_t i = 0; i < waves_->octaves().size(); ++i)
    octaveHeightVar_.push_back(float(std::pow(waves_->octaves()[i].amplitudeM * 0.27008, 2.0) * std::exp2(1.5 * double(i))));
  // Octave wavelengths (1 / lattice frequency) for the distance fade.
  for (const auto& o : allOctaves) octaveWavelengthM_.push_back(float(1.0 / o.frequencyPerM));
  // Models without octaves fade by the spectrum's peak wavelength.
  if (octaveWavelengthM_.empty()) octaveWavelengthM_.push_back(float(waves_->peakWavelengthM()));
  // Roughness: the slope variance of the spectrum's waves shorter than the
  // shortest drawn. A noise octave of lattice frequency f carries wave
  // numbers about 2 pi f, its band reaching up to sqrt 2 x that.
  constexpr double kTwoPi = 6.283185307179586;
  const waves::SeaState& sea = waves_->seaState();
  mssAbove_.assign(17, 0.0f);
  mssAbove_[0] = float(waves::slopeVarianceAbove(sea, 0.0));
  if (options_.model == waves::Model::Noise || options_.model == waves::Model::NoisePaper) {
    const auto& oc = allOctaves;
    for (std::size_t c = 1; c < 17; ++c)
      mssAbove_[c] = c <= oc.size() ? float(waves::slopeVarianceAbove(sea, kTwoPi * oc[c - 1].frequencyPerM * std::sqrt(2.0)))
                                    : mssAbove_[c - 1];
  } else {
    double kMax = 0.0;  // the shortest wave drawn
    for (const auto& c : waves_->components()) kMax = std::max(kMax, c.kRef);
    // FFT: the fine cascade (5.3 / 7.3 peak wavelengths over 128 texels) to its Nyquist.
    if (options_.model == waves::Model::Fft) kMax = kTwoPi / waves_->peakWavelengthM() * 7.3 / 5.3 * 64.0;
    mssAbove_[1] = float(waves::slopeVarianceAbove(sea, kMax));
  }
  // ocean.frag's uOctaveBands (noise_bands.glsl): per octave k <= 16 the
  // uniform arrays' values (0 past those set), (wavelength, mss above,
  // height variance, the height variances from k on); and uOctaveTexels,
  // the octave SSBO as RGBA32F. The last: the sum ocean.frag's trailing
  // loop makes, in float and its order (k up), so the programs without
  // pixel octaves, whose sum starts at 0, read it bit for bit.
  {
    std::vector<glm::vec4> bands(17, glm::vec4(0.0f));
    const std::size_t heightVars = std::min<std::size_t>(octaveHeightVar_.size(), 16);
    for (std::size_t k = 0; k < 17; ++k) {
      if (k < std::min<std::size_t>(octaveWavelengthM_.size(), 16)) bands[k].x = octaveWavelengthM_[k];
      bands[k].y = mssAbove_[k];
      if (k < heightVars) bands[k].z = octaveHeightVar_[k];
      float suffix = 0.0f;
      for (std::size_t j = k; j < heightVars; ++j) suffix += octaveHeightVar_[j];
      bands[k].w = suffix;
    }
    glCreateBuffers(1, &octaveBandBuf_);
    glNamedBufferData(octaveBandBuf_, GLsizeiptr(bands.size() * sizeof(glm::vec4)), bands.data(), GL_STATIC_DRAW);
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &octaveBandTex_);
    glTextureBuffer(octaveBandTex_, GL_RGBA32F, octaveBandBuf_);
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &octaveTexelTex_);
  }
  // Gerstner and FFT: the detail layer starts where the model's shortest
  // wave ends, 8 octaves of 4 waves (to 2 cm at
  // U = 10 for Gerstner): ocean.frag keeps those over 2 pixels.
  if (options_.detailNormals && options_.model != waves::Model::Noise) {
    double kLow = 0.0;
    if (options_.model == waves::Model::Fft)
      kLow = kTwoPi / waves_->peakWavelengthM() * 7.3 / 5.3 * 64.0;
    else if (options_.model == waves::Model::NoisePaper && !allOctaves.empty())
      kLow = kTwoPi * allOctaves.back().frequencyPerM * std::sqrt(2.0);  // the finest octave's band top
    else
      for (const auto& c : waves_->components()) kLow = std::max(kLow, c.kRef);
    if (kLow > 0.0) detail_ = waves::detailWaves(sea, kLow, 8, 4);
  }
  // Whitecaps: the crest height that the model's own heights (what
  // ocean.vert displaces by, at rest points) exceed on Monahan's fraction W
  // of the sea, from 16,384 points over 40 x 40 peak wavelengths at t = 0 and
  // 300 s (a 1/W-quantile of 16 k samples: +-12 % in W at 0.5 % cover). For
  // noise, per number of octaves ocean.vert keeps (dropping the short ones
  // lowers the crests): the same sea with c octaves has the first c octaves
  // of this one, scaled to the full Hs by sqrt(sum_all 4^-i / sum_c 4^-i).
  whitecap_ = whitecapCover(sea.windSpeedMps);
  windMps_ = sea.windSpeedMps, windFromRad_ = sea.windFromDeg * kTwoPi / 360.0;  // the glitter's axes
  foamHeightM_.assign(17, 0.0f);
  const auto quantile = [&](const waves::WaveField& field) {
    const double spanDeg = 40.0 * field.peakWavelengthM() / 111320.0;
    constexpr std::size_t kN = 16384;
    std::vector<double> h(kN), lat(kN), lon(kN), t(kN);
    std::uint32_t state = 12345u;
    const auto uniform = [&] { return double((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0; };
    for (std::size_t i = 0; i < kN; ++i) {
      lat[i] = sea.anchorLatDeg + (uniform() - 0.5) * spanDeg, lon[i] = sea.anchorLonDeg + (uniform() - 0.5) * spanDeg;
      t[i] = double(i & 1) * 300.0;
    }
    if (field.maxHorizontalM() == 0.0) {
      // Heights only (noise): the surface above a point is the rest point's
      // height, and the SIMD batch gives it 10x faster.
      std::vector<waves::SurfacePoint> sp(kN);
      field.surfaceBatch(lat.data(), lon.data(), t.data(), true, nullptr, kN, sp.data());
      for (std::size_t i = 0; i < kN; ++i) h[i] = sp[i].heightM;
    } else
      for (std::size_t i = 0; i < kN; ++i) h[i] = field.sample(lat[i], lon[i], t[i]).displacementEnuM.z;
    const std::size_t q = std::min(h.size() - 1, std::size_t((1.0 - whitecap_) * double(h.size())));
    std::nth_element(h.begin(), h.begin() + std::ptrdiff_t(q), h.end());
    return h[q];
  };
  foamHeightM_[0] = float(quantile(*waves_));
  // Noise models: per number of octaves ocean.vert keeps.
  if (options_.model == waves::Model::Noise || options_.model == waves::Model::NoisePaper) {
    const int n = sea.noiseOctaves;
    const auto sumSq = [](int c) {
      double s = 0.0;
      for (int i = 0; i < c; ++i) s += std::pow(0.25, i);
      return s;
    };
    foamHeightM_[0] = 1e30f;  // no octave drawn: no crest
    for (int c = 1; c <= 16; ++c) {
      if (c >= n) {
        foamHeightM_[c] = float(quantile(*waves_));
        for (int k = c + 1; k <= 16; ++k) foamHeightM_[k] = foamHeightM_[c];
        break;
      }
      waves::SeaState sc = sea;
      sc.noiseOctaves = c;
      std::string why;
      const auto wc = waves::WaveField::create(options_.model, sc, why);
      foamHeightM_[c] = float(quantile(*wc) / std::sqrt(sumSq(n) / sumSq(c)));
    }
  }
  if (options_.model == waves::Model::Noise) {
    // The whitecaps' crest field (noise_bands.glsl): octave i's height
    // weighted by 2^(3i/4), so shorter crests break the long waves' tops into
    // patches smaller than they are; its level exceeded on W of the sea, from
    // the same 16,384 points as the heights' (every octave of each point
    // from the shader's own kernel).
    const double spanDeg = 40.0 * waves_->peakWavelengthM() / 111320.0;
    constexpr std::size_t kN = 16384;
    std::vector<double> crest(kN);
    std::uint32_t state = 12345u;
    const auto uniform = [&] { return double((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0; };
    waves::WaveField::CpuPatch cp;
    waves::kd::Kernel k;
    for (std::size_t i = 0; i < kN; ++i) {
      const double lat = sea.anchorLatDeg + (uniform() - 0.5) * spanDeg, lon = sea.anchorLonDeg + (uniform() - 0.5) * spanDeg;
      waves_->cpuPatch(geo::toEcef({lat, lon, 0.0}), double(i & 1) * 300.0, cp);
      k.wvOctaves = cp.octaves.data();
      double c = 0.0;
      for (int o = 0; o < int(cp.octaves.size()); ++o)
        c += std::exp2(0.75 * o) * k.wv_solidNoise(o, 1, glm::dvec3(0.0), cp.frame).disp.w;
      crest[i] = c;
    }
    const std::size_t q = std::min(kN - 1, std::size_t((1.0 - whitecap_) * double(kN)));
    std::nth_element(crest.begin(), crest.begin() + std::ptrdiff_t(q), crest.end());
    crestM_ = crest[q];
  } else if (options_.model != waves::Model::NoisePaper)
    std::fill(foamHeightM_.begin() + 1, foamHeightM_.end(), foamHeightM_[0]);
  // Soft edge: 2 % of Hs either side (an anti-aliased rim, not a halo).
  foamSoftM_ = 0.02 * waves_->spectrumHsM();
}

std::array<double, OceanRenderer::kFoamTimes> OceanRenderer::foamTimes(double tS) {
  // Past samples on a fixed grid strictly before tS (ages in (0, 1], (1, 2], ..
  // steps): the same times for every frame within a step, so the FFT's
  // tables for them come from its cache.
  std::array<double, kFoamTimes> t{};
  t[0] = tS;
  const double last = std::ceil(tS / kFoamStepS) * kFoamStepS - kFoamStepS;
  for (int k = 1; k < kFoamTimes; ++k) t[std::size_t(k)] = last - (k - 1) * kFoamStepS;
  return t;
}

double OceanRenderer::foamOf(const double* det, const double* ageS) const {
  // foam.glsl's whitecapFoam in double: the samples, then the cubic Hermite
  // between them at kFoamSub points and its minimum in each step.
  const double e0 = foamJacobian_ - foamJacobianSoft_, e1 = foamJacobian_ + foamJacobianSoft_;
  const auto fold = [&](double j) {
    const double x = std::clamp((j - e0) / (e1 - e0), 0.0, 1.0);
    return 1.0 - x * x * (3.0 - 2.0 * x);
  };
  double foam = 0.0;
  for (int k = 0; k < kFoamTimes; ++k) foam = std::max(foam, fold(det[k]) * std::exp(-ageS[k] / kFoamDecayS));
  for (int k = 0; k + 1 < kFoamTimes; ++k) {
    const double a0 = ageS[k], a1 = ageS[k + 1], h = a1 - a0;
    const double m0 = k > 0 ? (det[k + 1] - det[k - 1]) / (a1 - ageS[k - 1]) : (det[k + 1] - det[k]) / h;
    const double m1 = k + 2 < kFoamTimes ? (det[k + 2] - det[k]) / (ageS[k + 2] - a0) : (det[k + 1] - det[k]) / h;
    const double p0 = det[k], p1 = det[k + 1], c1 = h * m0;
    const double c3 = 2.0 * p0 + h * m0 - 2.0 * p1 + h * m1, c2 = 3.0 * (p1 - p0) - 2.0 * h * m0 - h * m1;
    for (int i = 1; i < kFoamSub; ++i) {
      const double x = double(i) / kFoamSub;
      foam = std::max(foam, fold(((c3 * x + c2) * x + c1) * x + p0) * std::exp(-(a0 + x * h) / kFoamDecayS));
    }
    const double disc = c2 * c2 - 3.0 * c3 * c1;
    if (disc < 0.0) continue;
    const double sq = std::sqrt(disc);
    const double q = std::abs(c2) > 1e-6 ? -c1 / (2.0 * c2) : -1.0;  // a quadratic's
    const bool cubic = std::abs(c3) > 1e-6;
    const double u[2] = {cubic ? (-c2 - sq) / (3.0 * c3) : q, cubic ? (-c2 + sq) / (3.0 * c3) : q};
    for (double x : u)
      if (x > 0.0 && x < 1.0)
        foam = std::max(foam, fold(((c3 * x + c2) * x + c1) * x + p0) * std::exp(-(a0 + x * h) / kFoamDecayS));
  }
  return foam;
}

void OceanRenderer::calibrateJacobianFoam(double latDeg, double lonDeg) {
  // The Jacobian threshold at which the foam a frame draws covers W of the
  // sea around (latDeg, lonDeg): the Jacobian's statistics vary over the
  // globe (the FFT tile is seen up to 60 degrees oblique by its triplanar
  // plane, Gerstner directions follow great circles), so draw() calibrates
  // again where it looks once that has moved kFoamCalibrationM away.
  // 4096 particles over 40 x 40 peak wavelengths at 4 frame times (at
  // 0, 1/4, 1/2, 3/4 of a step past the grid, as frames fall), each with
  // its history; a pixel counts as foam where the foam is >= kFoamCounted,
  // weighted by the displaced surface's area
  // per rest area (the present determinant), as a top-down view sees it.
  // Sampling: +-12 % in W at 0.5 % cover (the noise quantile's figure).
  foamCalibratedAt_ = geo::toEcef({latDeg, lonDeg, 0.0});
  constexpr std::size_t kP = 4096;
  constexpr int kBases = 4;
  const double spanDeg = 40.0 * waves_->peakWavelengthM() / 111320.0;
  std::uint32_t state = 424242u;
  const auto uniform = [&] { return double((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0; };
  std::vector<glm::dvec3> at(kP);
  for (auto& o : at)
    o = geo::toEcef({latDeg + (uniform() - 0.5) * spanDeg, lonDeg + (uniform() - 0.5) * spanDeg, 0.0});
  std::vector<double> det(kP * kBases * kFoamTimes), age(kP * kBases * kFoamTimes), area(kP * kBases);
  waves::WaveField::CpuPatch patch;
  for (int b = 0; b < kBases; ++b) {
    const double tS = 300.0 * b + kFoamStepS * (0.25 * b + 0.01);
    const auto times = foamTimes(tS);
    for (int k = 0; k < kFoamTimes; ++k)
      for (std::size_t i = 0; i < kP; ++i) {
        waves_->cpuPatch(at[i], times[std::size_t(k)], patch);
        const std::size_t j = (std::size_t(b) * kP + i) * kFoamTimes + std::size_t(k);
        det[j] = waves_->foldJacobian(patch, glm::dvec3(0.0), 1e30);
        age[j] = tS - times[std::size_t(k)];
        if (k == 0) area[std::size_t(b) * kP + i] = std::max(det[j], 0.0);
      }
  }
  double total = 0.0;
  for (double a : area) total += a;
  const auto cover = [&](double thr) {
    foamJacobian_ = thr, foamJacobianSoft_ = 0.1 * thr;
    double c = 0.0;
    for (std::size_t p = 0; p < area.size(); ++p)
      if (foamOf(&det[p * kFoamTimes], &age[p * kFoamTimes]) >= kFoamCounted) c += area[p];
    return c / total;
  };
  double lo = 0.0, hi = 2.0;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cover(mid) < whitecap_ ? lo : hi) = mid;
  }
  cover(0.5 * (lo + hi));
}

double OceanRenderer::whitecapCover(double windSpeedMps) {
  // Their fit is for U10; the sea state's wind is at 19.5 m (U10 = U19.5 / 1.026).
  return std::min(3.84e-6 * std::pow(windSpeedMps / 1.026, 3.41), 1.0);
}

OceanRenderer::~OceanRenderer() {
  if (glAbandoned_) return;
  const GLuint tex[] = {elevationTex_, waterTex_, octaveBandTex_, octaveTexelTex_, reliefFloorTex_};
  glDeleteTextures(5, tex);
  glDeleteBuffers(1, &octaveBandBuf_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
  glDeleteBuffers(5, ssbo_);
  if (shadowSampler_) glDeleteSamplers(1, &shadowSampler_);
  releaseGBuffer();
  if (gVao_) glDeleteVertexArrays(1, &gVao_);
  if (gVbo_) glDeleteBuffers(1, &gVbo_);
}

void OceanRenderer::abandonGl() {
  glAbandoned_ = true;
  for (gl::GlProgram* p : {&farShaded_, &bare_, &resolve_}) p->abandon();
  if (spray_) spray_->abandon();
  for (PixelPrograms& v : pixel_)
    for (gl::GlProgram* p : {&v.sharp, &v.smooth, &v.open, &v.gSharp, &v.gSmooth, &v.gOpen, &v.shade, &v.coarse})
      p->abandon();
  if (pages_) pages_->abandonGl();
  if (elevPages_) elevPages_->abandonGl();
}

namespace {
// Reads back a mask (R8UI, one texel per block of bw x bh framebuffer
// pixels, cols x rows of them) written through an image unit, and makes
// its marked blocks rectangles for a draw: runs along each row, clipped to
// the viewport. Returns how many blocks were marked.
std::size_t markedRects(GLuint mask, int cols, int rows, int bw, int bh, const GLint* viewport,
                        std::vector<std::uint8_t>& bytes, std::vector<float>& rects) {
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  bytes.resize(std::size_t(cols) * std::size_t(rows));
  GLint packAlignment = 4;
  glGetIntegerv(GL_PACK_ALIGNMENT, &packAlignment);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(mask, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
  glPixelStorei(GL_PACK_ALIGNMENT, packAlignment);
  const int right = viewport[0] + viewport[2], top = viewport[1] + viewport[3];
  std::size_t marked = 0;
  rects.clear();
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols;) {
      if (!bytes[std::size_t(y) * std::size_t(cols) + std::size_t(x)]) {
        ++x;
        continue;
      }
      const int x0 = x;
      while (x < cols && bytes[std::size_t(y) * std::size_t(cols) + std::size_t(x)]) ++x;
      marked += std::size_t(x - x0);
      const float ax = float(std::max(x0 * bw, viewport[0])), bx = float(std::min(x * bw, right));
      const float ay = float(std::max(y * bh, viewport[1])), by = float(std::min((y + 1) * bh, top));
      for (float v : {ax, ay, bx, ay, bx, by, ax, ay, bx, by, ax, by}) rects.push_back(v);
    }
  return marked;
}

template <class T>
void upload(GLuint buf, const std::vector<T>& v) {
  // Never empty: a zero-size SSBO binding is an error.
  const std::size_t bytes = std::max<std::size_t>(v.size() * sizeof(T), 64);
  std::vector<unsigned char> tmp(bytes, 0);
  if (!v.empty()) std::memcpy(tmp.data(), v.data(), v.size() * sizeof(T));
  glNamedBufferData(buf, GLsizeiptr(bytes), tmp.data(), GL_STREAM_DRAW);
}

// The cells (6 indices each) in strips of kStripRows grid rows, column by
// column, each column's cells bottom to top; the order within a strip's
// column as given. llvmpipe's vertex cache (the draw module's) is reset
// every few dozen vertices, so row by row it shaded ~2 vertices a cell
// (each row's top vertices again for the next row); down a strip's columns
// it shades ~(k + 1) / k a cell (docs/PERFORMANCE.md). Counting sort: O(n).
constexpr std::uint32_t kStripRows = 8;
void stripOrder(std::vector<std::uint32_t>& idx, std::uint32_t cols, std::uint32_t rows,
                std::vector<std::uint32_t>& bucketOf, std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& out) {
  if (cols == 0 || rows == 0) return;
  const std::size_t cells = idx.size() / 6, buckets = std::size_t((rows + kStripRows - 1) / kStripRows) * cols;
  bucketOf.resize(cells);
  start.assign(buckets + 1, 0);
  for (std::size_t c = 0; c < cells; ++c) {
    const std::uint32_t v = idx[6 * c], row = std::min(v / cols, rows - 1), col = v % cols;
    bucketOf[c] = (row / kStripRows) * cols + col;
    ++start[bucketOf[c] + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  out.resize(idx.size());
  for (std::size_t c = 0; c < cells; ++c) std::copy_n(idx.begin() + std::ptrdiff_t(6 * c), 6, out.begin() + std::ptrdiff_t(6 * start[bucketOf[c]]++));
  idx.swap(out);
}
}  // namespace

std::vector<std::uint8_t> offscreenSides(const grid::GridFrame& f, const ScreenCull& v) {
  // Per vertex: the sides of the screen (bits: left, right, bottom, top)
  // that it stays beyond however the waves move it. The displacement is
  // bounded per view-space axis by h (the wave field's maximum plus the
  // vertex shader's sag raise for the cell), and x / z over the box of
  // possible positions is bounded by its corners when z - h > 0.
  const auto sides = [&](const glm::dvec3& p, double h) -> std::uint8_t {
    const double z = glm::dot(p, v.forward);
    if (!(z - h > 0.0)) return 0;
    const double x = glm::dot(p, v.right), y = glm::dot(p, v.up);
    const double zNear = z - h, zFar = z + h;
    const double xMin = std::min((x - h) / zNear, (x - h) / zFar), xMax = std::max((x + h) / zNear, (x + h) / zFar);
    const double yMin = std::min((y - h) / zNear, (y - h) / zFar), yMax = std::max((y + h) / zNear, (y + h) / zFar);
    return std::uint8_t((xMax < -v.tanX ? 1 : 0) | (xMin > v.tanX ? 2 : 0) | (yMax < -v.tanY ? 4 : 0) |
                        (yMin > v.tanY ? 8 : 0));
  };
  const auto sagM = [&](double dist) {
    const double cellM = 2.0 * dist * v.cellRadians;  // ocean.vert: footprint / max(sin, 0.5)
    return cellM * cellM / (3.0 * 6.3e6) + 1e-4 * dist;  // + float rounding
  };
  std::vector<std::uint8_t> out(f.vertices.size(), 0);
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < f.vertices.size(); ++i) {
    const grid::GridVertex& g = f.vertices[i];
    const glm::dvec3 p(g.eyeRelM[0], g.eyeRelM[1], g.eyeRelM[2]);
    const double dist = glm::length(p);
    const double h = v.maxDisplacementM + sagM(dist);
    out[i] = sides(p, h);
    if (glm::dot(p, v.forward) - h <= 0.0 && !(g.flags & grid::kVertexHorizon)) near.push_back(i);
  }
  // Near the eye the bound cannot decide (at 2 m above the sea, crests of
  // the 8 m bound could reach the eye): where the waves only move the sea
  // vertically, evaluate them (the CPU's SIMD batch of the same kernel) and
  // test the displaced vertex, within what the vertex shader may differ by:
  // the bound of the octaves it leaves out at that distance (those shorter
  // than 3 grid cells, with 1 % for its float footprint) and 1 cm for float
  // rounding.
  if (!v.waves || v.waves->maxHorizontalM() != 0.0 || near.empty()) return out;
  const auto& octaves = v.waves->octaves();
  std::vector<double> tailBoundM(octaves.size() + 1, 0.0);  // bound of octaves i.. together
  double ampSum = 0.0;
  for (const auto& o : octaves) ampSum += o.amplitudeM;
  for (std::size_t i = octaves.size(); i-- > 0;)
    tailBoundM[i] = tailBoundM[i + 1] + v.waves->maxVerticalM() * octaves[i].amplitudeM / std::max(ampSum, 1e-300);
  const auto omittedBoundM = [&](double dist) {
    std::size_t i = 0;
    // ocean.vert takes at most 16 octaves, longest first.
    while (i < octaves.size() && i < 16 && 1.0 / octaves[i].frequencyPerM > 3.03 * dist * v.cellRadians) ++i;
    return tailBoundM[i];
  };
  const auto exact = [&](const std::vector<std::size_t>& which, std::vector<waves::SurfacePoint>& sp) {
    std::vector<double> lat(which.size()), lon(which.size());
    for (std::size_t k = 0; k < which.size(); ++k)
      lat[k] = f.vertices[which[k]].latDeg, lon[k] = f.vertices[which[k]].lonDeg;
    sp.resize(which.size());
    v.waves->surfaceBatch(lat.data(), lon.data(), &v.timeS, false, nullptr, which.size(), sp.data());
  };
  const auto eyeRel = [&](std::size_t i) {
    const float* e = f.vertices[i].eyeRelM;
    return glm::dvec3(e[0], e[1], e[2]);
  };
  const auto test = [&](std::size_t i, double heightM, double slackM) {
    const grid::GridVertex& g = f.vertices[i];
    const glm::dvec3 p = eyeRel(i);
    const double dist = glm::length(p);
    return sides(p + geo::surfaceNormal(g.latDeg, g.lonDeg) * heightM,
                 omittedBoundM(dist) + 0.01 + sagM(dist) + slackM);
  };
  // Per block of B x B grid vertices, one height (the block's centre, or
  // its first near vertex) bounds the others' by the noise field's
  // Lipschitz constant L: |h(a) - h(b)| <= L |a - b| along the chord, as the
  // noise sum is a function of the ECEF point (wv_solidNoise). Per octave
  // |grad perlin3| <= 8.5 a lattice axis (the blended gradients' component
  // <= 1, plus the fade's slope 30/16 times the faces' difference <= 2 + 2),
  // and d/dECEF takes the rows: L = sum |a| 8.5 (|row0| + |row1| + |row2|).
  // Vertices the block's bound leaves undecided are evaluated themselves.
  // Near the eye the cells are centimetres, so a block's bound is tight
  // (L ~ 4 for the default sea): at 2 m, of ~110 k near vertices ~11 k are
  // evaluated (1.8 k blocks of 8, 4.7 k of 2, 4.8 k alone), not all.
  const std::size_t cols = std::size_t(std::max(f.cols, 0)), rows = std::size_t(std::max(f.rows, 0));
  std::vector<std::size_t> rest = near;
  if (v.waves->model() == waves::Model::Noise && cols * rows == f.vertices.size()) {
    double lipschitz = 0.0;
    for (const auto& o : octaves)
      lipschitz += std::abs(o.amplitudeM) * 8.5 * (glm::length(o.row[0]) + glm::length(o.row[1]) + glm::length(o.row[2]));
    // Blocks of 8 (one evaluation in 64), then of 2 for what is left there.
    for (const std::size_t block : {std::size_t(8), std::size_t(2)}) {
      const std::size_t bc = (cols + block - 1) / block, br = (rows + block - 1) / block;
      std::vector<std::size_t> rep(bc * br, SIZE_MAX), reps, undecided;
      const auto blockOf = [&](std::size_t i) { return (i / cols / block) * bc + (i % cols) / block; };
      for (std::size_t i : rest) {
        std::size_t& r = rep[blockOf(i)];
        if (r == SIZE_MAX) r = i;
      }
      for (std::size_t b = 0; b < rep.size(); ++b) {
        if (rep[b] == SIZE_MAX) continue;
        const std::size_t r = std::min(rows - 1, (b / bc) * block + block / 2);
        const std::size_t c = std::min(cols - 1, (b % bc) * block + block / 2);
        if (!(f.vertices[r * cols + c].flags & grid::kVertexHorizon)) rep[b] = r * cols + c;
        reps.push_back(rep[b]);
      }
      std::vector<waves::SurfacePoint> sp;
      exact(reps, sp);
      std::vector<double> repHeight(rep.size(), 0.0);
      for (std::size_t k = 0, b = 0; b < rep.size(); ++b)
        if (rep[b] != SIZE_MAX) repHeight[b] = sp[k++].heightM;
      for (std::size_t i : rest) {
        const std::size_t b = blockOf(i);
        const glm::dvec3 p = eyeRel(i), q = eyeRel(rep[b]);
        // The chord between the float rest positions, with their rounding.
        const double chordM = glm::length(p - q) + 1e-6 * (glm::length(p) + glm::length(q));
        out[i] = test(i, repHeight[b], lipschitz * chordM);
        if (!out[i] && i != rep[b]) undecided.push_back(i);
      }
      rest.swap(undecided);
    }
  }
  std::vector<waves::SurfacePoint> sp;
  exact(rest, sp);
  for (std::size_t k = 0; k < rest.size(); ++k) out[rest[k]] = test(rest[k], sp[k].heightM, 0.0);
  return out;
}

namespace {

// Whether every fragment of a cell (6 indices, two triangles) reads the
// pages minified: geo_uv.glsl's texels per pixel, length(|dP/dx| + |dP/dy|)
// of the level-0 texel position P, at least 1. Per triangle, P over the
// screen is affine between its vertices (the derivatives llvmpipe's quads
// take); perspective-correct interpolation scales the derivative within the
// triangle by at most (nearest / farthest depth)^2 of its vertices. Bound:
// that product at least 2 (a factor 2 for the quads' pixels beyond the
// triangle's edge and the waves' displacement of the vertices, metres
// against the >= 1 km pixels where the texels are minified).
bool minifiedCell(const grid::GridFrame& f, const std::uint32_t* cell, const glm::dvec2* texel, const ScreenCull& view,
                  double pxPerTan) {
  for (int t = 0; t < 6; t += 3) {
    glm::dvec2 sp[3];
    double dMin = 0.0, dMax = 0.0;
    for (int k = 0; k < 3; ++k) {
      const float* e = f.vertices[cell[t + k]].eyeRelM;
      const glm::dvec3 rel(e[0], e[1], e[2]);
      const double d = glm::dot(rel, view.forward);
      if (!(d > 0.0)) return false;
      sp[k] = pxPerTan / d * glm::dvec2(glm::dot(rel, view.right), glm::dot(rel, view.up));
      dMin = k == 0 ? d : std::min(dMin, d), dMax = std::max(dMax, d);
    }
    const glm::dvec2 s1 = sp[1] - sp[0], s2 = sp[2] - sp[0];
    const glm::dvec2 p1 = texel[t + 1] - texel[t], p2 = texel[t + 2] - texel[t];
    const double det = s1.x * s2.y - s2.x * s1.y;
    if (!(std::abs(det) > 1e-6)) return false;
    const glm::dvec2 dx = (p1 * s2.y - p2 * s1.y) / det, dy = (p2 * s1.x - p1 * s2.x) / det;
    const double tpp = glm::length(glm::abs(dx) + glm::abs(dy)) * (dMin / dMax) * (dMin / dMax);
    if (!(tpp >= 2.0)) return false;
  }
  return true;
}

}  // namespace

CellGroups partitionCells(const grid::GridFrame& f, const world::WaterIndex& wi, double cellPx, const ScreenCull& view,
                          bool cull, bool group, std::vector<std::uint32_t>& idx, double pagedTexels,
                          world::TileWaterIndex* fine) {
  // Cells whose every vertex stays beyond one side of the screen cannot
  // reach it (the clamp rectangle adds such cells at low altitude: 2 m above
  // the sea it spans up to 4 screens a side).
  const std::vector<std::uint8_t> sides = cull ? offscreenSides(f, view) : std::vector<std::uint8_t>();
  std::size_t kept = 0;
  for (std::size_t c = 0; cull && c + 6 <= idx.size(); c += 6) {
    std::uint8_t all = 0xF;
    for (std::size_t k = 0; k < 6; ++k) all &= sides[idx[c + k]];
    if (all == 0) std::copy(idx.begin() + c, idx.begin() + c + 6, idx.begin() + kept), kept += 6;
  }
  if (cull) idx.resize(kept);
  if (!group) return {idx.size(), 0, 0, 0};
  // Per cell (6 indices): its vertices' lon/lat box in texels, widened by
  // what a fragment inside can read: the B-spline's 2 texels and the
  // mipmapped tap's footprint, up to 3 texels per pixel. Texels per pixel:
  // the box's extent over the cell's size on screen, doubled for the
  // perspective across the cell. Cells touching the horizon (stretched
  // limb cells) always take the per-pixel path.
  // Smooth cells: at most kSmoothTexels across. The B-spline's second
  // derivative is at most 2 per texel^2 (|B''| <= 2, weights sum to 1), so
  // linear interpolation across h texels errs by <= h^2 / 4 in coverage;
  // where the shoreline is, the gradient is >= 0.3 per texel, so the 0.5
  // contour moves by <= h^2 / 1.2 texels = (h / 1.2) x cellPx pixels:
  // 0.4 px at h = 0.06 with 8 px cells (0.03 before: 42 km over the default
  // world's coasts then drew every cell per pixel, ~35 ms of the flight's
  // median frame; docs/PERFORMANCE.md).
  constexpr double kSmoothTexels = 0.06;
  std::vector<std::uint32_t> smooth, open, farOpen, minified;
  std::size_t sharp = 0;
  // Pixels per unit of view-plane tangent (cellRadians is cellPx pixels).
  const double pxPerTan = view.cellRadians > 0.0 ? cellPx / view.cellRadians : 0.0;
  const bool mini = view.minified && fine && pxPerTan > 0.0;
  for (std::size_t c = 0; c + 6 <= idx.size(); c += 6) {
    bool limb = wi.width() == 0;
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0, lon0 = 0, fx0 = 0, fx1 = 0, fy0 = 0, fy1 = 0;
    glm::dvec2 texel[6];  // the vertices' fine level-0 texels
    for (std::size_t k = 0; k < 6 && !limb; ++k) {
      const grid::GridVertex& v = f.vertices[idx[c + k]];
      if (v.flags & grid::kVertexHorizon) limb = true;
      double lon = v.lonDeg;
      if (k == 0) lon0 = lon;
      lon -= 360.0 * std::round((lon - lon0) / 360.0);  // the cell does not wrap
      const double x = wi.texelX(lon), y = wi.texelY(v.latDeg);
      if (k == 0) x0 = x1 = x, y0 = y1 = y;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      if (fine) {
        const double fx = fine->texelX(lon), fy = fine->texelY(v.latDeg);
        texel[k] = {fx, fy};
        if (k == 0) fx0 = fx1 = fx, fy0 = fy1 = fy;
        fx0 = std::min(fx0, fx), fx1 = std::max(fx1, fx), fy0 = std::min(fy0, fy), fy1 = std::max(fy1, fy);
      }
    }
    std::vector<std::uint32_t>* to = nullptr;
    if (!limb) {
      const double extent = std::max(x1 - x0, y1 - y0);
      // The paged coverage's footprint, length(fwidth) of its texel
      // position, is up to twice the mipmap's (geo_uv.glsl waterPagesAuto).
      const double margin = 3.0 + 3.0 * (pagedTexels > 0.0 ? 4.0 : 2.0) * extent / cellPx;
      bool water = wi.allWater(x0 - margin, x1 + margin, y0 - margin, y1 + margin);
      if (!water && fine) {
        // The same reach in the mask's own texels: near a coast most cells
        // are water (or land) throughout it though the grid's texel is not.
        // Magnified, a fragment at texel position x (texel j spans [j, j + 1))
        // reads the B-spline's texels floor(x - 0.5) - 1 .. floor(x - 0.5) + 2
        // (geo_uv.glsl pagePos, pageTexels4), all within [x - 2.5, x + 1.5],
        // widened by 0.05 for the shader's float position (ulp 0.004 texel
        // at 43200 texels); minified, the footprint's term as the grid's.
        const double fm = 12.0 * std::max(fx1 - fx0, fy1 - fy0) / cellPx;
        const auto cov = fine->cover(fx0 - 2.55 - fm, fx1 + 1.55 + fm, fy0 - 2.55 - fm, fy1 + 1.55 + fm);
        // All land: every fragment would read coverage 0 and discard.
        if (cov == world::TileWaterIndex::Cover::Land) continue;
        water = cov == world::TileWaterIndex::Cover::Water;
      }
      if (water) {
        // Far: ocean.vert's fade (footprint / longest wavelength >= 0.5)
        // is complete at every vertex, with 1 % for its float arithmetic.
        bool far = view.farFootprintM > 0.0;
        for (std::size_t k = 0; k < 6 && far; ++k) {
          const grid::GridVertex& gv = f.vertices[idx[c + k]];
          const float* e = gv.eyeRelM;
          const double dist = std::sqrt(double(e[0]) * e[0] + double(e[1]) * e[1] + double(e[2]) * e[2]);
          double footprint = dist * view.cellRadians;
          if (view.farAlongView) {
            const glm::dvec3 up = geo::surfaceNormal(gv.latDeg, gv.lonDeg);
            const double sinE = std::abs(glm::dot(glm::dvec3(e[0], e[1], e[2]), up)) / std::max(dist, 1e-9);
            footprint /= cellPx * std::max(sinE, 0.02);
          }
          far = footprint >= 1.01 * view.farFootprintM && dist >= 1.01 * view.farMinDistM;
        }
        // A wake's foam is drawn per fragment: its cells are not far (the
        // cell's first vertex within the reach widened by the cell's size).
        for (std::size_t w = 0; w < view.wakeReach.size() && far; ++w) {
          const float* e = f.vertices[idx[c]].eyeRelM;
          const glm::dvec3 d = glm::dvec3(e[0], e[1], e[2]) - glm::dvec3(view.wakeReach[w]);
          const double r = view.wakeReach[w].w + 2.0 * glm::length(glm::dvec3(e[0], e[1], e[2])) * view.cellRadians;
          far = glm::dot(d, d) > r * r;
        }
        to = far ? &farOpen : &open;
      }
      else if (extent * std::max(pagedTexels, 1.0) <= kSmoothTexels)  // in the texels drawn
        to = &smooth;
    }
    if (!to && !limb && mini && minifiedCell(f, idx.data() + c, texel, view, pxPerTan)) to = &minified;
    if (to)
      to->insert(to->end(), idx.begin() + c, idx.begin() + c + 6);
    else
      std::copy(idx.begin() + c, idx.begin() + c + 6, idx.begin() + sharp), sharp += 6;
  }
  std::copy(minified.begin(), minified.end(), idx.begin() + sharp);
  sharp += minified.size();
  std::copy(smooth.begin(), smooth.end(), idx.begin() + sharp);
  std::copy(open.begin(), open.end(), idx.begin() + sharp + smooth.size());
  std::copy(farOpen.begin(), farOpen.end(), idx.begin() + sharp + smooth.size() + open.size());
  idx.resize(sharp + smooth.size() + open.size() + farOpen.size());  // all-land cells dropped
  return {sharp, smooth.size(), open.size(), farOpen.size(), minified.size()};
}

void OceanRenderer::setGridMode(grid::GridMode mode) { grid_->setMode(mode); }

void OceanRenderer::draw(const camera::Camera& cam, const camera::Lighting& light, bool bare) {
  const auto t0 = std::chrono::steady_clock::now();
  grid_->build(cam, frame_);
  std::vector<std::uint32_t> idx;
  coarseBlocks_ = 0;
  if (middleWavelengthM_ > 0.0 && middleBlock_ > 1 && !bare) {
    // Issue 15 item 4, paper 003's middle band: a vertex may join a coarse
    // block where its cell along the view (ocean.vert's: footprint over the
    // sine of the elevation angle, at least 0.02) is kMiddleMeshFromR of
    // the longest breaking wavelength, 1 % over it for ocean.vert's floats.
    const double cellRadians = 2.0 * std::tan(0.5 * cam.vfovDeg() * 3.14159265358979 / 180.0) / cam.heightPx() *
                               options_.cellPx;
    // And where the water is at least kMiddleMeshMinDepth of that
    // wavelength deep (the relief's shallowest of the 2 x 2 texels
    // ocean.vert's bilinear read blends, repeated in longitude as the
    // texture): no breaking there, and the phases the fragments take from
    // the vertices (the foam texture's, the whitecaps' rest point) are
    // linear across a coarse cell. Over the shoaling beach they are not: the
    // foam texture's crests zigzagged along the fans (beach_breakers_300m).
    const double fromM = 1.01 * kMiddleMeshFromR * middleWavelengthM_;
    const float maxElevM = float(-kMiddleMeshMinDepth * middleWavelengthM_);
    // And where ocean.vert's vFar = smoothstep(0.02, 0.5, footprint /
    // octave wavelength 0) is below kMiddleMeshMaxFar: ocean.frag still
    // evaluates the whitecaps there, so the normal is the fragment's
    // (GEOCEAN_FRAGMENT_NORMAL); further on it fades to the vertices', which a
    // coarse block would soften. The smoothstep inverted, 1 % inside.
    const double farT = 0.5 - std::sin(std::asin(1.0 - 2.0 * kMiddleMeshMaxFar) / 3.0);
    const double farToM = 0.99 * (0.02 + 0.48 * farT) * double(octaveWavelengthM_[0]);
    const world::WorldLayer& relief = world_->elevation();
    const glm::dvec3 eye = cam.eyeEcef();
    constexpr double a2 = geo::kWgs84A * geo::kWgs84A, b2 = geo::kWgs84B * geo::kWgs84B;
    coarseVertex_.resize(frame_.vertices.size());
    for (std::size_t i = 0; i < frame_.vertices.size(); ++i) {
      const grid::GridVertex& v = frame_.vertices[i];
      const glm::dvec3 rel(v.eyeRelM[0], v.eyeRelM[1], v.eyeRelM[2]), p = eye + rel;
      const double dist = glm::length(rel);
      const glm::dvec3 up = glm::normalize(glm::dvec3(p.x / a2, p.y / a2, p.z / b2));
      const double sinE = std::abs(glm::dot(rel, up)) / std::max(dist, 1e-9);
      bool coarse = dist * cellRadians >= fromM * std::max(sinE, 0.02) && dist * cellRadians <= farToM;
      if (coarse && relief.width > 0) {
        const double fx = (v.lonDeg - relief.originLonDeg) / relief.lonStepDeg - 0.5;
        const double fy = (v.latDeg - relief.originLatDeg) / relief.latStepDeg - 0.5;
        const long x0 = long(std::floor(fx)), y0 = long(std::floor(fy)), w = relief.width, h = relief.height;
        for (long dy = 0; dy < 2 && coarse; ++dy)
          for (long dx = 0; dx < 2 && coarse; ++dx) {
            const long x = ((x0 + dx) % w + w) % w, y = std::clamp(y0 + dy, 0L, h - 1);
            coarse = relief.values[std::size_t(y * w + x) * std::size_t(relief.channels)] <= maxElevM;
          }
      }
      coarseVertex_[i] = coarse;
    }
    coarseBlocks_ = grid::coarseIndices(frame_, coarseVertex_, middleBlock_, idx);
  } else {
    idx = grid::compactIndices(frame_);
  }
  stripOrder(idx, std::uint32_t(frame_.cols), std::uint32_t(frame_.rows), stripBucket_, stripStart_, stripIdx_);
  if (pages_) {
    if (completeTiles_) pages_->complete(frame_, options_.cellPx);
    else pages_->request(frame_, options_.cellPx);
  }
  const double cellRadians = 2.0 * std::tan(0.5 * cam.vfovDeg() * 3.14159265358979 / 180.0) / cam.heightPx() *
                             options_.cellPx;  // ocean.vert's uCellRadians (cull.cellRadians below)
  if (elevPages_) {
    if (completeTiles_) elevPages_->complete(frame_, cellRadians);
    else elevPages_->request(frame_, cellRadians);
  }
  // Cells no wave can bring on screen are dropped; open water (coverage 1
  // throughout, WaterIndex) and cells much smaller than a water texel are
  // drawn by variants without the per-pixel coverage lookup, which was half
  // the ocean's fragment cost on llvmpipe. cull.cellRadians is also
  // ocean.vert's uCellRadians: the CPU's far and cull tests use its numbers.
  ScreenCull cull;
  cull.forward = cam.forward(), cull.right = cam.right(), cull.up = cam.up();
  cull.tanY = std::tan(0.5 * cam.vfovDeg() * 3.14159265358979 / 180.0);
  cull.tanX = cull.tanY * cam.widthPx() / cam.heightPx();
  cull.cellRadians = 2.0 * cull.tanY / cam.heightPx() * options_.cellPx;
  cull.maxDisplacementM = maxDisplacementM_;
  cull.waves = waves_.get();
  // The pixel footprint from which no noise octave is drawn per pixel: the
  // longest octave over pixelOctaveEndPx pixels (the far cells, the
  // programs without the octave loop and the deferral below all ask it).
  const double pixelOctaveEndM =
      octaveWavelengthM_.empty() ? 0.0 : double(octaveWavelengthM_[0]) / options_.pixelOctaveEndPx;
  // Noise: no octave is left per pixel (a pixel 1 / cellPx of a cell); the
  // other models: their fade's end.
  if (options_.farVertexShading && !octaveWavelengthM_.empty()) {
    cull.farFootprintM = pixelOctaveEndM;
    cull.farAlongView = options_.model == waves::Model::Noise;
  }
  // The planar reflection is sampled per pixel out to its reach
  // (ocean_shading.glsl's kReflectionFarM): vertex-shaded cells there drew
  // it in 8 px steps.
  const bool reflect = !bare && inputs_.reflectionColor != 0 && inputs_.reflectionCamera;
  if (reflect && cull.farFootprintM > 0.0) cull.farMinDistM = shaders::kReflectionReachM;
  // The same for the sun's shadow map, per pixel out to its reach.
  const bool shadow = !bare && inputs_.shadowDepth != 0 && inputs_.shadowSize > 0;
  if (shadow && cull.farFootprintM > 0.0) cull.farMinDistM = std::max(cull.farMinDistM, inputs_.shadowReachM);
  cull.timeS = light.timeS;
  cull.minified = options_.minifiedCoverage && !sharpMinDefines_.empty();
  // The bodies' foam (wake.glsl): the kMaxWakes nearest the eye of those
  // fast enough to make any (the others would add exactly nothing).
  struct WakeUniform {
    glm::vec4 centre, bow, track;
    double eyeDistance2;
  };
  std::vector<WakeUniform> wakes;
  if (!bare)
    for (const Wake& w : wakes_) {
      if (!(w.halfLengthM > 0.0 && w.halfBeamM > 0.0)) continue;
      const geo::Geodetic at = geo::fromEcef(w.centreEcef);
      const glm::dvec3 up = geo::surfaceNormal(at.latDeg, at.lonDeg);
      const glm::dvec3 v = w.velocityEcef - glm::dot(w.velocityEcef, up) * up;
      const double u = glm::length(v), froude = u / std::sqrt(9.81 * 2.0 * w.halfLengthM);
      if (!(u > kWakeStirredMps[0] || froude > kWakeBreakingFroude[0])) continue;
      const glm::dvec3 rel = w.centreEcef - cam.eyeEcef();
      wakes.push_back({glm::vec4(glm::vec3(rel), float(w.halfLengthM)), glm::vec4(glm::vec3(w.bowEcef), float(w.halfBeamM)),
                       glm::vec4(glm::vec3(v / u), float(u)), glm::dot(rel, rel)});
    }
  if (wakes.size() > std::size_t(kMaxWakes)) {
    std::partial_sort(wakes.begin(), wakes.begin() + kMaxWakes, wakes.end(),
                      [](const WakeUniform& a, const WakeUniform& b) { return a.eyeDistance2 < b.eyeDistance2; });
    wakes.resize(kMaxWakes);
  }
  std::vector<glm::vec4> wakeCentre, wakeBow, wakeTrack;
  for (const WakeUniform& w : wakes) {
    wakeCentre.push_back(w.centre), wakeBow.push_back(w.bow), wakeTrack.push_back(w.track);
    cull.wakeReach.emplace_back(glm::dvec3(w.centre),
                                double(w.centre.w) + 4.0 * kWakeDecayS * double(w.track.w) + double(w.bow.w));
  }
  const CellGroups groups =
      partitionCells(frame_, world_->waterIndex(), options_.cellPx, cull, options_.cullOffscreen,
                     !bare && options_.cheapCoverage && (!pages_ || pagesIndexed_), idx, pagedTexels_,
                     fineWater_.get());
  lastGroups_ = groups;
  gridMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (idx.empty()) {
    if (pages_) pages_->endFrame();
    if (elevPages_) elevPages_->endFrame();
    lastDeferred_ = false;
    return;
  }
  const std::size_t vbytes = frame_.vertices.size() * sizeof(grid::GridVertex);
  if (vbytes > vboBytes_) {  // grow only: memory stays flat over a flight
    vboBytes_ = vbytes;
    glNamedBufferData(vbo_, GLsizeiptr(vboBytes_), nullptr, GL_STREAM_DRAW);
  }
  glNamedBufferSubData(vbo_, 0, GLsizeiptr(vbytes), frame_.vertices.data());
  const std::size_t ibytes = idx.size() * sizeof(std::uint32_t);
  if (ibytes > iboBytes_) {
    iboBytes_ = ibytes;
    glNamedBufferData(ibo_, GLsizeiptr(iboBytes_), nullptr, GL_STREAM_DRAW);
  }
  glNamedBufferSubData(ibo_, 0, GLsizeiptr(ibytes), idx.data());
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(grid::GridVertex));
  glVertexArrayElementBuffer(vao_, ibo_);

  // Wave patch at the ground point under the eye: offsets stay small near
  // the camera, where precision is visible.
  const geo::Geodetic g = geo::fromEcef(cam.eyeEcef());
  const glm::dvec3 origin = geo::toEcef({g.latDeg, g.lonDeg, 0.0});
  // ocean.frag draws the Jacobian's whitecaps only where vFar < 0.75, a
  // cell's footprint under 0.3433 of the longest octave (ocean.vert's
  // smoothstep); no sea point is nearer than the eye's height less the
  // waves' reach, so from higher up the threshold is never read and its
  // calibration (0.7-1 s with Gerstner) is not made: a flight from orbit
  // made it every frame, its nadir moving more than kFoamCalibrationM.
  const bool crestsDrawn = octaveWavelengthM_.empty() ||
                           (g.heightM - maxDisplacementM_) * cull.cellRadians < 0.35 * octaveWavelengthM_[0];
  if (jacobianFoam() && !bare && crestsDrawn && glm::length(origin - foamCalibratedAt_) > kFoamCalibrationM)
    calibrateJacobianFoam(g.latDeg, g.lonDeg);
  waves_->gpuPatch(origin, light.timeS, patch_);
  const int modelOctaves = int(patch_.octaves.size());
  if (noiseDetail_) {
    noiseDetail_->gpuPatch(origin, light.timeS, pastPatch_);
    for (std::size_t i = pastPatch_.octaves.size() - std::size_t(noiseDetailOctaves_); i < pastPatch_.octaves.size(); ++i) {
      waves::kf::WvOctave o = pastPatch_.octaves[i];
      o.row0.w = float(o.row0.w * noiseDetailScale_);
      patch_.octaves.push_back(o);
    }
  }
  const int waveCount = int(patch_.waves.size());
  const auto foamT = foamTimes(light.timeS);
  if (jacobianFoam() && !bare) {
    // The past times' wave data after the present's (foam.glsl).
    const std::size_t texels = patch_.fftTexels.size();
    for (int k = 1; k < kFoamTimes; ++k) {
      waves_->gpuPatch(origin, foamT[std::size_t(k)], pastPatch_);
      patch_.waves.insert(patch_.waves.end(), pastPatch_.waves.begin(), pastPatch_.waves.end());
      for (auto pl : pastPatch_.fftPlanes) {
        pl.cell.z += int(std::size_t(k) * texels / waves::FftOcean::kTexelParts);
        patch_.fftPlanes.push_back(pl);
      }
      patch_.fftTexels.insert(patch_.fftTexels.end(), pastPatch_.fftTexels.begin(), pastPatch_.fftTexels.end());
    }
  }
  upload(ssbo_[0], patch_.octaves);
  static_assert(sizeof(waves::kf::WvOctave) == 6 * sizeof(glm::vec4), "noise_bands.glsl reads 6 texels an octave");
  glTextureBuffer(octaveTexelTex_, GL_RGBA32F, ssbo_[0]);  // its storage was just re-made
  upload(ssbo_[1], patch_.waves);
  upload(ssbo_[2], std::vector<waves::kf::WvFrame>{patch_.frame});
  for (int i = 0; i < 3; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, ssbo_[i]);
  // Bindings 3 and 4 (FFT, or the coast field) are restored after the draw: hosts may use them.
  GLint hostSsbo[2] = {0, 0};
  GLint64 hostStart[2] = {0, 0}, hostSize[2] = {0, 0};
  const bool fft = options_.model == waves::Model::Fft;
  const bool coast = waves_->coastField() != nullptr;
  if (fft || coast) {
    if (fft) {
      upload(ssbo_[3], patch_.fftPlanes);
      upload(ssbo_[4], patch_.fftTexels);
    } else {
      upload(ssbo_[3], std::vector<waves::kf::WvCoast>{patch_.coast});
    }
    for (int i = 0; i < 2; ++i) {
      glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(3 + i), &hostSsbo[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, GLuint(3 + i), &hostStart[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(3 + i), &hostSize[i]);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(3 + i), ssbo_[3 + i]);
    }
  }


  const glm::vec4 elevationGeo = world_->elevation().geo(), waterGeo = world_->water().geo();
  std::vector<float> detailF;  // wv_detailSlope's wvDetail at this patch and time
  for (const glm::dvec4& v : waves::detailPatch(detail_, origin, light.timeS))
    for (int c = 0; c < 4; ++c) detailF.push_back(float(v[c]));
  const auto setUniforms = [&](const gl::GlProgram& p) {
    glUniformMatrix4fv(p.uniform("uViewProj"), 1, GL_FALSE, &cam.gpu().viewProj[0][0]);
    const glm::vec3 eyeMinusO(cam.eyeEcef() - origin);
    glUniform3fv(p.uniform("uEyeMinusOrigin"), 1, &eyeMinusO[0]);
    glUniform1i(p.uniform("uOctaveCount"), modelOctaves);
    glUniform1i(p.uniform("uFragOctaves"), int(patch_.octaves.size()));
    glUniform1f(p.uniform("uPixelOctaveEndPx"), float(options_.pixelOctaveEndPx));
    if (!octaveHeightVar_.empty())
      glUniform1fv(p.uniform("uOctaveHeightVar"), GLsizei(std::min<std::size_t>(octaveHeightVar_.size(), 16)),
                   octaveHeightVar_.data());
    glUniform1f(p.uniform("uCrestM"), float(crestM_));
    float crestVar = 0.0f;
    for (float v : octaveHeightVar_) crestVar += v;
    glUniform1f(p.uniform("uCrestVar"), crestVar);
    glUniform1i(p.uniform("uWaveCount"), waveCount);
    glUniform1fv(p.uniform("uOctaveWavelengthM"), GLsizei(std::min<std::size_t>(octaveWavelengthM_.size(), 16)),
                 octaveWavelengthM_.data());
    // A cell's footprint on the ground is this x its distance.
    glUniform1f(p.uniform("uCellRadians"), float(cull.cellRadians));
    glUniform1fv(p.uniform("uMssAbove"), 17, mssAbove_.data());
    glUniform1fv(p.uniform("uFoamHeightM"), 17, foamHeightM_.data());
    glUniform1f(p.uniform("uFoamSoftM"), float(foamSoftM_));
    glUniform1f(p.uniform("uWhitecapCover"), float(whitecap_));
    glUniform2f(p.uniform("uWind"), float(windMps_ / 1.026), float(windFromRad_));  // U10, from (radians)
    glUniform1i(p.uniform("uDetailCount"), GLint(detailF.size() / 8));
    glUniform1f(p.uniform("uHsM"), float(waves_->spectrumHsM()));
    // noise-paper: the patch origin as wv_paperNoise takes it (3 vec4, contiguous).
    if (options_.model == waves::Model::NoisePaper) glUniform4fv(p.uniform("uPaper"), 3, &patch_.paper.horiz.x);
    glUniform1i(p.uniform("uSubsurface"), options_.subsurface ? 1 : 0);
    if (!detailF.empty()) glUniform4fv(p.uniform("wvDetail"), GLsizei(detailF.size() / 4), detailF.data());
    if (jacobianFoam()) {
      float ages[kFoamTimes];
      for (int k = 0; k < kFoamTimes; ++k) ages[k] = float(light.timeS - foamT[std::size_t(k)]);
      glUniform1fv(p.uniform("uFoamAgeS"), kFoamTimes, ages);
      glUniform1f(p.uniform("uFoamJacobian"), float(foamJacobian_));
      glUniform1f(p.uniform("uFoamJacobianSoft"), float(foamJacobianSoft_));
      glUniform1f(p.uniform("uFoamDecayS"), float(kFoamDecayS));
    }
    glUniform4fv(p.uniform("uElevationGeo"), 1, &elevationGeo[0]);
    glUniform4fv(p.uniform("uWaterGeo"), 1, &waterGeo[0]);
    const glm::vec3 sun(light.sunEcef);
    glUniform3fv(p.uniform("uSunDir"), 1, &sun[0]);
    glUniform1f(p.uniform("uEyeRadiusM"), float(glm::length(cam.eyeEcef())));
    glUniform1f(p.uniform("uEyeAltM"), float(g.heightM));
    glUniform1f(p.uniform("uRefLonDeg"), float(g.lonDeg));
    glUniform1f(p.uniform("uRefLatDeg"), float(g.latDeg));
    if (elevPages_) elevPages_->bind(p, float(g.latDeg), float(g.lonDeg));
    glUniform1f(p.uniform("uTimeS"), float(std::fmod(light.timeS, 3600.0)));
    glUniform1i(p.uniform("uWriteData"), writeDepthData_ ? 2 : writeData_ ? 1 : 0);
    glUniform1i(p.uniform("uCoastBandMode"), int(coastBands_));  // issue 15 item 4 (coast_bands.glsl)
    glUniform1i(p.uniform("uFragmentNormal"), fragmentNormal_ ? 1 : 0);  // issue 15 item 4 (ocean.frag)
    glUniform1i(p.uniform("uWakeCount"), GLint(wakes.size()));
    if (!wakes.empty()) {
      glUniform4fv(p.uniform("uWakeCentre"), GLsizei(wakes.size()), &wakeCentre[0][0]);
      glUniform4fv(p.uniform("uWakeBow"), GLsizei(wakes.size()), &wakeBow[0][0]);
      glUniform4fv(p.uniform("uWakeTrack"), GLsizei(wakes.size()), &wakeTrack[0][0]);
      glUniform1f(p.uniform("uWakeDecayS"), float(kWakeDecayS));
      glUniform4f(p.uniform("uWakeEdges"), float(kWakeBreakingFroude[0]), float(kWakeBreakingFroude[1]),
                  float(kWakeStirredMps[0]), float(kWakeStirredMps[1]));
    }
    glUniform1i(p.uniform("uSunPhong"), inputs_.sunPhong ? 1 : 0);
    glUniform1f(p.uniform("uPhongExponent"), float(inputs_.phongExponent));
    glUniform1i(p.uniform("uShadow"), shadow ? (inputs_.shadowPaper ? 2 : 1) : 0);
    if (shadow) {
      // Eye-relative positions to the map's [0, 1]^3: the host's matrix
      // after the move from its origin to this eye (double, then float).
      glm::dmat4 toUv(0.5);
      toUv[2][2] = 1.0, toUv[3] = glm::dvec4(0.5, 0.5, 0.0, 1.0);
      const glm::dmat4 m = toUv * inputs_.shadowMatrix *
                           glm::translate(glm::dmat4(1.0), cam.eyeEcef() - inputs_.shadowOriginEcef);
      const glm::mat4 mf(m);
      glUniformMatrix4fv(p.uniform("uShadowMatrix"), 1, GL_FALSE, &mf[0][0]);
      // 0.3 m in the map's depth units (its z row is depth per metre along the sun).
      const double perM = glm::length(glm::dvec3(inputs_.shadowMatrix[0][2], inputs_.shadowMatrix[1][2],
                                                 inputs_.shadowMatrix[2][2]));
      glUniform1f(p.uniform("uShadowBias"), float(0.3 * perM));
    }
    glUniform1i(p.uniform("uRefraction"), inputs_.refraction ? 1 : 0);
    glUniform1i(p.uniform("uReflection"), reflect ? 1 : 0);
    if (reflect) {
      const camera::Camera& m = *inputs_.reflectionCamera;
      glUniformMatrix4fv(p.uniform("uReflViewProj"), 1, GL_FALSE, &m.gpu().viewProj[0][0]);
      // The mirror plane from the mirrored eye alone: the host mirrors in the
      // tangent plane at the nadir of the eye it drew the map for, so that
      // eye's image lies on the plane's normal line, as far under it as the
      // eye was above: its geodetic height is minus the plane's distance.
      // A map reused from an earlier frame (FrameSettings::reflectionEvery)
      // keeps its plane while this eye moves.
      const glm::dvec3 offset = cam.eyeEcef() - m.eyeEcef();
      const geo::Geodetic mg = geo::fromEcef(m.eyeEcef());
      const glm::dvec3 n0 = geo::surfaceNormal(mg.latDeg, mg.lonDeg);
      const glm::vec3 offsetF(offset), n0F(n0);
      glUniform3fv(p.uniform("uReflEyeOffset"), 1, &offsetF[0]);
      glUniform3fv(p.uniform("uNadirUp"), 1, &n0F[0]);
      const double heightM = glm::dot(offset, n0) + mg.heightM;  // this eye over the mirror plane
      glUniform1f(p.uniform("uEyeHeightM"), float(heightM));
      // The eye the map was drawn for: the mirrored one reflected back.
      const glm::dvec3 moved = offset - (heightM - mg.heightM) * n0;
      glUniform1f(p.uniform("uReflEyeMovedM"), float(glm::length(moved)));
    }
    if (fft) {
      // The coarse cascade's texel: its waves carry the height; the fine one
      // fades with it (fading by the fine texel flattened the sea 40 m away).
      float texelM = 0.0f;
      for (const auto& pl : patch_.fftPlanes) texelM = std::max(texelM, pl.axis.w);
      glUniform1i(p.uniform("uFftCascades"), patch_.fftCascades);
      glUniform1f(p.uniform("uFftTexelM"), texelM);
    }
  };

  glEnable(GL_BLEND);
  glBlendFunci(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glBlendFunci(1, GL_ONE, GL_ZERO);
  // The sea wins over coastal terrain at the same depth: pull it towards
  // the eye by a few hundred float-depth units (reversed Z: positive = nearer).
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0.0f, 256.0f);
  glBindVertexArray(vao_);
  glBindTextureUnit(1, elevationTex_);
  glBindTextureUnit(2, waterTex_);
  glBindTextureUnit(8, reliefFloorTex_);
  if (reflect) glBindTextureUnit(3, inputs_.reflectionColor);
  // Unit 14: the sun's depth map through the ocean's own sampler (reversed
  // depth: lit where the point is at least as near the sun as the map).
  GLint hostSampler14 = 0;
  if (shadow) {
    if (!shadowSampler_) {
      glCreateSamplers(1, &shadowSampler_);
      glSamplerParameteri(shadowSampler_, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
      glSamplerParameteri(shadowSampler_, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
      glSamplerParameteri(shadowSampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glSamplerParameteri(shadowSampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glSamplerParameteri(shadowSampler_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glSamplerParameteri(shadowSampler_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE14);
    glGetIntegerv(GL_SAMPLER_BINDING, &hostSampler14);
    glActiveTexture(GLenum(active));
    glBindTextureUnit(14, inputs_.shadowDepth);
    glBindSampler(14, shadowSampler_);
  }
  // Units 12, 13 (the terrain's imagery layers use 8-11): the host's buffer
  // textures there, if any, are put back after the draws.
  GLint hostActive = 0, hostBufferTex[2] = {0, 0};
  glGetIntegerv(GL_ACTIVE_TEXTURE, &hostActive);
  for (int u = 0; u < 2; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE12 + u));
    glGetIntegerv(GL_TEXTURE_BINDING_BUFFER, &hostBufferTex[u]);
  }
  glActiveTexture(GLenum(hostActive));
  glBindTextureUnit(12, octaveTexelTex_);
  glBindTextureUnit(13, octaveBandTex_);
  // Noise: no pixel of the view under 1 / pixelOctaveEndPx of the longest
  // octave, so no fragment visits one (ocean.frag's f = 0 for all): its
  // programs without the octave loop (llvmpipe ran its body once, masked,
  // for ~40 ms of a frame at 42 km; docs/PERFORMANCE.md). The bound: a pixel's back-
  // projection onto a plane at distance h, of normal n (camera axes, away
  // from the eye), has area h^2 / (f^2 (n.u)^3) for the pixel's ray u =
  // (x / f, y / f, 1), f the focal length in pixels; n.u is at most K =
  // n_z + tanX |n_x| + tanY |n_y| over the view, and the fragments'
  // footprint (the pixel's longer axis) is at least the square root of
  // that area. The sea is the ellipsoid below its tangent plane at the
  // nadir (farther, and seen more obliquely: a larger area), h the eye's
  // height less the waves' bound; 5 % for the cells' chords and the
  // derivatives' finite differences (OceanOptions::noPixelOctaveMargin).
  bool noPixelOctaves = false;
  if (options_.model == waves::Model::Noise && !octaveWavelengthM_.empty() && !bare) {
    const glm::dvec3 down = -geo::surfaceNormal(g.latDeg, g.lonDeg);
    const double k = glm::dot(down, cull.forward) + cull.tanX * std::abs(glm::dot(down, cull.right)) +
                     cull.tanY * std::abs(glm::dot(down, cull.up));
    const double h = g.heightM - maxDisplacementM_;
    noPixelOctaves = k > 0.0 && h > 0.0 &&
                     h * (cull.cellRadians / options_.cellPx) / std::pow(k, 1.5) >=
                                                options_.noPixelOctaveMargin * pixelOctaveEndM;
  }
  lastNoPixelOctaves_ = noPixelOctaves;
  // No reflection variant made for a bare draw.
  const PixelPrograms& pixel =
      pixelPrograms(!wakes.empty(), reflect || bare, inputs_.refraction, inputs_.sunPhong, noPixelOctaves);
  std::size_t first = 0;
  const auto drawGroup = [&](const gl::GlProgram& prog, std::size_t count, bool coverage) {
    if (count > 0) {
      prog.use();
      setUniforms(prog);
      if (pages_ && coverage) pages_->bind(prog);
      glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
    }
    first += count;
  };
  GLint hostFbo = 0, viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &hostFbo);
  glGetIntegerv(GL_VIEWPORT, viewport);
  // Deferred has a fixed cost a frame (G-buffer clear and writes, the tile
  // read-back; 10-15 ms at 1280 x 720 on llvmpipe with 7 targets and two
  // depth copies, less since) and saved 5-25 % of the
  // ocean where its per-pixel shading is dear: where some noise octave is
  // drawn per pixel (the nadir's pixel under 1 / pixelOctaveEndPx of the
  // longest octave).
  // Above that (~40 km here) the sea's pixels are roughness alone
  // (docs/PERFORMANCE.md).
  const bool octavesPerPixel =
      !octaveWavelengthM_.empty() && g.heightM * cull.cellRadians / options_.cellPx < pixelOctaveEndM;
  // Reduced rate (OceanOptions::reducedRateDeferBelowM) also pays without
  // octaves per pixel where the sea fills much of the view.
  const bool reducedAbove = options_.reducedRate && g.heightM < options_.reducedRateDeferBelowM;
  const bool deferred = !bare && (octavesPerPixel || reducedAbove) && pixel.shade.id() != 0 &&
                        groups.sharp + groups.smooth + groups.open > 0 && gBufferFor(hostFbo, viewport);
  lastDeferred_ = deferred;
  if (deferred) {
    // The grid writes the G-buffer against the host's own depth (attached
    // to the G-buffer's framebuffer by gBufferFor for this pass: no copies),
    // one pass over the tiles with sea shades. Targets and tiles are in the
    // framebuffer's pixels; the viewport stays the host's.
    const GLint w = viewport[2], h = viewport[3];
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(gFbo_, GL_COLOR, 0, zero);  // alpha 0: no sea (the others are read only under alpha > 0)
    const std::uint8_t noTile = 0;
    glClearTexImage(gTiles_, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &noTile);
    // Image unit 7: the host's binding there is put back after.
    GLint hostImage[5] = {0, 0, 0, 0, 0};
    const GLenum imageQuery[5] = {GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED,
                                  GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_FORMAT};
    for (int i = 0; i < 5; ++i) glGetIntegeri_v(imageQuery[i], 7, &hostImage[i]);
    GLint hostAccess = GL_READ_ONLY;
    glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, 7, &hostAccess);
    glBindImageTexture(7, gTiles_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gFbo_);
    glDisable(GL_BLEND);
    drawGroup(pixel.gSharp, groups.sharp - groups.minified, true);
    drawGroup(pixel.gSharpMin, groups.minified, true);
    drawGroup(pixel.gSmooth, groups.smooth, true);
    drawGroup(pixel.gOpen, groups.open, false);
    glBindImageTexture(7, GLuint(hostImage[0]), hostImage[1], GLboolean(hostImage[2]), hostImage[3], GLenum(hostAccess),
                       hostImage[4] ? GLenum(hostImage[4]) : GL_R8UI);
    // The tiles with sea, as rectangles (runs along each row of tiles).
    const int right = viewport[0] + w, top = viewport[1] + h;
    const std::size_t seaTiles = markedRects(gTiles_, (right + kGTilePx - 1) / kGTilePx, (top + kGTilePx - 1) / kGTilePx,
                                             kGTilePx, kGTilePx, viewport, gTileMask_, gRects_);
    glNamedFramebufferTexture(gFbo_, GL_DEPTH_ATTACHMENT, 0, 0);  // the host's depth is not kept (it may go)
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(hostFbo));
    // Units 15-18: the host's textures there are put back after.
    constexpr int kUnits = kGTargets + 1;
    GLint hostTex[kUnits] = {};
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int i = 0; i < kUnits; ++i) {
      glActiveTexture(GLenum(GL_TEXTURE15 + i));
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &hostTex[i]);
    }
    glActiveTexture(GLenum(active));
    for (int i = 0; i < kGTargets; ++i) glBindTextureUnit(GLuint(15 + i), gTex_[i]);
    const GLboolean depthTest = glIsEnabled(GL_DEPTH_TEST);
    glDisable(GL_DEPTH_TEST);  // the depth is in already
    const auto drawRects = [&](const std::vector<float>& rects) {
      const std::size_t rectBytes = rects.size() * sizeof(float);
      if (rectBytes > gVboBytes_) {
        gVboBytes_ = rectBytes;
        glNamedBufferData(gVbo_, GLsizeiptr(gVboBytes_), nullptr, GL_STREAM_DRAW);
      }
      if (rectBytes > 0) {
        glNamedBufferSubData(gVbo_, 0, GLsizeiptr(rectBytes), rects.data());
        glBindVertexArray(gVao_);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(rects.size() / 2));
        glBindVertexArray(vao_);
      }
    };
    const bool reduced = options_.reducedRate && pixel.coarse.id() != 0 && resolve_.id() != 0 && gCoarseFbo_ != 0;
    if (reduced) {
      // The even pixels shaded exactly into the half-size target (no blend).
      const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearNamedFramebufferfv(gCoarseFbo_, GL_COLOR, 0, none);  // alpha 0: not shaded, never interpolated
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gCoarseFbo_);
      glViewport(0, 0, gCoarseW_, gCoarseH_);
      pixel.coarse.use();
      setUniforms(pixel.coarse);
      glUniform2i(pixel.coarse.uniform("uGOrigin"), 0, 0);
      glUniform2f(pixel.coarse.uniform("uGSize"), float(2 * gCoarseW_), float(2 * gCoarseH_));
      drawRects(gRects_);
      glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(hostFbo));
      glEnable(GL_BLEND);
      // The resolve: the pixels between them interpolated, or their 4 x 2
      // groups marked for full rate (image unit 7, the host's put back).
      glBindTextureUnit(18, gCoarse_);
      const std::uint8_t noBlock = 0;
      glClearTexImage(gFull_, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &noBlock);
      glBindImageTexture(7, gFull_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
      resolve_.use();
      setUniforms(resolve_);
      glUniform2i(resolve_.uniform("uGOrigin"), viewport[0], viewport[1]);
      glUniform2f(resolve_.uniform("uGSize"), float(w), float(h));
      glUniform1f(resolve_.uniform("uRateTolerance"), float(options_.reducedRateTolerance));
      glUniform2i(resolve_.uniform("uFullRateBlock"), kFullRateW, kFullRateH);
      drawRects(gRects_);
      glBindImageTexture(7, GLuint(hostImage[0]), hostImage[1], GLboolean(hostImage[2]), hostImage[3],
                         GLenum(hostAccess), hostImage[4] ? GLenum(hostImage[4]) : GL_R8UI);
      // The marked groups as runs along each row, for the full-rate pass.
      const std::size_t marked = markedRects(gFull_, (gWidth_ + kFullRateW - 1) / kFullRateW,
                                             (gHeight_ + kFullRateH - 1) / kFullRateH, kFullRateW, kFullRateH,
                                             viewport, gFullMask_, gFullRects_);
      const double blocksPerTile = double(kGTilePx / kFullRateW) * double(kGTilePx / kFullRateH);
      lastFullRateShare_ = seaTiles > 0 ? double(marked) / (double(seaTiles) * blocksPerTile) : 0.0;
    } else {
      glEnable(GL_BLEND);
      lastFullRateShare_ = 1.0;
    }
    // Every tile with sea, or with reduced rate the groups marked for full rate.
    pixel.shade.use();
    setUniforms(pixel.shade);
    glUniform2i(pixel.shade.uniform("uGOrigin"), viewport[0], viewport[1]);
    glUniform2f(pixel.shade.uniform("uGSize"), float(w), float(h));
    drawRects(reduced ? gFullRects_ : gRects_);
    if (depthTest) glEnable(GL_DEPTH_TEST);
    for (int i = 0; i < kUnits; ++i) {
      glActiveTexture(GLenum(GL_TEXTURE15 + i));
      glBindTexture(GL_TEXTURE_2D, GLuint(hostTex[i]));
    }
    glActiveTexture(GLenum(active));
  } else {
    drawGroup(bare ? bare_ : pixel.sharp, groups.sharp - groups.minified, !bare);
    drawGroup(bare ? bare_ : pixel.sharpMin, groups.minified, !bare);
    drawGroup(pixel.smooth, groups.smooth, true);
    drawGroup(pixel.open, groups.open, false);
  }
  drawGroup(farShaded_, groups.farOpen, false);
  // Issue 15 item 4 hook: the near band's breaking spray (Spray.h), over the sea.
  if (spray_ && sprayOn_ && !bare)
    spray_->draw(cam, origin, g.latDeg, g.lonDeg, light.timeS, waveCount, elevationGeo, light.sunEcef);
  glBindVertexArray(0);
  for (int u = 0; u < 2; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE12 + u));
    glBindTexture(GL_TEXTURE_BUFFER, GLuint(hostBufferTex[u]));
  }
  glActiveTexture(GLenum(hostActive));
  if (shadow) glBindSampler(14, GLuint(hostSampler14));
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_BLEND);
  if (pages_) pages_->endFrame();  // finished loads go up after the draws
  if (elevPages_) elevPages_->endFrame();
  if (fft || coast)
    for (int i = 0; i < 2; ++i) {
      if (hostSsbo[i] != 0 && hostSize[i] > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, GLuint(3 + i), GLuint(hostSsbo[i]), GLintptr(hostStart[i]),
                          GLsizeiptr(hostSize[i]));
      else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(3 + i), GLuint(hostSsbo[i]));
    }
}

const OceanRenderer::PixelPrograms& OceanRenderer::pixelPrograms(bool wakes, bool reflection, bool refraction,
                                                                 bool sunPhong, bool noPixelOctaves) {
  PixelPrograms& v = pixel_[(wakes ? 1 : 0) | (reflection ? 0 : 2) | (refraction ? 0 : 4) | (sunPhong ? 8 : 0) |
                            (noPixelOctaves ? 16 : 0)];
  if (v.sharp.id() == 0) {
    const auto optics = [&](std::vector<std::string>& d) {
      if (wakes) d.push_back("GEOCEAN_WAKES 1");
      if (!reflection) d.push_back("GEOCEAN_NO_REFLECTION 1");
      d.push_back("GEOCEAN_OPTICS_FIXED 1");
      if (!refraction) d.push_back("GEOCEAN_NO_REFRACTION 1");
      if (sunPhong) d.push_back("GEOCEAN_SUN_PHONG 1");
      if (!options_.subsurface) d.push_back("GEOCEAN_NO_SUBSURFACE 1");
      if (noPixelOctaves) d.push_back("GEOCEAN_NO_PIXEL_OCTAVES 1");
    };
    const auto make = [&](std::vector<std::string> d) {
      optics(d);
      return gl::GlProgram::graphics("ocean.vert", "ocean.frag", d);
    };
    v.sharp = make(sharpDefines_);
    if (!sharpMinDefines_.empty()) v.sharpMin = make(sharpMinDefines_);
    v.smooth = make(smoothDefines_);
    v.open = make(openDefines_);
    // Deferred: octaves per pixel, or reduced rate (OceanOptions::reducedRateDeferBelowM).
    if (options_.deferred && options_.model == waves::Model::Noise && (!noPixelOctaves || options_.reducedRate)) {
      const auto gMake = [&](std::vector<std::string> d) {
        d.push_back("GEOCEAN_GBUFFER 1");
        return gl::GlProgram::graphics("ocean.vert", "ocean.frag", d);
      };
      v.gSharp = gMake(sharpDefines_);
      if (!sharpMinDefines_.empty()) v.gSharpMin = gMake(sharpMinDefines_);
      v.gSmooth = gMake(smoothDefines_);
      v.gOpen = gMake(openDefines_);
      auto d = openDefines_;
      d.push_back("GEOCEAN_DEFERRED 1");
      optics(d);
      v.shade = gl::GlProgram::graphics("ocean_deferred.vert", "ocean.frag", d);
      if (options_.reducedRate) {
        d.push_back("GEOCEAN_COARSE 1");
        v.coarse = gl::GlProgram::graphics("ocean_deferred.vert", "ocean.frag", d);
        if (resolve_.id() == 0) resolve_ = gl::GlProgram::graphics("ocean_deferred.vert", "ocean_resolve.frag", {});
      }
    }
  }
  return v;
}

void OceanRenderer::releaseGBuffer() {
  if (gFbo_) glDeleteFramebuffers(1, &gFbo_);
  glDeleteTextures(kGTargets, gTex_);
  glDeleteTextures(1, &gTiles_);
  if (gCoarseFbo_) glDeleteFramebuffers(1, &gCoarseFbo_);
  glDeleteTextures(1, &gCoarse_);
  glDeleteTextures(1, &gFull_);
  gCoarseFbo_ = gCoarse_ = gFull_ = 0;
}

bool OceanRenderer::gBufferFor(GLint hostFbo, const GLint* vp) {
  if (hostFbo == 0 || vp[2] <= 0 || vp[3] <= 0 || glIsEnabled(GL_SCISSOR_TEST)) return false;
  GLboolean depthWrites = GL_FALSE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthWrites);
  if (!depthWrites) return false;
  const GLuint fbo = GLuint(hostFbo);
  GLint type = GL_NONE, name = 0, format = 0, samples = 0, hostLevel = 0;
  glGetNamedFramebufferAttachmentParameteriv(fbo, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
  if (type != GL_RENDERBUFFER && type != GL_TEXTURE) return false;
  glGetNamedFramebufferAttachmentParameteriv(fbo, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
  if (type == GL_RENDERBUFFER) {
    glGetNamedRenderbufferParameteriv(GLuint(name), GL_RENDERBUFFER_INTERNAL_FORMAT, &format);
    glGetNamedRenderbufferParameteriv(GLuint(name), GL_RENDERBUFFER_SAMPLES, &samples);
  } else {
    GLint level = 0, layered = GL_FALSE;
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &level);
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_LAYERED, &layered);
    if (layered) return false;
    GLint target = GL_NONE;
    glGetTextureParameteriv(GLuint(name), GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D) return false;
    glGetTextureLevelParameteriv(GLuint(name), level, GL_TEXTURE_INTERNAL_FORMAT, &format);
    glGetTextureLevelParameteriv(GLuint(name), level, GL_TEXTURE_SAMPLES, &samples);
    hostLevel = level;
  }
  if (format != GL_DEPTH_COMPONENT32F || samples > 1) return false;
  // The targets cover the framebuffer's pixels up to the viewport's far corner.
  const int width = vp[0] + vp[2], height = vp[1] + vp[3];
  const auto attachHostDepth = [&]() {
    if (type == GL_RENDERBUFFER)
      glNamedFramebufferRenderbuffer(gFbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, GLuint(name));
    else
      glNamedFramebufferTexture(gFbo_, GL_DEPTH_ATTACHMENT, GLuint(name), hostLevel);
    if (glCheckNamedFramebufferStatus(gFbo_, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return true;
    glNamedFramebufferTexture(gFbo_, GL_DEPTH_ATTACHMENT, 0, 0);
    return false;
  };
  if (gFbo_ && gWidth_ == width && gHeight_ == height) return attachHostDepth();
  releaseGBuffer();
  if (!gVao_) {
    glCreateVertexArrays(1, &gVao_);
    glCreateBuffers(1, &gVbo_);
    glEnableVertexArrayAttrib(gVao_, 0);
    glVertexArrayAttribFormat(gVao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(gVao_, 0, 0);
    glVertexArrayVertexBuffer(gVao_, 0, gVbo_, 0, 2 * sizeof(float));
  }
  glCreateTextures(GL_TEXTURE_2D, 1, &gTiles_);
  glTextureStorage2D(gTiles_, 1, GL_R8UI, (width + kGTilePx - 1) / kGTilePx, (height + kGTilePx - 1) / kGTilePx);
  glCreateFramebuffers(1, &gFbo_);
  glCreateTextures(GL_TEXTURE_2D, kGTargets, gTex_);
  GLenum bufs[kGTargets];
  for (int i = 0; i < kGTargets; ++i) {
    glTextureStorage2D(gTex_[i], 1, GL_RGBA32F, width, height);
    glNamedFramebufferTexture(gFbo_, GLenum(GL_COLOR_ATTACHMENT0 + i), gTex_[i], 0);
    bufs[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
  }
  glNamedFramebufferDrawBuffers(gFbo_, kGTargets, bufs);
  if (options_.reducedRate) {
    gCoarseW_ = (width + 1) / 2 + 1, gCoarseH_ = (height + 1) / 2 + 1;
    glCreateTextures(GL_TEXTURE_2D, 1, &gCoarse_);
    glTextureStorage2D(gCoarse_, 1, GL_RGBA32F, gCoarseW_, gCoarseH_);  // float: the even pixels exact
    glCreateFramebuffers(1, &gCoarseFbo_);
    glNamedFramebufferTexture(gCoarseFbo_, GL_COLOR_ATTACHMENT0, gCoarse_, 0);
    glCreateTextures(GL_TEXTURE_2D, 1, &gFull_);
    glTextureStorage2D(gFull_, 1, GL_R8UI, (width + kFullRateW - 1) / kFullRateW,
                       (height + kFullRateH - 1) / kFullRateH);
  }
  gWidth_ = width, gHeight_ = height;
  if (attachHostDepth()) return true;
  glDeleteFramebuffers(1, &gFbo_);
  gFbo_ = 0, gWidth_ = gHeight_ = 0;
  return false;
}

bool OceanRenderer::swapCoast(std::shared_ptr<const waves::WaveField> w) {
  if (!w || !w->coastField() || !waves_->coastField() || w->model() != waves_->model()) return false;
  const waves::SeaState &a = w->seaState(), &b = waves_->seaState();
  if (a.windSpeedMps != b.windSpeedMps || a.windFromDeg != b.windFromDeg || a.fetchM != b.fetchM ||
      a.seed != b.seed || a.anchorLatDeg != b.anchorLatDeg || a.anchorLonDeg != b.anchorLonDeg ||
      a.referenceDepthM != b.referenceDepthM || a.gerstnerComponents != b.gerstnerComponents ||
      w->coastField()->components() != waves_->coastField()->components())
    return false;
  const std::vector<glm::vec4> texels = w->coastField()->gpuTexels();
  glNamedBufferData(ssbo_[4], GLsizeiptr(texels.size() * sizeof(glm::vec4)), texels.data(), GL_STATIC_DRAW);
  waves_ = std::move(w);
  options_.coast = waves_->coastFieldShared();
  return true;
}

bool OceanRenderer::coversOpaquely(double lat0, double lat1, double lon0, double lon1, double footprintM) const {
  if (pages_ && !pagesIndexed_) return false;  // a regional mask: the water index is the layers' below
  return ocean_render::coversOpaquely(*world_, options_.cellPx, lat0, lat1, lon0, lon1, footprintM, pages_ != nullptr);
}

}  // namespace geocean::ocean_render
