#pragma once
// Float heightmaps as OpenEXR: one 32-bit float channel "Y" holding heights in metres, row 0
// north, ZIP-compressed, with the cell size in a "sandtin:cell_size" double attribute.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/heightmap_raster.hpp"

namespace sandtin {

/// Encodes the raster's heights (no-data samples become NaN). Heights are rounded to float.
std::vector<std::uint8_t> encode_exr_heightmap(const HeightRaster& raster);

/// Decodes a single-channel EXR (or the Y, Z, R or "height" channel of a multi-channel one).
/// NaN/Inf samples are errors unless `nonfinite_as_nodata`. Throws std::runtime_error naming
/// `name` for anything OpenEXR cannot read or a size beyond `limits`.
HeightRaster decode_exr_heightmap(std::span<const std::uint8_t> bytes, const std::string& name,
                                  const RasterLimits& limits, bool nonfinite_as_nodata);

}  // namespace sandtin
