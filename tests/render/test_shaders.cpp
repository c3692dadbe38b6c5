// Shader building: every embedded stage compiles, and failures name the file.
#include "RenderFixture.h"

#include "globe/gl/GlProgram.h"
#include "shaders/Shaders.h"

namespace geocean::render::test {
namespace {

TEST(Shaders, AllRendererProgramsBuild) {
  session();
  EXPECT_NO_THROW(GlProgram::graphics("terrain.vert", "terrain.frag"));
  EXPECT_NO_THROW(GlProgram::graphics("sky.vert", "sky.frag"));
  EXPECT_NO_THROW(GlProgram::graphics("terrain.vert", "bare.frag", {"GEOCEAN_BARE 1"}));
}

TEST(Shaders, CompileErrorNamesTheFileAndCarriesTheLog) {
  session();
  try {
    // A define that breaks the vertex stage's source.
    GlProgram::graphics("terrain.vert", "terrain.frag", {"aNormal )"});
    FAIL() << "expected ShaderError";
  } catch (const ShaderError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("shaders/terrain.vert"), std::string::npos) << m;
    EXPECT_NE(m.find("geo_uv.glsl"), std::string::npos) << m;  // the includes are listed
    EXPECT_NE(m.find("error"), std::string::npos) << m;        // the driver's log
  }
}

TEST(Shaders, MissingShaderIsNamed) {
  session();
  try {
    GlProgram::graphics("no_such.vert", "terrain.frag");
    FAIL() << "expected ShaderError";
  } catch (const ShaderError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such.vert"), std::string::npos);
  }
}

}  // namespace
}  // namespace geocean::render::test
