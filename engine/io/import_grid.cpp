#include "io/import_grid.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sandtin {

namespace {

std::optional<double> positive_at(const nlohmann::json& j, const char* pointer) {
    const nlohmann::json::json_pointer p(pointer);
    if (!j.contains(p) || !j.at(p).is_number()) return std::nullopt;
    const double v = j.at(p).get<double>();
    return std::isfinite(v) && v > 0.0 ? std::optional<double>(v) : std::nullopt;
}

/// Whether `offset` is a whole number of `cell`s, to a millionth of a cell.
bool on_lattice(double offset, double cell) {
    const double steps = offset / cell;
    return std::abs(steps - std::round(steps)) <= 1e-6;
}

}  // namespace

std::optional<ImportGrid> import_grid_of(const std::string& metadata_json) {
    const nlohmann::json j = nlohmann::json::parse(metadata_json, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return std::nullopt;
    const std::optional<double> cell = positive_at(j, "/import/raster/cell_size");
    if (!cell) return std::nullopt;
    ImportGrid grid;
    grid.cell_size = *cell;
    grid.cell_height = positive_at(j, "/import/raster/cell_height").value_or(0.0);
    return grid;
}

Georeference import_georeference_of(const std::string& metadata_json) {
    Georeference g;
    const nlohmann::json j = nlohmann::json::parse(metadata_json, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return g;
    const nlohmann::json::json_pointer at("/import/georeference");
    if (!j.contains(at) || !j.at(at).is_object()) return g;
    const nlohmann::json& r = j.at(at);
    const auto number = [&](const char* key) -> std::optional<double> {
        if (!r.contains(key) || !r.at(key).is_number()) return std::nullopt;
        const double v = r.at(key).get<double>();
        return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
    };
    const auto text = [&](const char* key) {
        return r.contains(key) && r.at(key).is_string() ? r.at(key).get<std::string>()
                                                        : std::string();
    };
    const std::optional<double> west = number("west");
    const std::optional<double> south = number("south");
    if (!west || !south) return g;
    g.known = true;
    g.west = *west;
    g.south = *south;
    g.crs = text("crs");
    g.horizontal_unit = text("horizontal_unit");
    return g;
}

bool tin_lies_on_grid(const Tin& tin, const ImportGrid& grid) {
    const Vec2 origin = tin.domain().min;
    const VertexArrays& va = tin.vertices();
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const Vec2 p = va.position[v];
        if (!on_lattice(p.x - origin.x, grid.cell_size) ||
            !on_lattice(p.y - origin.y, grid.row_spacing())) {
            return false;
        }
    }
    return true;
}

DefaultSampling default_sampling(const Tin& tin, const ImportGrid& grid, double fallback_cell) {
    if (tin_lies_on_grid(tin, grid)) return {grid.cell_size, grid.cell_height, false};
    const double finest = std::min({grid.cell_size, grid.row_spacing(), fallback_cell});
    return {finest, 0.0, true};
}

std::optional<DefaultSampling> apply_import_defaults(const Tin& tin,
                                                     const std::string& metadata_json,
                                                     ExportOptions& options, bool size_given) {
    options.georeference = import_georeference_of(metadata_json);
    if (options.cell_size || size_given) return std::nullopt;
    const std::optional<ImportGrid> grid = import_grid_of(metadata_json);
    if (!grid || options.map_size < 2) return std::nullopt;
    const Rect d = tin.domain();
    const DefaultSampling sampling =
        default_sampling(tin, *grid, std::max(d.width(), d.height()) / (options.map_size - 1));
    options.cell_size = sampling.cell_size;
    if (sampling.cell_height > 0.0) options.cell_height = sampling.cell_height;
    return sampling;
}

}  // namespace sandtin
