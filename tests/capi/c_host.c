/* A minimal host engine in plain C: dlopens the ocean plugin, checks its ABI
 * version, loads the default world and queries the surface class and
 * elevation at known places. Proof that a host needs nothing but the C
 * header and the shared library.
 *   c_host PLUGIN.so   (the default world comes from $GEOCEAN_DATA or the
 *                       plugin's install prefix)
 * Exit status 0 only if every check holds. */
#include "geocean/geocean_ocean.h"

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

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

  if (argc != 2) {
    fprintf(stderr, "usage: c_host PLUGIN.so\n");
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
  destroy(ocean);
  dlclose(lib);
  return failures == 0 ? 0 : 1;
}
