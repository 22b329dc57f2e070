#pragma once
// Heightmaps stored as PNG: 8/16-bit grayscale, and Mapbox Terrain-RGB.
//
//  - Grayscale (1 channel, or 2 with alpha): raw height = sample / max sample, in [0, 1]; the
//    importer's z-scale (metres at full white) and z-offset turn it into metres. A PNG that
//    sandtin exported carries its own scale in tEXt chunks (kPngKey*), used when the caller
//    gives none.
//  - Terrain-RGB (3 channels, or 4 with alpha, 8-bit): height in metres
//    = -10000 + (R * 65536 + G * 256 + B) * 0.1.
// Samples with alpha 0 are no-data.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "formats/png_image.hpp"
#include "io/heightmap_raster.hpp"

namespace sandtin {

enum class PngHeightEncoding : std::uint8_t {
    Auto,        ///< gray for 1-2 channels or a grey palette, Terrain-RGB for 8-bit colour
    Gray,        ///< reject anything but grayscale
    TerrainRgb,  ///< reject anything but 8-bit colour
};

/// tEXt keys of sandtin's own heightmap exports: height = z_offset + sample / max * z_range.
inline constexpr const char* kPngKeyZOffset = "sandtin:z_offset";
inline constexpr const char* kPngKeyZRange = "sandtin:z_range";
inline constexpr const char* kPngKeyCellSize = "sandtin:cell_size";
/// Between rows, when it differs from the cell size (between columns).
inline constexpr const char* kPngKeyCellHeight = "sandtin:cell_height";
/// Where the map's south-west sample lies in the source's coordinates, and in which system
/// (Georeference), when the terrain was imported from a georeferenced file.
inline constexpr const char* kPngKeyWest = "sandtin:west";
inline constexpr const char* kPngKeySouth = "sandtin:south";
inline constexpr const char* kPngKeyCrs = "sandtin:crs";
inline constexpr const char* kPngKeyHorizontalUnit = "sandtin:horizontal_unit";
/// Normal and albedo maps: metres per texel across (texel_size) and, when different, down
/// (texel_height). Their texels are centred in those cells, so these are not height-map sample
/// spacings; sandtin:west and sandtin:south give the terrain's south-west corner as above.
inline constexpr const char* kPngKeyTexelSize = "sandtin:texel_size";
inline constexpr const char* kPngKeyTexelHeight = "sandtin:texel_height";

/// A decoded PNG heightmap. Heights are raw: metres for Terrain-RGB, [0, 1] for grayscale.
/// A grayscale PNG that sandtin exported also carries its scale (height = z_offset + raw *
/// z_range) and cell size.
struct PngHeightmap {
    HeightRaster raster;
    std::optional<double> z_offset;
    std::optional<double> z_range;
    std::optional<double> cell_size;
    std::optional<double> cell_height;  ///< metres between rows, when not the cell size
};
/// Throws std::runtime_error naming `name` for anything that is not a PNG heightmap within
/// `limits`.
PngHeightmap decode_png_heightmap(std::span<const std::uint8_t> bytes, const std::string& name,
                                  PngHeightEncoding encoding, const RasterLimits& limits);

}  // namespace sandtin
