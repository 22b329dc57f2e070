#pragma once
// The sample grid a terrain was imported on, as its session's metadata records it, and what
// map exports should sample by default: that grid while the terrain still lies on it, so that
// export followed by import gives back the same samples; a finer one once edits have put
// vertices between its samples, so that the edits are not sampled away.

#include <optional>
#include <string>

#include "io/export_terrain.hpp"
#include "io/heightmap_raster.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Metres between the imported raster's columns and rows, from the domain's south-west corner.
struct ImportGrid {
    double cell_size = 0.0;
    double cell_height = 0.0;  ///< metres between rows when not cell_size, else 0
    double row_spacing() const { return cell_height > 0.0 ? cell_height : cell_size; }
};

/// The grid under "/import/raster" of a session's metadata; nullopt when the terrain was not
/// imported, or the metadata is not JSON or holds no positive, finite spacing.
std::optional<ImportGrid> import_grid_of(const std::string& metadata_json);

/// The georeference under "/import/georeference" of a session's metadata (where the terrain's
/// south-west corner lies in the imported file's coordinates); `known` false when there is
/// none or it is not a pair of finite numbers.
Georeference import_georeference_of(const std::string& metadata_json);

/// Whether every live vertex of `tin` lies on a sample of `grid`, to a millionth of a cell.
/// True for a fresh import; false once an edit has inserted a vertex between samples.
bool tin_lies_on_grid(const Tin& tin, const ImportGrid& grid);

/// The default sampling of an exported map or simplification raster for an imported terrain.
struct DefaultSampling {
    double cell_size = 0.0;
    double cell_height = 0.0;  ///< 0: rows as columns
    bool edited = false;       ///< the terrain left its import grid, so the cell is finer
};

/// The import grid while `tin` lies on it. Otherwise square cells of the smallest of the
/// import spacings and `fallback_cell` (the default map size's spacing).
DefaultSampling default_sampling(const Tin& tin, const ImportGrid& grid, double fallback_cell);

/// What an export of an imported terrain takes from its session's metadata, as defaults: the
/// sampling (default_sampling, against the spacing of `options.map_size`) unless
/// `options.cell_size` is set or `size_given`, and the georeference. Returns the sampling it
/// chose, if any.
std::optional<DefaultSampling> apply_import_defaults(const Tin& tin,
                                                     const std::string& metadata_json,
                                                     ExportOptions& options,
                                                     bool size_given = false);

}  // namespace sandtin
