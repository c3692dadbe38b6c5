#include "globe/app/LayerOptions.h"

#include "globe/app/Command.h"

#include "globe/raster/World.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace geocean::app {

// allow_extra_args(false): a vector option otherwise swallows the words
// after its file (`query --mask m.tif 36 -5.6` lost its LAT LON).
void addLayerOptions(CLI::App& sub, LayerOptions& o, bool withEncoding) {
  sub.add_option("--mask", o.masks,
                 "land/sea/lake mask raster, repeatable: layers over the default world, the finest answers")
      ->take_all()
      ->expected(1)
      ->allow_extra_args(false);
  sub.add_option("--elevation", o.elevations,
                 "elevation raster, repeatable: layers over the default world; finer than every mask it decides "
                 "land (> 0 m) and sea")
      ->take_all()
      ->expected(1)
      ->allow_extra_args(false);
  if (withEncoding)
    sub.add_option("--mask-encoding", o.maskEncoding,
                   "mask values of the --mask files, e.g. 0=ocean,1=land,2=lake (the default)");
  sub.add_flag("--no-default-world", o.noDefaultWorld, "no bundled world underneath: only the given rasters");
}

namespace {
// `--mask ''` would otherwise reach the raster reader and print ": no such file".
void requireFileNames(const LayerOptions& o) {
  for (const std::string& m : o.masks)
    if (m.empty()) throw std::invalid_argument("--mask: the file name is empty");
  for (const std::string& e : o.elevations)
    if (e.empty()) throw std::invalid_argument("--elevation: the file name is empty");
  for (const std::string& i : o.imagery)
    if (i.empty()) throw std::invalid_argument("--imagery: the file name is empty");
}
}  // namespace

void addImageryOption(CLI::App& sub, LayerOptions& o) {
  sub.add_option("--imagery", o.imagery,
                 "imagery raster (RGB or RGBA, 8-bit), repeatable: drawn over the default imagery, the finest on "
                 "top; nodata or alpha 0 shows the layer below")
      ->take_all()
      ->expected(1)
      ->allow_extra_args(false);
}

void applyLayers(ocean::Ocean& ocean, const LayerOptions& o, const raster::OpenOptions& ro) {
  requireFileNames(o);
  const bool noElevation = o.noElevation;
  if (o.noDefaultWorld && o.masks.empty() && (o.elevations.empty() || noElevation))
    throw std::invalid_argument("--no-default-world needs --mask or --elevation");
  const ocean::MaskEncoding enc =
      o.maskEncoding.empty() ? ocean::MaskEncoding{} : ocean::MaskEncoding::parse(o.maskEncoding);
  if (!o.noDefaultWorld) {
    const auto world = raster::defaultWorld();
    // The encoding before the rasters: the land/sea is then built once.
    if (o.masks.empty() && !o.maskEncoding.empty()) ocean.setMaskEncoding(enc);
    ocean.setRasters(raster::Raster::open(world.mask, ro),
                     noElevation ? nullptr : raster::Raster::open(world.elevation, ro));
  }
  for (const std::string& m : o.masks) ocean.addMaskLayerFile(m, 0, enc, ro);
  if (!noElevation)
    for (const std::string& e : o.elevations) ocean.addElevationLayerFile(e, 0, ro);
}

std::vector<world::LayerSource> layerSources(const LayerOptions& o) {
  requireFileNames(o);
  if (o.noDefaultWorld && o.masks.empty() && o.elevations.empty())
    throw std::invalid_argument("--no-default-world needs --mask or --elevation");
  // The drawn default world keeps its own encoding: an encoding without a mask would do nothing.
  if (!o.maskEncoding.empty() && o.masks.empty()) throw std::invalid_argument("--mask-encoding needs --mask");
  if (!o.maskEncoding.empty()) (void)ocean::MaskEncoding::parse(o.maskEncoding);  // named before any file is read
  std::vector<world::LayerSource> s;
  for (const std::string& m : o.masks) s.push_back({world::LayerKind::Mask, m, o.maskEncoding, 0});
  for (const std::string& e : o.elevations) s.push_back({world::LayerKind::Elevation, e, "", 0});
  return s;
}

int loadDrawnWorld(const char* command, const LayerOptions& o, std::vector<world::LayerSource>& sources,
                   world::WorldData& data) {
  try {
    sources = layerSources(o);
    std::vector<world::LayerSource> drawn = sources;
    for (const std::string& i : o.imagery) drawn.push_back({world::LayerKind::Imagery, i, "", 0});
    // The host reads its regional masks and reliefs only to draw them
    // (resampled once onto the grids, then by tile into the pyramids), which
    // streaming serves as well; the ocean plugin holds its own copy for
    // queries. Over 64 MB as floats they stream here: a 10 x 8 degree 6"
    // relief is not held twice (issue 12 item 6).
    raster::OpenOptions ro;
    ro.regionalInMemoryLimitBytes = std::size_t(64) << 20;
    data = world::loadLayeredWorld(drawn, !o.noDefaultWorld, ro);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "geocean %s: %s\n", command, e.what());
    return kExitBadInput;
  } catch (const raster::RasterError& e) {
    std::fprintf(stderr, "geocean %s: %s\n", command, e.what());
    return kExitDataError;
  }
  return kExitOk;
}

std::vector<std::string> layerLabels(const LayerOptions& o) {
  std::vector<std::string> labels;
  auto add = [&](const char* kind, const std::vector<std::string>& files) {
    for (const std::string& f : files) labels.push_back(std::string(kind) + std::filesystem::path(f).filename().string());
  };
  add("mask  ", o.masks);
  add("elevation  ", o.elevations);
  add("imagery  ", o.imagery);
  return labels;
}

LayerOptions shownLayers(const LayerOptions& o, const std::vector<char>& shown) {
  LayerOptions s = o;
  std::size_t i = 0;
  auto keep = [&](const std::vector<std::string>& files, std::vector<std::string>& out) {
    out.clear();
    for (const std::string& f : files) {
      if (i >= shown.size() || shown[i]) out.push_back(f);
      ++i;
    }
  };
  keep(o.masks, s.masks);
  keep(o.elevations, s.elevations);
  keep(o.imagery, s.imagery);
  if (s.masks.empty()) s.maskEncoding.clear();  // the encoding is the masks': none shown, none to apply
  return s;
}

}  // namespace geocean::app
