#include "globe/gl/GlDebug.h"

#include <epoxy/gl.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace geocean::gl {

namespace {
std::atomic<std::size_t> gErrors{0};

void GLAPIENTRY onMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                          const GLchar* message, const void*) {
  (void)source;
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  const bool error = type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH;
  if (error) ++gErrors;
  std::fprintf(stderr, "GL %s (id %u): %s\n", error ? "error" : "warning", id, message);
}
}  // namespace

bool glDebugWanted() {
#ifndef NDEBUG
  return true;
#else
  return std::getenv("GEOCEAN_GL_DEBUG") != nullptr;
#endif
}

bool enableGlDebug() {
  if (!glDebugWanted()) return false;
  if (epoxy_gl_version() < 43 && !epoxy_has_gl_extension("GL_KHR_debug")) return false;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onMessage, nullptr);
  return true;
}

std::size_t glDebugErrorCount() { return gErrors.load(); }

std::string glErrors(const char* where) {
  std::string out;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s0x%04x", out.empty() ? "" : ", ", e);
    out += buf;
  }
  return out.empty() ? out : std::string("GL error at ") + where + ": " + out;
}

}  // namespace geocean::gl
