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
// set (naming the GL step) on failure. `shadow` (if given): per entry, how
// far D_obs replaces the eikonal's Kr (0 .. 1), as CoastField::islandTable's.
std::vector<glm::vec4> buildIslandTableGpu(const waves::CoastField::IslandInputs& in, std::string& error,
                                           std::vector<float>* shadow = nullptr);

// The field's texels for wvCoastTexels[] with the island table built here on
// the GPU (the renderer's): CoastField::gpuTexelsWith of this build; empty
// and `error` set on failure.
std::vector<glm::vec4> coastTexelsGpuIslands(const waves::CoastField& field, std::string& error);

}  // namespace geocean::ocean_render
