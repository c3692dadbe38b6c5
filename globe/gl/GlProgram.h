// GLSL programs built from the shaders embedded at build time
// (shaders/Shaders.h). A failing stage throws ShaderError naming the stage
// file's source path, the snippets it includes and the driver's log.
#pragma once

#include <epoxy/gl.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace geocean::gl {

class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GlProgram {
 public:
  GlProgram() = default;
  // Vertex + fragment program from embedded stage files (e.g. "terrain.vert").
  static GlProgram graphics(const std::string& vert, const std::string& frag,
                            const std::vector<std::string>& defines = {});
  static GlProgram compute(const std::string& comp, const std::vector<std::string>& defines = {});
  ~GlProgram();
  GlProgram(GlProgram&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  GlProgram& operator=(GlProgram&& o) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  // Forgets the program without a GL call (its context is gone or not
  // current: the context owns it now).
  void abandon() { id_ = 0; }
  void use() const { glUseProgram(id_); }
  // Uniform location, -1 if the uniform is absent or optimised away.
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

// Compiles one stage; throws ShaderError with path and log on failure.
GLuint compileStage(GLenum stage, const std::string& stageName, const std::vector<std::string>& defines);

}  // namespace geocean::gl
