/* The public header compiles as strict C99 (-std=c99 -pedantic -Werror) and
 * a C program linked against the plugin (no dlopen) can use it. Exits
 * non-zero at the first failed check. */
#include "geocean/geocean_ocean.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond)                                                  \
  do {                                                               \
    if (!(cond)) {                                                   \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                    \
    }                                                                \
  } while (0)

int main(void) {
  geocean_ocean* ocean = NULL;
  geocean_grid_placement placement;
  float mask[4] = {0.0f, 1.0f, 2.0f, 0.0f}; /* 2 x 2: ocean land / lake ocean */
  double lat[2] = {45.0, -45.0}, lon[2] = {-90.0, 90.0};
  uint8_t cls[2] = {99, 99};

  CHECK(geocean_abi_version() == GEOCEAN_ABI_VERSION);
  CHECK(strcmp(geocean_status_string(GEOCEAN_ERROR_RASTER), "GEOCEAN_ERROR_RASTER") == 0);
  CHECK(strlen(geocean_version_string()) > 0);

  /* A host from a future major is refused, with a message. */
  CHECK(geocean_create(GEOCEAN_ABI_VERSION + (1u << 16), &ocean) == GEOCEAN_ERROR_ABI_VERSION);
  CHECK(ocean == NULL);
  CHECK(strstr(geocean_last_error(), "ABI") != NULL);

  CHECK(geocean_create(GEOCEAN_ABI_VERSION, &ocean) == GEOCEAN_OK);
  CHECK(ocean != NULL);
  CHECK(strcmp(geocean_last_error(), "") == 0);

  /* Whole Earth in 2 x 2 cells of 180 x 90 degrees, north up. */
  placement.origin_lon_deg = -180.0;
  placement.origin_lat_deg = 90.0;
  placement.lon_step_deg = 180.0;
  placement.lat_step_deg = -90.0;
  placement.global = 1;
  placement.has_nodata = 0;
  placement.nodata = 0.0;
  CHECK(geocean_query_class(ocean, 2, lat, lon, cls) == GEOCEAN_ERROR_NOT_READY);
  CHECK(geocean_set_mask_pixels(ocean, mask, 2, 2, &placement) == GEOCEAN_OK);
  CHECK(geocean_query_class(ocean, 2, lat, lon, cls) == GEOCEAN_OK);
  CHECK(cls[0] == GEOCEAN_SURFACE_OCEAN); /* north-west cell */
  CHECK(cls[1] == GEOCEAN_SURFACE_OCEAN); /* south-east cell */
  lon[0] = 90.0;
  CHECK(geocean_query_class(ocean, 1, lat, lon, cls) == GEOCEAN_OK);
  CHECK(cls[0] == GEOCEAN_SURFACE_LAND); /* north-east cell */

  CHECK(geocean_query_class(NULL, 2, lat, lon, cls) == GEOCEAN_ERROR_NULL_ARGUMENT);
  CHECK(strstr(geocean_last_error(), "ocean is NULL") != NULL);
  geocean_destroy(ocean);
  geocean_destroy(NULL);
  if (failures == 0) printf("header_c99: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
