// geocean-import-world: converts the raw global sources (GSHHG masks, ETOPO
// relief, Blue Marble; see data/README.md) into the project's own tiled,
// compressed GeoTIFFs in data/. Run once by a developer; the product only
// reads data/.
#include "globe/raster/GeoTiffWriter.h"
#include "globe/raster/ImageIo.h"

#include <CLI/CLI.hpp>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace geocean::raster;

namespace {
std::string gunzip(const fs::path& p) {
  gzFile f = gzopen(p.c_str(), "rb");
  if (!f) throw std::runtime_error(p.string() + ": cannot open");
  std::string out;
  char buf[1 << 16];
  int n;
  while ((n = gzread(f, buf, sizeof buf)) > 0) out.append(buf, std::size_t(n));
  const bool bad = n < 0;
  gzclose(f);
  if (bad) throw std::runtime_error(p.string() + ": corrupt gzip stream");
  return out;
}

GeoTransform globalTransform(int width, int height) {
  GeoTransform t;
  t.originLonDeg = -180.0;
  t.originLatDeg = 90.0;
  t.lonStepDeg = 360.0 / width;
  t.latStepDeg = -180.0 / height;
  t.global = true;
  return t;
}

// GSHHG mask: uint8, south row first -> north-up tiled deflate GeoTIFF.
void convertMask(const fs::path& src, const fs::path& dst, int width, int height) {
  const std::string raw = gunzip(src);
  if (raw.size() != std::size_t(width) * height)
    throw std::runtime_error(src.string() + ": " + std::to_string(raw.size()) + " bytes, expected " +
                             std::to_string(std::size_t(width) * height));
  std::vector<unsigned char> img(raw.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(raw.data() + std::size_t(height - 1 - y) * width, width, img.data() + std::size_t(y) * width);
  for (unsigned char v : img)
    if (v > 2) throw std::runtime_error(src.string() + ": mask value " + std::to_string(v) + " is not 0/1/2");
  GeoTiffWriteOptions o;
  o.transform = globalTransform(width, height);
  writeGeoTiff(dst.string(), img.data(), width, height, 1, SampleType::U8, o);
}

// ETOPO 20': 540 rows x 1081 columns of ASCII metres, south row first, columns
// starting at 20 1/6 deg east with the last repeating the first.
void convertEtopo(const fs::path& dir, const fs::path& dst) {
  constexpr int kW = 1080, kH = 540;
  std::istringstream lats(gunzip(dir / "etopo20lats.txt.gz")), lons(gunzip(dir / "etopo20lons.txt.gz"));
  std::vector<double> la, lo;
  for (double v; lats >> v;) la.push_back(v);
  for (double v; lons >> v;) lo.push_back(v);
  if (la.size() != kH || lo.size() != kW + 1) throw std::runtime_error("etopo20 lat/lon axes have unexpected sizes");
  const double step = 1.0 / 3.0;
  if (std::abs(la[0] - (-90.0 + step / 2)) > 1e-3 || std::abs(lo[0] - (20.0 + step / 2)) > 1e-3)
    throw std::runtime_error("etopo20 axes do not start at (-89.8333, 20.1667)");
  std::istringstream data(gunzip(dir / "etopo20data.txt.gz"));
  std::vector<std::int16_t> img(std::size_t(kW) * kH);
  // Column c of the source is at lon 20 1/6 + c/3; output column starts at -180.
  const int shift = static_cast<int>(std::lround((lo[0] - step / 2 + 180.0) / step));  // 600
  for (int r = 0; r < kH; ++r) {
    for (int c = 0; c <= kW; ++c) {
      double v;
      if (!(data >> v)) throw std::runtime_error("etopo20data: short row " + std::to_string(r));
      if (c == kW) continue;  // repeat of column 0
      const int outCol = (c + shift) % kW;
      img[std::size_t(kH - 1 - r) * kW + outCol] = static_cast<std::int16_t>(std::lround(v));
    }
  }
  GeoTiffWriteOptions o;
  o.transform = globalTransform(kW, kH);
  writeGeoTiff(dst.string(), img.data(), kW, kH, 1, SampleType::I16, o);
}

void convertBlueMarble(const fs::path& src, const fs::path& dst) {
  const Image8 img = readImage8(src.string());
  if (img.channels != 3) throw std::runtime_error(src.string() + ": expected RGB");
  GeoTiffWriteOptions o;
  o.transform = globalTransform(img.width, img.height);
  o.compression = Compression::Jpeg;
  o.jpegQuality = 90;
  writeGeoTiff(dst.string(), img.pixels.data(), img.width, img.height, 3, SampleType::U8, o);
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Convert the raw world sources into Geocean's data/ GeoTIFFs"};
  std::string source, out;
  app.add_option("--source", source, "folder with the raw sources (see data/README.md)")->required();
  app.add_option("--out", out, "output folder (the project's data/)")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    const fs::path s(source), o(out);
    fs::create_directories(o);
    convertMask(s / "gshhg_lsmask_5min_h.u8.gz", o / "landmask_5m.tif", 4320, 2160);
    std::puts("landmask_5m.tif");
    convertMask(s / "gshhg_lsmask_1.25min_h.u8.gz", o / "landmask_1.25m.tif", 17280, 8640);
    std::puts("landmask_1.25m.tif");
    convertEtopo(s, o / "etopo_20m.tif");
    std::puts("etopo_20m.tif");
    convertBlueMarble(s / "bmng.jpg", o / "bluemarble.tif");
    std::puts("bluemarble.tif");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geocean-import-world: %s\n", e.what());
    return 3;
  }
  return 0;
}
