#include "globe/gl/HeadlessContext.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>

namespace geocean::gl {

namespace {
std::string eglFail(const char* what) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04x)", what, eglGetError());
  return buf;
}
}  // namespace

std::unique_ptr<HeadlessContext> HeadlessContext::create(std::string& error, bool debug) {
  // Mesa's surfaceless platform needs no X server and no GPU.
  EGLDisplay dpy = EGL_NO_DISPLAY;
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
    dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY) {
    error = "no EGL surfaceless platform (EGL_MESA_platform_surfaceless); install libegl-mesa0";
    return nullptr;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor)) {
    error = eglFail("eglInitialize");
    return nullptr;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    error = eglFail("eglBindAPI(EGL_OPENGL_API)");
    eglTerminate(dpy);
    return nullptr;
  }
  const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                          EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
  if (ctx == EGL_NO_CONTEXT) {
    error = eglFail("eglCreateContext(OpenGL 4.5 core)");
    eglTerminate(dpy);
    return nullptr;
  }
  std::unique_ptr<HeadlessContext> c(new HeadlessContext);
  c->display_ = dpy;
  c->context_ = ctx;
  if (!c->makeCurrent()) {
    error = eglFail("eglMakeCurrent");
    return nullptr;
  }
  return c;
}

HeadlessContext::~HeadlessContext() {
  if (display_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
}

bool HeadlessContext::makeCurrent() {
  return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE;
}

std::string HeadlessContext::renderer() const {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return r ? r : "";
}

}  // namespace geocean::gl
