#include "plugin/bodies/Validate.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geocean::bodies::detail {

void fail(std::string_view field, double value, std::string_view unit, std::string_view rule) {
  std::ostringstream m;
  m.precision(17);
  m << "geocean::bodies: " << field << " = " << value;
  if (!unit.empty()) m << ' ' << unit;
  m << " (" << rule << ')';
  throw std::invalid_argument(m.str());
}

void requirePositive(std::string_view field, double value, std::string_view unit) {
  if (!(std::isfinite(value) && value > 0.0)) fail(field, value, unit, "must be finite and > 0");
}

void requireNonNegative(std::string_view field, double value, std::string_view unit) {
  if (!(std::isfinite(value) && value >= 0.0)) fail(field, value, unit, "must be finite and >= 0");
}

void requireFinite(std::string_view field, double value, std::string_view unit) {
  if (!std::isfinite(value)) fail(field, value, unit, "must be finite");
}

void requireFinite(std::string_view field, const glm::dvec3& v, std::string_view unit) {
  static constexpr const char* kAxis[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i])) fail(std::string(field) + kAxis[i], v[i], unit, "must be finite");
  }
}

}  // namespace geocean::bodies::detail
