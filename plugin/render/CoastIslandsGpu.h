// The coast field's island table (D_blo, theta_blo, D_obs, theta_def) built
// on the GPU by a compute shader (shaders/coast_islands_comp.glsl), from the
// same inputs and the same function (shaders/coast_islands.glsl) as the CPU
// build waves::CoastField::islandTable. Needs a current GL 4.5 context.
#pragma once

#include "plugin/waves/CoastField.h"

#include <glm/vec4.hpp>

#include <string>
#include <vector>

namespace geocean::ocean_render {

// The table, component-major like CoastField::islands(); empty and `error`
// set (naming the GL step) on failure.
std::vector<glm::vec4> buildIslandTableGpu(const waves::CoastField::IslandInputs& in, std::string& error);

}  // namespace geocean::ocean_render
