// Parsing of the render commands' arguments (camera, size, sun), with
// errors that name the option and the offending value.
#pragma once

#include "globe/camera/Camera.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace geocean::render {

class ArgError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "a,b,c" -> exactly `count` finite doubles; throws ArgError naming `option`.
std::vector<double> parseNumbers(const std::string& text, std::size_t count, const char* option);
// "LAT,LON,ALT,HEADING,PITCH" into pose (keeps fov and size).
void parseCamera(const std::string& text, camera::ViewPose& pose);
// "WxH" (1..16384 each).
void parseSize(const std::string& text, camera::ViewPose& pose);
// --reflection-size: 0 (the viewport's size) or 16..8192 pixels.
void checkReflectionSize(int size);
// --reflection-every M: 1..1000 frames.
void checkReflectionEvery(int every);

}  // namespace geocean::render
