// Writes the GeoTIFF seeds of corpus/fuzz_geotiff/ with Geocean's own writer
// (globe/raster/GeoTiffWriter), each a few hundred bytes: every sample type,
// strips and tiles, each compression, pixel-is-point, nodata, global, and
// the refused kinds (projected CRS, rotation, no GeoKeys); and, given a
// second folder, the tile-cache indexes of corpus/fuzz_tile_index/ as
// TilePyramid writes them for fuzz_tile_index's source. Regenerate with
//   cmake --build build-fuzz --target fuzz_make_seeds && build-fuzz/tests/fuzz/fuzz_make_seeds \
//       tests/fuzz/corpus/fuzz_geotiff tests/fuzz/corpus/fuzz_tile_index
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/Raster.h"
#include "globe/raster/TilePyramid.h"
#include "tests/fuzz/TileIndexSource.h"

#include <unistd.h>

#include <filesystem>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

using namespace geocean::raster;

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: %s <geotiff seed dir> [<tile index seed dir>]\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  const int w = 16, h = 8;
  std::vector<std::uint8_t> u8(w * h * 3);
  std::vector<std::int16_t> i16(w * h);
  std::vector<float> f32(w * h);
  for (int i = 0; i < w * h; ++i) {
    u8[i] = std::uint8_t(i % 3);
    u8[w * h + i] = std::uint8_t(i * 7);
    u8[2 * w * h + i] = std::uint8_t(255 - i);
    i16[i] = std::int16_t(i * 97 - 6000);
    f32[i] = i % 11 == 0 ? -9999.0f : float(i) * 12.5f - 800.0f;
  }
  GeoTransform global;
  global.lonStepDeg = 360.0 / w;
  global.latStepDeg = -180.0 / h;
  GeoTransform regional;
  regional.originLonDeg = -10.0;
  regional.originLatDeg = 45.0;
  regional.lonStepDeg = 0.25;
  regional.latStepDeg = -0.25;

  struct Seed {
    const char* name;
    const void* data;
    int channels;
    SampleType type;
    GeoTiffWriteOptions o;
  };
  std::vector<Seed> seeds;
  auto add = [&](const char* name, const void* d, int c, SampleType t, GeoTiffWriteOptions o) {
    seeds.push_back({name, d, c, t, o});
  };
  GeoTiffWriteOptions o;
  o.transform = global;
  o.tileSize = 16;
  add("mask_u8_tiled_deflate.tif", u8.data(), 1, SampleType::U8, o);
  o.tileSize = 0;
  o.compression = Compression::None;
  add("mask_u8_strips_raw.tif", u8.data(), 1, SampleType::U8, o);
  o.transform = regional;
  add("relief_i16_regional.tif", i16.data(), 1, SampleType::I16, o);
  o.nodata = -9999.0;
  o.pixelIsPoint = true;
  add("relief_f32_point_nodata.tif", f32.data(), 1, SampleType::F32, o);
  GeoTiffWriteOptions j;
  j.transform = global;
  j.tileSize = 16;
  j.compression = Compression::Jpeg;
  j.jpegQuality = 50;
  add("imagery_rgb_jpeg.tif", u8.data(), 3, SampleType::U8, j);
  GeoTiffWriteOptions bad = o;
  bad.nodata.reset();
  bad.projectedEpsg = 32630;
  add("refused_projected.tif", i16.data(), 1, SampleType::I16, bad);
  bad.projectedEpsg.reset();
  bad.rotationTerm = 0.01;
  add("refused_rotated.tif", i16.data(), 1, SampleType::I16, bad);
  GeoTiffWriteOptions nokeys = o;
  nokeys.writeGeoKeys = false;
  add("no_geokeys.tif", f32.data(), 1, SampleType::F32, nokeys);

  for (const auto& s : seeds) {
    const std::string path = dir + "/" + s.name;
    writeGeoTiff(path, s.data, w, h, s.channels, s.type, s.o);
    std::printf("%s\n", path.c_str());
  }
  if (argc == 3) {
    // The index the pyramid writes, for two tile sizes (8: the fuzzer's build; 16: another key).
    namespace fs = std::filesystem;
    const fs::path tmp = fs::temp_directory_path() / ("geocean_make_seeds_" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    const std::string src = (tmp / "src.tif").string();
    geocean::fuzz::writeTileIndexSource(src);
    for (int tile : {8, 16}) {
      auto o = geocean::fuzz::tileIndexPyramidOptions((tmp / "cache").string());
      o.tileSize = tile;
      auto p = TilePyramid::open(Raster::open(src), o);
      const std::string out = std::string(argv[2]) + "/index_40x24_tile" + std::to_string(tile);
      fs::copy_file(p->stats().cachePath + "/index", out, fs::copy_options::overwrite_existing);
      std::printf("%s\n", out.c_str());
    }
    fs::remove_all(tmp);
  }
  return 0;
}
