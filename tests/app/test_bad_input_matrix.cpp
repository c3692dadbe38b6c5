// The bad-input matrix (issue 17 item 5), table-driven over every `geocean`
// subcommand: NaN, infinities, out-of-range, empty, huge and wrong-typed
// values. The README's contract: exit 2 (3: a data file that cannot be
// read), and a message naming the option (or row), the field and the value; nothing on stdout but what was answered
// before a bad row. Rows here fail before any GL context or GMT run, so the
// matrix needs neither (nor a display: view checks its arguments first).
// Each row's `mustSay` is what the user has to read.
// The C ABI's rows are tests/capi (CapiMisuse.*, CapiTimes.*, CapiV12.*).
#include "tests/support/Subprocess.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

using geocean::test::run;

namespace {
const std::string kGeocean = GEOCEAN_EXE;

struct Row {
  const char* args;     // after "geocean "
  const char* mustSay;  // substring of stderr
  int exitCode = 2;     // 3: a data file that cannot be read (README)
};

// Found by this matrix (fixed with it): `float --seconds 1e300` printed a
// header and exited 0 (the output count overflowed its conversion to long);
// `query --fetch 1e-300` answered null heights on ocean (JONSWAP's peak
// ran away); `fly --fps 1e-300` and `render --time nan` exited 3 with the
// plugin's message instead of 2 with the option's.
const Row kRows[] = {
    // query
    {"query 0", "LAT LON"},
    {"query nan 0", "nan"},
    {"query 0 inf", "inf"},
    {"query 91 0", "latitude 91 is outside [-90, 90]"},
    {"query 0 361", "longitude 361 is outside [-180, 360]"},
    {"query 0 0 --time 1e33", "--time 1e+33 s is outside -1e12 .. 1e12 s"},
    {"query 0 0 --time abc", "--time 'abc' is not a finite number"},
    {"query 0 0 --wind 1e300", "--wind 1e300 m/s is outside 0.2 .. 60 m/s"},
    {"query 0 0 --wind nan", "--wind 'nan' is not a finite number"},
    {"query 0 0 --fetch -inf", "--fetch '-inf' is not a finite number"},
    {"query 0 0 --fetch 1e-300", "--fetch 1e-300 m is below 1 m"},
    {"query 0 0 --seed 99999999999", "--seed '99999999999' is not an integer"},
    {"query 0 0 --beaufort inf", "--beaufort 'inf' is not a finite number"},
    {"query 0 0 --anchor 0,inf", "--anchor '0,inf' is not LAT,LON"},
    {"query 0 0 --format xml", "xml"},
    {"query 0 0 --waves gerstner --coast-region 0,0,1e300", "--coast-region size 1e300 m is outside 500 .. 40000 m"},
    {"query 0 0 --mask /nonexistent/m.tif", "/nonexistent/m.tif: no such file", 3},
    {"query --points /nonexistent/points.csv", "--points /nonexistent/points.csv: cannot open", 3},
    {"query 0 0 --mask ''", "--mask: the file name is empty"},
    {"query 0 0 --elevation ''", "--elevation: the file name is empty"},
    // render (argument checks come before the GL context)
    {"render --out x.png --size 0x0", "--size: '0x0' is not WIDTHxHEIGHT with each in 1..16384"},
    {"render --out x.png --size 99999999999x2", "is not WIDTHxHEIGHT"},
    {"render --out x.png --camera nan,0,100,0,-90", "--camera LAT,LON,ALT,HEADING,PITCH: 'nan' is not a number"},
    {"render --out x.png --fov inf", "--fov: inf must be in (1, 170) degrees"},
    {"render --out x.png --sun 0,nan", "--sun AZ,EL: 'nan' is not a number"},
    {"render --out x.png --exaggeration -1", "--exaggeration: -1"},
    {"render --out x.png --time nan", "--time nan is not a finite number"},
    {"render --out x.png --time -1e13", "--time -1e+13 s is outside -1e12 .. 1e12 s"},
    {"render --out x.png --time abc", "--time"},
    {"render", "--out is required"},
    {"render --out x.png --elevation ''", "--elevation: the file name is empty"},
    {"render --out x.png --beaufort 13", "--beaufort 13 is not a Beaufort number 0..12"},
    {"render --out x.png --beaufort nan", "--beaufort: 'nan' is not a number"},
    {"render --out x.png --wind 5 --beaufort 3", "give either --wind or --beaufort, not both"},
    {"render --out x.png --reflection-size 8", "--reflection-size: 8 must be in 16..8192 pixels"},
    {"render --out x.png --grid spherical", "--grid: spherical not in {direct,ispg}"},
    {"render --out x.png --shadow-model half", "--shadow-model: half not in {physical,paper}"},
    {"render --out x.png --sun-model blinn", "--sun-model: blinn not in {microfacet,phong}"},
    // fly
    {"fly --out o --frames 1", "--frames: 1 must be in 2..1000000"},
    {"fly --out o --frames 1e9", "--frames"},
    {"fly --out o --fps 0", "--fps must be positive"},
    {"fly --out o --fps nan", "--fps must be positive"},
    {"fly --out o --fps 1e-300", "--fps 1e-300: the last frame's time"},
    {"fly --out o --to 0,inf", "--to LAT,LON: 'inf' is not a number"},
    {"fly --out o --from 95,0,1000", "--from: latitude must be in [-90, 90]"},
    {"fly --out o --beaufort 2.5", "--beaufort 2.5 is not a Beaufort number 0..12"},
    {"fly --out o --reflection-size 99999", "--reflection-size: 99999 must be in 16..8192 pixels"},
    {"fly --out o --grid ''", "--grid:  not in {direct,ispg}"},
    {"fly --out o --reflection-every 0", "--reflection-every: 0 must be in 1..1000 frames"},
    {"fly --out o --shadow-model ''", "--shadow-model:  not in {physical,paper}"},
    // pick
    {"pick --ray nan,0,0,1,0,0", "--ray: 'nan' in 'nan,0,0,1,0,0' is not a finite number"},
    {"pick --ray 0,0,0,0,0,0", "--ray direction 0,0,0 is zero"},
    {"pick --ray 1,2,3", "--ray: expected 6 comma-separated numbers, got 3"},
    {"pick --camera 0,0,100,0,-90 --fov 45 --size 10x10 --pixel 50,5", "--pixel 50,5 is outside the 10x10 viewport"},
    {"pick --rays /nonexistent/rays.csv", "--rays /nonexistent/rays.csv: cannot open", 3},
    {"pick --ray 0,0,100,0,0,-1 --mask ''", "--mask: the file name is empty"},
    // float
    {"float --body box:1x1x1 --density nan --at 0,0", "--density 'nan' is not a finite number"},
    {"float --body box:0x1x1 --density 500 --at 0,0", "--body 'box:0x1x1': size 0 m must be > 0"},
    {"float --body boat:inf --density 500 --at 0,0", "--body 'boat:inf': size 'inf' is not a finite number"},
    {"float --body box:1x1x1 --density 500 --at 95,0", "--at: latitude 95 is outside [-90, 90]"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --seconds 1e300", "--seconds 1e300 s is above 1e12 s"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --seconds -1", "--seconds -1 must be >= 0"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --dt 0", "--dt 0 s must be > 0"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --dt 1", "--dt 1 s is above 0.5 s"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --every 0", "--every 0 s must be > 0"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --wind inf", "--wind 'inf' is not a finite number"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --waves foam", "--waves 'foam' is not none, noise, noise-paper, gerstner or fft"},
    {"float --body box:1x1x1 --density 500 --at 0,0 --mask ''", "--mask: the file name is empty"},
    // mask (argument checks come before GMT)
    {"mask --region nan/1/0/1 --resolution 3s --out m.tif", "--region 'nan/1/0/1': 'nan' is not a number"},
    {"mask --region 0/1/0/1 --resolution 7q --out m.tif", "--resolution '7q': unit 'q' is not s, m or d"},
    {"mask --region 0/1/0/1 --resolution 3s", "--out is required"},
    // the drawing commands' sea options, before the GL context (named by
    // the option, not by the plugin's field)
    {"render --out x.png --wind nan", "--wind nan m/s is outside 0.2 .. 60 m/s"},
    {"render --out x.png --wind-dir inf", "--wind-dir inf is not a finite angle"},
    {"render --out x.png --waves gerstner --coast-region 52.6,4.45,1e300",
     "--coast-region '52.6,4.45,1e300': size 1e+300 m is outside 500 .. 40000 m"},
    {"render --out x.png --coast-region ''", "--coast-region: the value is empty"},
    {"render --out x.png --boats -1", "--boats -1 is not in 0..10000"},
    {"fly --out o --wind 1e300", "--wind 1e+300 m/s is outside 0.2 .. 60 m/s"},
    {"fly --out o --waves gerstner --coast-region 52.6,nan", "'nan' in '52.6,nan' is not a finite number"},
    {"fly --out o --waves gerstner --coast-follow", "--coast-follow needs --coast-region LAT,LON[,SIZE_M]"},
    {"fly --out o --boats 2 --follow 3", "--follow 3 is not a boat of --boats 2"},
    // view: every check comes before the display's, so these exit 2 with no
    // display at all (the runner unsets DISPLAY; with one, ViewWindow.*)
    {"view --fly-to nan,0", "--fly-to LAT,LON: 'nan' is not a number"},
    {"view --fly-to 0,inf", "--fly-to LAT,LON: 'inf' is not a number"},
    {"view --fly-to 95,0", "--fly-to: latitude 95 is outside [-90, 90]"},
    {"view --fly-to 0,1e300", "--fly-to: longitude 1e+300 is outside [-180, 360]"},
    {"view --fly-to ''", "--fly-to: the value is empty"},
    {"view --grid ISPG", "--grid: ISPG not in {direct,ispg}"},
    {"view --reflection-every 1001", "--reflection-every: 1001 must be in 1..1000 frames"},
    {"view --fly-to 36", "--fly-to LAT,LON"},
    {"view --frames -1", "--frames: -1 must be >= 0"},
    {"view --frames nan", "--frames"},
    {"view --frames 1e9", "--frames"},
    {"view --frames 99999999999", "--frames"},
    {"view --flight-seconds inf", "--flight-seconds: inf must be positive"},
    {"view --flight-seconds nan", "--flight-seconds: nan must be positive"},
    {"view --frames 10 --flight-frames 1", "--flight-frames: 1 must be >= 2"},
    {"view --screenshot x.png", "--screenshot needs --frames N"},
    {"view --size 0x0", "--size: '0x0' is not WIDTHxHEIGHT with each in 1..16384"},
    {"view --size 99999999999x2", "is not WIDTHxHEIGHT"},
    {"view --boats -1", "--boats -1 is not in 0..10000"},
    {"view --boats 10001", "--boats 10001 is not in 0..10000"},
    {"view --boats 1e9", "--boats"},
    {"view --boats 2 --follow 3", "--follow 3 is not a boat of --boats 2"},
    {"view --coast-region nan,0", "--coast-region: 'nan' in 'nan,0' is not a finite number"},
    {"view --coast-region 95,0", "--coast-region: latitude 95 is outside [-90, 90]"},
    {"view --waves gerstner --coast-region 52.6,4.45,1e300",
     "--coast-region '52.6,4.45,1e300': size 1e+300 m is outside 500 .. 40000 m"},
    {"view --waves gerstner --coast-region 52.6,4.45,0", "size 0 m is outside 500 .. 40000 m"},
    {"view --coast-region ''", "--coast-region: the value is empty"},
    {"view --waves gerstner --coast-follow", "--coast-follow needs --coast-region LAT,LON[,SIZE_M]"},
    {"view --coast-region 1,2,3,4", "--coast-region '1,2,3,4' is not LAT,LON[,SIZE_M]"},
    {"view --wind nan", "--wind nan m/s is outside 0.2 .. 60 m/s"},
    {"view --wind inf", "--wind inf m/s is outside 0.2 .. 60 m/s"},
    {"view --wind -inf", "--wind -inf m/s is outside 0.2 .. 60 m/s"},
    {"view --wind 1e300", "--wind 1e+300 m/s is outside 0.2 .. 60 m/s"},
    {"view --wind 0", "--wind 0 m/s is outside 0.2 .. 60 m/s"},
    {"view --wind-dir nan", "--wind-dir nan is not a finite angle"},
    {"view --waves foam", "--waves 'foam' is not a GPU wave model"},
    // demo, the top level
    {"demo --bogus", "--bogus"},
    {"bogus", "A subcommand is required"},
};

}  // namespace

TEST(BadInputMatrix, EverySubcommandExitsTwoNamingTheValue) {
  const auto dir = std::filesystem::temp_directory_path() / ("geocean-matrix-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  int n = 0;
  for (const Row& r : kRows) {
    // No display: a bad argument is exit 2 whether or not there is one.
    const auto res = run("cd " + dir.string() + " && env -u DISPLAY -u WAYLAND_DISPLAY " + kGeocean + " " + r.args +
                         " </dev/null");
    EXPECT_EQ(res.exitCode, r.exitCode) << r.args << "\n" << res.err;
    EXPECT_NE(res.err.find(r.mustSay), std::string::npos) << r.args << ": " << res.err;
    EXPECT_TRUE(res.out.empty()) << r.args << ": " << res.out;
    ++n;
  }
  std::filesystem::remove_all(dir);
  std::printf("%d bad-input rows over demo, query, render, fly, view, pick, float, mask\n", n);
}

// Batches: a bad row is named by its number and field; the rows before it
// are answered; an empty file or a header alone is an empty batch (exit 0,
// the header only), documented in the README.
TEST(BadInputMatrix, BatchRowsAndEmptyBatches) {
  const struct {
    const char* cmd;
    const char* input;
    int exitCode;
    const char* mustSay;
  } rows[] = {
      {" query --points -", "0,nan\n", 2, "row 1: longitude 'nan' is not a finite number"},
      {" query --points -", "0,0\n0,0,1e300\n", 2, "row 2: time 1e+300 s is outside -1e12 .. 1e12 s"},
      {" query --points -", "0,0,x\n", 2, "row 1: time 'x' is not a finite number"},
      {" query --points -", "1,2,3,4\n", 2, "row 1: more than 3 fields"},
      {" query --points -", ",\n", 2, "row 1: latitude '' is not a finite number"},
      {" pick --rays -", "0,0,0,inf,0,0\n", 2, "inf"},
      {" pick --rays -", "7e6,0,0,-1,0\n", 2, "expected 6 comma-separated numbers, got 5"},
  };
  for (const auto& r : rows) {
    const auto res = run(kGeocean + r.cmd, r.input);
    EXPECT_EQ(res.exitCode, r.exitCode) << r.cmd << " <<< " << r.input << res.err;
    EXPECT_NE(res.err.find(r.mustSay), std::string::npos) << r.cmd << " <<< " << r.input << ": " << res.err;
  }
  // A row longer than the reader's 1 MiB block (no line end): refused by
  // number, the rows before it answered, memory not grown to hold it.
  const auto huge = run(kGeocean + " query --points -", "0,0\n" + std::string(3 << 20, '7') + "\n0,0\n");
  EXPECT_EQ(huge.exitCode, 2) << huge.err;
  EXPECT_NE(huge.err.find("row 2: longer than 1 MiB (no line end), not a point row"), std::string::npos) << huge.err;
  EXPECT_EQ(std::count(huge.out.begin(), huge.out.end(), '\n'), 2) << "header and row 1";
  for (const char* empty : {"", "lat,lon,time\n", "\n\n"}) {
    const auto res = run(kGeocean + " query --points -", empty);
    EXPECT_EQ(res.exitCode, 0) << "'" << empty << "': " << res.err;
    EXPECT_EQ(res.out.rfind("lat,lon,surface,", 0), 0u) << res.out;
    EXPECT_EQ(std::count(res.out.begin(), res.out.end(), '\n'), 1) << "'" << empty << "': " << res.out;
  }
}
