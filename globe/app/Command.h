// `geocean` subcommands register themselves here; main() dispatches.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace geocean::app {

struct Command {
  std::string name;
  std::string help;
  // Adds the subcommand's options to `sub` and returns the action to run
  // when it is selected; the action returns the process exit code.
  std::function<std::function<int()>(CLI::App& sub)> setup;
};

std::vector<Command>& registry();

struct Register {
  explicit Register(Command c) { registry().push_back(std::move(c)); }
};

// Exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;   // bad arguments or input rows
inline constexpr int kExitDataError = 3;  // unreadable / unsupported data file
inline constexpr int kExitNoDisplay = 4;  // no display / GL context

}  // namespace geocean::app
