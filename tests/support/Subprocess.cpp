#include "tests/support/Subprocess.h"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace geocean::test {

namespace {
std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}
}  // namespace

ProcessResult run(const std::string& command, const std::string& input) {
  char dir[] = "/tmp/geocean-test-XXXXXX";
  if (!mkdtemp(dir)) return {};
  const std::string d = dir;
  { std::ofstream(d + "/in", std::ios::binary) << input; }
  const std::string full = "(" + command + ") <" + d + "/in >" + d + "/out 2>" + d + "/err";
  const int status = std::system(full.c_str());
  ProcessResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(d + "/out");
  r.err = slurp(d + "/err");
  std::system(("rm -rf " + d).c_str());
  return r;
}

bool haveTool(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

ProcessResult runUnderXvfb(const std::string& screen, const std::string& command, const std::string& input) {
  static std::atomic<int> calls{0};
  ProcessResult r;
  for (int attempt = 0; attempt < 5; ++attempt) {
    const int k = calls++;
    // Server numbers 200-999, spread by pid so parallel test processes
    // start apart; -a still skips any number whose lock file exists.
    const int server = 200 + int((unsigned(getpid()) * 37u + unsigned(k) * 101u) % 800u);
    const std::string auth = "/tmp/geocean-xauth-" + std::to_string(getpid()) + "-" + std::to_string(k);
    r = run("xvfb-run -a -n " + std::to_string(server) + " -f " + auth + " -s '-screen 0 " + screen + "' " + command,
            input);
    std::remove(auth.c_str());
    if (r.err.find("Xvfb failed to start") == std::string::npos) return r;
  }
  return r;
}

}  // namespace geocean::test
