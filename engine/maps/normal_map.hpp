#pragma once
// CPU normal-map bake. Smooth: vertex normals interpolated across each triangle and
// renormalised, so long TIN edges shade smoothly (the seeds' main visual weakness). Faceted:
// the normal of the containing triangle.
//
// The normals are in the terrain's frame (x east, y north, z up). For a mesh textured with
// u = east and v = down the image (row 0 north), that is exactly an OpenGL-convention
// (+Y = green = up the image) tangent-space normal map, which is what glTF expects.

#include <cstdint>

#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

enum class NormalMode : std::uint8_t { Smooth, Faceted };

/// Three channels (x, y, z), unit length, z > 0. `z_scale` exaggerates heights first.
MapImage bake_normal_map(const Tin& tin, const MapGrid& grid, NormalMode mode = NormalMode::Smooth,
                         double z_scale = 1.0);

}  // namespace sandtin
