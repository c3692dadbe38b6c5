#include "globe/render/CliParse.h"

#include <charconv>
#include <cmath>

namespace geocean::render {

std::vector<double> parseNumbers(const std::string& text, std::size_t count, const char* option) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    double v = 0.0;
    const char* b = item.data();
    const char* e = b + item.size();
    if (b != e && *b == '+') ++b;
    const auto r = std::from_chars(b, e, v);
    if (item.empty() || r.ec != std::errc() || r.ptr != e || !std::isfinite(v))
      throw ArgError(std::string(option) + ": '" + item + "' is not a number (in '" + text + "')");
    out.push_back(v);
    start = end + 1;
  }
  if (out.size() != count)
    throw ArgError(std::string(option) + ": expected " + std::to_string(count) + " comma-separated numbers, got " +
                   std::to_string(out.size()) + " in '" + text + "'");
  return out;
}

void parseCamera(const std::string& text, camera::ViewPose& pose) {
  const auto v = parseNumbers(text, 5, "--camera LAT,LON,ALT,HEADING,PITCH");
  if (v[0] < -90.0 || v[0] > 90.0) throw ArgError("--camera: latitude " + std::to_string(v[0]) + " is outside [-90, 90]");
  if (v[2] <= 0.0 || v[2] > 1.0e9)
    throw ArgError("--camera: altitude " + std::to_string(v[2]) + " m must be in (0, 1e9]");
  if (v[4] < -90.0 || v[4] > 90.0) throw ArgError("--camera: pitch " + std::to_string(v[4]) + " is outside [-90, 90]");
  pose.latDeg = v[0];
  pose.lonDeg = v[1];
  pose.altM = v[2];
  pose.headingDeg = v[3];
  pose.pitchDeg = v[4];
}

void parseSize(const std::string& text, camera::ViewPose& pose) {
  const auto x = text.find_first_of("xX");
  int w = 0, h = 0;
  bool ok = x != std::string::npos;
  if (ok) {
    auto r1 = std::from_chars(text.data(), text.data() + x, w);
    auto r2 = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
    ok = r1.ec == std::errc() && r1.ptr == text.data() + x && r2.ec == std::errc() &&
         r2.ptr == text.data() + text.size();
  }
  if (!ok || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw ArgError("--size: '" + text + "' is not WIDTHxHEIGHT with each in 1..16384");
  pose.width = w;
  pose.height = h;
}

void checkReflectionSize(int size) {
  if (size != 0 && (size < 16 || size > 8192))
    throw ArgError("--reflection-size: " + std::to_string(size) + " must be in 16..8192 pixels (0: the viewport's size)");
}

void checkReflectionEvery(int every) {
  if (every < 1 || every > 1000)
    throw ArgError("--reflection-every: " + std::to_string(every) + " must be in 1..1000 frames");
}

}  // namespace geocean::render
