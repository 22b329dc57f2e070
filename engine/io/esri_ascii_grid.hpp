#pragma once
// ESRI ASCII grids (.asc):
//
//   ncols 4            number of columns (> 0)
//   nrows 3            number of rows (> 0)
//   xllcorner 100.0    or xllcenter: west edge (or first column centre) in source units
//   yllcorner 200.0    or yllcenter: south edge (or last row centre)
//   cellsize 5.0       square cells (> 0); or dx and dy, column and row spacing, as GDAL
//                      writes oblong cells
//   NODATA_value -9999 optional; ESRI's default is -9999 (kEsriDefaultNodata); "nan" makes NaN
//                      samples no-data
//   then nrows lines of ncols heights, north row first.
//
// Keys are case-insensitive and may come in any order; anything else in the header, a missing
// or repeated key, or a malformed value is an error naming the key and the line.

#include <cstdint>
#include <span>
#include <string>

#include "io/heightmap_raster.hpp"

namespace sandtin {

/// The no-data value of a grid whose header does not give one (ESRI's ASCII raster format).
inline constexpr double kEsriDefaultNodata = -9999.0;

/// Parses an ESRI ASCII grid. Heights are metres as written; NaN or infinite values are
/// errors unless `nonfinite_as_nodata`. Throws std::runtime_error naming `name`.
HeightRaster parse_esri_ascii_grid(std::span<const std::uint8_t> bytes, const std::string& name,
                                   const RasterLimits& limits, bool nonfinite_as_nodata);

}  // namespace sandtin
