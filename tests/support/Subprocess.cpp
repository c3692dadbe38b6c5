#include "tests/support/Subprocess.h"

#include <sys/wait.h>
#include <unistd.h>

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

}  // namespace geocean::test
