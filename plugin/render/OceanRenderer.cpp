#include "plugin/render/OceanRenderer.h"

#include "globe/camera/Camera.h"
#include "globe/raster/World.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <cmath>
#include <stdexcept>

namespace geocean::ocean_render {

std::shared_ptr<const ocean::LandSea> defaultLandSea() {
  const auto files = raster::defaultWorld();
  return std::make_shared<ocean::LandSea>(raster::Raster::open(files.mask), raster::Raster::open(files.elevation));
}

OceanRenderer::OceanRenderer(std::shared_ptr<const render::WorldTextures> world,
                             std::shared_ptr<const ocean::LandSea> landSea, OceanOptions options)
    : world_(std::move(world)), options_(options) {
  std::string err;
  waves_ = waves::WaveField::create(options_.model, options_.sea, err);
  if (!waves_) throw std::invalid_argument("sea state: " + err);
  if (options_.model == waves::Model::NoisePaper)
    throw std::invalid_argument("--waves noise-paper has no GPU form; render with noise, gerstner or fft");
  grid::GridOptions go;
  go.cellPx = options_.cellPx;
  go.maxDisplacementM = waves_->maxDisplacementM();
  // Cells are skipped only where the drawn shoreline cannot reach (the
  // fragment shader cuts the exact coastline); nearest-cell classes would
  // drop sea that the smooth shoreline shows as water.
  grid::SurfaceClassifier classifier;
  if (landSea)
    classifier = [ls = landSea](const double* lat, const double* lon, std::size_t n, ocean::Surface* out) {
      ls->classifyNearWaterBatch(lat, lon, n, out);
    };
  grid_ = std::make_unique<grid::ScreenGrid>(go, classifier);
  std::vector<std::string> model = {options_.model == waves::Model::Gerstner ? "WV_MODEL 1"
                                    : options_.model == waves::Model::Fft    ? "WV_MODEL 2"
                                                                             : "WV_MODEL 0"};
  if (options_.model == waves::Model::Fft) model.push_back("WV_FFT 1");
  program_ = render::GlProgram::graphics("ocean.vert", "ocean.frag", model);
  {
    auto open = model;
    open.push_back("GEOCEAN_OPEN_WATER 1");
    openWater_ = render::GlProgram::graphics("ocean.vert", "ocean.frag", open);
  }
  model.push_back("GEOCEAN_BARE 1");
  bare_ = render::GlProgram::graphics("ocean.vert", "bare.frag", model);
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glCreateBuffers(1, &ibo_);
  glCreateBuffers(5, ssbo_);
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
  // Octave wavelengths (1 / lattice frequency) for the distance fade.
  for (const auto& o : waves_->octaves()) octaveWavelengthM_.push_back(float(1.0 / o.frequencyPerM));
  // Models without octaves fade by the spectrum's peak wavelength.
  if (octaveWavelengthM_.empty()) octaveWavelengthM_.push_back(float(waves_->peakWavelengthM()));
}

OceanRenderer::~OceanRenderer() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
  glDeleteBuffers(5, ssbo_);
}

namespace {
template <class T>
void upload(GLuint buf, const std::vector<T>& v) {
  // Never empty: a zero-size SSBO binding is an error.
  const std::size_t bytes = std::max<std::size_t>(v.size() * sizeof(T), 64);
  std::vector<unsigned char> tmp(bytes, 0);
  if (!v.empty()) std::memcpy(tmp.data(), v.data(), v.size() * sizeof(T));
  glNamedBufferData(buf, GLsizeiptr(bytes), tmp.data(), GL_STREAM_DRAW);
}
}  // namespace

std::size_t partitionOpenWater(const grid::GridFrame& f, const render::WaterIndex& wi, double cellPx,
                               std::vector<std::uint32_t>& idx) {
  // Per cell (6 indices): its vertices' lon/lat box in texels, widened by
  // what a fragment inside can read: the B-spline's 2 texels and the
  // mipmapped tap's footprint, up to 3 texels per pixel. Texels per pixel:
  // the box's extent over the cell's size on screen, doubled for the
  // perspective across the cell. Cells touching the horizon (stretched
  // limb cells) always take the coverage path.
  std::vector<std::uint32_t> open;
  std::size_t coast = 0;
  for (std::size_t c = 0; c + 6 <= idx.size(); c += 6) {
    bool isOpen = wi.width() > 0;
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0, lon0 = 0;
    for (std::size_t k = 0; k < 6 && isOpen; ++k) {
      const grid::GridVertex& v = f.vertices[idx[c + k]];
      if (v.flags & grid::kVertexHorizon) isOpen = false;
      double lon = v.lonDeg;
      if (k == 0) lon0 = lon;
      lon -= 360.0 * std::round((lon - lon0) / 360.0);  // the cell does not wrap
      const double x = wi.texelX(lon), y = wi.texelY(v.latDeg);
      if (k == 0) x0 = x1 = x, y0 = y1 = y;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (isOpen) {
      const double tpp = 2.0 * std::max(x1 - x0, y1 - y0) / cellPx;
      const double margin = 3.0 + 3.0 * tpp;
      isOpen = wi.allWater(x0 - margin, x1 + margin, y0 - margin, y1 + margin);
    }
    if (isOpen)
      open.insert(open.end(), idx.begin() + c, idx.begin() + c + 6);
    else
      std::copy(idx.begin() + c, idx.begin() + c + 6, idx.begin() + coast), coast += 6;
  }
  std::copy(open.begin(), open.end(), idx.begin() + coast);
  return coast;
}

void OceanRenderer::draw(const render::ViewMatrices& vm, const render::ViewPose& pose, const render::Lighting& light,
                         bool bare) {
  const camera::Camera cam = camera::Camera::fromEcef(vm.eyeEcef, vm.forward, vm.up, pose.fovYDeg, pose.width,
                                                      pose.height);
  const auto t0 = std::chrono::steady_clock::now();
  grid_->build(cam, frame_);
  std::vector<std::uint32_t> idx = grid::compactIndices(frame_);
  // Open water (coverage 1 throughout, WaterIndex) is drawn by a variant
  // without the shoreline's coverage lookup: from orbit most cells, and on
  // llvmpipe the coverage was half the ocean's fragment cost.
  const std::size_t coastIndices =
      bare || !options_.openWaterShader ? idx.size() : partitionOpenWater(frame_, world_->waterIndex(), options_.cellPx, idx);
  gridMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (idx.empty()) return;
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
  const geo::Geodetic g = geo::fromEcef(vm.eyeEcef);
  const glm::dvec3 origin = geo::toEcef({g.latDeg, g.lonDeg, 0.0});
  waves_->gpuPatch(origin, light.timeS, patch_);
  upload(ssbo_[0], patch_.octaves);
  upload(ssbo_[1], patch_.waves);
  upload(ssbo_[2], std::vector<waves::kf::WvFrame>{patch_.frame});
  for (int i = 0; i < 3; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, ssbo_[i]);
  // Bindings 3 and 4 (FFT) are restored after the draw: hosts may use them.
  GLint hostSsbo[2] = {0, 0};
  GLint64 hostStart[2] = {0, 0}, hostSize[2] = {0, 0};
  const bool fft = options_.model == waves::Model::Fft;
  if (fft) {
    upload(ssbo_[3], patch_.fftPlanes);
    upload(ssbo_[4], patch_.fftTexels);
    for (int i = 0; i < 2; ++i) {
      glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(3 + i), &hostSsbo[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, GLuint(3 + i), &hostStart[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(3 + i), &hostSize[i]);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(3 + i), ssbo_[3 + i]);
    }
  }

  const auto setUniforms = [&](const render::GlProgram& p) {
    glUniformMatrix4fv(p.uniform("uViewProj"), 1, GL_FALSE, &vm.viewProj[0][0]);
  const glm::vec3 eyeMinusO(vm.eyeEcef - origin);
  glUniform3fv(p.uniform("uEyeMinusOrigin"), 1, &eyeMinusO[0]);
  glUniform1i(p.uniform("uOctaveCount"), int(patch_.octaves.size()));
  glUniform1i(p.uniform("uWaveCount"), int(patch_.waves.size()));
  glUniform1fv(p.uniform("uOctaveWavelengthM"), GLsizei(std::min<std::size_t>(octaveWavelengthM_.size(), 16)),
               octaveWavelengthM_.data());
  // Metres per pixel at 1 m distance: a cell's footprint is this x cellPx x distance.
  const double radPerPx = 2.0 * std::tan(0.5 * pose.fovYDeg * 3.14159265358979 / 180.0) / pose.height;
  glUniform1f(p.uniform("uCellRadians"), float(radPerPx * options_.cellPx));
  glUniform1f(p.uniform("uMaxVerticalM"), float(waves_->maxVerticalM()));
  glUniform4fv(p.uniform("uElevationGeo"), 1, &world_->elevationGeo()[0]);
  glUniform4fv(p.uniform("uWaterGeo"), 1, &world_->waterGeo()[0]);
  const glm::vec3 sun(light.sunEcef);
  glUniform3fv(p.uniform("uSunDir"), 1, &sun[0]);
  glUniform1f(p.uniform("uEyeRadiusM"), float(glm::length(vm.eyeEcef)));
  glUniform1f(p.uniform("uEyeAltM"), float(g.heightM));
  glUniform1f(p.uniform("uRefLonDeg"), float(g.lonDeg));
  glUniform1f(p.uniform("uTimeS"), float(std::fmod(light.timeS, 3600.0)));
  glUniform1i(p.uniform("uWriteData"), writeData_ ? 1 : 0);
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
  world_->bind();
  const std::pair<const render::GlProgram*, std::size_t> passes[2] = {
      {bare ? &bare_ : &program_, coastIndices}, {&openWater_, idx.size() - coastIndices}};
  std::size_t first = 0;
  for (const auto& [prog, count] : passes) {
    if (count == 0) continue;
    prog->use();
    setUniforms(*prog);
    glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
    first += count;
  }
  glBindVertexArray(0);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_BLEND);
  if (fft)
    for (int i = 0; i < 2; ++i) {
      if (hostSsbo[i] != 0 && hostSize[i] > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, GLuint(3 + i), GLuint(hostSsbo[i]), GLintptr(hostStart[i]),
                          GLsizeiptr(hostSize[i]));
      else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(3 + i), GLuint(hostSsbo[i]));
    }
}

}  // namespace geocean::ocean_render

namespace geocean::ocean_render {
std::string addDefaultOcean(render::GlobeRenderer& renderer, std::shared_ptr<const render::WorldTextures> world,
                            const std::string& modelName, double windMps, double windFromDeg,
                            std::shared_ptr<OceanRenderer>* created) {
  OceanOptions oo;
  const auto model = waves::parseModel(modelName);
  if (!model || *model == waves::Model::NoisePaper)
    return "--waves '" + modelName + "' is not a GPU wave model (noise, gerstner, fft)";
  oo.model = *model;
  oo.sea.windSpeedMps = windMps;
  oo.sea.windFromDeg = windFromDeg;
  try {
    auto o = std::make_shared<OceanRenderer>(std::move(world), defaultLandSea(), oo);
    renderer.addLayer(o);
    if (created) *created = o;
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}
}  // namespace geocean::ocean_render
