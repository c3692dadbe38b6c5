#include "globe/gl/GlProgram.h"

#include "shaders/Shaders.h"

#include <sstream>

namespace geocean::gl {

namespace {
// The embedded files a stage pulls in, for the error message.
std::string includedPaths(const std::string& stageName) {
  std::string out;
  auto s = shaders::find(stageName);
  if (!s) return out;
  std::istringstream in(s->text);
  std::string line;
  while (std::getline(in, line)) {
    const auto p = line.find("#include");
    if (p == std::string::npos || line.find_first_not_of(" \t") != p) continue;
    const auto q1 = line.find('"', p), q2 = line.find('"', q1 + 1);
    if (q1 == std::string::npos || q2 == std::string::npos) continue;
    auto inc = shaders::find(line.substr(q1 + 1, q2 - q1 - 1));
    if (inc) out += std::string("\n  includes ") + inc->sourcePath;
  }
  return out;
}
}  // namespace

GLuint compileStage(GLenum stage, const std::string& stageName, const std::vector<std::string>& defines) {
  const auto embedded = shaders::find(stageName);
  if (!embedded) throw ShaderError("shader '" + stageName + "' is not embedded in this binary");
  std::string text;
  // Snippets shared between stages test this for derivative functions.
  std::vector<std::string> all = defines;
  if (stage == GL_FRAGMENT_SHADER) all.push_back("GEOCEAN_FRAGMENT_STAGE 1");
  try {
    text = shaders::assemble(stageName, all);
  } catch (const std::exception& e) {
    throw ShaderError(std::string(embedded->sourcePath) + ": " + e.what());
  }
  const GLuint sh = glCreateShader(stage);
  const char* src = text.c_str();
  glShaderSource(sh, 1, &src, nullptr);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
    glGetShaderInfoLog(sh, len, nullptr, log.data());
    glDeleteShader(sh);
    throw ShaderError("GLSL compile failed: " + std::string(embedded->sourcePath) +
                      includedPaths(stageName) + "\n" + log.c_str());
  }
  return sh;
}

namespace {
GLuint link(const std::vector<GLuint>& stages, const std::string& what) {
  const GLuint p = glCreateProgram();
  for (GLuint s : stages) glAttachShader(p, s);
  glLinkProgram(p);
  for (GLuint s : stages) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
    glGetProgramInfoLog(p, len, nullptr, log.data());
    glDeleteProgram(p);
    throw ShaderError("GLSL link failed: " + what + "\n" + log.c_str());
  }
  return p;
}
}  // namespace

GlProgram GlProgram::graphics(const std::string& vert, const std::string& frag,
                              const std::vector<std::string>& defines) {
  const GLuint v = compileStage(GL_VERTEX_SHADER, vert, defines);
  GLuint f = 0;
  try {
    f = compileStage(GL_FRAGMENT_SHADER, frag, defines);
  } catch (...) {
    glDeleteShader(v);
    throw;
  }
  GlProgram p;
  p.id_ = link({v, f}, vert + " + " + frag);
  return p;
}

GlProgram GlProgram::compute(const std::string& comp, const std::vector<std::string>& defines) {
  GlProgram p;
  p.id_ = link({compileStage(GL_COMPUTE_SHADER, comp, defines)}, comp);
  return p;
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

}  // namespace geocean::gl
