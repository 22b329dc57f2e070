#pragma once
// The colours exports bake into albedo maps and mesh materials: the scene's own materials, so an
// exported terrain looks as it does in the viewport, recoloured materials included.

#include "maps/albedo_map.hpp"
#include "physics/material.hpp"

namespace sandtin {

/// Each material's colour (linear RGB, as the viewport shades it) by material id, with the
/// viewport's darkening of wet sand (kWetReflectance).
MaterialColours export_palette(const MaterialTable& materials);

}  // namespace sandtin
