#pragma once
// A height raster: what every heightmap importer produces and what greedy insertion meshes.
//
// Units: cell sizes and heights in metres. Sample (col, row) sits at the terrain position
// origin + (col * cell_size, (height - 1 - row) * row_spacing()): row 0 is the top (north) row
// of the image, and the samples are the corners of the terrain domain (grid registration), so
// a W x H raster covers (W - 1) x (H - 1) cells. Imported rasters start at (0, 0) and have
// square cells; only maps baked from a TIN, to fit its exact domain, may not.
//
// Invariants (check_raster()): width, height >= 2; heights.size() == width * height; `valid` is
// empty (every sample has data) or has one entry per sample; every valid height is finite.
// Heights of no-data samples are meaningless until fill_nodata() sets them.

#include <cstdint>
#include <string>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

/// Size limit for every importer. A raster beyond it is rejected before its samples are read.
struct RasterLimits {
    std::uint32_t max_width = 16384;
    std::uint32_t max_height = 16384;
};

/// Where the raster sits in its source coordinate system (informational: the terrain itself
/// always starts at (0, 0) so positions stay small enough for float GPU buffers).
struct Georeference {
    bool known = false;
    double west = 0.0;   ///< source x of the first column's samples
    double south = 0.0;  ///< source y of the last row's samples
    std::string crs;     ///< coordinate reference system (WKT) when the source names one
    /// The source's length units as it names them ("metre", "US survey foot"), empty when it
    /// names none. `west` and `south` stay in the horizontal unit; cell sizes and heights in
    /// the raster are already converted to metres.
    std::string horizontal_unit;
    std::string vertical_unit;
    /// The stored samples are counts: height in `vertical_unit` = count * count_scale +
    /// count_offset (a GeoTIFF band's scale and offset; an Int16 DEM in cm has scale 0.01).
    double count_scale = 1.0;
    double count_offset = 0.0;
};

struct HeightRaster {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    double cell_size = 1.0;           ///< metres between neighbouring columns (and rows)
    double cell_height = 0.0;         ///< metres between rows when not cell_size, else 0
    Vec2 origin;                      ///< terrain position of the south-west sample
    std::vector<double> heights;      ///< row-major, row 0 first (north)
    std::vector<std::uint8_t> valid;  ///< empty: all valid; else 1 = sample has data
    Georeference georeference;
    std::string source_format;  ///< e.g. "png-gray16", "terrain-rgb", "esri-ascii"
    /// Bands (channels of data) the source file holds; heights come from the first. More than
    /// one is worth a warning: a GeoTIFF of imagery is not an elevation model.
    std::uint32_t source_bands = 1;

    std::size_t size() const { return static_cast<std::size_t>(width) * height; }
    std::size_t index(std::uint32_t col, std::uint32_t row) const {
        return static_cast<std::size_t>(row) * width + col;
    }
    double at(std::uint32_t col, std::uint32_t row) const { return heights[index(col, row)]; }
    bool is_valid(std::size_t i) const { return valid.empty() || valid[i] != 0; }
    double row_spacing() const { return cell_height > 0.0 ? cell_height : cell_size; }
    std::size_t nodata_count() const;
    /// The terrain rectangle the samples span, in metres, from the origin.
    Rect domain() const;
    Vec2 position(std::uint32_t col, std::uint32_t row) const {
        return {origin.x + col * cell_size, origin.y + (height - 1 - row) * row_spacing()};
    }
};

/// Throws std::runtime_error naming `name` when the raster breaks an invariant above or the
/// limits: a 0 x 0 or single-row raster, a size beyond the limits, a non-finite valid height,
/// a non-positive or non-finite cell size, or no valid sample at all.
void check_raster(const HeightRaster& raster, const std::string& name,
                  const RasterLimits& limits = {});

/// Throws std::runtime_error naming `name` when width x height exceeds the limits or is
/// empty; importers call it as soon as they know the size, before allocating.
void check_raster_size(std::uint64_t width, std::uint64_t height, const std::string& name,
                       const RasterLimits& limits);

/// Gives every no-data sample the height of its nearest valid sample (breadth-first over the
/// 4-neighbourhood), so the TIN has heights everywhere; `valid` is kept, so the error bound
/// still ignores those samples. Returns how many samples were filled.
std::size_t fill_nodata(HeightRaster& raster);

}  // namespace sandtin
