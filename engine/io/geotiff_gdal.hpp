#pragma once
// GeoTIFF heightmaps through GDAL: band 1, square north-up pixels, the band's no-data value.
// GeoTIFF pixels are areas by default, so samples sit at pixel centres.

#include <cstdint>
#include <span>
#include <string>

#include "io/heightmap_raster.hpp"

namespace sandtin {

/// Decodes a GeoTIFF held in memory (through a GDAL in-memory file). The cell size is the pixel
/// size in metres (and cell_height the row spacing, when the pixels are not square), converted from
/// the projection's linear unit (US survey feet in many state plane grids); a file in geographic
/// coordinates (degrees) needs `pixel_size_override`. Heights are converted to metres from the unit
/// the band or a compound CRS's vertical part declares, unless `z_scale_override` (the caller
/// scales them itself); an unknown unit is an error. NaN/Inf samples are no-data when the band
/// declares NaN as its no-data value or `nonfinite_as_nodata`, else an error. Throws
/// std::runtime_error naming `name` and GDAL's message.
HeightRaster decode_geotiff(std::span<const std::uint8_t> bytes, const std::string& name,
                            const RasterLimits& limits, bool nonfinite_as_nodata,
                            bool pixel_size_override, bool z_scale_override = false);

}  // namespace sandtin
