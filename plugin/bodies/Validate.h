// Input checks shared by the bodies library: every bad value throws
// std::invalid_argument naming the field and the value.
#pragma once

#include <glm/vec3.hpp>

#include <string_view>

namespace geocean::bodies::detail {

// Throws unless `value` is finite and > 0.
void requirePositive(std::string_view field, double value, std::string_view unit);
// Throws unless `value` is finite and >= 0.
void requireNonNegative(std::string_view field, double value, std::string_view unit);
// Throws unless every component of `v` is finite.
void requireFinite(std::string_view field, const glm::dvec3& v, std::string_view unit);
void requireFinite(std::string_view field, double value, std::string_view unit);
[[noreturn]] void fail(std::string_view field, double value, std::string_view unit, std::string_view rule);

}  // namespace geocean::bodies::detail
