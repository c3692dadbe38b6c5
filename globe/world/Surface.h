// Surface classes and the mask encoding: the one place where a mask value
// becomes ocean, land or lake, and hence water or not. The classifier
// (plugin/landsea), the host's world textures and the ocean's own water
// grids all go through MaskEncoding::classify.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace geocean::world {

enum class Surface : std::uint8_t { Ocean = 0, Land = 1, Lake = 2 };
const char* toString(Surface s);  // "ocean" | "land" | "lake"

// How mask values map to classes (default: 0 ocean, 1 land, 2 lake;
// values >= 256 or unmapped count as land).
struct MaskEncoding {
  std::array<Surface, 256> classOf{};
  MaskEncoding();
  static MaskEncoding parse(const std::string& spec);  // "0=ocean,1=land,2=lake,3=land"

  // A sample's class: NaN, negative and > 255 are land; others round to
  // the nearest integer value.
  Surface classify(float value) const;
  // The water rule: ocean and lake are water.
  bool isWater(float value) const { return classify(value) != Surface::Land; }
};

}  // namespace geocean::world
