// The tests' main: each test process gets its own scratch directory as
// TEST_TMPDIR, which ::testing::TempDir() returns. ctest runs every test in
// its own process and two at once, and many tests name their files
// (island.tif, out.png) under TempDir(): with a shared /tmp two tests that
// pick the same name remove or overwrite each other's file (CI's stop 26:
// SeaLight.CalmWater... lost reflection_island_off.png to its neighbour).
// The directory sits under the caller's TEST_TMPDIR (or /tmp); it is removed
// when every test passed and kept, with its path printed, when one failed.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  std::string base = "/tmp";
  if (const char* t = std::getenv("TEST_TMPDIR"); t && *t) base = t;
  while (base.size() > 1 && base.back() == '/') base.pop_back();
  std::error_code ec;
  std::filesystem::create_directories(base, ec);
  std::string dir = base + "/geocean-" + std::to_string(::getpid()) + "-XXXXXX";
  if (!::mkdtemp(dir.data())) {
    std::fprintf(stderr, "cannot make a scratch directory %s: %s\n", dir.c_str(), std::strerror(errno));
    return 2;
  }
  ::setenv("TEST_TMPDIR", dir.c_str(), 1);
  const int rc = RUN_ALL_TESTS();
  if (rc == 0)
    std::filesystem::remove_all(dir, ec);
  else
    std::fprintf(stderr, "scratch files kept in %s\n", dir.c_str());
  return rc;
}
