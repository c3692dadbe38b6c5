// An OpenGL 4.5 core context with no window and no display: EGL on Mesa's
// surfaceless platform. Used by `geocean render/fly` and by GL tests; render
// into an FBO. Only GL targets include this header.
#pragma once

#include <memory>
#include <string>

namespace geocean::gl {

class HeadlessContext {
 public:
  // Creates the context and makes it current on the calling thread.
  // Returns nullptr and sets `error` (naming the EGL call and error code) on failure.
  static std::unique_ptr<HeadlessContext> create(std::string& error, bool debug = false);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  bool makeCurrent();
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace geocean::gl
