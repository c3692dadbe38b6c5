#include "globe/world/Surface.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geocean::world {

const char* toString(Surface s) {
  switch (s) {
    case Surface::Ocean: return "ocean";
    case Surface::Land: return "land";
    case Surface::Lake: return "lake";
  }
  return "land";
}

MaskEncoding::MaskEncoding() {
  classOf.fill(Surface::Land);
  classOf[0] = Surface::Ocean;
  classOf[2] = Surface::Lake;
}

MaskEncoding MaskEncoding::parse(const std::string& spec) {
  MaskEncoding e;
  e.classOf.fill(Surface::Land);
  std::istringstream in(spec);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("mask encoding item '" + item + "' is not VALUE=CLASS");
    const std::string vs = item.substr(0, eq), cs = item.substr(eq + 1);
    char* end = nullptr;
    const long v = std::strtol(vs.c_str(), &end, 10);
    if (end == vs.c_str() || *end || v < 0 || v > 255)
      throw std::invalid_argument("mask encoding value '" + vs + "' is not an integer in [0, 255]");
    if (cs == "ocean") e.classOf[std::size_t(v)] = Surface::Ocean;
    else if (cs == "land") e.classOf[std::size_t(v)] = Surface::Land;
    else if (cs == "lake") e.classOf[std::size_t(v)] = Surface::Lake;
    else throw std::invalid_argument("mask encoding class '" + cs + "' is not ocean, land or lake");
  }
  return e;
}

Surface MaskEncoding::classify(float v) const {
  if (std::isnan(v) || v < 0.0f || v > 255.0f) return Surface::Land;
  return classOf[static_cast<std::size_t>(std::lround(v))];
}

}  // namespace geocean::world
