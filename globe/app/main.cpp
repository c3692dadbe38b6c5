#include "globe/app/Command.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace geocean::app {
std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}
}  // namespace geocean::app

int main(int argc, char** argv) {
  using namespace geocean::app;
#if defined(__GLIBC__)
  // glibc gives each thread that allocates (tile workers, llvmpipe's) an
  // arena of its own that keeps what it frees: 2 cap the flights' peak
  // RSS (issue 12 item 6) at the same CPU. The user's setting wins.
  if (!std::getenv("MALLOC_ARENA_MAX") && !std::getenv("GLIBC_TUNABLES")) mallopt(M_ARENA_MAX, 2);
#endif
  CLI::App app{"Geocean: a living ocean on the WGS84 ellipsoid"};
  app.require_subcommand(1);
  std::function<int()> action;
  for (auto& c : registry()) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    auto run = std::make_shared<std::function<int()>>();
    *run = c.setup(*sub);
    sub->callback([run, &action] { action = *run; });
  }
#if !GEOCEAN_WITH_HUD
  // Built without the window (GEOCEAN_BUILD_VIEWER=OFF): say so instead of
  // CLI11's "A subcommand is required".
  if (argc > 1 && std::string(argv[1]) == "view") {
    std::fprintf(stderr, "geocean view: this geocean was built with GEOCEAN_BUILD_VIEWER=OFF (no window); "
                         "use geocean render or geocean fly\n");
    return kExitBadInput;
  }
#endif
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
