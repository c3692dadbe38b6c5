// The render commands as a user runs them: bad input is named, no display
// is reported, a frame is written.
#include "RenderFixture.h"

#include "tests/support/Subprocess.h"

#include <filesystem>

namespace geocean::render::test {
namespace {

const std::string kExe = GEOCEAN_EXE;

TEST(RenderCli, BadCameraIsNamedAndExits2) {
  const auto r = geocean::test::run(kExe + " render --camera 0,abc,100,0,-90 --out /tmp/x.png");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("'abc' is not a number"), std::string::npos) << r.err;
  const auto r2 = geocean::test::run(kExe + " render --camera 95,0,100,0,-90 --out /tmp/x.png");
  EXPECT_EQ(r2.exitCode, 2);
  EXPECT_NE(r2.err.find("latitude"), std::string::npos) << r2.err;
  const auto r3 = geocean::test::run(kExe + " render --size 0x10 --out /tmp/x.png");
  EXPECT_EQ(r3.exitCode, 2);
  EXPECT_NE(r3.err.find("--size"), std::string::npos) << r3.err;
}

TEST(RenderCli, RendersAFrameWithNegativeCoordinates) {
  const std::string out = ::testing::TempDir() + "/cli_frame.png";
  std::filesystem::remove(out);
  const auto r = geocean::test::run(kExe + " render --camera -33.9,18.4,200000,0,-90 --size 64x48 --out " + out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image img = readImage(out);
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 48);
}

}  // namespace
}  // namespace geocean::render::test
