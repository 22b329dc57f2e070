#pragma once
// Artist brushes: raise/lower, smooth, flatten, weather and paint material, applied as dabs
// inside a radius with a falloff. Before a dab, edges longer than the brush spacing inside the disc
// are split so the brush has the resolution it needs.

#include <cstdint>
#include <optional>

#include "tin/tin.hpp"
#include "tools/falloff.hpp"
#include "tools/sculpt_context.hpp"

namespace sandtin {

enum class BrushKind : std::uint8_t { Raise, Lower, Smooth, Flatten, PaintMaterial, Weather };

struct BrushSettings {
    BrushKind kind = BrushKind::Raise;
    double radius = 0.05;  ///< metres
    /// Raise/Lower: metres at the centre per dab. Smooth/Flatten: fraction in [0, 1] of the
    /// way to the target per dab. Weather: fraction in [0, 1] of one weathering iteration's
    /// largest wear (physics/curvature_weathering.hpp) at the centre per dab.
    double strength = 0.005;
    Falloff falloff = Falloff::Smooth;
    /// Longest edge inside the disc before the dab (m); 0 = radius / 6.
    double refine_spacing = 0.0;
    std::uint16_t material = 0;  ///< PaintMaterial
    /// PaintMaterial: the saturation in [0, 1] painted with the material. Callers pass the
    /// material's default_moisture (physics/material.hpp), so painted moist sand holds the
    /// steeper slopes its moisture gives.
    float moisture = 0.0f;
    std::optional<double>
        flatten_to;  ///< Flatten target height (m); default: surface at the centre
};

struct BrushReport {
    std::size_t vertices_changed = 0;
    std::size_t vertices_inserted = 0;
    /// Bent edges constrained so that refining the disc re-shapes nothing outside it
    /// (tools/refine.hpp): 0 on sand, some on a coarse elevation model.
    std::size_t edges_fenced = 0;
    double volume_change = 0.0;  ///< m³
};

/// One dab of the brush at `centre`.
BrushReport apply_brush(Tin& tin, Vec2 centre, const BrushSettings& settings,
                        SculptContext& context);

}  // namespace sandtin
