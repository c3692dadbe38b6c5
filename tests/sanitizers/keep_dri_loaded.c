/* Preloaded (LD_PRELOAD) by the ASan build's test environment only
 * (tests/sanitizers/sanitizer_env.cmake); never part of the product.
 *
 * Mesa's EGL loads its driver (swrast_dri.so: the gallium megadriver with
 * llvmpipe, package libgl1-mesa-dri) with dlopen and dlcloses it in
 * eglTerminate. The driver keeps 112 bytes (two 56-byte callocs) reachable
 * only from its own globals and does not free them at unload; once it is
 * unmapped LeakSanitizer sees them as leaked from "<unknown module>" at exit.
 * Loading *_dri.so with RTLD_NODELETE keeps the driver mapped, so LSan scans
 * its globals, finds the blocks reachable and reports nothing, while a leak
 * of ours through the driver (a GL object never deleted) is still reported:
 * no suppression is needed. Built without sanitizers: it is also preloaded
 * into the non-instrumented programs the tests run (cmake, gmt, cs2cs). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <string.h>

void* dlopen(const char* file, int mode) {
  static void* (*real)(const char*, int);
  if (!real) real = (void* (*)(const char*, int))dlsym(RTLD_NEXT, "dlopen");
  size_t n = file ? strlen(file) : 0;
  if (n > 7 && strcmp(file + n - 7, "_dri.so") == 0) mode |= RTLD_NODELETE;
  return real(file, mode);
}
