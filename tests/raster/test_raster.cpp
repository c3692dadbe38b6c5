// Raster reading: georeferencing variants, sampling, wrap/poles, nodata and
// every kind of bad file. Fixtures are written with GeoTiffWriter (libtiff),
// OpenImageIO (PNG + world file) and, as an independent writer, GMT.
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/ImageIo.h"
#include "globe/raster/Raster.h"
#include "tests/support/TempDir.h"
#include "tests/support/Subprocess.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

using namespace geocean::raster;
namespace fs = std::filesystem;

namespace {
struct TempDir : geocean::test::TempDir {
  TempDir() : geocean::test::TempDir("geocean-raster") {}
};

// A 36 x 18 global float raster whose value encodes its cell: 100*row + col.
std::vector<float> cellIds(int w, int h) {
  std::vector<float> v(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v[std::size_t(y) * w + x] = float(100 * y + x);
  return v;
}

GeoTransform global(int w, int h) {
  GeoTransform t;
  t.lonStepDeg = 360.0 / w;
  t.latStepDeg = -180.0 / h;
  return t;
}

std::string openError(const std::string& path, OpenOptions o = {}) {
  try {
    Raster::open(path, o);
  } catch (const RasterError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Raster, PixelIsAreaGeoTiffSamplesTheRightCell) {
  TempDir d;
  auto v = cellIds(36, 18);
  GeoTiffWriteOptions o;
  o.transform = global(36, 18);
  o.tileSize = 16;
  writeGeoTiff(d / "a.tif", v.data(), 36, 18, 1, SampleType::F32, o);
  auto r = Raster::open(d / "a.tif");
  ASSERT_TRUE(r->inMemory());
  EXPECT_TRUE(r->transform().global);
  // Cell (col 19, row 4) spans lon [10, 20), lat (40, 50].
  EXPECT_EQ(r->sampleNearest(45.0, 15.0), 419.0f);
  EXPECT_EQ(r->sampleNearest(40.0001, 10.0001), 419.0f);
  // Bilinear at a cell centre is the cell value; halfway between two centres the mean.
  EXPECT_FLOAT_EQ(r->sampleBilinear(45.0, 15.0), 419.0f);
  EXPECT_FLOAT_EQ(r->sampleBilinear(45.0, 20.0), 419.5f);
}

TEST(Raster, LongitudeWrapsAndPolesClamp) {
  TempDir d;
  auto v = cellIds(36, 18);
  GeoTiffWriteOptions o;
  o.transform = global(36, 18);
  writeGeoTiff(d / "g.tif", v.data(), 36, 18, 1, SampleType::F32, o);
  auto r = Raster::open(d / "g.tif");
  EXPECT_EQ(r->sampleNearest(0.5, 180.0), r->sampleNearest(0.5, -180.0));
  EXPECT_EQ(r->sampleNearest(0.5, 359.0), r->sampleNearest(0.5, -1.0));
  // lat 0.5 is in row 8 (lat 0..10); lon 179.999 in column 35, -179.999 in column 0.
  EXPECT_EQ(r->sampleNearest(0.5, 179.999), 835.0f);
  EXPECT_EQ(r->sampleNearest(0.5, -179.999), 800.0f);
  // Bilinear across the antimeridian: continuous, halfway between columns 35 and 0.
  EXPECT_FLOAT_EQ(r->sampleBilinear(-5.0, 180.0), (935.0f + 900.0f) / 2);
  EXPECT_NEAR(r->sampleBilinear(-5.0, 179.9999), r->sampleBilinear(-5.0, -179.9999), 0.01);
  // Poles: the edge row, not NaN.
  EXPECT_EQ(r->sampleNearest(90.0, 5.0), 18.0f);
  EXPECT_EQ(r->sampleNearest(-90.0, 5.0), 1700.0f + 18.0f);
  EXPECT_FLOAT_EQ(r->sampleBilinear(89.99, 5.0), 18.0f);
  EXPECT_TRUE(std::isnan(r->sampleNearest(NAN, 5.0)));
  EXPECT_TRUE(std::isnan(r->sampleBilinear(5.0, INFINITY)));
}

TEST(Raster, PixelIsPointAndNodata) {
  TempDir d;
  // 10 x 10 local grid, 0.1 degree, pixel centres tied at (40.0 N, 10.0 E).
  std::vector<float> v(100, 7.0f);
  v[55] = -9999.0f;
  GeoTiffWriteOptions o;
  o.transform.originLonDeg = 10.0 - 0.05;
  o.transform.originLatDeg = 40.0 + 0.05;
  o.transform.lonStepDeg = 0.1;
  o.transform.latStepDeg = -0.1;
  o.pixelIsPoint = true;
  o.nodata = -9999.0;
  writeGeoTiff(d / "p.tif", v.data(), 10, 10, 1, SampleType::F32, o);
  auto r = Raster::open(d / "p.tif");
  EXPECT_FALSE(r->transform().global);
  EXPECT_NEAR(r->transform().originLonDeg, 9.95, 1e-12);
  EXPECT_NEAR(r->transform().originLatDeg, 40.05, 1e-12);
  ASSERT_TRUE(r->nodata());
  EXPECT_TRUE(std::isnan(r->sampleNearest(39.5, 10.5)));     // pixel (5, 5)
  EXPECT_FLOAT_EQ(r->sampleBilinear(39.55, 10.5), 7.0f);    // nodata neighbour ignored
  EXPECT_TRUE(std::isnan(r->sampleNearest(45.0, 10.5)));     // outside a local raster
}

TEST(Raster, GmtPixelIsPointGridAgreesAtItsNodes) {
  // GMT writes float32 pixel-is-point GeoTIFFs through GDAL: an independent writer.
  if (!geocean::test::haveTool("gmt")) GTEST_SKIP() << "gmt not installed";
  TempDir d;
  auto g = geocean::test::run("cd " + d.path.string() +
                              " && gmt grdlandmask -R-10/10/30/50 -I0.5 -Dl -N0/1/0/1/0 -Gm.tif=gd:GTiff"
                              " && gmt grd2xyz m.tif");
  ASSERT_EQ(g.exitCode, 0) << g.err;
  auto r = Raster::open(d / "m.tif");
  std::istringstream xyz(g.out);
  double lon, lat, z;
  int n = 0;
  while (xyz >> lon >> lat >> z) {
    ++n;
    ASSERT_EQ(r->sampleNearest(lat, lon), float(z)) << lat << "," << lon;
    ASSERT_FLOAT_EQ(r->sampleBilinear(lat, lon), float(z)) << lat << "," << lon;
  }
  EXPECT_EQ(n, 41 * 41);
  EXPECT_EQ(r->sampleNearest(40.4, -3.7), 1.0f);  // Madrid: land
  EXPECT_EQ(r->sampleNearest(45.0, -5.0), 0.0f);  // Bay of Biscay: sea
}

TEST(Raster, PngWithWorldFileAndGlobalEquirect) {
  TempDir d;
  std::vector<unsigned char> px(8 * 4, 0);
  px[1 * 8 + 6] = 200;  // row 1, column 6
  {
    auto out = OIIO::ImageOutput::create(d / "w.png");
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(8, 4, 1, OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(out->open(d / "w.png", spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
    out->close();
  }
  EXPECT_NE(openError(d / "w.png").find("no georeferencing"), std::string::npos);
  OpenOptions eq;
  eq.georef = Georef::GlobalEquirect;
  auto g = Raster::open(d / "w.png", eq);
  // Column 6 of 8 spans lon [90, 135); row 1 of 4 spans lat (0, 45].
  EXPECT_EQ(g->sampleNearest(20.0, 100.0), 200.0f);  // the raw value, not 200/255
  std::ofstream(d / "w.pgw") << "0.5\n0\n0\n-0.5\n10.25\n50.75\n";  // centre of UL pixel
  auto w = Raster::open(d / "w.png");
  EXPECT_FALSE(w->transform().global);
  EXPECT_EQ(w->sampleNearest(50.25, 13.25), 200.0f);  // column 6, row 1
}

TEST(Raster, RejectsWhatItCannotReadWithAClearMessage) {
  TempDir d;
  std::vector<float> v(16 * 16, 1.0f);
  GeoTiffWriteOptions o;
  o.transform.originLonDeg = 500000;
  o.transform.originLatDeg = 4649776;
  o.transform.lonStepDeg = 30;
  o.transform.latStepDeg = -30;
  o.projectedEpsg = 32633;  // UTM zone 33N
  writeGeoTiff(d / "utm.tif", v.data(), 16, 16, 1, SampleType::F32, o);
  const std::string utm = openError(d / "utm.tif");
  EXPECT_NE(utm.find("utm.tif"), std::string::npos) << utm;
  EXPECT_NE(utm.find("projected"), std::string::npos) << utm;

  GeoTiffWriteOptions rot;
  rot.transform = global(16, 16);
  rot.rotationTerm = 0.01;
  writeGeoTiff(d / "rot.tif", v.data(), 16, 16, 1, SampleType::F32, rot);
  EXPECT_NE(openError(d / "rot.tif").find("rotated"), std::string::npos);

  GeoTiffWriteOptions nokeys;
  nokeys.transform = o.transform;  // metres but no GeoKeys at all
  nokeys.writeGeoKeys = false;
  writeGeoTiff(d / "nokeys.tif", v.data(), 16, 16, 1, SampleType::F32, nokeys);
  EXPECT_NE(openError(d / "nokeys.tif").find("outside [-90, 90]"), std::string::npos);

  EXPECT_NE(openError(d / "missing.tif").find("no such file"), std::string::npos);
  std::ofstream(d / "text.tif") << "this is not an image\n";
  EXPECT_NE(openError(d / "text.tif").find("text.tif"), std::string::npos);

  // Truncated: a real GeoTIFF cut in half.
  std::vector<float> big(256 * 256);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = float(i % 977);
  GeoTiffWriteOptions g;
  g.transform = global(256, 256);
  g.compression = Compression::None;
  writeGeoTiff(d / "t.tif", big.data(), 256, 256, 1, SampleType::F32, g);
  fs::resize_file(d / "t.tif", fs::file_size(d / "t.tif") / 2);
  const std::string trunc = openError(d / "t.tif");
  EXPECT_NE(trunc.find("t.tif"), std::string::npos);
  EXPECT_FALSE(trunc.empty());
  // Truncated and read through the cache: the probe may pass, but samples never crash.
  try {
    OpenOptions cached;
    cached.inMemoryLimitBytes = 0;
    auto c = Raster::open(d / "t.tif", cached);
    std::vector<double> la(100, -80.0), lo(100, 170.0);
    std::vector<float> out(100);
    c->sampleNearestBatch(la.data(), lo.data(), 100, out.data());
  } catch (const RasterError&) {
  }
}

// A w x h one-band byte TIFF of `value`, uncompressed (tileSize 0: one
// strip), whose header patchTiffTags then rewrites.
void writePatchable(const fs::path& path, int w, int h, int tileSize, std::uint8_t value) {
  std::vector<unsigned char> px(std::size_t(w) * h, value);
  GeoTiffWriteOptions o;
  o.transform = global(w, h);
  o.tileSize = tileSize;
  o.compression = Compression::None;
  writeGeoTiff(path, px.data(), w, h, 1, SampleType::U8, o);
}

// Sets the first IFD's entries for `tags` (SHORT or LONG) to the LONG `v`.
void patchTiffTags(const fs::path& path, std::initializer_list<int> tags, uint32_t v) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  unsigned char hdr[8];
  f.read(reinterpret_cast<char*>(hdr), 8);
  ASSERT_EQ(hdr[0], 'I');  // little-endian, as libtiff writes on x86
  const uint32_t ifd = hdr[4] | hdr[5] << 8 | hdr[6] << 16 | uint32_t(hdr[7]) << 24;
  f.seekg(ifd);
  unsigned char cnt[2];
  f.read(reinterpret_cast<char*>(cnt), 2);
  const int n = cnt[0] | cnt[1] << 8;
  int patched = 0;
  for (int i = 0; i < n; ++i) {
    unsigned char e[12];
    const std::streamoff at = ifd + 2 + 12 * i;
    f.seekg(at);
    f.read(reinterpret_cast<char*>(e), 12);
    const int tag = e[0] | e[1] << 8;
    if (std::find(tags.begin(), tags.end(), tag) != tags.end()) {
      e[2] = 4;  // type LONG
      e[3] = 0;
      std::memcpy(e + 8, &v, 4);
      f.seekp(at);
      f.write(reinterpret_cast<char*>(e), 12);
      ++patched;
    }
  }
  ASSERT_EQ(patched, int(tags.size()));
}

TEST(Raster, RejectsAbsurdDimensionsBeforeAllocating) {
  TempDir d;
  // A header that claims 200000 x 200000 pixels (40 G samples) with one tiny strip.
  writePatchable(d / "small.tif", 16, 1, 0, 0);
  patchTiffTags(d / "small.tif", {256, 257}, 200000);  // ImageWidth, ImageLength
  const std::string err = openError(d / "small.tif");
  EXPECT_NE(err.find("exceed"), std::string::npos) << err;
  EXPECT_NE(err.find("200000"), std::string::npos) << err;
}

TEST(Raster, RejectsAbsurdTilesBeforeAllocating) {
  // A 32 x 32 image whose header claims tiles of 65536 x 65536 (4 G
  // samples: every read path allocated a tile of that size; CI's
  // fuzz_geotiff, stop 25). Refused naming the tile size, on every path.
  TempDir d;
  writePatchable(d / "tiles.tif", 32, 32, 16, 7);
  patchTiffTags(d / "tiles.tif", {322, 323}, 65536);  // TileWidth, TileLength
  for (int path = 0; path < 3; ++path) {
    OpenOptions opt;
    opt.fewLookups = path == 1;
    if (path == 2) opt.inMemoryLimitBytes = 0;
    const std::string err = openError(d / "tiles.tif", opt);
    EXPECT_NE(err.find("tiles.tif"), std::string::npos) << path << ": " << err;
    EXPECT_NE(err.find("tile size 65536 x 65536"), std::string::npos) << path << ": " << err;
  }
  // Tiles each within the limit whose blocks over the image are not: a
  // 4096 x 8 image of 16 x 4096 tiles decodes 256 tiles of 64 k samples
  // (16 M) for 32 k pixels (fuzz_geotiff's timeout had 1237 of 2.7 M).
  writePatchable(d / "tall.tif", 4096, 8, 16, 7);
  patchTiffTags(d / "tall.tif", {323}, 4096);  // TileLength
  OpenOptions small;
  small.maxPixels = std::int64_t(1) << 22;
  const std::string err = openError(d / "tall.tif", small);
  EXPECT_NE(err.find("256 tiles of 16 x 4096"), std::string::npos) << err;
  small.maxPixels = std::int64_t(1) << 24;  // exactly the blocks' samples: not refused for them
  const std::string at = openError(d / "tall.tif", small);  // (the patched tiles' data is short)
  EXPECT_EQ(at.find("tiles of"), std::string::npos) << at;
}

// The OpenImageIO module mapped into this process (ctest runs each test
// in a process of its own).
bool oiioModuleLoaded() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("geocean_oiio") != std::string::npos) return true;
  return false;
}

// A TIFF too big to load (here: over a tiny inMemoryLimitBytes) streams
// through libtiff's tile reads and never loads OpenImageIO (issue 12 item
// 6: its ~110 MB of mapped libraries and ~29 MB of its own were most of
// what a streamed 3" relief's flight had over 1 GB), whatever it reads:
// every pixel, against the values written, in an LRU of fewer tiles than
// the file has (so tiles are evicted and read again), from many threads
// at once (Raster's const methods are called from the render's workers).
// A TIFF of strips bigger than a quarter of the cache still streams
// through OpenImageIO's ImageCache, loaded on the first pixel read (a
// truncated file through the cache: RejectsWhatItCannotReadWithAClearMessage).
TEST(Raster, ABigTiffStreamsThroughLibtiffWithoutOpenImageIO) {
  if (oiioModuleLoaded()) {  // an earlier test of this process loaded it (ctest runs one a process)
    const auto r = geocean::test::run(fs::read_symlink("/proc/self/exe").string() +
                                      " --gtest_filter=Raster.ABigTiffStreamsThroughLibtiffWithoutOpenImageIO");
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    return;
  }
  TempDir d;
  // Two channels of int16 (the relief's type; the block cache keeps it as
  // int16), tiles of 64: 8 x 4 tiles of 16 KB, a cache of 64 KB holds 4.
  constexpr int kW = 512, kH = 256;
  std::vector<std::int16_t> v(std::size_t(kW) * kH * 2);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::int16_t(int(i % 30011) - 15000);
  auto want = [&](int x, int y, int c) { return float(v[(std::size_t(y) * kW + x) * 2 + c]); };
  GeoTiffWriteOptions o;
  o.transform = global(kW, kH);
  o.tileSize = 64;
  writeGeoTiff(d / "big.tif", v.data(), kW, kH, 2, SampleType::I16, o);
  OpenOptions big;
  big.inMemoryLimitBytes = 1024;
  big.cacheBytes = 64 << 10;
  auto r = Raster::open(d / "big.tif", big);
  ASSERT_FALSE(r->inMemory());
  EXPECT_EQ(r->memoryBytes(), big.cacheBytes);
  std::vector<std::thread> threads;
  std::atomic<long> wrong{0};
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int y = t; y < kH; y += 4)
        for (int x = 0; x < kW; ++x)
          for (int c = 0; c < 2; ++c)
            if (r->pixel(x, y, c) != want(x, y, c)) ++wrong;
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
  // Batches (a tile and its apron from up to four tiles), against single pixels.
  std::vector<double> la, lo;
  for (double lat = -89.7; lat < 90; lat += 0.91)
    for (double lon = -179.8; lon < 180; lon += 1.37) la.push_back(lat), lo.push_back(lon);
  for (int c = 0; c < 2; ++c) {
    std::vector<float> n(la.size()), b(la.size());
    r->sampleNearestBatch(la.data(), lo.data(), la.size(), n.data(), c);
    r->sampleBilinearBatch(la.data(), lo.data(), la.size(), b.data(), c);
    for (std::size_t i = 0; i < la.size(); ++i) {
      ASSERT_EQ(n[i], r->sampleNearest(la[i], lo[i], c)) << la[i] << "," << lo[i];
      ASSERT_EQ(b[i], r->sampleBilinear(la[i], lo[i], c)) << la[i] << "," << lo[i];
    }
  }
  EXPECT_FALSE(oiioModuleLoaded()) << "streaming a tiled TIFF loaded OpenImageIO";

  // Strips of 64 rows of 512 floats (128 KB) over a cache of 64 KB: the ImageCache.
  std::vector<float> f(std::size_t(kW) * kH);
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = float(i);
  o.tileSize = 0;
  o.compression = Compression::None;
  writeGeoTiff(d / "strip.tif", f.data(), kW, kH, 1, SampleType::F32, o);
  auto s = Raster::open(d / "strip.tif", big);
  ASSERT_FALSE(s->inMemory());
  EXPECT_FALSE(oiioModuleLoaded()) << "opening loaded OpenImageIO";
  EXPECT_EQ(s->pixel(300, 200), f[200 * kW + 300]);
  EXPECT_TRUE(oiioModuleLoaded()) << "the pixel should come through OpenImageIO's ImageCache";
  for (int y = 0; y < kH; y += 37)
    for (int x = 0; x < kW; x += 41) ASSERT_EQ(s->pixel(x, y), f[std::size_t(y) * kW + x]) << x << "," << y;
}

// 8- and 16-bit TIFFs loaded into memory keep their own samples (a 16-bit
// relief is half its floats, an 8-bit mask a quarter: issue 12 item 6) and
// read exactly as written, nodata as NaN, the same as through libtiff's
// blocks; a drawing host's regional limit streams a regional raster only.
TEST(Raster, EightAndSixteenBitRastersKeepTheirSamplesInMemory) {
  TempDir d;
  const int w = 200, h = 100;
  for (const SampleType type : {SampleType::U8, SampleType::I16})
    for (const int c : {1, 2}) {
      const bool u8 = type == SampleType::U8;
      const double nd = u8 ? 255.0 : -32768.0;
      std::vector<std::uint8_t> b(std::size_t(w) * h * c);
      std::vector<std::int16_t> s(b.size());
      std::vector<float> want(b.size());
      for (std::size_t i = 0; i < b.size(); ++i) {
        const bool hole = i % 97 == 5;
        b[i] = std::uint8_t(hole ? 255 : (i * 7) % 255);
        s[i] = std::int16_t(hole ? -32768 : int((i * 131) % 20001) - 10000);
        want[i] = hole ? NAN : u8 ? float(b[i]) : float(s[i]);
      }
      GeoTiffWriteOptions o;
      o.transform = global(w, h);
      o.tileSize = 32;
      o.nodata = nd;
      const std::string path = d / ("n" + std::to_string(int(u8)) + std::to_string(c) + ".tif");
      if (u8)
        writeGeoTiff(path, b.data(), w, h, c, type, o);
      else
        writeGeoTiff(path, s.data(), w, h, c, type, o);
      const std::string what = path + (u8 ? " (uint8 x " : " (int16 x ") + std::to_string(c) + ")";
      const auto mem = Raster::open(path);
      OpenOptions streamed;
      streamed.inMemoryLimitBytes = 0;
      const auto blocks = Raster::open(path, streamed);
      ASSERT_TRUE(mem->inMemory()) << what;
      ASSERT_FALSE(blocks->inMemory()) << what;
      EXPECT_EQ(mem->memoryBytes(), b.size() * (u8 ? 1u : 2u)) << what;
      const std::vector<float> px = mem->pixels();
      ASSERT_EQ(px.size(), want.size()) << what;
      for (std::size_t i = 0; i < want.size(); ++i) {
        const int x = int(i / c) % w, y = int(i / c) / w, k = int(i % c);
        ASSERT_TRUE(px[i] == want[i] || (std::isnan(px[i]) && std::isnan(want[i]))) << what << " sample " << i;
        const float v = mem->pixel(x, y, k);
        ASSERT_TRUE(v == want[i] || (std::isnan(v) && std::isnan(want[i]))) << what << " pixel " << x << "," << y;
      }
      for (double lat = -89.95; lat < 90; lat += 3.7)
        for (double lon = -179.9; lon < 180; lon += 5.3)
          for (int k = 0; k < c; ++k) {
            const float n0 = mem->sampleNearest(lat, lon, k), n1 = blocks->sampleNearest(lat, lon, k);
            const float b0 = mem->sampleBilinear(lat, lon, k), b1 = blocks->sampleBilinear(lat, lon, k);
            ASSERT_TRUE(n0 == n1 || (std::isnan(n0) && std::isnan(n1))) << what << " " << lat << "," << lon;
            ASSERT_TRUE(b0 == b1 || (std::isnan(b0) && std::isnan(b1))) << what << " " << lat << "," << lon;
          }
    }
  // The regional rule: a regional raster over the limit streams, a global one does not.
  std::vector<float> f(std::size_t(w) * h, 1.0f);
  GeoTiffWriteOptions g;
  g.transform = global(w, h);
  GeoTiffWriteOptions r = g;
  r.transform.lonStepDeg = 0.01;
  r.transform.latStepDeg = -0.01;
  writeGeoTiff(d / "g.tif", f.data(), w, h, 1, SampleType::F32, g);
  writeGeoTiff(d / "r.tif", f.data(), w, h, 1, SampleType::F32, r);
  OpenOptions drawing;
  drawing.regionalInMemoryLimitBytes = 1024;
  EXPECT_TRUE(Raster::open(d / "g.tif", drawing)->inMemory());
  EXPECT_FALSE(Raster::open(d / "r.tif", drawing)->inMemory());
  EXPECT_TRUE(Raster::open(d / "r.tif")->inMemory());
}

TEST(Raster, FewLookupsTilesEqualInMemoryAndImagesRoundTrip) {
  TempDir d;
  // int16 with negative values through libtiff tiles (no normalisation, sign kept).
  std::vector<std::int16_t> v(600 * 300);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::int16_t(int(i % 20011) - 10000);
  GeoTiffWriteOptions o;
  o.transform = global(600, 300);
  o.tileSize = 64;
  writeGeoTiff(d / "e.tif", v.data(), 600, 300, 1, SampleType::I16, o);
  auto mem = Raster::open(d / "e.tif");
  OpenOptions few;
  few.fewLookups = true;
  auto tiles = Raster::open(d / "e.tif", few);
  ASSERT_TRUE(mem->inMemory());
  ASSERT_FALSE(tiles->inMemory());
  EXPECT_EQ(mem->pixel(599, 299), float(v[599 + 299 * 600]));
  for (double lat = -89.9; lat < 90; lat += 7.3)
    for (double lon = -179.95; lon < 180; lon += 11.1) {
      ASSERT_EQ(tiles->sampleNearest(lat, lon), mem->sampleNearest(lat, lon)) << lat << "," << lon;
      ASSERT_EQ(tiles->sampleBilinear(lat, lon), mem->sampleBilinear(lat, lon)) << lat << "," << lon;
    }
  // PNG out (our zlib writer) and back through the OpenImageIO module
  // (libpng: an independent decoder, which checks the chunks' CRCs); TIFF
  // back through libtiff.
  std::vector<unsigned char> rgb(5 * 3 * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<unsigned char>(i * 5);
  writeImage8(d / "x.png", rgb.data(), 5, 3, 3);
  const Image8 back = readImage8(d / "x.png");
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.channels, 3);
  EXPECT_EQ(back.pixels, rgb);
  // Every channel count, rows that pick each of the five filters (flat,
  // ramps across and down, noise), a width that is not a multiple of 4.
  for (int c = 1; c <= 4; ++c) {
    const int w = 61, h = 23;
    std::vector<unsigned char> px(std::size_t(w) * h * c);
    std::uint32_t r = 12345;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < c; ++k) {
          r = r * 1664525u + 1013904223u;
          const int band = y / 5;
          const bool alpha = (c == 2 || c == 4) && k == c - 1;  // opaque: the zlib writer's case
          px[(std::size_t(y) * w + x) * c + k] = static_cast<unsigned char>(
              alpha ? 255 : band == 0 ? 200 : band == 1 ? x * 4 + k : band == 2 ? y * 11 + k * 3 : band == 3 ? (x + y) * 3 : r >> 24);
        }
    const std::string name = d / ("c" + std::to_string(c) + ".PNG");
    writeImage8(name, px.data(), w, h, c);
    const Image8 in = readImage8(name);
    EXPECT_EQ(in.width, w);
    EXPECT_EQ(in.height, h);
    EXPECT_EQ(in.channels, c);
    EXPECT_EQ(in.pixels, px) << c << " channels";
  }
  EXPECT_THROW(readImage8(d / "none.png"), RasterError);
  EXPECT_THROW(writeImage8("/nonexistent-dir/x.png", rgb.data(), 5, 3, 3), RasterError);
  EXPECT_THROW(writeImage8(d / "five.png", rgb.data(), 1, 3, 5), RasterError);
  // A partial alpha goes through OpenImageIO as before (it stores colour
  // divided by alpha, and multiplies it back when reading).
  const unsigned char half[8] = {100, 50, 0, 128, 10, 20, 30, 255};
  writeImage8(d / "alpha.png", half, 2, 1, 4);
  const Image8 ha = readImage8(d / "alpha.png");
  ASSERT_EQ(ha.pixels.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(ha.pixels[std::size_t(i)], half[i], 1) << i;
}
