// The tile pyramid (globe/raster/TilePyramid.h): values against direct reads
// and block means of the source through Raster (the existing reader), the
// on-disk cache (reuse, invalidation, corrupt index, unwritable or full
// folder), sparse rasters, and the resident-memory bound while building a
// 43200 x 21600 raster.
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/Raster.h"
#include "globe/raster/TileIndex.h"
#include "globe/raster/TilePyramid.h"
#include "tests/support/ProcStatus.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

using namespace geocean::raster;
namespace fs = std::filesystem;

namespace {

struct TempDir : geocean::test::TempDir {
  TempDir() : geocean::test::TempDir("geocean-tiles") {}
};
using geocean::test::statusKb;

// A small float raster with a nodata hole, as a tiled GeoTIFF (tiles of 48,
// not a divisor of the pyramid's 64, so blocks straddle tiles).
constexpr int kSW = 1000, kSH = 600;
constexpr float kNodata = -9999.0f;
float smallValue(int x, int y, float seed) {
  if (x > 300 && x < 420 && y > 100 && y < 180) return kNodata;
  return seed + std::sin(x * 0.05f) * 100.0f + float(y) * 0.5f;
}
void writeSmall(const std::string& path, float seed, bool global) {
  std::vector<float> v(std::size_t(kSW) * kSH);
  for (int y = 0; y < kSH; ++y)
    for (int x = 0; x < kSW; ++x) v[std::size_t(y) * kSW + x] = smallValue(x, y, seed);
  GeoTiffWriteOptions o;
  o.transform.lonStepDeg = global ? 360.0 / kSW : 0.01;
  o.transform.latStepDeg = global ? -180.0 / kSH : -0.01;
  o.transform.originLonDeg = global ? -180.0 : 10.0;
  o.transform.originLatDeg = global ? 90.0 : 50.0;
  o.tileSize = 48;
  o.nodata = kNodata;
  writeGeoTiff(path, v.data(), kSW, kSH, 1, SampleType::F32, o);
}

// The reference pyramid computed directly from the full image: level l is
// the NaN-ignoring mean of 2 x 2 texels of level l-1.
std::vector<std::vector<float>> referenceLevels(const Raster& r, int levels) {
  std::vector<std::vector<float>> out(levels);
  int w = r.width(), h = r.height();
  out[0].resize(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out[0][std::size_t(y) * w + x] = r.pixel(x, y);
  for (int l = 1; l < levels; ++l) {
    const int pw = w, ph = h;
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    out[l].assign(std::size_t(w) * h, NAN);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        float s = 0;
        int n = 0;
        for (int d = 0; d < 4; ++d) {
          const int sx = 2 * x + (d & 1), sy = 2 * y + (d >> 1);
          if (sx >= pw || sy >= ph) continue;
          const float v = out[l - 1][std::size_t(sy) * pw + sx];
          if (!std::isnan(v)) s += v, ++n;
        }
        if (n) out[l][std::size_t(y) * w + x] = s / float(n);
      }
  }
  return out;
}

PyramidOptions quiet(const fs::path& cache, int tileSize = 64) {
  PyramidOptions o;
  o.cacheDir = cache.string();
  o.tileSize = tileSize;
  o.progress = BuildProgress::Off;
  return o;
}

}  // namespace

TEST(TilePyramid, EveryLevelIsTheMeanOfValidTexelsWithBordersFromNeighbours) {
  for (const bool global : {false, true}) {
    TempDir t;
    const std::string path = (t.path / "small.tif").string();
    writeSmall(path, 0.0f, global);
    auto src = Raster::open(path);
    auto p = TilePyramid::open(src, quiet(t.path / "cache"));
    // 1000 x 600 in 64-texel tiles: 16 x 10, 8 x 5, 4 x 3, 2 x 2, 1 x 1.
    ASSERT_EQ(p->levels(), 5);
    EXPECT_EQ(p->tilesX(0), 16);
    EXPECT_EQ(p->tilesY(1), 5);
    EXPECT_EQ(p->levelWidth(3), 125);
    EXPECT_EQ(p->levelHeight(4), 38);
    const auto ref = referenceLevels(*src, p->levels());
    const int T = p->tileSize(), B = T + 2;
    std::vector<float> tile(std::size_t(B) * B);
    long bad = 0, checked = 0;
    for (int l = 0; l < p->levels(); ++l) {
      const int W = p->levelWidth(l), H = p->levelHeight(l);
      for (int ty = 0; ty < p->tilesY(l); ++ty)
        for (int tx = 0; tx < p->tilesX(l); ++tx) {
          p->readTile({l, tx, ty}, tile.data());
          for (int j = 0; j < B; ++j)
            for (int i = 0; i < B; ++i) {
              int gx = tx * T + i - 1, gy = std::clamp(ty * T + j - 1, 0, H - 1);
              gx = global ? (gx + W) % W : std::clamp(gx, 0, W - 1);
              const float want = ref[l][std::size_t(gy) * W + gx], got = tile[std::size_t(j) * B + i];
              ++checked;
              // Same operations in the same order as the reference: exact.
              if (!(want == got || (std::isnan(want) && std::isnan(got)))) ++bad;
            }
        }
    }
    EXPECT_EQ(bad, 0) << "of " << checked << (global ? " (global)" : " (regional)");
    // The nodata hole (x 301..419, y 101..179) is NaN at level 0 and still
    // NaN at level 2 where all 16 source pixels are in it.
    std::vector<float> t0(std::size_t(B) * B);
    p->readTile({0, 350 / 64, 140 / 64}, t0.data());
    EXPECT_TRUE(std::isnan(t0[std::size_t(140 % 64 + 1) * B + 350 % 64 + 1]));
    EXPECT_TRUE(std::isnan(ref[2][std::size_t(35) * p->levelWidth(2) + 90]));
    // A block mean where every pixel is valid, to float rounding (16 values
    // of magnitude <= 400 summed in two stages: well under 1e-3).
    double s = 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) s += src->pixel(40 + x, 20 + y);
    p->readTile({2, 0, 0}, tile.data());
    EXPECT_NEAR(tile[std::size_t(5 + 1) * B + 10 + 1], s / 16.0, 1e-3);
  }
}

TEST(TilePyramid, CacheIsReusedAndRebuiltWhenTheSourceChanges) {
  TempDir t;
  const std::string path = (t.path / "src.tif").string();
  writeSmall(path, 0.0f, false);
  std::vector<float> a(66 * 66), b(66 * 66);
  {
    auto p = TilePyramid::open(Raster::open(path), quiet(t.path / "cache"));
    EXPECT_TRUE(p->stats().builtNow);
    EXPECT_FALSE(p->stats().inMemory);
    EXPECT_TRUE(fs::exists(fs::path(p->stats().cachePath) / "index"));
    p->readTile({2, 1, 1}, a.data());
  }
  {
    auto p = TilePyramid::open(Raster::open(path), quiet(t.path / "cache"));
    EXPECT_FALSE(p->stats().builtNow);  // second open: no rebuild
    p->readTile({2, 1, 1}, b.data());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * 4));
  }
  // Touch: same bytes, new mtime -> rebuilt.
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(5));
  {
    auto p = TilePyramid::open(Raster::open(path), quiet(t.path / "cache"));
    EXPECT_TRUE(p->stats().builtNow);
  }
  // Rewrite with other values (same size, the mtime put back): the header
  // hash differs (libtiff writes the IFD after the data... the data differ
  // in the last 64 KiB) -> rebuilt with the new values.
  const auto mtime = fs::last_write_time(path);
  writeSmall(path, 1000.0f, false);
  fs::last_write_time(path, mtime);
  {
    auto p = TilePyramid::open(Raster::open(path), quiet(t.path / "cache"));
    EXPECT_TRUE(p->stats().builtNow);
    p->readTile({2, 1, 1}, b.data());
    EXPECT_NEAR(b[70] - a[70], 1000.0f, 1e-2);
  }
  // A different value map is a different cache.
  {
    PyramidOptions o = quiet(t.path / "cache");
    o.valueMapId = "double";
    o.valueMap = [](float* v, std::size_t n, int) {
      for (std::size_t i = 0; i < n; ++i) v[i] *= 2.0f;
    };
    auto p = TilePyramid::open(Raster::open(path), o);
    EXPECT_TRUE(p->stats().builtNow);
    std::vector<float> c(66 * 66);
    p->readTile({2, 1, 1}, c.data());
    EXPECT_NEAR(c[70], 2.0f * b[70], 1e-2);
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(t.path / "cache"), fs::directory_iterator{}), 2);
}

TEST(TilePyramid, CorruptIndexIsRebuiltWithAWarning) {
  TempDir t;
  const std::string path = (t.path / "src.tif").string();
  writeSmall(path, 0.0f, false);
  std::string index;
  {
    auto p = TilePyramid::open(Raster::open(path), quiet(t.path / "cache"));
    index = p->stats().cachePath + "/index";
  }
  {
    // Flip the byte's bits: byte 40 is in the source's path, whose temp
    // folder's name is random, so writing a fixed 'U' left the index intact
    // whenever the name had a 'U' there (failed once under ASan, 2026-12-04).
    std::fstream f(index, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(40);
    const char was = char(f.get());
    f.seekp(40);
    f.put(char(~was));
  }
  testing::internal::CaptureStderr();
  auto p = TilePyramid::open(Raster::open(path), quiet(t.path / "cache"));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(p->stats().builtNow);
  EXPECT_NE(err.find("tile cache index is corrupt: checksum mismatch"), std::string::npos) << err;
  EXPECT_NE(err.find(index), std::string::npos) << err;
}

// Level 0 is in the cache (format 2): a warm open reads every level-0 tile
// from it, bit for bit the source's texels (through Raster::pixel, the
// other reader) with the value map applied, and never reads the source: a
// source truncated after the warm open still gives every tile (the old
// cache read level 0 from the source: NaN or an error here). Two sources:
// floats with a nodata hole (float tiles) and 8-bit classes with nodata
// mapped by a value map as a mask's (byte tiles, NaN given a free code).
// An index of the old format (version 1, no level 0) is rebuilt with a
// warning naming the version, never read as this one.
TEST(TilePyramid, WarmCacheHoldsLevel0AndNeverReadsTheSource) {
  TempDir t;
  for (const bool classes : {false, true}) {
    const std::string path = (t.path / (classes ? "classes.tif" : "floats.tif")).string();
    PyramidOptions o = quiet(t.path / "cache");
    if (classes) {
      std::vector<std::uint8_t> v(std::size_t(kSW) * kSH);
      for (int y = 0; y < kSH; ++y)
        for (int x = 0; x < kSW; ++x)
          v[std::size_t(y) * kSW + x] = smallValue(x, y, 0.0f) == kNodata ? 255 : std::uint8_t((x / 7 + y / 5) % 5);
      GeoTiffWriteOptions w;
      w.transform.lonStepDeg = 0.01, w.transform.latStepDeg = -0.01;
      w.transform.originLonDeg = 10.0, w.transform.originLatDeg = 50.0;
      w.tileSize = 48;
      w.nodata = 255;
      writeGeoTiff(path, v.data(), kSW, kSH, 1, SampleType::U8, w);
      o.valueMapId = "water-of-classes";
      o.valueMap = [](float* tex, std::size_t n, int) {  // classes 1 and 3 water, as a mask's encoding
        for (std::size_t i = 0; i < n; ++i)
          tex[i] = std::isnan(tex[i]) ? tex[i] : (tex[i] == 1.0f || tex[i] == 3.0f) ? 1.0f : 0.0f;
      };
    } else {
      writeSmall(path, 0.0f, false);
    }
    OpenOptions ro;
    ro.inMemoryLimitBytes = 0;  // read from the file (a raster in memory would answer after truncation)
    auto src = Raster::open(path, ro);
    ASSERT_FALSE(src->inMemory());
    std::vector<float> want(std::size_t(kSW) * kSH);
    for (int y = 0; y < kSH; ++y)
      for (int x = 0; x < kSW; ++x) want[std::size_t(y) * kSW + x] = src->pixel(x, y);
    if (o.valueMap) o.valueMap(want.data(), want.size(), 1);
    std::string index;
    {
      auto cold = TilePyramid::open(src, o);
      ASSERT_TRUE(cold->stats().builtNow);
      index = cold->stats().cachePath + "/index";
    }
    auto warm = TilePyramid::open(src, o);
    ASSERT_FALSE(warm->stats().builtNow);
    EXPECT_TRUE(warm->stats().level0Stored);
    fs::resize_file(path, 0);  // nothing is read from the source from now on
    long bad = 0;
    for (int ty = 0; ty < warm->tilesY(0); ++ty)
      for (int tx = 0; tx < warm->tilesX(0); ++tx) {
        const auto tile = warm->interior({0, tx, ty});
        for (int y = 0; y < 64; ++y)
          for (int x = 0; x < 64; ++x) {
            const int gx = tx * 64 + x, gy = ty * 64 + y;
            const float got = (*tile)[std::size_t(y) * 64 + x];
            const float w = gx < kSW && gy < kSH ? want[std::size_t(gy) * kSW + gx] : NAN;
            std::uint32_t a, b;
            std::memcpy(&a, &got, 4), std::memcpy(&b, &w, 4);
            bad += std::isnan(w) ? !std::isnan(got) : a != b;
          }
      }
    EXPECT_EQ(bad, 0) << path;

    // The old format: the same index written as version 1 (checksum right).
    std::string bytes;
    {
      std::ifstream f(index, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(f), {});
    }
    ASSERT_GT(bytes.size(), 20u);
    const std::uint32_t v1 = 1;
    std::memcpy(bytes.data() + 8, &v1, 4);
    const std::uint64_t sum = fnv1a(bytes.data(), bytes.size() - 8);
    std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    { std::ofstream(index, std::ios::binary | std::ios::trunc) << bytes; }
    if (classes) {
      // A source to rebuild from (the truncated one cannot be read).
      fs::remove(path);
      continue;
    }
    writeSmall(path, 0.0f, false);
    testing::internal::CaptureStderr();
    auto rebuilt = TilePyramid::open(Raster::open(path), o);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_TRUE(rebuilt->stats().builtNow);
    EXPECT_NE(err.find(index + ": tile cache index has format version 1, this build reads 2: rebuilding it"),
              std::string::npos)
        << err;
  }
}

TEST(TilePyramid, UnwritableOrFullCacheFolderFallsBackToMemoryWithAWarning) {
  TempDir t;
  const std::string path = (t.path / "src.tif").string();
  writeSmall(path, 0.0f, false);
  auto src = Raster::open(path);
  const auto ref = referenceLevels(*src, 5);
  std::vector<float> tile(66 * 66);
  // Not a folder (running as root, permissions would not stop us).
  { std::ofstream(t.path / "file") << "x"; }
  testing::internal::CaptureStderr();
  auto p = TilePyramid::open(src, quiet(t.path / "file" / "cache"));
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(p->stats().inMemory);
  EXPECT_NE(err.find("cannot be written (Not a directory)"), std::string::npos) << err;
  EXPECT_NE(err.find("in memory"), std::string::npos) << err;
  p->readTile({3, 1, 0}, tile.data());
  EXPECT_EQ(tile[67], ref[3][64]);

  // Full: a file-size limit of 20 KB stops the writes part way (as a full
  // disk would, EFBIG instead of ENOSPC); what was written moves to memory.
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  rlimit lim = old;
  lim.rlim_cur = 20000;
  setrlimit(RLIMIT_FSIZE, &lim);
  testing::internal::CaptureStderr();
  p = TilePyramid::open(src, quiet(t.path / "full"));
  err = testing::internal::GetCapturedStderr();
  setrlimit(RLIMIT_FSIZE, &old);
  EXPECT_TRUE(p->stats().inMemory);
  EXPECT_GT(p->stats().storedBytes, 20000u);
  EXPECT_NE(err.find("File too large"), std::string::npos) << err;
  long bad = 0;
  for (int l = 1; l < 5; ++l)
    for (int ty = 0; ty < p->tilesY(l); ++ty)
      for (int tx = 0; tx < p->tilesX(l); ++tx) {
        p->readTile({l, tx, ty}, tile.data());
        const int gx = tx * 64, gy = ty * 64;
        const float want = ref[l][std::size_t(gy) * p->levelWidth(l) + gx];
        bad += !(tile[67] == want || (std::isnan(want) && std::isnan(tile[67])));
      }
  EXPECT_EQ(bad, 0);
  // Nothing half-written is left to be mistaken for a cache.
  EXPECT_FALSE(fs::exists(fs::path(p->stats().cachePath.empty() ? "" : p->stats().cachePath) / "index"));
}

TEST(TileIndex, RoundTripsAndRejectsEveryTruncationAndBadField) {
  TileIndex idx;
  idx.key = {"/data/a.tif", 1234, 5678, 42, "water:default", 64, 1, 1000, 600, 5};
  for (int l = 0; l < 5; ++l)
    for (std::uint32_t y = 0; y < levelTiles(600, l, 64); ++y)
      for (std::uint32_t x = 0; x < levelTiles(1000, l, 64); ++x)
        idx.records.push_back({std::uint8_t(l), TileKind::Constant, x, y, idx.dataBytes += 4, 4});
  idx.dataBytes += 4;
  const std::string s = serializeTileIndex(idx);
  const TileIndex back = parseTileIndex(s.data(), s.size(), "i");
  EXPECT_TRUE(back.key == idx.key);
  ASSERT_EQ(back.records.size(), idx.records.size());
  EXPECT_EQ(back.records.back().offset, idx.records.back().offset);
  for (std::size_t n = 0; n < s.size(); ++n) EXPECT_THROW(parseTileIndex(s.data(), n, "i"), RasterError) << n;
  // A wrong field with a right checksum: the message names the field.
  TileIndex bad = idx;
  bad.key.levels = 4;
  std::string b = serializeTileIndex(bad);
  try {
    parseTileIndex(b.data(), b.size(), "idx");
    ADD_FAILURE();
  } catch (const RasterError& e) {
    EXPECT_NE(std::string(e.what()).find("idx: tile cache index is corrupt: levels 4"), std::string::npos) << e.what();
  }
  bad = idx;
  bad.records[3].offset = 1u << 30;
  b = serializeTileIndex(bad);
  EXPECT_THROW(parseTileIndex(b.data(), b.size(), "idx"), RasterError);
}

// The 30" world (43200 x 21600, 933 M pixels; 3.7 GB as float): built
// through the source's tiles with bounded memory, values against direct
// reads and block means, the second open reuses the cache.
// Faults (issue 17 item 4): the file under a cached (not in-memory) raster
// is replaced by a rename (the usual way a file is updated) or truncated in
// place while reads go on, through the cached read path of a tiled TIFF
// (libtiff tiles, for few lookups and for a big raster alike: the cache's
// bound differs). Every answer is the old
// file's value or NaN (no data), never a value of another file or garbage;
// nothing crashes; tiles read before stay right. Replaced: the reader keeps
// the old file open, so it answers the old file (a new open sees the new
// one). Truncated: tiles beyond the new end are unreadable, NaN (libtiff
// memory-mapped the file and crashed with SIGBUS there before "rm"); tiles
// read before stay (they were the file's). OpenImageIO's ImageCache (now
// only for other formats and TIFFs of huge strips) noticed the change at its
// first tile read from disk and answered NaN from then on (OiioModule.cpp).
TEST(RasterFaults, FileReplacedOrTruncatedUnderCachedReads) {
  for (const bool fewLookups : {true, false}) {
    TempDir t;
    const std::string path = (t.path / "src.tif").string();
    writeSmall(path, 0.0f, false);
    OpenOptions o;
    o.inMemoryLimitBytes = 0;
    o.fewLookups = fewLookups;
    auto at = [](const Raster& r, int x, int y) {  // a pixel centre, through the sampler
      const auto& g = r.transform();
      return r.sampleNearest(g.latOf(y + 0.5), g.lonOf(x + 0.5));
    };
    auto old = Raster::open(path, o);
    ASSERT_FALSE(old->inMemory());
    EXPECT_EQ(at(*old, 10, 10), smallValue(10, 10, 0.0f));  // a tile now in the cache
    writeSmall(path + ".new", 1000.0f, false);
    fs::rename(path + ".new", path);
    for (int y = 0; y < kSH; y += 37)
      for (int x = 0; x < kSW; x += 41) {
        const float want = smallValue(x, y, 0.0f), v = at(*old, x, y);
        ASSERT_TRUE(want == kNodata ? std::isnan(v) : v == want) << x << "," << y << " fewLookups " << fewLookups;
      }
    auto fresh = Raster::open(path, o);
    EXPECT_EQ(at(*fresh, 10, 10), smallValue(10, 10, 1000.0f));
    // Truncated to a third while open: the early tiles read, the rest NaN.
    const auto size = fs::file_size(path);
    fs::resize_file(path, size / 3);
    long answered = 0, missing = 0;
    for (int y = kSH - 1; y >= 0; y -= 37)  // the end of the file first: those tiles were never read
      for (int x = 0; x < kSW; x += 41) {
        const float want = smallValue(x, y, 1000.0f), v = at(*fresh, x, y);
        if (std::isnan(v)) {
          ++missing;
          continue;
        }
        ASSERT_EQ(v, want) << x << "," << y << " fewLookups " << fewLookups;
        ++answered;
      }
    EXPECT_GT(missing, 100) << "fewLookups " << fewLookups;  // the lost two thirds at least
    EXPECT_EQ(at(*fresh, 10, 10), smallValue(10, 10, 1000.0f));  // cached before: still right
    std::printf("fewLookups %d: after truncation %ld answered, %ld no data\n", int(fewLookups), answered, missing);
  }
}

// A read-only cache folder (EACCES: the test drops root to "nobody" in a
// child, since root ignores permissions) falls back to memory with a
// warning, as an unwritable or full one does.
TEST(TilePyramid, ReadOnlyCacheFolderFallsBackToMemory) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // the process has TBB / OIIO threads
  TempDir t;
  fs::permissions(t.path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec);
  const std::string path = (t.path / "src.tif").string();
  writeSmall(path, 0.0f, false);
  fs::create_directory(t.path / "ro");
  fs::permissions(t.path / "ro", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                     fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  EXPECT_EXIT(
      {
        if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) std::_Exit(3);
        auto src = Raster::open(path);
        const auto ref = referenceLevels(*src, 4);
        std::fprintf(stderr, "[child] ");
        auto p = TilePyramid::open(src, quiet(t.path / "ro" / "cache"));
        std::vector<float> tile(66 * 66);
        p->readTile({3, 1, 0}, tile.data());
        std::_Exit(p->stats().inMemory && tile[67] == ref[3][64] ? 0 : 4);
      },
      testing::ExitedWithCode(0), "cannot be written \\(Permission denied\\).*in memory");
}

TEST(TilePyramidBig, Global30ArcSecondRasterBuildsWithBoundedMemory) {
  constexpr int kW = 43200, kH = 21600;
  auto value = [](int x, int y) { return std::uint8_t(((x >> 3) ^ (y >> 3)) & 255); };
  TempDir t;
  const std::string path = (t.path / "big.tif").string();
  GeoTiffWriteOptions o;
  o.transform.lonStepDeg = 360.0 / kW;
  o.transform.latStepDeg = -180.0 / kH;
  o.deflateLevel = 1;
  writeGeoTiffTiles(path, kW, kH, 1, SampleType::U8, o, [&](int x0, int y0, void* tile) {
    auto* v = static_cast<std::uint8_t*>(tile);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) v[y * 256 + x] = value(x0 + x, y0 + y);
  });
  OpenOptions ro;
  ro.fewLookups = true;
  auto src = Raster::open(path, ro);
  { std::ofstream("/proc/self/clear_refs") << "5"; }
  const long baseKb = statusKb("VmRSS:");
  PyramidOptions po = quiet(t.path / "cache", 256);
  auto p = TilePyramid::open(src, po);
  const long peakKb = statusKb("VmHWM:");
  ASSERT_TRUE(p->stats().builtNow);
  EXPECT_EQ(p->levels(), 9);  // 169 x 85 tiles at level 0 ... 1 x 1 at level 8
  // The bound: the stated resident bound (source blocks, 64 decoded tiles,
  // the index) plus 32 MB for libtiff/zlib buffers and the allocator.
  const long boundMb = long(p->residentBoundBytes() >> 20);
  const long deltaMb = (peakKb - baseKb) / 1024;
  std::printf("peak RSS growth building the pyramid: %ld MB (stated bound %ld MB), cache %.1f MB\n", deltaMb, boundMb,
              double(p->stats().storedBytes) / 1e6);
  EXPECT_LT(deltaMb, boundMb + 32);
  EXPECT_LT(boundMb, 160);  // and far below the 933 MB of the pixels
  // Texels of every level against the mean of their source block (direct
  // reads through Raster). Integer values: the float means are exact up
  // to the last 2x2 mean's rounding (sums of <= 4 values < 256 are exact;
  // each stage rounds once: 1e-4 relative at most after 8 stages).
  long bad = 0;
  std::vector<float> tile(258 * 258);
  for (int l = 0; l < p->levels(); ++l) {
    const int s = 1 << l;
    for (int k = 0; k < 3; ++k) {
      const int tx = (k * 37 + 11) % p->tilesX(l), ty = (k * 23 + 5) % p->tilesY(l);
      p->readTile({l, tx, ty}, tile.data());
      for (const auto& [i, j] : {std::pair{0, 0}, {17, 200}, {255, 3}, {128, 128}}) {
        const int gx = tx * 256 + i, gy = ty * 256 + j;
        if ((gx + 1) * s > kW || (gy + 1) * s > kH) continue;  // blocks past the edge are partial
        double sum = 0;
        for (int y = 0; y < s; ++y)
          for (int x = 0; x < s; ++x) sum += src->pixel(gx * s + x, gy * s + y);
        const double want = sum / (double(s) * s), got = tile[std::size_t(j + 1) * 258 + i + 1];
        if (!(std::abs(got - want) <= 1e-4 * std::max(1.0, want))) {  // NaN is wrong too
          ++bad;
          ADD_FAILURE() << "level " << l << " texel " << gx << "," << gy << ": " << got << " vs " << want;
        }
      }
    }
  }
  EXPECT_EQ(bad, 0);
  const auto again = TilePyramid::open(src, po);
  EXPECT_FALSE(again->stats().builtNow);
  EXPECT_TRUE(again->stats().level0Stored);
  EXPECT_EQ(again->stats().storedBytes, p->stats().storedBytes);
  // Level 0 read back from the warm cache: the source's bytes.
  for (const auto& [tx, ty] : {std::pair{0, 0}, {100, 40}, {168, 84}}) {
    const auto t0 = again->interior({0, tx, ty});
    long wrong = 0;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        const int gx = tx * 256 + x, gy = ty * 256 + y;
        const float got = (*t0)[std::size_t(y) * 256 + x];
        wrong += gx < kW && gy < kH ? got != float(value(gx, gy)) : !std::isnan(got);
      }
    EXPECT_EQ(wrong, 0) << tx << "," << ty;
  }
}

// 86400 x 43200 (15"), nodata except a 1000 x 700 patch and a corner: the
// file is sparse (nodata tiles not written) and small, the build stores almost nothing, empty tiles are Empty at every
// level and data values are right.
TEST(TilePyramidBig, SparseRasterStoresOnlyItsData) {
  constexpr int kW = 86400, kH = 43200;
  auto inPatch = [](int x, int y) {
    return (x >= 40000 && x < 41000 && y >= 10000 && y < 10700) || (x >= 86000 && y >= 42900);
  };
  TempDir t;
  const std::string path = (t.path / "sparse.tif").string();
  GeoTiffWriteOptions o;
  o.transform.lonStepDeg = 360.0 / kW;
  o.transform.latStepDeg = -180.0 / kH;
  o.deflateLevel = 1;
  o.nodata = 255;
  o.sparse = true;  // nodata tiles are not written at all (byte count 0)
  writeGeoTiffTiles(path, kW, kH, 1, SampleType::U8, o, [&](int x0, int y0, void* tile) {
    auto* v = static_cast<std::uint8_t*>(tile);
    if (!inPatch(x0, y0) && !inPatch(x0 + 255, y0 + 255) && !inPatch(x0, y0 + 255) && !inPatch(x0 + 255, y0) &&
        !(x0 >= 39800 && x0 < 41000 && y0 >= 9800 && y0 < 10700)) {
      std::memset(v, 255, 256 * 256);
      return;
    }
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) v[y * 256 + x] = inPatch(x0 + x, y0 + y) ? std::uint8_t((x0 + x + y0 + y) % 200) : 255;
  });
  EXPECT_LT(fs::file_size(path), 2u << 20);
  OpenOptions ro;
  ro.fewLookups = true;
  auto src = Raster::open(path, ro);
  // The existing reader reads the unwritten tiles as nodata too.
  EXPECT_TRUE(std::isnan(src->pixel(0, 0)));
  EXPECT_EQ(src->pixel(40000, 10000), float((40000 + 10000) % 200));
  auto p = TilePyramid::open(src, quiet(t.path / "cache", 256));
  EXPECT_EQ(p->levels(), 10);
  const auto& st = p->stats();
  std::printf("sparse: %llu empty, %llu constant, %llu data tiles, %llu bytes stored\n",
              (unsigned long long)st.tilesEmpty, (unsigned long long)st.tilesConstant,
              (unsigned long long)st.tilesData, (unsigned long long)st.storedBytes);
  EXPECT_GT(st.tilesEmpty, 18000u);
  // Each level l >= 1 sees the 1000 x 700 patch in at most 3 x 3 tiles at
  // level 1 and 2 x 2 above, the corner patch in one: 9 + 8 x 4 + 9 = 50.
  EXPECT_LE(st.tilesData, 50u);
  EXPECT_LT(st.storedBytes, 4u << 20);
  EXPECT_EQ(p->kind({0, 0, 0}), TileKind::Empty);
  EXPECT_EQ(p->kind({4, 0, 0}), TileKind::Empty);
  EXPECT_EQ(p->kind({0, 40000 / 256, 10000 / 256}), TileKind::Data);
  std::vector<float> tile(258 * 258);
  p->readTile({0, 0, 0}, tile.data());
  for (float v : tile) ASSERT_TRUE(std::isnan(v));
  // Level 1 at (20250, 5150): the mean of source (40500..40501, 10300..10301).
  p->readTile({1, 20250 / 256, 5150 / 256}, tile.data());
  const float want = (src->pixel(40500, 10300) + src->pixel(40501, 10300) + src->pixel(40500, 10301) +
                      src->pixel(40501, 10301)) / 4.0f;
  EXPECT_EQ(tile[std::size_t(5150 % 256 + 1) * 258 + 20250 % 256 + 1], want);
  // The top (one tile) still sees both patches.
  p->readTile({9, 0, 0}, tile.data());
  int seen = 0;
  for (float v : tile) seen += !std::isnan(v);
  EXPECT_GT(seen, 0);
}
