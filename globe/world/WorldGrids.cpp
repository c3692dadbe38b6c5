#include "globe/world/WorldGrids.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geocean::world {

namespace {
float bilinear(const WorldLayer& l, double latDeg, double lonDeg) {
  double x = (lonDeg - l.originLonDeg) / l.lonStepDeg - 0.5;
  double y = (latDeg - l.originLatDeg) / l.latStepDeg - 0.5;
  x = std::fmod(x, double(l.width));
  if (x < 0) x += l.width;
  y = std::clamp(y, 0.0, double(l.height - 1));
  const int x0 = int(x), y0 = int(y);
  const int x1 = (x0 + 1) % l.width, y1 = std::min(y0 + 1, l.height - 1);
  const double fx = x - x0, fy = y - y0;
  auto v = [&](int xi, int yi) { return double(l.values[(std::size_t(yi) * l.width + xi) * l.channels]); };
  return float((v(x0, y0) * (1 - fx) + v(x1, y0) * fx) * (1 - fy) + (v(x0, y1) * (1 - fx) + v(x1, y1) * fx) * fy);
}
}  // namespace

void checkLayer(const WorldLayer& l, const char* what, int channels) {
  if (l.width <= 0 || l.height <= 0 || l.channels < channels ||
      l.values.size() != std::size_t(l.width) * l.height * l.channels)
    throw std::runtime_error(std::string("world layer '") + what + "' is empty or inconsistent (" +
                             std::to_string(l.width) + "x" + std::to_string(l.height) + "x" +
                             std::to_string(l.channels) + ")");
}

WorldGrids::WorldGrids(WorldLayer elevation, WorldLayer water)
    : elevation_(std::move(elevation)), water_(std::move(water)) {
  checkLayer(elevation_, "elevation", 1);
  checkLayer(water_, "water", 1);
  waterIndex_ = WaterIndex(water_);
  for (const WorldLayer* l : {&elevation_, &water_})
    for (const double step : {std::abs(l->lonStepDeg), std::abs(l->latStepDeg)})
      if (step > 0.0 && (finestShapeTexelDeg_ == 0.0 || step < finestShapeTexelDeg_)) finestShapeTexelDeg_ = step;
}

float WorldGrids::elevationAt(double latDeg, double lonDeg) const { return bilinear(elevation_, latDeg, lonDeg); }
float WorldGrids::waterAt(double latDeg, double lonDeg) const { return bilinear(water_, latDeg, lonDeg); }

}  // namespace geocean::world
