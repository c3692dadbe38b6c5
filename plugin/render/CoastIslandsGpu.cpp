#include "plugin/render/CoastIslandsGpu.h"

#include "globe/gl/GlProgram.h"

#include <algorithm>
#include <exception>

namespace geocean::ocean_render {

namespace {
template <class T>
GLuint buffer(GLuint binding, const T* data, std::size_t count) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferStorage(b, GLsizeiptr(std::max<std::size_t>(1, count) * sizeof(T)), count ? data : nullptr,
                       GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b);
  return b;
}
}  // namespace

std::vector<glm::vec4> buildIslandTableGpu(const waves::CoastField::IslandInputs& in, std::string& error,
                                           std::vector<float>* shadow) {
  std::vector<glm::vec4> table;
  const int n = in.nodes;
  if (n <= 0 || in.components <= 0) return table;
  gl::GlProgram prog;
  try {
    prog = gl::GlProgram::compute("coast_islands_comp.glsl");
  } catch (const std::exception& e) {
    error = std::string("island table (GPU): ") + e.what();
    return table;
  }
  std::vector<float> elev(in.elevation.begin(), in.elevation.end());
  std::vector<glm::vec4> travel;
  for (const auto& t : in.travel) travel.push_back(glm::vec4(t));
  table.assign(std::size_t(in.components) * n * n, glm::vec4(0.0f));
  const GLuint bufs[] = {buffer(0, elev.data(), elev.size()), buffer(1, travel.data(), travel.size()),
                         buffer(2, table.data(), table.size()), buffer(3, table.data(), 1),
                         buffer(4, table.data(), 1), buffer(5, in.landSat.data(), in.landSat.size()),
                         buffer<float>(6, nullptr, table.size())};
  prog.use();
  glUniform1i(prog.uniform("uNodes"), n);
  glUniform1i(prog.uniform("uComps"), in.components);
  glUniform1f(prog.uniform("uCellM"), float(in.cellM));
  glUniform1f(prog.uniform("uRadiusCells"), float(in.radiusCells));
  glDispatchCompute(GLuint((n + 7) / 8), GLuint((n + 7) / 8), 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(bufs[2], 0, GLsizeiptr(table.size() * sizeof(glm::vec4)), table.data());
  if (shadow) {
    shadow->assign(table.size(), 0.0f);
    glGetNamedBufferSubData(bufs[6], 0, GLsizeiptr(shadow->size() * sizeof(float)), shadow->data());
  }
  glUseProgram(0);
  glDeleteBuffers(7, bufs);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    error = "island table (GPU): GL error " + std::to_string(e);
    table.clear();
    if (shadow) shadow->clear();
  }
  return table;
}

std::vector<glm::vec4> coastTexelsGpuIslands(const waves::CoastField& field, std::string& error) {
  std::vector<float> shadow;
  const std::vector<glm::vec4> table = buildIslandTableGpu(field.islandInputs(), error, &shadow);
  if (table.empty()) return {};
  std::vector<glm::vec4> texels = field.gpuTexelsWith(table, shadow);
  if (texels.empty()) error = "island table (GPU): its size is not the coast field's";
  return texels;
}

}  // namespace geocean::ocean_render
