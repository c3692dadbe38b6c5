// Scratch files for tests: a fresh directory under /tmp, removed with
// everything in it at scope exit.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace geocean::test {

struct TempDir {
  std::filesystem::path path;
  // /tmp/<prefix>-XXXXXX: the prefix says which test left it, if one crashes.
  explicit TempDir(const std::string& prefix = "geocean-test") {
    std::string t = "/tmp/" + prefix + "-XXXXXX";
    if (!mkdtemp(t.data())) throw std::runtime_error("mkdtemp " + t + " failed");
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& file) const { return (path / file).string(); }
};

}  // namespace geocean::test
