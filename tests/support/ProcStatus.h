// This process's memory figures from /proc/self/status (Linux).
#pragma once

#include <cstring>
#include <fstream>
#include <string>

namespace geocean::test {

// The value in kB of a field such as "VmRSS:" or "VmHWM:", or -1 if absent.
inline long statusKb(const char* field) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(field, 0) == 0) return std::stol(line.substr(std::strlen(field)));
  return -1;
}

}  // namespace geocean::test
