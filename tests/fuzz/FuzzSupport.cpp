#include "tests/fuzz/FuzzSupport.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

namespace geocean::fuzz {

std::string scratchPath(const std::string& stem, const std::string& ext) {
  std::string dir = "/dev/shm";
  if (!std::filesystem::is_directory(dir)) {
    const char* t = std::getenv("TMPDIR");
    dir = t && *t ? t : "/tmp";
  }
  std::string path = dir + "/geocean_fuzz_" + std::to_string(::getpid()) + "_" + stem + ext;
  // Removed at a normal exit (a crash leaves it, beside libFuzzer's artifact).
  static std::vector<std::string> made;
  static std::once_flag once;
  std::call_once(once, [] {
    std::atexit([] {
      for (const auto& p : made) std::remove(p.c_str());
    });
  });
  made.push_back(path);
  return path;
}

void writeFile(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror(path.c_str());
    std::abort();
  }
}

}  // namespace geocean::fuzz
