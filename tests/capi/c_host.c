/* A minimal host engine in plain C: dlopens the ocean plugin, checks its ABI
 * version, loads the default world and queries the surface class and
 * elevation at known places; with OUT_DIR it also makes its own headless
 * OpenGL context (EGL surfaceless through libepoxy), renders frames of the
 * ocean into its own FBO through the ABI, checks the pixels against the
 * land/sea mask and writes them as PNG. Proof that a host needs nothing but
 * the C header and the shared library.
 *   c_host PLUGIN.so [OUT_DIR]   (the default world comes from $GEOCEAN_DATA
 *                                 or the plugin's install prefix)
 * Exit status 0 only if every check holds. */
#include "geocean/geocean_ocean.h"

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef C_HOST_RENDER
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#endif

typedef uint32_t (*abi_version_fn)(void);
typedef const char* (*last_error_fn)(void);
typedef geocean_status (*create_fn)(uint32_t, geocean_ocean**);
typedef void (*destroy_fn)(geocean_ocean*);
typedef geocean_status (*set_default_world_fn)(geocean_ocean*);
typedef geocean_status (*query_class_fn)(const geocean_ocean*, size_t, const double*, const double*, uint8_t*);
typedef geocean_status (*query_elevation_fn)(const geocean_ocean*, size_t, const double*, const double*, float*);

/* dlsym returns void*; ISO C has no cast from it to a function pointer, so copy the bits. */
static void* sym(void* lib, const char* name) {
  void* p = dlsym(lib, name);
  if (!p) fprintf(stderr, "c_host: missing symbol %s\n", name);
  return p;
}
#define RESOLVE(var, type, name)                  \
  do {                                            \
    void* p_ = sym(lib, name);                    \
    if (!p_) return 1;                            \
    memcpy(&var, &p_, sizeof var);                \
  } while (0)

#ifdef C_HOST_RENDER
/* ---- Rendering through the ABI 1.1 functions --------------------------- */

typedef geocean_status (*sea_state_init_fn)(geocean_sea_state*);
typedef geocean_status (*set_sea_state_fn)(geocean_ocean*, const geocean_sea_state*);
typedef geocean_status (*view_init_fn)(geocean_view*);
typedef geocean_status (*view_from_pose_fn)(geocean_view*, double, double, double, double, double, double, int32_t,
                                            int32_t);
typedef geocean_status (*update_fn)(geocean_ocean*, const geocean_view*);
typedef geocean_status (*draw_fn)(geocean_ocean*);
typedef geocean_status (*release_gl_fn)(geocean_ocean*);

enum { W = 256, H = 256 };
static const double kPi = 3.14159265358979323846;

/* An uncompressed PNG (stored deflate blocks): no image library needed. */
static uint32_t crc_table[256];
static void crc_init(void) {
  uint32_t n, c;
  int k;
  for (n = 0; n < 256; ++n) {
    c = n;
    for (k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
    crc_table[n] = c;
  }
}
static uint32_t crc(uint32_t c, const unsigned char* p, size_t n) {
  while (n--) c = crc_table[(c ^ *p++) & 0xff] ^ (c >> 8);
  return c;
}
static void be32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16), p[2] = (unsigned char)(v >> 8);
  p[3] = (unsigned char)v;
}
static void chunk(FILE* f, const char* type, const unsigned char* data, uint32_t n) {
  unsigned char b[4];
  uint32_t c;
  be32(b, n);
  fwrite(b, 1, 4, f);
  fwrite(type, 1, 4, f);
  if (n) fwrite(data, 1, n, f);
  c = crc(0xffffffffu, (const unsigned char*)type, 4);
  c = crc(c, data, n) ^ 0xffffffffu;
  be32(b, c);
  fwrite(b, 1, 4, f);
}
/* rgba: W x H, bottom row first (as glReadPixels gives it). */
static int write_png(const char* path, const unsigned char* rgba) {
  const size_t row = 1 + 4 * W, raw_n = row * H;
  const size_t blocks = (raw_n + 65534) / 65535;
  unsigned char* raw = malloc(raw_n);
  unsigned char* z = malloc(2 + raw_n + 5 * blocks + 4);
  unsigned char hdr[13];
  size_t i, o = 0;
  uint32_t a = 1, b = 0;
  int y;
  FILE* f = fopen(path, "wb");
  if (!f || !raw || !z) {
    fprintf(stderr, "c_host: cannot write %s\n", path);
    if (f) fclose(f);
    free(raw), free(z);
    return 1;
  }
  for (y = 0; y < H; ++y) { /* PNG rows top first */
    raw[y * row] = 0;
    memcpy(raw + y * row + 1, rgba + (size_t)(H - 1 - y) * 4 * W, 4 * W);
  }
  z[o++] = 0x78, z[o++] = 0x01;
  for (i = 0; i < raw_n; i += 65535) {
    const size_t n = raw_n - i < 65535 ? raw_n - i : 65535;
    z[o++] = (unsigned char)(i + n == raw_n);
    z[o++] = (unsigned char)n, z[o++] = (unsigned char)(n >> 8);
    z[o++] = (unsigned char)~n, z[o++] = (unsigned char)(~n >> 8);
    memcpy(z + o, raw + i, n);
    o += n;
  }
  for (i = 0; i < raw_n; ++i) a = (a + raw[i]) % 65521u, b = (b + a) % 65521u;
  be32(z + o, (b << 16) | a);
  o += 4;
  fwrite("\211PNG\r\n\032\n", 1, 8, f);
  be32(hdr, W), be32(hdr + 4, H);
  hdr[8] = 8, hdr[9] = 6, hdr[10] = 0, hdr[11] = 0, hdr[12] = 0; /* 8-bit RGBA */
  chunk(f, "IHDR", hdr, 13);
  chunk(f, "IDAT", z, (uint32_t)o);
  chunk(f, "IEND", NULL, 0);
  fclose(f);
  free(raw), free(z);
  printf("wrote %s\n", path);
  return 0;
}

/* The host's background: a colour the ocean never makes (pure red). */
static int is_background(const unsigned char* p) { return p[0] == 255 && p[1] == 0 && p[2] == 0; }
/* Sea colour: blue channel above red (deep water, sky reflection, glint
 * whitens but stays >= red); the red background and land never pass. */
static int is_sea(const unsigned char* p) { return !is_background(p) && p[2] >= p[0] && p[2] > 40; }

/* Geodetic latitude/longitude where the ray eye + t dir meets the WGS84
 * ellipsoid (height 0); 0 if it misses. Plain C on purpose: truth that is not
 * the plugin's code. Latitude by 3 fixed-point steps (converges to 1e-9 rad). */
static int ray_to_lat_lon(const double eye[3], const double dir[3], double* lat_deg, double* lon_deg) {
  const double a = 6378137.0, f = 1.0 / 298.257223563, b = a * (1.0 - f), e2 = f * (2.0 - f);
  const double ex = eye[0] / a, ey = eye[1] / a, ez = eye[2] / b, dx = dir[0] / a, dy = dir[1] / a, dz = dir[2] / b;
  const double qa = dx * dx + dy * dy + dz * dz, qb = 2.0 * (ex * dx + ey * dy + ez * dz),
               qc = ex * ex + ey * ey + ez * ez - 1.0;
  const double disc = qb * qb - 4.0 * qa * qc;
  double t, x, y, zz, p, lat;
  int k;
  if (disc < 0.0) return 0;
  t = (-qb - sqrt(disc)) / (2.0 * qa);
  if (t <= 0.0) return 0;
  x = eye[0] + t * dir[0], y = eye[1] + t * dir[1], zz = eye[2] + t * dir[2];
  p = sqrt(x * x + y * y);
  lat = atan2(zz, p * (1.0 - e2));
  for (k = 0; k < 3; ++k) {
    const double s = sin(lat), n = a / sqrt(1.0 - e2 * s * s);
    lat = atan2(zz + e2 * n * s, p);
  }
  *lat_deg = lat * 180.0 / kPi;
  *lon_deg = atan2(y, x) * 180.0 / kPi;
  return 1;
}

static int render_frames(void* lib, geocean_ocean* ocean, const char* out_dir) {
  last_error_fn last_error;
  sea_state_init_fn sea_state_init;
  set_sea_state_fn set_sea_state;
  view_init_fn view_init;
  view_from_pose_fn view_from_pose;
  update_fn update;
  draw_fn draw;
  release_gl_fn release_gl;
  query_class_fn query_class;
  EGLDisplay dpy;
  EGLContext ctx;
  GLuint fbo, rb[2];
  geocean_sea_state sea;
  geocean_view view;
  static unsigned char px[W * H * 4];
  static double lat[W * H], lon[W * H];
  static uint8_t cls[W * H];
  char path[4096];
  int failures = 0, frame;
  const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  /* Nadir over the open Atlantic, a low look at the horizon there, nadir
     over the Sahara, and the Strait of Gibraltar from 400 km. */
  static const struct {
    const char* name;
    double lat, lon, height, heading, pitch, fov;
  } frames[4] = {{"atlantic_nadir", 30.0, -40.0, 2000.0, 0.0, -90.0, 45.0},
                 {"atlantic_horizon", 30.0, -40.0, 30.0, 90.0, -2.0, 45.0},
                 {"sahara_nadir", 23.0, 10.0, 5000.0, 0.0, -90.0, 45.0},
                 {"gibraltar", 36.0, -5.5, 400000.0, 0.0, -90.0, 40.0}};

  RESOLVE(last_error, last_error_fn, "geocean_last_error");
  RESOLVE(sea_state_init, sea_state_init_fn, "geocean_sea_state_init");
  RESOLVE(set_sea_state, set_sea_state_fn, "geocean_set_sea_state");
  RESOLVE(view_init, view_init_fn, "geocean_view_init");
  RESOLVE(view_from_pose, view_from_pose_fn, "geocean_view_from_pose");
  RESOLVE(update, update_fn, "geocean_update");
  RESOLVE(draw, draw_fn, "geocean_draw");
  RESOLVE(release_gl, release_gl_fn, "geocean_release_gl");
  RESOLVE(query_class, query_class_fn, "geocean_query_class");
  crc_init();

  /* The host's own context: EGL surfaceless (Mesa), OpenGL 4.5 core. */
  dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_API)) {
    fprintf(stderr, "c_host: no EGL surfaceless display (0x%04x)\n", eglGetError());
    return 1;
  }
  ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
  if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    fprintf(stderr, "c_host: no OpenGL 4.5 context (0x%04x)\n", eglGetError());
    return 1;
  }
  glGenFramebuffers(1, &fbo);
  glGenRenderbuffers(2, rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
  glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, W, H);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    fprintf(stderr, "c_host: incomplete framebuffer\n");
    return 1;
  }
  glViewport(0, 0, W, H);

  if (sea_state_init(&sea) != GEOCEAN_OK || set_sea_state(ocean, &sea) != GEOCEAN_OK ||
      view_init(&view) != GEOCEAN_OK) {
    fprintf(stderr, "c_host: %s\n", last_error());
    return 1;
  }
  view.sun_dir_ecef[0] = 0.3, view.sun_dir_ecef[1] = -0.8, view.sun_dir_ecef[2] = 0.5;
  view.time_s = 10.0;
  for (frame = 0; frame < 4; ++frame) {
    int x, y, sea_px = 0, bg_px = 0, top_bg = 0, bottom_sea = 0, agree = 0, classified = 0, sea_mask = 0;
    if (view_from_pose(&view, frames[frame].lat, frames[frame].lon, frames[frame].height, frames[frame].heading,
                       frames[frame].pitch, frames[frame].fov, W, H) != GEOCEAN_OK) {
      fprintf(stderr, "c_host: %s\n", last_error());
      return 1;
    }
    /* The host's frame: reversed Z as geocean_view_from_pose's projection expects. */
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClearDepth(0.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    if (update(ocean, &view) != GEOCEAN_OK || draw(ocean) != GEOCEAN_OK) {
      fprintf(stderr, "c_host: %s: %s\n", frames[frame].name, last_error());
      return 1;
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    snprintf(path, sizeof path, "%s/c_host_%s.png", out_dir, frames[frame].name);
    failures += write_png(path, px);
    for (y = 0; y < H; ++y)
      for (x = 0; x < W; ++x) {
        const unsigned char* p = px + 4 * (y * W + x);
        sea_px += is_sea(p);
        bg_px += is_background(p);
        if (y >= H * 3 / 4) top_bg += is_background(p); /* y = 0 is the bottom row */
        if (y < H / 4) bottom_sea += is_sea(p);
      }
    printf("%-18s sea %5.1f %%  background %5.1f %%\n", frames[frame].name, 100.0 * sea_px / (W * H),
           100.0 * bg_px / (W * H));
    switch (frame) {
      case 0: /* open ocean under the camera: all sea */
        if (sea_px != W * H) ++failures, fprintf(stderr, "c_host: atlantic_nadir: %d pixels not sea\n", W * H - sea_px);
        break;
      case 1: /* 2 deg down at the horizon: the lower quarter is sea, the upper quarter is sky (the host's) */
        if (bottom_sea != W * H / 4) ++failures, fprintf(stderr, "c_host: horizon: lower quarter %d sea\n", bottom_sea);
        if (top_bg != W * H / 4) ++failures, fprintf(stderr, "c_host: horizon: upper quarter %d background\n", top_bg);
        break;
      case 2: /* desert: the ocean draws nothing */
        if (bg_px != W * H) ++failures, fprintf(stderr, "c_host: sahara: %d pixels drawn\n", W * H - bg_px);
        break;
      default: {
        /* Coast: every pixel against the mask's class where its ray meets the ellipsoid. */
        const double* m = view.view_matrix;
        const double tan_y = tan(0.5 * frames[frame].fov * kPi / 180.0), tan_x = tan_y * W / H;
        int n = 0;
        for (y = 0; y < H; ++y)
          for (x = 0; x < W; ++x) {
            /* eye-space direction -> ECEF through the transposed view rotation */
            const double ex = (2.0 * (x + 0.5) / W - 1.0) * tan_x, ey = (2.0 * (y + 0.5) / H - 1.0) * tan_y;
            double d[3];
            int c;
            for (c = 0; c < 3; ++c) d[c] = m[c * 4 + 0] * ex + m[c * 4 + 1] * ey - m[c * 4 + 2];
            if (!ray_to_lat_lon(view.eye_ecef_m, d, &lat[n], &lon[n])) lat[n] = 0.0, lon[n] = 0.0;
            ++n;
          }
        if (query_class(ocean, (size_t)n, lat, lon, cls) != GEOCEAN_OK) {
          fprintf(stderr, "c_host: %s\n", last_error());
          return 1;
        }
        for (y = 0; y < H; ++y)
          for (x = 0; x < W; ++x) {
            const unsigned char* p = px + 4 * (y * W + x);
            const int mask_sea = cls[y * W + x] == GEOCEAN_SURFACE_OCEAN;
            sea_mask += mask_sea;
            ++classified;
            agree += mask_sea == !is_background(p);
          }
        printf("%-18s mask sea %5.1f %%  drawn == mask at %5.2f %% of pixels\n", frames[frame].name,
               100.0 * sea_mask / classified, 100.0 * agree / classified);
        /* 400 km up, a pixel spans ~0.5 km; the 5' (9 km) mask's cells are
           blended along the shoreline over about one cell, so pixels within
           a cell of the coast may differ: the coast is ~3 % of this frame. */
        if (agree < classified * 0.96) ++failures, fprintf(stderr, "c_host: gibraltar: drawn sea disagrees with the mask\n");
        if (sea_mask < classified / 10 || sea_mask > classified * 9 / 10)
          ++failures, fprintf(stderr, "c_host: gibraltar frame is not a coast\n");
      }
    }
  }
  /* The plugin's GL objects were made in ctx: release them while it is current. */
  if (release_gl(ocean) != GEOCEAN_OK) ++failures, fprintf(stderr, "c_host: %s\n", last_error());
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(2, rb);
  eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(dpy, ctx);
  eglTerminate(dpy);
  return failures;
}
#endif

int main(int argc, char** argv) {
  abi_version_fn abi_version;
  last_error_fn last_error;
  create_fn create;
  destroy_fn destroy;
  set_default_world_fn set_default_world;
  query_class_fn query_class;
  query_elevation_fn query_elevation;
  void* lib;
  geocean_ocean* ocean = NULL;
  /* Known places: mid-Atlantic, Sahara, Lake Superior, Challenger Deep, Everest. */
  static const char* names[5] = {"Atlantic", "Sahara", "Lake Superior", "Challenger Deep", "Everest"};
  static const double lat[5] = {30.0, 23.0, 47.6, 11.35, 27.99};
  static const double lon[5] = {-40.0, 10.0, -87.5, 142.2, 86.93};
  static const uint8_t expected[5] = {GEOCEAN_SURFACE_OCEAN, GEOCEAN_SURFACE_LAND, GEOCEAN_SURFACE_LAKE,
                                      GEOCEAN_SURFACE_OCEAN, GEOCEAN_SURFACE_LAND};
  uint8_t cls[5];
  float elev[5];
  int i, failures = 0;
  uint32_t plugin_abi;
  const uint32_t host_abi = GEOCEAN_ABI_VERSION;

  if (argc != 2 && argc != 3) {
    fprintf(stderr, "usage: c_host PLUGIN.so [OUT_DIR]\n");
    return 2;
  }
  lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    fprintf(stderr, "c_host: %s\n", dlerror());
    return 1;
  }
  RESOLVE(abi_version, abi_version_fn, "geocean_abi_version");
  plugin_abi = abi_version();
  if (plugin_abi >> 16 != host_abi >> 16 || (plugin_abi & 0xffffu) < (host_abi & 0xffffu)) {
    fprintf(stderr, "c_host: plugin ABI 0x%08x, host needs 0x%08x\n", (unsigned)plugin_abi, (unsigned)host_abi);
    return 1;
  }
  RESOLVE(last_error, last_error_fn, "geocean_last_error");
  RESOLVE(create, create_fn, "geocean_create");
  RESOLVE(destroy, destroy_fn, "geocean_destroy");
  RESOLVE(set_default_world, set_default_world_fn, "geocean_set_default_world");
  RESOLVE(query_class, query_class_fn, "geocean_query_class");
  RESOLVE(query_elevation, query_elevation_fn, "geocean_query_elevation");

  if (create(GEOCEAN_ABI_VERSION, &ocean) != GEOCEAN_OK || set_default_world(ocean) != GEOCEAN_OK ||
      query_class(ocean, 5, lat, lon, cls) != GEOCEAN_OK || query_elevation(ocean, 5, lat, lon, elev) != GEOCEAN_OK) {
    fprintf(stderr, "c_host: %s\n", last_error());
    destroy(ocean);
    return 1;
  }
  for (i = 0; i < 5; ++i) {
    printf("%-16s lat %7.3f lon %8.3f class %d elevation %7.0f m\n", names[i], lat[i], lon[i], cls[i], elev[i]);
    if (cls[i] != expected[i]) {
      fprintf(stderr, "c_host: %s: class %d, expected %d\n", names[i], cls[i], expected[i]);
      ++failures;
    }
  }
  /* ETOPO at 20': the trench cell is far below -5000 m, Everest's far above 4000 m
     (the coarse cells average the extremes away, so no tighter bound). */
  if (!(elev[3] < -5000.0f)) ++failures, fprintf(stderr, "c_host: Challenger Deep at %g m\n", elev[3]);
  if (!(elev[4] > 4000.0f)) ++failures, fprintf(stderr, "c_host: Everest at %g m\n", elev[4]);
#ifdef C_HOST_RENDER
  if (argc == 3) failures += render_frames(lib, ocean, argv[2]);
#endif
  destroy(ocean);
  dlclose(lib);
  return failures == 0 ? 0 : 1;
}
