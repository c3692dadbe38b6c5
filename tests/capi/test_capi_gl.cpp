// The C ABI's rendering (ABI 1.1) in a host's own headless context, through
// the run-time loader: call order, the host's GL state left as it was,
// resources tied to their context, queries from other threads while the
// host draws.
#include "globe/gl/HeadlessContext.h"
#include "tests/capi/LoadedPlugin.h"

#include <malloc.h>
#if defined(__SANITIZE_ADDRESS__)
#define GEOCEAN_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GEOCEAN_TEST_ASAN 1
#endif
#endif
#ifdef GEOCEAN_TEST_ASAN
// The sanitizers' allocator interface (GCC ships no header for it).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using geocean::host::OceanPlugin;

using namespace geocean::capitest;

constexpr int kSize = 128;

// The host: a context and an FBO with colour + float depth, reversed Z.
struct Host {
  std::unique_ptr<geocean::gl::HeadlessContext> ctx;
  GLuint fbo = 0, rb[2] = {0, 0};
  Host() {
    std::string error;
    ctx = geocean::gl::HeadlessContext::create(error);
    if (!ctx) {
      ADD_FAILURE() << error;
      return;
    }
    glCreateFramebuffers(1, &fbo);
    glCreateRenderbuffers(2, rb);
    glNamedRenderbufferStorage(rb[0], GL_RGBA8, kSize, kSize);
    glNamedRenderbufferStorage(rb[1], GL_DEPTH_COMPONENT32F, kSize, kSize);
    glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  }
  ~Host() {
    // A context whose display another Host terminated cannot be made current.
    if (!ctx || !ctx->makeCurrent()) return;
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb);
  }
  void beginFrame() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, kSize, kSize);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClearDepth(0.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
  }
  // Pixels not the red background.
  int drawnPixels() const {
    std::vector<unsigned char> px(std::size_t(kSize) * kSize * 4);
    glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    int n = 0;
    for (std::size_t i = 0; i < px.size(); i += 4) n += !(px[i] == 255 && px[i + 1] == 0 && px[i + 2] == 0);
    return n;
  }
};

struct Ocean {
  geocean_ocean* h = nullptr;
  explicit Ocean(bool withSea = true) {
    EXPECT_EQ(api().create(GEOCEAN_ABI_VERSION, &h), GEOCEAN_OK);
    if (!withSea) return;
    geocean_sea_state s;
    EXPECT_EQ(api().seaStateInit(&s), GEOCEAN_OK);
    EXPECT_EQ(api().setSeaState(h, &s), GEOCEAN_OK);
  }
  ~Ocean() { api().destroy(h); }
};

geocean_view nadir(double latDeg, double lonDeg, double heightM) {
  geocean_view v;
  EXPECT_EQ(api().viewInit(&v), GEOCEAN_OK);
  EXPECT_EQ(api().viewFromPose(&v, latDeg, lonDeg, heightM, 0.0, -90.0, 45.0, kSize, kSize), GEOCEAN_OK);
  return v;
}

TEST(CapiGl, DrawNeedsAnUpdateAndASeaStateFirst) {
  Host host;
  ASSERT_TRUE(host.ctx);
  Ocean noSea(false);
  host.beginFrame();
  EXPECT_EQ(api().draw(noSea.h), GEOCEAN_ERROR_NOT_READY);
  EXPECT_EQ(lastError(), "geocean_draw: no view: call geocean_update first");
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(noSea.h, &v), GEOCEAN_OK);
  EXPECT_EQ(api().draw(noSea.h), GEOCEAN_ERROR_NOT_READY);
  EXPECT_EQ(lastError(), "geocean_draw: no sea state: call geocean_set_sea_state first");
  // A sea state draws: no rasters = all deep ocean, the whole frame is sea;
  // the paper's 2D noise too (its GPU form, shaders/waves_paper.glsl).
  geocean_sea_state s;
  ASSERT_EQ(api().seaStateInit(&s), GEOCEAN_OK);
  s.model = GEOCEAN_WAVES_NOISE_PAPER;
  ASSERT_EQ(api().setSeaState(noSea.h, &s), GEOCEAN_OK);
  ASSERT_EQ(api().draw(noSea.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(host.drawnPixels(), kSize * kSize);
  host.beginFrame();
  s.model = GEOCEAN_WAVES_GERSTNER;
  ASSERT_EQ(api().setSeaState(noSea.h, &s), GEOCEAN_OK);
  ASSERT_EQ(api().draw(noSea.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(host.drawnPixels(), kSize * kSize);
  EXPECT_EQ(api().releaseGl(noSea.h), GEOCEAN_OK);
}

TEST(CapiGl, TheHostsGlStateIsLeftAsItWas) {
  Host host;
  ASSERT_TRUE(host.ctx);
  Ocean o;
  host.beginFrame();
  // Distinctive host state in everything the ocean touches.
  GLuint vao = 0, tex[3] = {0, 0, 0}, buf = 0;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glCreateTextures(GL_TEXTURE_2D, 3, tex);
  for (int u = 0; u < 3; ++u) glBindTextureUnit(GLuint(u), tex[u]);
  glActiveTexture(GL_TEXTURE5);
  glCreateBuffers(1, &buf);
  glNamedBufferData(buf, 1024, nullptr, GL_STATIC_DRAW);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, buf, 256, 512);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
  glEnablei(GL_BLEND, 1);
  glDisablei(GL_BLEND, 0);
  glBlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  glPolygonOffset(1.5f, 2.5f);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 8);

  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(o.h, &v), GEOCEAN_OK);
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();  // first draw: creates resources too
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  EXPECT_GT(host.drawnPixels(), kSize * kSize / 2);

  GLint i = 0;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &i);
  EXPECT_EQ(GLuint(i), vao);
  glGetIntegerv(GL_CURRENT_PROGRAM, &i);
  EXPECT_EQ(i, 0);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &i);
  EXPECT_EQ(i, GL_TEXTURE5);
  for (int u = 0; u < 3; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &i);
    EXPECT_EQ(GLuint(i), tex[u]) << "unit " << u;
  }
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 1, &i);
  EXPECT_EQ(GLuint(i), buf);
  GLint64 start = 0, size = 0;
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 1, &start);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 1, &size);
  EXPECT_EQ(start, 256);
  EXPECT_EQ(size, 512);
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &i);
  EXPECT_EQ(i, 0);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &i);
  EXPECT_EQ(GLuint(i), buf);
  EXPECT_FALSE(glIsEnabledi(GL_BLEND, 0));
  EXPECT_TRUE(glIsEnabledi(GL_BLEND, 1));
  glGetIntegeri_v(GL_BLEND_SRC_RGB, 0, &i);
  EXPECT_EQ(i, GL_ONE);
  glGetIntegeri_v(GL_BLEND_DST_ALPHA, 0, &i);
  EXPECT_EQ(i, GL_ONE);
  EXPECT_FALSE(glIsEnabled(GL_POLYGON_OFFSET_FILL));
  GLfloat f = 0.0f;
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &f);
  EXPECT_EQ(f, 1.5f);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &f);
  EXPECT_EQ(f, 2.5f);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &i);
  EXPECT_EQ(i, 8);
  // The host's depth test and framebuffer are its own.
  glGetIntegerv(GL_DEPTH_FUNC, &i);
  EXPECT_EQ(i, GL_GREATER);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &i);
  EXPECT_EQ(GLuint(i), host.fbo);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));

  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_OK);
  glDeleteVertexArrays(1, &vao);
  glDeleteTextures(3, tex);
  glDeleteBuffers(1, &buf);
}

// ABI 1.8: a host's shadow map. Filled with 1 (everything nearer the sun
// than the sea: the whole view in shadow) and GEOCEAN_DRAW_SHADOW_PAPER,
// every drawn pixel is paper 001's half of the unshadowed one (to the
// display's rounding); cleared to 0 (nothing casts), the picture is the
// unshadowed one. The host's texture and sampler on unit 14 are put back.
// The noise sea's deferred shading (a 500 m nadir view takes it) in a
// viewport off the framebuffer's origin: its G-buffer and tiles are in the
// framebuffer's pixels, the host's depth attached as it is, so the picture
// is the one drawn at the origin and nothing is drawn outside the
// viewport. Not bit for bit: llvmpipe interpolates a varying from the
// framebuffer's origin (a0 + x dadx + y dady), so a shifted triangle's
// values round differently (measured: 3 of 16,384 pixels by 1 of 255; a
// forward draw shifts the same way). A misplaced tile or G-buffer texel
// would move whole 8 x 8 tiles: at most 1 of 255 on 0.1 % of the pixels.
// An even offset: the 2 x 2 quads of the derivatives pair the same pixels.
TEST(CapiGl, AViewportOffTheFramebuffersOriginDrawsTheSamePicture) {
  Host host;
  ASSERT_TRUE(host.ctx);
  Ocean o;
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(o.h, &v), GEOCEAN_OK);
  host.beginFrame();
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  std::vector<unsigned char> atOrigin(std::size_t(kSize) * kSize * 4);
  glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_UNSIGNED_BYTE, atOrigin.data());
  constexpr int kBig = 2 * kSize, kX = 40, kY = 24;
  GLuint fbo = 0, rb[2] = {0, 0};
  glCreateFramebuffers(1, &fbo);
  glCreateRenderbuffers(2, rb);
  glNamedRenderbufferStorage(rb[0], GL_RGBA8, kBig, kBig);
  glNamedRenderbufferStorage(rb[1], GL_DEPTH_COMPONENT32F, kBig, kBig);
  glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
  glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, kBig, kBig);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);  // red, depth 0 (beginFrame's)
  glViewport(kX, kY, kSize, kSize);
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  std::vector<unsigned char> big(std::size_t(kBig) * kBig * 4);
  glReadPixels(0, 0, kBig, kBig, GL_RGBA, GL_UNSIGNED_BYTE, big.data());
  int differ = 0, outside = 0, sea = 0, maxDiff = 0;
  for (int y = 0; y < kBig; ++y)
    for (int x = 0; x < kBig; ++x) {
      const unsigned char* p = &big[(std::size_t(y) * kBig + std::size_t(x)) * 4];
      const bool red = p[0] == 255 && p[1] == 0 && p[2] == 0;
      if (x < kX || y < kY || x >= kX + kSize || y >= kY + kSize) {
        outside += !red;
        continue;
      }
      const unsigned char* q = &atOrigin[(std::size_t(y - kY) * kSize + std::size_t(x - kX)) * 4];
      differ += std::memcmp(p, q, 4) != 0;
      for (int c = 0; c < 3; ++c) maxDiff = std::max(maxDiff, std::abs(int(p[c]) - int(q[c])));
      sea += !red;
    }
  EXPECT_EQ(sea, kSize * kSize);
  EXPECT_LE(differ, kSize * kSize / 1000) << "max " << maxDiff;
  EXPECT_LE(maxDiff, 1) << differ << " pixels differ";
  EXPECT_EQ(outside, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(2, rb);
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_OK);
}

TEST(CapiGl, AHostsShadowMapDarkensTheSeaByThePapersHalfAndUnit14IsLeftAsItWas) {
  Host host;
  ASSERT_TRUE(host.ctx);
  Ocean o;
  GLuint depth = 0, hostTex = 0, hostSampler = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &depth);
  glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 64, 64);
  glCreateTextures(GL_TEXTURE_2D, 1, &hostTex);
  glCreateSamplers(1, &hostSampler);
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  // The map over the whole view: an orthographic box along the sun (the
  // view's default, over the nadir) 4 km across around the eye.
  geocean_layer_inputs in{};
  in.struct_size = sizeof in;
  in.shadow_depth_texture = depth;
  in.shadow_size_px = 64;
  for (int i = 0; i < 3; ++i) in.shadow_origin_ecef_m[i] = v.eye_ecef_m[i];
  for (int c = 0; c < 4; ++c) in.shadow_matrix[5 * c] = c < 2 ? 1.0 / 2000.0 : c == 2 ? 0.0 : 1.0;
  in.shadow_matrix[14] = 0.5;  // every point at depth 0.5
  in.shadow_reach_m = 2000.0;
  const auto frame = [&](float fill, uint32_t flags) {
    glClearTexImage(depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &fill);
    host.beginFrame();
    glBindTextureUnit(14, hostTex);
    glBindSampler(14, hostSampler);
    geocean_view w = v;
    w.draw_flags = flags;
    EXPECT_EQ(api().setLayerInputs(o.h, &in), GEOCEAN_OK) << lastError();
    EXPECT_EQ(api().update(o.h, &w), GEOCEAN_OK) << lastError();
    EXPECT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
    std::vector<unsigned char> px(std::size_t(kSize) * kSize * 4);
    glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    return px;
  };
  const auto lit = frame(0.0f, GEOCEAN_DRAW_SHADOW_PAPER);
  const auto shaded = frame(1.0f, GEOCEAN_DRAW_SHADOW_PAPER);
  int drawn = 0, off = 0;
  for (std::size_t i = 0; i < lit.size(); i += 4) {
    if (lit[i] == 255 && lit[i + 1] == 0 && lit[i + 2] == 0) continue;
    ++drawn;
    for (int c = 0; c < 3; ++c) off += std::abs(2 * int(shaded[i + c]) - int(lit[i + c])) > 2;
  }
  EXPECT_GT(drawn, kSize * kSize / 2);
  EXPECT_EQ(off, 0) << "of " << drawn << " pixels";
  GLint i = 0;
  glActiveTexture(GL_TEXTURE14);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &i);
  EXPECT_EQ(GLuint(i), hostTex);
  glGetIntegerv(GL_SAMPLER_BINDING, &i);
  EXPECT_EQ(GLuint(i), hostSampler);
  glActiveTexture(GL_TEXTURE0);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  // A bad map size is named.
  in.shadow_size_px = 0;
  EXPECT_EQ(api().setLayerInputs(o.h, &in), GEOCEAN_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("shadow_size_px 0"), std::string::npos) << lastError();
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_OK);
  glDeleteTextures(1, &depth);
  glDeleteTextures(1, &hostTex);
  glDeleteSamplers(1, &hostSampler);
}

TEST(CapiGl, ResourcesBelongToTheContextOfTheFirstDraw) {
  Host a, b;  // b was made last, so it is current
  ASSERT_TRUE(a.ctx && b.ctx);
  Ocean o;
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(o.h, &v), GEOCEAN_OK);
  ASSERT_TRUE(a.ctx->makeCurrent());
  a.beginFrame();
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  ASSERT_TRUE(b.ctx->makeCurrent());
  b.beginFrame();
  EXPECT_EQ(api().draw(o.h), GEOCEAN_ERROR_GL);
  EXPECT_NE(lastError().find("belong to another context"), std::string::npos) << lastError();
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_ERROR_GL);
  EXPECT_EQ(b.drawnPixels(), 0);
  ASSERT_TRUE(a.ctx->makeCurrent());
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_OK);
  // Released: the next draw may be in any context.
  ASSERT_TRUE(b.ctx->makeCurrent());
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(b.drawnPixels(), kSize * kSize);
  // destroy (Ocean's destructor) with b current releases them itself.
}

TEST(CapiGl, ChangingTheSeaStateOrRastersBetweenFramesRebuilds) {
  Host host;
  ASSERT_TRUE(host.ctx);
  Ocean o;
  // Land everywhere from memory, then ocean everywhere: the frame follows.
  const geocean_grid_placement pl{-180.0, 90.0, 360.0, -180.0, 1, 0, 0.0};
  const float land = 1.0f, sea = 0.0f;
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(o.h, &v), GEOCEAN_OK);
  ASSERT_EQ(api().setMaskPixels(o.h, &land, 1, 1, &pl), GEOCEAN_OK);
  host.beginFrame();
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(host.drawnPixels(), 0);
  ASSERT_EQ(api().setMaskPixels(o.h, &sea, 1, 1, &pl), GEOCEAN_OK);
  host.beginFrame();
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(host.drawnPixels(), kSize * kSize);
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_OK);
}

TEST(CapiGl, QueriesFromOtherThreadsWhileTheHostDraws) {
  Host host;
  ASSERT_TRUE(host.ctx);
  Ocean o;
  ASSERT_EQ(api().setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  // Reference answers before any drawing.
  std::vector<double> lat, lon;
  for (int i = 0; i < 500; ++i) {
    lat.push_back(-60.0 + 0.24 * i);
    lon.push_back(-170.0 + 0.68 * i);
  }
  const std::size_t n = lat.size();
  std::vector<double> refH(n), refN(3 * n);
  std::vector<uint8_t> refC(n);
  ASSERT_EQ(api().querySeaSurface(o.h, n, lat.data(), lon.data(), 5.0, refH.data(), refN.data(), refC.data()),
            GEOCEAN_OK);

  std::atomic<bool> stop{false};
  std::atomic<int> queries{0}, mismatches{0}, failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t)
    threads.emplace_back([&] {
      std::vector<double> h(n), nrm(3 * n);
      std::vector<uint8_t> c(n);
      while (!stop.load()) {
        if (api().querySeaSurface(o.h, n, lat.data(), lon.data(), 5.0, h.data(), nrm.data(), c.data()) !=
            GEOCEAN_OK) {
          ++failures;
          continue;
        }
        for (std::size_t i = 0; i < n; ++i) {
          // Same inputs, same answer, bit for bit (NaN on land compares by class).
          const bool same = c[i] == refC[i] && (std::isnan(refH[i]) ? std::isnan(h[i]) : h[i] == refH[i]);
          if (!same) ++mismatches;
        }
        ++queries;
      }
    });
  int drawn = 0;
  for (int frame = 0; frame < 6; ++frame) {
    geocean_view v;
    ASSERT_EQ(api().viewInit(&v), GEOCEAN_OK);
    ASSERT_EQ(api().viewFromPose(&v, 36.0, -5.5, 20000.0 + 50000.0 * frame, 10.0 * frame, -60.0, 45.0, kSize,
                                 kSize),
              GEOCEAN_OK);
    v.time_s = 0.5 * frame;
    host.beginFrame();
    if (api().update(o.h, &v) == GEOCEAN_OK && api().draw(o.h) == GEOCEAN_OK) ++drawn;
    glFinish();
  }
  // Let every thread finish at least one query while frames were in flight.
  while (queries.load() < 3) std::this_thread::yield();
  stop = true;
  for (auto& t : threads) t.join();
  EXPECT_EQ(drawn, 6) << lastError();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_GT(host.drawnPixels(), 0);
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_OK);
}

TEST(CapiGl, DestroyWithoutTheContextCurrentDoesNotCrash) {
  auto host = std::make_unique<Host>();
  ASSERT_TRUE(host->ctx);
  geocean_ocean* h = nullptr;
  ASSERT_EQ(api().create(GEOCEAN_ABI_VERSION, &h), GEOCEAN_OK);
  geocean_sea_state s;
  ASSERT_EQ(api().seaStateInit(&s), GEOCEAN_OK);
  ASSERT_EQ(api().setSeaState(h, &s), GEOCEAN_OK);
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(h, &v), GEOCEAN_OK);
  host->beginFrame();
  ASSERT_EQ(api().draw(h), GEOCEAN_OK) << lastError();
  host.reset();  // the host destroys its context first (it takes the ocean's GL objects with it)
  api().destroy(h);
  EXPECT_EQ(lastError(), "");
}

// Heap in use (small chunks + mmapped ones: the grids are mmapped). Under
// AddressSanitizer malloc is the sanitizer's (mallinfo2 reads zeros): ask it.
std::size_t heapInUse() {
#ifdef GEOCEAN_TEST_ASAN
  return __sanitizer_get_current_allocated_bytes();
#else
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
#endif
}

// What geocean_destroy frees of an ocean on the default world, in a process
// whose host has already destroyed the context of its draws.
std::size_t freedByDestroy(bool drawFirst) {
  auto host = std::make_unique<Host>();
  EXPECT_TRUE(host->ctx);
  Ocean o;
  EXPECT_EQ(api().setDefaultWorld(o.h), GEOCEAN_OK) << lastError();
  if (drawFirst) {
    const geocean_view v = nadir(30.0, -40.0, 500.0);
    EXPECT_EQ(api().update(o.h, &v), GEOCEAN_OK);
    host->beginFrame();
    EXPECT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  }
  host.reset();  // no context current from here
  const std::size_t before = heapInUse();
  api().destroy(o.h);
  o.h = nullptr;
  const std::size_t after = heapInUse();
  return before > after ? before - after : 0;
}

TEST(CapiGl, DestroyWithoutTheContextFreesTheCpuSide) {
  // Without its context only the GL names may be abandoned: the ocean's
  // water and elevation grids (5' water as floats: 4320 x 2160 x 4 B =
  // 37.3 MB) must go too. The difference to an ocean that never drew is
  // what the draw state held on the CPU.
  const std::size_t plain = freedByDestroy(false);
  const std::size_t drawn = freedByDestroy(true);
  EXPECT_GT(drawn, plain + std::size_t(30) * 1024 * 1024) << "freed " << drawn << " B after a draw, " << plain
                                                           << " B without one";
}

}  // namespace

namespace {

// Issue 17 item 4, the GL context lost mid-session: unbound between draws,
// destroyed while another context is current, destroyed and replaced by a
// new context at the same handle. Each a clear status (or, for the last, a
// correct frame), never a crash, never a draw into the wrong context.
TEST(CapiGl, ContextLostMidSessionIsAClearErrorNeverACrash) {
  auto a = std::make_unique<Host>();
  ASSERT_TRUE(a->ctx);
  Ocean o;
  const geocean_view v = nadir(30.0, -40.0, 500.0);
  ASSERT_EQ(api().update(o.h, &v), GEOCEAN_OK);
  a->beginFrame();
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  ASSERT_EQ(a->drawnPixels(), kSize * kSize);
  const double lat = 30.0, lon = -40.0;
  double h0 = 0.0, h1 = 1.0;
  ASSERT_EQ(api().querySeaSurface(o.h, 1, &lat, &lon, 2.0, &h0, nullptr, nullptr), GEOCEAN_OK);

  // 1. Unbound between draws: NO_GL_CONTEXT, the rest of the ocean works,
  //    and with the context current again the next draw is whole.
  const EGLDisplay dpy = eglGetCurrentDisplay();
  ASSERT_TRUE(eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
  EXPECT_EQ(api().draw(o.h), GEOCEAN_ERROR_NO_GL_CONTEXT);
  EXPECT_EQ(lastError(), "geocean_draw: no OpenGL context is current on this thread (neither EGL nor GLX): make "
                         "the host's context current");
  EXPECT_EQ(api().releaseGl(o.h), GEOCEAN_ERROR_NO_GL_CONTEXT);
  EXPECT_EQ(api().update(o.h, &v), GEOCEAN_OK);
  ASSERT_EQ(api().querySeaSurface(o.h, 1, &lat, &lon, 2.0, &h1, nullptr, nullptr), GEOCEAN_OK);
  EXPECT_EQ(h0, h1);
  ASSERT_TRUE(a->ctx->makeCurrent());
  a->beginFrame();
  ASSERT_EQ(api().draw(o.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(a->drawnPixels(), kSize * kSize);
  const void* handleA = eglGetCurrentContext();

  // 2. Destroyed while another context is current: GL error, nothing drawn
  //    into the other context; destroy frees the CPU side with no GL call.
  {
    auto b = std::make_unique<Host>();  // current now
    ASSERT_TRUE(b->ctx);
    // The host destroys a's context (by EGL: a's HeadlessContext would also
    // terminate the display both share, and b with it).
    ASSERT_TRUE(eglDestroyContext(dpy, const_cast<void*>(handleA)));
    b->beginFrame();
    EXPECT_EQ(api().draw(o.h), GEOCEAN_ERROR_GL);
    EXPECT_NE(lastError().find("geocean_draw: the ocean's GL resources belong to another context"), std::string::npos)
        << lastError();
    EXPECT_EQ(b->drawnPixels(), 0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    ASSERT_EQ(api().querySeaSurface(o.h, 1, &lat, &lon, 2.0, &h1, nullptr, nullptr), GEOCEAN_OK);
    EXPECT_EQ(h0, h1);
    Ocean fresh;  // the host's way on: a new ocean draws in the live context
    ASSERT_EQ(api().update(fresh.h, &v), GEOCEAN_OK);
    ASSERT_EQ(api().draw(fresh.h), GEOCEAN_OK) << lastError();
    EXPECT_EQ(b->drawnPixels(), kSize * kSize);
  }
  a.reset();  // its context was destroyed above; its display with b's
  api().destroy(o.h);  // its context is gone and none is current: CPU side freed, no GL call
  o.h = nullptr;
  EXPECT_EQ(lastError(), "");

  // 3. The same handle, but not the names: a context destroyed and a new
  //    one given its address (EGL and GLX may reuse it; Mesa 22 here did not
  //    in 8 tries) leaves the ocean's names dead and the host's new objects
  //    owning some of those numbers. Made deterministic: the host deletes
  //    every buffer name 1..4096 of the current context (the plugin's among
  //    them) and makes 8 buffers of its own. The draw must notice and make
  //    its resources anew, not draw with (or write into) those names.
  Host c;
  ASSERT_TRUE(c.ctx);
  Ocean p;
  ASSERT_EQ(api().update(p.h, &v), GEOCEAN_OK);
  c.beginFrame();
  ASSERT_EQ(api().draw(p.h), GEOCEAN_OK) << lastError();
  std::vector<GLuint> names(4096);
  for (GLuint i = 0; i < names.size(); ++i) names[i] = i + 1;
  glDeleteBuffers(GLsizei(names.size()), names.data());
  GLuint hostBuffers[8];
  glCreateBuffers(8, hostBuffers);
  for (GLuint b : hostBuffers) glNamedBufferData(b, 16, nullptr, GL_STATIC_DRAW);
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  c.beginFrame();
  EXPECT_EQ(api().draw(p.h), GEOCEAN_OK) << lastError();
  EXPECT_EQ(c.drawnPixels(), kSize * kSize) << "drew with names the context no longer has";
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  for (GLuint b : hostBuffers) {
    GLint size = 0;
    glGetNamedBufferParameteriv(b, GL_BUFFER_SIZE, &size);
    EXPECT_EQ(size, 16) << "the host's buffer " << b << " was written by the ocean";
  }
  EXPECT_EQ(api().releaseGl(p.h), GEOCEAN_OK) << lastError();
  glDeleteBuffers(8, hostBuffers);
}

}  // namespace
