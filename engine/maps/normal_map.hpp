#pragma once
// CPU normal-map bake. Smooth: vertex normals interpolated across each triangle and
// renormalised, so long TIN edges shade smoothly (the seeds' main visual weakness). Faceted:
// the normal of the containing triangle.
//
// The normals are in the terrain's frame (x east, y north, z up): an object-space map, green =
// north = up the image. A mesh export needs them in each triangle's own frame instead
// (tangent_normal_map.hpp).

#include <cstdint>

#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

enum class NormalMode : std::uint8_t { Smooth, Faceted };

/// Three channels (x, y, z), unit length, z > 0. `z_scale` exaggerates heights first.
MapImage bake_normal_map(const Tin& tin, const MapGrid& grid, NormalMode mode = NormalMode::Smooth,
                         double z_scale = 1.0);

}  // namespace sandtin
