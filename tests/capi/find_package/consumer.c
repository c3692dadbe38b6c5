/* Links the installed plugin and loads the installed default world (found
 * beside the library, <prefix>/share/geocean/data). Exit 0 if the mid-Atlantic
 * is ocean and the Sahara land. */
#include <geocean/geocean_ocean.h>

#include <stdio.h>

int main(void) {
  geocean_ocean* ocean = NULL;
  const double lat[2] = {30.0, 23.0}, lon[2] = {-40.0, 10.0};
  uint8_t cls[2] = {99, 99};
  if (geocean_create(GEOCEAN_ABI_VERSION, &ocean) != GEOCEAN_OK || geocean_set_default_world(ocean) != GEOCEAN_OK ||
      geocean_query_class(ocean, 2, lat, lon, cls) != GEOCEAN_OK) {
    fprintf(stderr, "consumer: %s\n", geocean_last_error());
    geocean_destroy(ocean);
    return 1;
  }
  geocean_destroy(ocean);
  printf("consumer: Geocean %s, Atlantic class %d, Sahara class %d\n", geocean_version_string(), cls[0], cls[1]);
  return cls[0] == GEOCEAN_SURFACE_OCEAN && cls[1] == GEOCEAN_SURFACE_LAND ? 0 : 1;
}
