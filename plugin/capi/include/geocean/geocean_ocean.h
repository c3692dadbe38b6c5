/* Geocean ocean plugin: the whole public surface, as C99.
 *
 * A host engine loads libgeocean_ocean.so (dlopen or link), checks the ABI
 * version, creates an ocean, gives it rasters (mask, elevation) and a sea
 * state, and queries the sea surface. Nothing C++ crosses this boundary.
 *
 * Conventions
 *   - Every function returning geocean_status returns GEOCEAN_OK (0) on
 *     success; on failure a status and a message for the calling thread,
 *     read with geocean_last_error(). Every call that returns a status clears
 *     the calling thread's message first.
 *   - Angles are degrees, lengths metres, times seconds (names say so).
 *     Simulation times are within -1e12 .. 1e12 s (31,700 years either
 *     way; Unix-epoch seconds fit): beyond, a wave's phase w t has no
 *     precision left, and every call taking a time refuses it with
 *     INVALID_ARGUMENT naming the field and the value.
 *     Latitude/longitude are geodetic on WGS84, in double.
 *   - Thread safety: see each function. In short: create/destroy and the
 *     setters may be called from any thread; queries may run from any
 *     number of threads at once, also while a setter runs on another thread
 *     (a query sees the state before or after the setter, never a mix);
 *     destroy must not overlap any other call on the same ocean.
 *
 *   - Rendering (ABI 1.1): geocean_update and geocean_draw run on the
 *     host's render thread, never overlapping each other, geocean_release_gl
 *     or geocean_destroy; queries and setters may run on other threads
 *     meanwhile. GL resources belong to the context current at the first
 *     draw.
 *   - Floating bodies (ABI 1.4): a geocean_bodies simulation belongs to one
 *     ocean; its calls may run on any thread, concurrently with that
 *     ocean's queries, setters and drawing (a step reads the sea state of
 *     one snapshot). Calls on one geocean_bodies are serialised inside
 *     (poses are read before or after a step, never within one).
 *
 * Full reference: docs/PLUGIN_ABI.md. */
#ifndef GEOCEAN_OCEAN_H
#define GEOCEAN_OCEAN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(GEOCEAN_OCEAN_BUILD)
#define GEOCEAN_API __attribute__((visibility("default")))
#else
#define GEOCEAN_API
#endif

/* ABI version: MAJOR changes break compatibility; MINOR adds functions.
 * A host built against MAJOR.MINOR runs with a plugin of the same MAJOR and
 * a MINOR at least as high. */
#define GEOCEAN_ABI_VERSION_MAJOR 1
#define GEOCEAN_ABI_VERSION_MINOR 8
#define GEOCEAN_ABI_VERSION ((uint32_t)((GEOCEAN_ABI_VERSION_MAJOR << 16) | GEOCEAN_ABI_VERSION_MINOR))

/* Enums that cross the boundary as values have int32_t as their C++
 * underlying type: an enum without a fixed type may hold only its
 * enumerators' bit range in C++, so a host passing another value (say
 * georef 7) would be undefined behaviour inside the plugin before it could
 * be rejected. C keeps the plain enum, which GCC and Clang pass as the same
 * 4-byte integer, so the ABI is unchanged. */
#ifdef __cplusplus
#define GEOCEAN_ENUM_INT32 : int32_t
#else
#define GEOCEAN_ENUM_INT32
#endif

typedef enum geocean_status GEOCEAN_ENUM_INT32 {
  GEOCEAN_OK = 0,
  GEOCEAN_ERROR_NULL_ARGUMENT = 1,    /* a required pointer or handle was NULL */
  GEOCEAN_ERROR_INVALID_ARGUMENT = 2, /* a value out of range (the message names it) */
  GEOCEAN_ERROR_ABI_VERSION = 3,      /* the host's ABI version is not served by this plugin */
  GEOCEAN_ERROR_RASTER = 4,           /* a raster could not be opened or read (message names the file) */
  GEOCEAN_ERROR_NOT_READY = 5,        /* called in the wrong order: a prerequisite is missing */
  GEOCEAN_ERROR_NO_GL_CONTEXT = 6,    /* no OpenGL context is current on the calling thread */
  GEOCEAN_ERROR_GL = 7,               /* OpenGL failed (shader compile, missing extension) */
  GEOCEAN_ERROR_OUT_OF_MEMORY = 8,
  GEOCEAN_ERROR_INTERNAL = 9          /* a bug: please report the message */
} geocean_status;

/* Surface classes returned by the class queries. */
typedef enum geocean_surface {
  GEOCEAN_SURFACE_OCEAN = 0,
  GEOCEAN_SURFACE_LAND = 1,
  GEOCEAN_SURFACE_LAKE = 2
} geocean_surface;

/* How a raster file is placed on the Earth. */
typedef enum geocean_georef GEOCEAN_ENUM_INT32 {
  GEOCEAN_GEOREF_FROM_FILE = 0,       /* GeoTIFF tags, or a world file beside a PNG/JPEG */
  GEOCEAN_GEOREF_GLOBAL_EQUIRECT = 1  /* whole Earth, north up, column 0 starts at -180 */
} geocean_georef;

/* Placement of a raster given from memory. Pixel (i, j) covers
 * [i, i+1) x [j, j+1) in pixel space; pixel-space (0, 0) is at
 * (origin_lat_deg, origin_lon_deg). */
typedef struct geocean_grid_placement {
  double origin_lon_deg; /* longitude of the left edge of column 0 */
  double origin_lat_deg; /* latitude of the top edge of row 0 */
  double lon_step_deg;   /* degrees per column, > 0 */
  double lat_step_deg;   /* degrees per row, != 0 (< 0: north up) */
  int32_t global;        /* non-zero: the columns span 360 degrees and longitude wraps */
  int32_t has_nodata;    /* non-zero: pixels equal to nodata mean "no data" */
  double nodata;
} geocean_grid_placement;

/* Wave models (docs/ARCHITECTURE.md, plugin/waves). */
typedef enum geocean_wave_model {
  GEOCEAN_WAVES_NOISE = 0,       /* solid fractal noise on the 3D surface point (default) */
  GEOCEAN_WAVES_NOISE_PAPER = 1, /* paper 002's 2D noise at (lon cos(lat), lat); has a seam at 180 deg */
  GEOCEAN_WAVES_GERSTNER = 2,    /* trochoidal waves from the sea spectrum, depth-aware */
  GEOCEAN_WAVES_FFT = 3          /* ABI 1.1: Tessendorf FFT ocean (paper 001), 2 cascades, choppy */
} geocean_wave_model;

/* The sea state. Fill with geocean_sea_state_init() first, then change
 * fields: struct_size lets later minor versions append fields. */
typedef struct geocean_sea_state {
  uint32_t struct_size;        /* sizeof(geocean_sea_state), set by geocean_sea_state_init */
  int32_t model;               /* a geocean_wave_model */
  double wind_speed_mps;       /* at 19.5 m (Pierson-Moskowitz reference height), 0.2 .. 60 */
  double wind_from_deg;        /* direction the wind blows FROM, clockwise from north */
  double fetch_m;              /* 0: fully developed sea (Pierson-Moskowitz); >= 1 m: JONSWAP */
  uint32_t seed;               /* same seed, same sea */
  int32_t gerstner_components; /* 1 .. 64 */
  int32_t noise_octaves;       /* 1 .. 12 */
  double anchor_lat_deg;       /* where wind_from_deg holds exactly (Gerstner waves follow great circles) */
  double anchor_lon_deg;
  double reference_depth_m;    /* depth setting Gerstner wave numbers, >= 0.01 m; 1e30 = deep water */
} geocean_sea_state;

typedef struct geocean_ocean geocean_ocean; /* opaque */

/* ---- Version and errors ------------------------------------------------ */

/* The plugin's GEOCEAN_ABI_VERSION. Thread-safe; callable before anything. */
GEOCEAN_API uint32_t geocean_abi_version(void);
/* "MAJOR.MINOR.PATCH" of the Geocean release. Thread-safe; static string. */
GEOCEAN_API const char* geocean_version_string(void);
/* The message of the calling thread's last failed call ("" if the last call
 * succeeded). Valid until the thread's next geocean_* call. Never NULL. */
GEOCEAN_API const char* geocean_last_error(void);
/* A static name for a status, e.g. "GEOCEAN_ERROR_RASTER". Never NULL. */
GEOCEAN_API const char* geocean_status_string(geocean_status status);

/* ---- Lifetime ----------------------------------------------------------- */

/* Creates an ocean with no rasters and no sea state. host_abi_version: pass
 * GEOCEAN_ABI_VERSION from the header the host was built with.
 * Errors: NULL_ARGUMENT (out), ABI_VERSION. *out is NULL on failure. */
GEOCEAN_API geocean_status geocean_create(uint32_t host_abi_version, geocean_ocean** out);
/* Destroys an ocean; NULL is allowed and ignored. Must not overlap any other
 * call on the same ocean. */
GEOCEAN_API void geocean_destroy(geocean_ocean* ocean);

/* ---- Rasters ------------------------------------------------------------ */

/* Land/sea mask from a raster file: values 0 ocean, 1 land, 2 lake (other
 * values land). Replaces the previous mask. Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (georef), RASTER (missing, unreadable or not
 * georeferenced file; the message names the file and the field). */
GEOCEAN_API geocean_status geocean_set_mask_file(geocean_ocean* ocean, const char* path, geocean_georef georef);
/* Terrain elevation in metres (ocean depth negative) from a raster file.
 * Errors as geocean_set_mask_file. */
GEOCEAN_API geocean_status geocean_set_elevation_file(geocean_ocean* ocean, const char* path,
                                                      geocean_georef georef);
/* The same from memory: width x height floats, row-major, copied. Errors:
 * NULL_ARGUMENT, INVALID_ARGUMENT (size, placement). */
GEOCEAN_API geocean_status geocean_set_mask_pixels(geocean_ocean* ocean, const float* values, int32_t width,
                                                   int32_t height, const geocean_grid_placement* placement);
GEOCEAN_API geocean_status geocean_set_elevation_pixels(geocean_ocean* ocean, const float* values_m,
                                                        int32_t width, int32_t height,
                                                        const geocean_grid_placement* placement);
/* Loads Geocean's default world (5' mask, 20' ETOPO elevation) from
 * $GEOCEAN_DATA, else <prefix>/share/geocean/data beside the installed
 * library, else the build's data directory. Errors: NULL_ARGUMENT, RASTER. */
GEOCEAN_API geocean_status geocean_set_default_world(geocean_ocean* ocean);
/* Removes both rasters. Errors: NULL_ARGUMENT. */
GEOCEAN_API geocean_status geocean_clear_rasters(geocean_ocean* ocean);

/* ABI 1.2: how a raster file is read. Fill with
 * geocean_raster_options_init() first (struct_size lets later minor
 * versions append fields). */
typedef struct geocean_raster_options {
  uint32_t struct_size; /* sizeof(geocean_raster_options), set by geocean_raster_options_init */
  int32_t georef;       /* a geocean_georef */
  int32_t few_lookups;  /* non-zero: read only the tiles lookups touch (tiled TIFF), for a handful of
                           points (what `geocean query LAT LON` does); 0: decode into memory */
} geocean_raster_options;

/* ABI 1.2: fills *options with GEOCEAN_GEOREF_FROM_FILE and few_lookups 0.
 * Errors: NULL_ARGUMENT. Thread-safe. */
GEOCEAN_API geocean_status geocean_raster_options_init(geocean_raster_options* options);
/* ABI 1.2: geocean_set_mask_file, geocean_set_elevation_file and
 * geocean_set_default_world with read options. Errors as those, and
 * INVALID_ARGUMENT (options->struct_size, options->georef). */
GEOCEAN_API geocean_status geocean_set_mask_file_with_options(geocean_ocean* ocean, const char* path,
                                                              const geocean_raster_options* options);
GEOCEAN_API geocean_status geocean_set_elevation_file_with_options(geocean_ocean* ocean, const char* path,
                                                                   const geocean_raster_options* options);
GEOCEAN_API geocean_status geocean_set_default_world_with_options(geocean_ocean* ocean,
                                                                  const geocean_raster_options* options);
/* ABI 1.2: how mask values map to classes, e.g. "0=ocean,1=land,2=lake"
 * (the default; NULL or "" restores it). Values 0..255; a value not listed,
 * and every value >= 256, is land. Applies to the current and later masks.
 * Errors: NULL_ARGUMENT (ocean), INVALID_ARGUMENT (the message names the
 * bad item); the previous encoding stays. */
GEOCEAN_API geocean_status geocean_set_mask_encoding(geocean_ocean* ocean, const char* spec);

/* ---- Raster layers (ABI 1.3) -------------------------------------------
 * Masks and elevations stacked over the rasters the setters above give (the
 * base, e.g. the default world). At each point the first layer with data
 * answers the class and the elevation: higher priority first, then the
 * finer cell, then the order of adding; the base answers last. Masks
 * classify by their own encoding, elevation layers by sign (below 0 m
 * ocean), so a user's relief finer than every mask decides land and sea
 * there. Nodata (the file's GDAL_NODATA, or a placement's) is "no data
 * here": the next layer answers. A layer is named by its path (files) or
 * the name given (memory); a kind holds each name once. */

/* ABI 1.3: adds a mask layer from a file. priority: any value above
 * INT32_MIN (the base's); 0 is the usual. encoding: as
 * geocean_set_mask_encoding, NULL or "" for the default. options: NULL for
 * the defaults. Errors: NULL_ARGUMENT (ocean, path), INVALID_ARGUMENT
 * (priority, encoding, options, a mask layer of this path already added),
 * RASTER (the message names the file). The previous state stays on error. */
GEOCEAN_API geocean_status geocean_add_mask_layer_file(geocean_ocean* ocean, const char* path, int32_t priority,
                                                       const char* encoding, const geocean_raster_options* options);
/* ABI 1.3: adds an elevation layer (metres) from a file. Errors as
 * geocean_add_mask_layer_file. */
GEOCEAN_API geocean_status geocean_add_elevation_layer_file(geocean_ocean* ocean, const char* path,
                                                            int32_t priority, const geocean_raster_options* options);
/* ABI 1.3: the same from memory (width x height floats, row-major, copied),
 * named `name` for geocean_remove_layer. Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (size, placement, priority, encoding, name in use). */
GEOCEAN_API geocean_status geocean_add_mask_layer_pixels(geocean_ocean* ocean, const char* name, const float* values,
                                                         int32_t width, int32_t height,
                                                         const geocean_grid_placement* placement, int32_t priority,
                                                         const char* encoding);
GEOCEAN_API geocean_status geocean_add_elevation_layer_pixels(geocean_ocean* ocean, const char* name,
                                                              const float* values_m, int32_t width, int32_t height,
                                                              const geocean_grid_placement* placement,
                                                              int32_t priority);
/* ABI 1.3: removes the layers (of either kind) named `path`; *out_removed
 * (may be NULL) gets how many, 0 when none was. Errors: NULL_ARGUMENT
 * (ocean, path). */
GEOCEAN_API geocean_status geocean_remove_layer(geocean_ocean* ocean, const char* path, size_t* out_removed);
/* ABI 1.3: removes every layer (the base stays). Errors: NULL_ARGUMENT. */
GEOCEAN_API geocean_status geocean_clear_layers(geocean_ocean* ocean);
/* ABI 1.3: how many layers are added (the base not counted). Errors:
 * NULL_ARGUMENT. */
GEOCEAN_API geocean_status geocean_layer_count(const geocean_ocean* ocean, size_t* out_count);

/* ---- Queries (thread-safe, any number of threads) ----------------------- */

/* Surface class at count points. Needs a mask or an elevation raster.
 * out_class: count bytes of geocean_surface. count 0 is allowed (pointers
 * may then be NULL). Errors: NULL_ARGUMENT, NOT_READY (no raster). */
GEOCEAN_API geocean_status geocean_query_class(const geocean_ocean* ocean, size_t count, const double* lat_deg,
                                               const double* lon_deg, uint8_t* out_class);
/* Terrain elevation (m, bilinear; NaN where no data) at count points.
 * Errors: NULL_ARGUMENT, NOT_READY (no elevation raster). */
GEOCEAN_API geocean_status geocean_query_elevation(const geocean_ocean* ocean, size_t count,
                                                   const double* lat_deg, const double* lon_deg,
                                                   float* out_elevation_m);

/* ---- Sea state and sea-surface queries ---------------------------------- */

/* Fills *sea_state with the defaults (noise model, 10 m/s from 270 deg,
 * fully developed, seed 1, 16 Gerstner components, 8 noise octaves, anchor
 * at (0, 0), deep water). Errors: NULL_ARGUMENT. Thread-safe. */
GEOCEAN_API geocean_status geocean_sea_state_init(geocean_sea_state* sea_state);
/* Sets wind_speed_mps for a Beaufort number 0..12 (middle of the WMO class
 * at 10 m, converted to 19.5 m); other fields untouched. Errors:
 * NULL_ARGUMENT, INVALID_ARGUMENT (beaufort). Thread-safe. */
GEOCEAN_API geocean_status geocean_sea_state_set_beaufort(geocean_sea_state* sea_state, int32_t beaufort);
/* Sets the sea state, replacing the previous one. Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (struct_size, model or a field out of range: the message
 * names the field and the value); the previous sea state stays. */
GEOCEAN_API geocean_status geocean_set_sea_state(geocean_ocean* ocean, const geocean_sea_state* sea_state);

/* The displaced sea surface exactly above count points at simulation time
 * time_s (seconds; the same t always gives the same surface):
 *   out_height_m[i]      height above the WGS84 ellipsoid (m) of the surface
 *                        above the point (horizontal displacement inverted to
 *                        0.1 mm); NaN on land and lakes.
 *   out_normal_enu[3i..] unit normal, east-north-up at the point; NaN on land
 *                        and lakes. May be NULL.
 *   out_class[i]         geocean_surface. May be NULL.
 * Classes and water depth come from the rasters; with none, every point is
 * deep ocean. Depth is -elevation, at least 1 m where the mask says ocean
 * (coarse relief and mask disagree along coasts). Large batches run on all
 * cores. Needs a sea state.
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (time_s not finite or outside
 * -1e12 .. 1e12 s), NOT_READY (no sea state). */
GEOCEAN_API geocean_status geocean_query_sea_surface(const geocean_ocean* ocean, size_t count,
                                                     const double* lat_deg, const double* lon_deg, double time_s,
                                                     double* out_height_m, double* out_normal_enu,
                                                     uint8_t* out_class);
/* ABI 1.2: what geocean_query_surface writes. Every array may be NULL (not
 * computed unless another needs it); count entries unless said otherwise.
 * Fill with geocean_surface_outputs_init() first, then set the arrays:
 * struct_size lets later minor versions append outputs. */
typedef struct geocean_surface_outputs {
  uint32_t struct_size;               /* sizeof(geocean_surface_outputs), set by the init */
  uint8_t* surface_class;             /* geocean_surface */
  float* elevation_m;                 /* terrain, m (ocean depth negative); NaN without elevation data */
  double* height_m;                   /* sea surface above the WGS84 ellipsoid exactly above the point, m */
  double* normal_enu;                 /* 3 x count: unit normal, east-north-up at the point */
  double* vertical_velocity_mps;      /* d(height_m)/dt at the fixed point, m/s */
  double* horizontal_velocity_en_mps; /* 2 x count (east, north): velocity of the water particle now at
                                         the surface above the point, m/s */
} geocean_surface_outputs;

/* ABI 1.2: sets struct_size and every array to NULL. Errors: NULL_ARGUMENT.
 * Thread-safe. */
GEOCEAN_API geocean_status geocean_surface_outputs_init(geocean_surface_outputs* outputs);
/* ABI 1.2: class, elevation and the sea surface at count points in one
 * pass, exactly what `geocean query` prints. time_s: time_count values, 1
 * (one time for every point) or count (one per point); may be NULL with
 * time_count 0 when no sea output (height .. horizontal velocity) is asked
 * for. Sea outputs are NaN on land and lakes, and off the globe (|lat| > 90,
 * |lon| > 360, NaN). Without rasters every point
 * is deep ocean (elevation NaN). Large batches run on all cores.
 * Errors: NULL_ARGUMENT (ocean, outputs; lat_deg, lon_deg, time_s when
 * needed and count > 0), INVALID_ARGUMENT (outputs->struct_size,
 * time_count, a time not finite or outside -1e12 .. 1e12 s: the message
 * names its index), NOT_READY
 * (a sea output without a sea state). */
GEOCEAN_API geocean_status geocean_query_surface(const geocean_ocean* ocean, size_t count, const double* lat_deg,
                                                 const double* lon_deg, const double* time_s, size_t time_count,
                                                 const geocean_surface_outputs* outputs);

/* Significant wave height (m) of the current sea state's spectrum, 4 sqrt(m0).
 * Errors: NULL_ARGUMENT, NOT_READY (no sea state). */
GEOCEAN_API geocean_status geocean_significant_wave_height(const geocean_ocean* ocean, double* out_hs_m);

/* ABI 1.5: the sea state at count points, at each point's water depth (the
 * columns hs_m, peak_period_s, peak_wavelength_m, wave_from_deg of
 * `geocean query`): significant wave height (m), peak period (s), peak
 * wavelength (m), direction the waves come FROM (degrees clockwise from
 * north, [0, 360)). NaN where the point is not ocean (land, lakes). Every
 * output may be NULL (not written). Runs on all cores. Errors:
 * NULL_ARGUMENT (lat_deg, lon_deg when count > 0), NOT_READY (no sea state). */
GEOCEAN_API geocean_status geocean_query_sea_state(const geocean_ocean* ocean, size_t count, const double* lat_deg,
                                                   const double* lon_deg, double* out_hs_m,
                                                   double* out_peak_period_s, double* out_peak_wavelength_m,
                                                   double* out_wave_from_deg);

/* Since ABI 1.5: the near-shore region of interest (issue 15; `geocean query
 * --coast-region LAT,LON,SIZE_M`): a square of size_m (500 .. 40000 m) on
 * the tangent plane at (lat_deg, lon_deg) where a Gerstner sea's waves take
 * the local depth's wavelength and turn by refraction (from the rasters'
 * water depth, rebuilt when rasters or sea state change). Queries and the
 * draw both use it. Replaces a previous region; a later sea state of
 * another model leaves it without effect until a Gerstner one is set.
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (a value not finite or out of
 * range, or the current sea state is not GEOCEAN_WAVES_GERSTNER: the
 * message names it); the previous region stays. */
GEOCEAN_API geocean_status geocean_set_coast_region(geocean_ocean* ocean, double lat_deg, double lon_deg,
                                                    double size_m);
/* Since ABI 1.5: removes the region (deep-water phase everywhere again).
 * No region is not an error. Errors: NULL_ARGUMENT. */
GEOCEAN_API geocean_status geocean_clear_coast_region(geocean_ocean* ocean);

/* ---- Rendering (ABI 1.1) ------------------------------------------------ */

/* The host's camera for one frame. Fill with geocean_view_init() (or
 * geocean_view_from_pose()) first, then change fields: struct_size lets
 * later minor versions append fields. Matrices are column-major as in
 * OpenGL (element (row r, column c) at [4 c + r]). */
typedef struct geocean_view {
  uint32_t struct_size;          /* sizeof(geocean_view), set by geocean_view_init */
  double eye_ecef_m[3];          /* the eye, ECEF metres: double keeps mm at 6400 km */
  double view_matrix[16];        /* ECEF -> eye space (looking down -z, y up). Only its
                                    rotation (upper 3x3, orthonormal, right-handed) is read:
                                    the position is eye_ecef_m, so a float-precision
                                    translation never costs precision */
  double projection_matrix[16];  /* eye -> clip space, a symmetric perspective with aspect
                                    viewport_width_px / viewport_height_px (within 0.1 %).
                                    The ocean is drawn with exactly this matrix, so its depth
                                    agrees with the host's own geometry */
  int32_t viewport_width_px;     /* the viewport the host draws into, 1 .. 16384 */
  int32_t viewport_height_px;
  double time_s;                 /* simulation time, -1e12 .. 1e12 s; the same t gives the same sea as the queries */
  double sun_dir_ecef[3];        /* towards the sun (any length > 0) */
  uint32_t draw_flags;           /* GEOCEAN_DRAW_* bits, 0 by default */
} geocean_view;

/* geocean_view.draw_flags: the same geometry with a flat colour, the
 * reference a host times the full shading against. */
#define GEOCEAN_DRAW_REFERENCE 1u
/* Draw the water without what is seen through it (the bottom,
 * refracted and absorbed): the depth-tinted colour alone (--no-refraction).
 * Since ABI 1.5: a plugin built before it rejects the bit
 * (INVALID_ARGUMENT naming draw_flags). */
#define GEOCEAN_DRAW_NO_REFRACTION 2u
/* A single picture: where the ocean draws a streamed mask's coverage from
 * tiles (a layer's global mask finer than its water grid, issue 12), the
 * draw first waits (bounded) for the tiles its view asks for instead of
 * drawing their coarser ancestors. Views leave it off: they never wait.
 * ABI 1.6 (first shipped inside a 1.5 build; a 1.5 plugin rejects the
 * bit with INVALID_ARGUMENT naming draw_flags). */
#define GEOCEAN_DRAW_COMPLETE_TILES 4u
/* The coast region (geocean_set_coast_region) follows the camera: at each
 * geocean_update with this bit, when the camera's nadir is more than a
 * quarter of the region's size from its centre (east or north), a region
 * of the same size centred on the nadir is built on a worker thread; the
 * old one serves queries and the draw until a later geocean_update
 * publishes the finished one for both at once. The update never waits for
 * the build. ABI 1.7 (a 1.6 plugin rejects the bit with INVALID_ARGUMENT
 * naming draw_flags). */
#define GEOCEAN_DRAW_FOLLOW_COAST 8u

/* ABI 1.7: the ocean's screen grid from paper 000's improved spherical
 * projected grid (ISPG: the tangent plane under the eye, mapped radially
 * onto the ellipsoid) instead of the default direct projector (each vertex's
 * ray meets the ellipsoid), for comparing the two; a 1.6 plugin rejects the
 * bit (INVALID_ARGUMENT naming draw_flags). */
#define GEOCEAN_DRAW_GRID_ISPG 16u

/* ABI 1.8: the sun's specular on the water from paper 001's Phong term
 * (eq. 19: k_s I cos^n(phi), phi between the mirrored view ray and the
 * sun, n = 1 / (2 mss) of the slopes not drawn, k_s = F (n + 2) / 2 pi)
 * instead of the default microfacet glitter (Cox-Munk slopes). A 1.7
 * plugin rejects the bit (INVALID_ARGUMENT naming draw_flags). */
#define GEOCEAN_DRAW_SUN_PHONG 32u
/* ABI 1.8: in the sun's shadow (geocean_layer_inputs' shadow map), paper
 * 001's darkening: the shadowed pixel times 0.5. Without it (default) the
 * sun's direct light is removed there (glitter, sun-lit water body,
 * subsurface light, sun-lit foam) and the sky's light stays. A 1.7 plugin
 * rejects the bit. */
#define GEOCEAN_DRAW_SHADOW_PAPER 64u

/* Fills *view with defaults: struct_size, a 1280x720 view 10,000 km above
 * (0 N, 0 E) looking down, 45 deg field of view, reversed-Z projection,
 * time 0, sun over (0 N, 0 E). Errors: NULL_ARGUMENT. Thread-safe. */
GEOCEAN_API geocean_status geocean_view_init(geocean_view* view);
/* Fills the camera fields of *view (eye, matrices, viewport) from a geodetic
 * pose, the way Geocean's own viewer does: heading clockwise from north,
 * pitch up from the horizontal (-90 = straight down), vertical field of
 * view, and a REVERSED-Z projection with an infinite far plane for
 * glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): clear depth to 0 and test
 * with GL_GREATER. time_s and sun_dir_ecef are untouched. Errors:
 * NULL_ARGUMENT, INVALID_ARGUMENT (a value not finite or out of range:
 * |lat| <= 90, fov 1 .. 170, viewport 1 .. 16384; the message names it).
 * Thread-safe. */
GEOCEAN_API geocean_status geocean_view_from_pose(geocean_view* view, double lat_deg, double lon_deg,
                                                  double height_m, double heading_deg, double pitch_deg,
                                                  double fov_y_deg, int32_t width_px, int32_t height_px);
/* Sets the camera and time of the next geocean_draw. Needs no GL context.
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (struct_size, a non-finite value,
 * a view rotation that is not orthonormal, a projection that is not a
 * symmetric perspective or does not match the viewport's aspect, a zero
 * sun direction: the message names the field); the previous view stays. */
GEOCEAN_API geocean_status geocean_update(geocean_ocean* ocean, const geocean_view* view);
/* Draws the ocean into the framebuffer bound in the calling thread's current
 * OpenGL (4.5 core) context, with the host's viewport, depth test and depth
 * buffer as they are set. On the first draw (and after rasters or sea state
 * change) the plugin creates its GL resources in that context. Every GL
 * state the draw changes is restored before it returns (see
 * docs/PLUGIN_ABI.md for the list). Errors: NULL_ARGUMENT, NO_GL_CONTEXT (no
 * EGL or GLX context current), NOT_READY (no geocean_update yet, or no sea
 * state), GL (context older than 4.5, a shader failed to build, or the
 * resources belong to another context: call geocean_release_gl there
 * first). */
GEOCEAN_API geocean_status geocean_draw(geocean_ocean* ocean);
/* Deletes the GL resources; call with the context of the first draw
 * current. Nothing to release is not an error. Errors: NULL_ARGUMENT,
 * NO_GL_CONTEXT, GL (a different context is current). geocean_destroy also
 * releases them when that context is current; otherwise it leaves them to
 * the context (they are freed when the host destroys it). */
GEOCEAN_API geocean_status geocean_release_gl(geocean_ocean* ocean);

/* ---- The host/layer contract (since ABI 1.2) ----------------------------
 * A host that draws the ocean as a layer over its own terrain asks it what it
 * covers (instead of assuming), so the host may leave out terrain under
 * opaque water, and which extra inputs its draw wants. */
#define GEOCEAN_LAYER_OPAQUE_WATER 1u       /* geocean_covers_opaquely answers */
#define GEOCEAN_LAYER_WANTS_REFLECTION 2u   /* sky and terrain mirrored in the sea plane */
#define GEOCEAN_LAYER_WANTS_SCENE_COPY 4u   /* the scene's colour and depth before the ocean */
/* ABI 1.8: the sun's depth map of what casts shadows onto the water near
 * the eye (terrain, floating bodies): geocean_layer_inputs' shadow_* fields.
 * A 1.2-1.7 host ignores the bit and gives none: the water is then unshadowed. */
#define GEOCEAN_LAYER_WANTS_SHADOW_MAP 8u
typedef struct geocean_layer_info {
  uint32_t struct_size; /* sizeof(geocean_layer_info), set by the caller */
  uint32_t flags;       /* GEOCEAN_LAYER_* */
  double cell_px;       /* the ocean's grid cell on screen, pixels */
} geocean_layer_info;
/* Fills *out (set out->struct_size first). Needs no GL context. Errors:
 * NULL_ARGUMENT, INVALID_ARGUMENT (struct_size too small). */
GEOCEAN_API geocean_status geocean_get_layer_info(const geocean_ocean* ocean, geocean_layer_info* out);
/* *out_covers = 1 when the ocean draws every pixel over the rectangle
 * [lat0, lat1] x [lon0, lon1] (degrees) opaquely, for pixels whose footprint
 * on the surface there is up to pixel_footprint_m metres; 0 otherwise (also
 * without rasters). Builds the ocean's water grids on first use (no GL).
 * Render thread (same rule as geocean_draw). Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (a non-finite value, footprint <= 0). */
GEOCEAN_API geocean_status geocean_covers_opaquely(geocean_ocean* ocean, double lat0_deg, double lat1_deg,
                                                   double lon0_deg, double lon1_deg, double pixel_footprint_m,
                                                   int32_t* out_covers);
/* Inputs the host made for the next geocean_draw when the layer info asked
 * for them: GL texture names in the draw's context (0 = not given) and, for
 * the reflection, the mirrored camera it was drawn with (as a geocean_view:
 * project mirrored points with its matrices). */
typedef struct geocean_layer_inputs {
  uint32_t struct_size;              /* sizeof(geocean_layer_inputs) */
  uint32_t reflection_color_texture; /* RGBA8, reflection_view's size */
  uint32_t scene_color_texture;      /* RGBA8 copy of the scene before the ocean */
  uint32_t scene_depth_texture;      /* DEPTH32F copy, reversed Z */
  geocean_view reflection_view;      /* valid with reflection_color_texture */
  /* ABI 1.8 (read only when struct_size covers them; a 1.7 host's shorter
   * struct is accepted and draws without shadows): the sun's depth map. */
  uint32_t shadow_depth_texture;     /* DEPTH32F (or any depth format), square, 0 = none; REVERSED:
                                        1 nearest the sun, cleared to 0 (nothing) */
  uint32_t shadow_size_px;           /* its side, 1 .. 16384 */
  double shadow_origin_ecef_m[3];    /* the origin shadow_matrix's positions are relative to */
  double shadow_matrix[16];          /* (ECEF - origin) -> clip: x, y in -1..1 over the map, z its
                                        depth in 0..1 (orthographic along the sun); column-major */
  double shadow_reach_m;             /* the map covers the sea out to this distance from the eye */
} geocean_layer_inputs;
/* Sets (or with NULL clears) the inputs of the next draws. Call with the
 * draw's context current when a texture name is non-zero. Errors:
 * NULL_ARGUMENT, INVALID_ARGUMENT (struct_size, a name that is not a
 * texture of the current context, a bad reflection_view), NO_GL_CONTEXT. */
GEOCEAN_API geocean_status geocean_set_layer_inputs(geocean_ocean* ocean, const geocean_layer_inputs* inputs);

/* ---- Floating bodies (ABI 1.4) -----------------------------------------
 * Rigid bodies on WGS84 that float on this ocean's sea (plugin/bodies: the
 * hull clipped against the surface geocean_query_sea_surface gives and
 * geocean_draw draws), stepped at a fixed step: the state at time t is the
 * same whatever times the host advanced through. Thread rules: every
 * function may be called from any thread, also while the ocean's queries,
 * setters, geocean_update or geocean_draw run on other threads; calls on
 * one geocean_bodies are serialised by a lock inside (a pose read waits for
 * a step to end). geocean_bodies_destroy must not overlap another call on
 * the same bodies, and the bodies must be destroyed before their ocean. */
typedef struct geocean_bodies geocean_bodies; /* opaque */
typedef uint64_t geocean_body_id;             /* 1, 2, ...; never reused by one geocean_bodies */

typedef enum geocean_hull GEOCEAN_ENUM_INT32 {
  GEOCEAN_HULL_BOX = 0,      /* size_m: length (x, bow), beam (y), height (z) */
  GEOCEAN_HULL_CYLINDER = 1, /* vertical axis; size_m: radius, height (third unused) */
  GEOCEAN_HULL_BOAT = 2      /* 242-triangle displacement hull; size_m[0]: length (beam L/3.5, depth L/8) */
} geocean_hull;

/* A simulation's settings. Fill with geocean_bodies_config_init() first. */
typedef struct geocean_bodies_config {
  uint32_t struct_size;       /* sizeof(geocean_bodies_config), set by the init */
  double step_s;              /* fixed step, s: > 0, <= 0.5 (default 1/60) */
  double start_s;             /* simulation time of the initial states, -1e12 .. 1e12 s (default 0) */
  double water_density_kg_m3; /* default 1025 */
  /* ABI 1.6 (read only when struct_size covers it; a 1.4/1.5 host's shorter
   * struct gets 0): repulsion between bodies (paper 000 eq. 3-4, F_c), N per
   * m of overlap of the spheres along each hull (ceil(L/B) spheres of radius
   * B/2 on its centre line), acting at the spheres' centres; finite, >= 0;
   * 0 (default): bodies pass through each other. */
  double repulsion_stiffness_n_per_m;
} geocean_bodies_config;

/* The forces of the water on a body (ABI 1.6). */
typedef enum geocean_body_forces GEOCEAN_ENUM_INT32 {
  GEOCEAN_BODY_FORCES_HULL = 0,          /* the hull mesh clipped against the sea every step (default) */
  GEOCEAN_BODY_FORCES_CONTACT_POINTS = 1 /* paper 000 eq. 3-4: 4 x 2 points of a hollow-cylinder proxy */
} geocean_body_forces;

/* A body to add. Fill with geocean_body_desc_init() first. The body starts
 * upright at rest, floating at its still-water draft (centre of mass at
 * -resting waterline above the ellipsoid), bow towards heading_deg. */
typedef struct geocean_body_desc {
  uint32_t struct_size;  /* sizeof(geocean_body_desc), set by the init */
  int32_t hull;          /* a geocean_hull (default BOAT) */
  double size_m[3];      /* see geocean_hull (default boat of 20 m) */
  double density_kg_m3;  /* of the homogeneous solid hull: > 0, below the water density (default 500) */
  double lat_deg, lon_deg;
  double heading_deg;    /* bow, clockwise from north (default 0) */
  double thrust_n;       /* engine force along the bow, N (default 0) */
  /* ABI 1.6 (read only when struct_size covers it; a 1.4/1.5 host's shorter
   * struct gets HULL): a geocean_body_forces. CONTACT_POINTS: the proxy of
   * length L (the hull's) and radius R = min(B/2, H) (beam B, height H),
   * mass density x pi R^2 L, isotropic inertia (paper eq. 2); it starts at
   * the proxy's own draft. */
  int32_t forces;
} geocean_body_desc;

/* One body's state. Orientation rotates body vectors (x bow, y port, z up)
 * into ECEF: v_ecef = q v_body q*, q = (w, x, y, z). */
typedef struct geocean_body_pose {
  geocean_body_id id;
  double position_ecef_m[3];    /* centre of mass */
  double orientation_wxyz[4];   /* unit quaternion, body -> ECEF */
  double velocity_ecef_mps[3];
  double angular_velocity_body_rps[3];
  double lat_deg, lon_deg, height_m; /* centre of mass, geodetic on WGS84 */
} geocean_body_pose;

/* ABI 1.4: fills *config with the defaults (1.6: repulsion 0). Errors: NULL_ARGUMENT. Thread-safe. */
GEOCEAN_API geocean_status geocean_bodies_config_init(geocean_bodies_config* config);
/* ABI 1.4: fills *desc with the defaults. Errors: NULL_ARGUMENT. Thread-safe. */
GEOCEAN_API geocean_status geocean_body_desc_init(geocean_body_desc* desc);
/* ABI 1.4: an empty simulation on `ocean`'s sea (config NULL: the
 * defaults). Each step reads the ocean's current sea state and rasters;
 * without a sea state the sea is flat at 0 m. Errors: NULL_ARGUMENT (ocean,
 * out), INVALID_ARGUMENT (struct_size, a field: the message names it). */
GEOCEAN_API geocean_status geocean_bodies_create(geocean_ocean* ocean, const geocean_bodies_config* config,
                                                 geocean_bodies** out);
/* ABI 1.4: NULL is allowed and ignored. */
GEOCEAN_API void geocean_bodies_destroy(geocean_bodies* bodies);
/* ABI 1.4: adds a body at the simulation's current time; *out_id (may be
 * NULL) gets its id. Errors: NULL_ARGUMENT (bodies, desc), INVALID_ARGUMENT
 * (struct_size, hull, 1.6: forces, a size not finite or not > 0, density not in
 * (0, water density), latitude or longitude out of range, a value not
 * finite, a point on land or a lake: no sea to float on; the message names
 * the field and the value). */
GEOCEAN_API geocean_status geocean_bodies_add(geocean_bodies* bodies, const geocean_body_desc* desc,
                                              geocean_body_id* out_id);
/* ABI 1.4: removes a body. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (no body
 * of that id: "no such body"). */
GEOCEAN_API geocean_status geocean_bodies_remove(geocean_bodies* bodies, geocean_body_id id);
/* ABI 1.4: how many bodies there are. Errors: NULL_ARGUMENT. */
GEOCEAN_API geocean_status geocean_bodies_count(const geocean_bodies* bodies, size_t* out_count);
/* ABI 1.4: runs every whole step ending at or before time_s; *out_steps
 * (may be NULL) gets how many. The remainder is kept for the interpolated
 * poses. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (time_s not finite,
 * outside -1e12 .. 1e12 s or before the simulation time; a force that is not finite: the bodies stay
 * as they were before that step). */
GEOCEAN_API geocean_status geocean_bodies_advance_to(geocean_bodies* bodies, double time_s, int64_t* out_steps);
/* ABI 1.4: the time of the last whole step, s. Errors: NULL_ARGUMENT. */
GEOCEAN_API geocean_status geocean_bodies_time(const geocean_bodies* bodies, double* out_time_s);
/* ABI 1.4: the poses of every body in the order of their ids. capacity:
 * entries of out; *out_count gets the number of bodies (call with capacity
 * 0 and out NULL to ask). interpolate: 0 the state at geocean_bodies_time;
 * non-zero, for drawing, the pose between the last two steps at the time
 * last given to geocean_bodies_advance_to (velocities are the last step's).
 * Errors: NULL_ARGUMENT (bodies, out_count; out with capacity > 0),
 * INVALID_ARGUMENT (capacity below the count: nothing is written). */
GEOCEAN_API geocean_status geocean_bodies_get_poses(const geocean_bodies* bodies, int32_t interpolate,
                                                    geocean_body_pose* out, size_t capacity, size_t* out_count);
/* ABI 1.4: the hull of body `id` as a closed triangle mesh in body axes
 * about the centre of mass (metres, outward counter-clockwise winding), to
 * draw it: vertex_capacity x 3 doubles and index_capacity uint32 indices.
 * *out_vertex_count and *out_index_count get the sizes (pass capacities 0
 * and NULL arrays to ask). Errors: NULL_ARGUMENT, INVALID_ARGUMENT (no
 * such body, a capacity below the size: nothing is written). */
GEOCEAN_API geocean_status geocean_bodies_get_hull(const geocean_bodies* bodies, geocean_body_id id,
                                                   double* vertices_xyz_m, size_t vertex_capacity,
                                                   uint32_t* indices, size_t index_capacity,
                                                   size_t* out_vertex_count, size_t* out_index_count);

#ifdef __cplusplus
}
#endif

#endif /* GEOCEAN_OCEAN_H */
