// GLSL sources embedded at build time (shaders/embed.cmake).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geocean::shaders {

struct EmbeddedShader {
  const char* name;        // file name, e.g. "ocean.vert"
  const char* sourcePath;  // path at build time, for error messages
  const char* text;
};

namespace detail {
extern const EmbeddedShader kEmbedded[];
}

// How far from the eye a layer uses the host's planar reflection map
// (issue 13 item 4): one number for the host's pass (globe/render/Layer.h
// skips it above this height), the ocean's per-vertex shading (never
// nearer) and ocean_shading.glsl's fade, which assemble() gives every
// stage as GEOCEAN_REFLECTION_REACH_M.
constexpr double kReflectionReachM = 40000.0;

// The embedded shader called `name`, or nullopt.
std::optional<EmbeddedShader> find(std::string_view name);

// Names of all embedded shaders.
std::vector<std::string> names();

// Assemble a stage: "#version 450 core", GEOCEAN_REFLECTION_REACH_M, the
// defines, then each snippet
// (by name) and the stage file; `#include "x.glsl"` lines in any part are
// replaced by the embedded file (once each). Throws std::runtime_error naming
// the missing file when a name is not embedded.
std::string assemble(std::string_view stageName, const std::vector<std::string>& defines = {});

}  // namespace geocean::shaders
