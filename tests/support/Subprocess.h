// Running reference tools (cs2cs, gmt, geocean itself) from tests.
#pragma once

#include <string>

namespace geocean::test {

struct ProcessResult {
  int exitCode = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `command` through /bin/sh with `input` on stdin.
ProcessResult run(const std::string& command, const std::string& input = {});

// True if `tool` is on PATH.
bool haveTool(const std::string& tool);

}  // namespace geocean::test
