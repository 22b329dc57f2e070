#pragma once
// Heightmap import: any supported raster file to an error-bounded TIN. The CLI's `import` and
// the editor's File menu both call import_heightmap().
//
// Formats are recognised by content, not by name: PNG (8/16-bit gray, Terrain-RGB), GeoTIFF
// (GDAL), ESRI ASCII grid, OpenEXR. Heights in metres = raw height * z_scale + z_offset, where
// the raw height is metres for Terrain-RGB, GeoTIFF, ASCII grids and EXR, and sample / max in
// [0, 1] for grayscale PNG (so z_scale is then the height of full white).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "io/greedy_tin.hpp"
#include "io/heightmap_png.hpp"
#include "io/heightmap_raster.hpp"
#include "io/progress.hpp"

namespace sandtin {

struct HeightmapReadOptions {
    RasterLimits limits;
    std::optional<double> pixel_size;  ///< metres; overrides the file's own
    std::optional<double> z_scale;     ///< default 1 (or a sandtin PNG's own scale)
    std::optional<double> z_offset;    ///< metres; default 0
    bool nonfinite_as_nodata = false;  ///< NaN/Inf samples become no-data instead of errors
    PngHeightEncoding png_encoding = PngHeightEncoding::Auto;
};

/// Reads and scales a heightmap; no-data samples are flagged, not yet filled. Throws
/// std::runtime_error naming the file for every kind of bad input (missing, empty, truncated,
/// unknown format, 0 x 0, beyond the limits, non-finite heights, a malformed header).
HeightRaster read_heightmap(const std::filesystem::path& path,
                            const HeightmapReadOptions& options = {});
/// The same for bytes in memory (`name` appears in messages). GeoTIFFs need a file: they are
/// read through a temporary in-memory GDAL file.
HeightRaster decode_heightmap(std::span<const std::uint8_t> bytes, const std::string& name,
                              const HeightmapReadOptions& options = {});

struct ImportOptions {
    HeightmapReadOptions read;
    GreedyOptions greedy;
};

struct ImportReport {
    std::string source;
    std::string format;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    double cell_size = 0.0;          ///< metres between columns
    double cell_height = 0.0;        ///< metres between rows (the cell size for square cells)
    std::size_t nodata_samples = 0;  ///< filled from their nearest valid sample, not measured
    std::uint32_t source_bands = 1;  ///< bands in the file; heights come from the first
    Georeference georeference;
    GreedyOptions greedy;
    GreedyStats stats;
    double read_ms = 0.0;
    double total_ms = 0.0;
};

struct ImportResult {
    Tin tin;
    ImportReport report;
};

/// `progress` (io/progress.hpp) hears the reading of the file and the greedy insertion.
ImportResult import_heightmap(const std::filesystem::path& path, const ImportOptions& options,
                              const ProgressCallback& progress = {});

/// The report as JSON: source, format, raster {width, height, cell_size, cell_height,
/// nodata_samples}, georeference {west, south, crs, horizontal_unit, vertical_unit} when known,
/// max_error_target, max_points, points, triangles, max_error, rmsd, reached_error,
/// fix_up_points, decimated_points, and times in ms (decimate_ms is part of build_ms). Stored in
/// the session's metadata under "import".
nlohmann::json to_json(const ImportReport& report);

}  // namespace sandtin
