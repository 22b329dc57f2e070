#pragma once
// Pouring and removing sand: a volume (m³) added to or taken from the terrain around a point,
// spread with a radial falloff. The volume is exact: with lumped areas A_i the heights change
// by dh_i = V k_i / sum(A_j k_j), so sum(A_i dh_i) = V. Where the terrain is coarse, points are
// first inserted so the pour has a shape. The physics then lets the sand slide.

#include <optional>
#include <string>

#include "tin/tin.hpp"
#include "tools/falloff.hpp"
#include "tools/sculpt_context.hpp"

namespace sandtin {

struct PourSettings {
    double radius = 0.02;  ///< metres
    Falloff falloff = Falloff::Smooth;
    /// Longest edge kept inside the pour disc (m); 0 = radius / 4.
    double refine_spacing = 0.0;
};

struct PourReport {
    double volume = 0.0;  ///< m³ actually added (positive) or removed (negative)
    std::size_t vertices_inserted = 0;
    std::size_t vertices_changed = 0;
    /// Bent edges constrained so that refining the disc re-shapes nothing outside it
    /// (tools/refine.hpp): 0 on sand, some on a coarse elevation model.
    std::size_t edges_fenced = 0;
};

/// Adds `volume` m³ (>= 0) centred at `centre`.
PourReport pour_sand(Tin& tin, Vec2 centre, double volume, const PourSettings& settings,
                     SculptContext& context);
/// Removes up to `volume` m³ (>= 0) of sand centred at `centre`; never below the bedrock, so
/// the report may show less than asked for when the sand runs out.
PourReport remove_sand(Tin& tin, Vec2 centre, double volume, const PourSettings& settings,
                       SculptContext& context);

/// The warning for a pour or removal that moved less than 99 % of the `asked` m³ (`moved` is
/// the reports' volume, negative for a removal), saying how much and why; none otherwise. The
/// script runner and the editor both show it.
std::optional<std::string> short_pour_warning(bool remove, double asked, double moved);

}  // namespace sandtin
