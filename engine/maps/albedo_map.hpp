#pragma once
// CPU albedo bake: each vertex's material colour, darkened by its moisture (wet sand is
// darker), interpolated across the triangles.

#include <span>
#include <vector>

#include "geom/vec3.hpp"
#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Colour of a material index: linear RGB albedo in [0, 1], as the viewport shades it (files
/// store it sRGB-encoded: io/export_maps.hpp). Indices past the end use the last.
struct MaterialColours {
    std::vector<Vec3> colours;
    /// Reflectance kept at full moisture: colour * (1 - (1 - wet_factor) * moisture). 1: wet
    /// sand is not darker; export_palette sets the viewport's (kWetReflectance).
    double wet_factor = 1.0;
};

/// Three channels (r, g, b) of linear albedo in [0, 1].
MapImage bake_albedo_map(const Tin& tin, const MapGrid& grid, const MaterialColours& palette);

}  // namespace sandtin
