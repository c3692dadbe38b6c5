// KHR_debug: GL errors and warnings reported through a callback. Enabled in
// debug builds (NDEBUG unset) or when GEOCEAN_GL_DEBUG is set in the
// environment; release builds skip it because synchronous debug output
// serialises the driver.
#pragma once

#include <cstddef>
#include <string>

namespace geocean::gl {

// Installs the callback when debug output is wanted; returns whether it is on.
// Messages of high/medium severity go to stderr and are counted.
bool enableGlDebug();
bool glDebugWanted();
// High-severity or error-type messages seen since enableGlDebug().
std::size_t glDebugErrorCount();

// glGetError() drained into one message naming `where`; empty when clean.
std::string glErrors(const char* where);

}  // namespace geocean::gl
