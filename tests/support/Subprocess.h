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

// Runs `command` (through /bin/sh) in its own Xvfb server of `screen`
// ("WxHxDEPTH") via xvfb-run. Tests run in parallel: `xvfb-run -a` alone
// races for a server number (two can pick the same free one; the loser
// exits 1 with "Xvfb failed to start") and shares ./.Xauthority, so each
// call takes a server number from its pid and its own auth file, and
// retries (up to 5 times) only when Xvfb itself failed to start.
ProcessResult runUnderXvfb(const std::string& screen, const std::string& command, const std::string& input = {});

}  // namespace geocean::test
