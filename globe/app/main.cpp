#include "globe/app/Command.h"

#include <cstdio>
#include <exception>
#include <memory>

namespace geocean::app {
std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}
}  // namespace geocean::app

int main(int argc, char** argv) {
  using namespace geocean::app;
  CLI::App app{"Geocean: a living ocean on the WGS84 ellipsoid"};
  app.require_subcommand(1);
  std::function<int()> action;
  for (auto& c : registry()) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    auto run = std::make_shared<std::function<int()>>();
    *run = c.setup(*sub);
    sub->callback([run, &action] { action = *run; });
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : kExitBadInput;
  }
  try {
    return action ? action() : kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geocean: %s\n", e.what());
    return kExitDataError;
  }
}
