#pragma once
// One stamp of a tool into the terrain (seed 000 §7.3, seed 003 §3.3, seed 004 §3.4). stamp()
// places the contours in the world, clipped to the domain (a tool that misses changes nothing),
// and runs these phases (tools/detail/stamp_phases.hpp):
//   1. sample the contours (sample_contours): the terrain along the outer contour O, sampled
//      until the rim follows it within the tool's tolerance; at the inner contour I, with the
//      points its chords need where the tool stands above the sand; at a curved profile's
//      interior samples;
//   2. find the active segments (find_active_segments): the parts of I that would move sand and
//      the parts of O next to them or crossed by an older constraint; none, and the stamp
//      changes nothing;
//   3. fence (fence_rim): on a terrain coarser than the tool, constrain the bent edges that
//      inserting O would re-triangulate;
//   4. clear (clear_replaced_sand): remove in bulk, on dense sand, the vertices the stamp would
//      remove anyway;
//   5. enforce O (enforce_rim): constrain O's active segments at the terrain's heights (each
//      segment its own constraint, tagged with the stamp's generation);
//   6. release (release_under_footprint): older constraints inside O, and those past their
//      lifetime;
//   7. enforce I (enforce_contour): constrain I's active segments at the imprint's heights;
//   8. imprint (imprint_inside): set every vertex inside I to the profile, adding a curved
//      profile's samples where the surface strays from it;
//   9. clean the band (clean_band): empty the wall band between I and O of old vertices, or
//      lower them to the wall, then even out slivers;
//  10. simplify (simplify_footprint): remove the vertices inside O that became redundant;
//  11. extrude (extrude): optionally push the displaced volume into a ridge outside O.

#include <optional>
#include <string>

#include "tin/bulk_removal.hpp"
#include "tin/tin.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/tool.hpp"

namespace sandtin {

struct StampReport {
    bool applied = false;  ///< false when the tool missed the terrain entirely
    Generation generation = 0;
    /// m³ the stamp took from the terrain before extrusion (negative when it added): what the
    /// inner part cut, less retriangulation_volume.
    double displaced_volume = 0.0;
    /// m³ the surface gained by re-triangulating around the rim's new vertices. They go in at
    /// the terrain's heights, but Delaunay insertion re-shapes the triangles around them,
    /// which on a coarse, curved TIN (an imported elevation model) reaches far beyond the
    /// tool. Extrusion carries it back only while it is below a layer as thick as the tool's
    /// radius over the tool's outer contour; beyond that it is no sand the tool moved, and it
    /// stays in volume_change.
    double retriangulation_volume = 0.0;
    double deposited_volume = 0.0;  ///< m³ put back by extrusion
    /// m³ extrusion had to put back but could not: the band beside the tool where its ridge
    /// goes lay wholly outside the domain (a tool covering the whole terrain). That volume
    /// left the terrain with the sand pushed over its edge. 0 without extrusion, and up to
    /// rounding whenever any of the band lies in the domain.
    double undeposited_volume = 0.0;
    double volume_change = 0.0;  ///< m³ net change of the terrain volume
    std::size_t vertices_inserted = 0;
    std::size_t vertices_removed = 0;
    std::size_t triangles_touched = 0;  ///< triangle slots the stamp changed
    std::size_t constraints_released = 0;
    /// Bent edges constrained so the rim's insertion could not re-shape the surface beyond O
    /// (Tin::fence_bent_edges): 0 on dense sand, some on a coarse elevation model.
    std::size_t edges_fenced = 0;
    SimplifyReport simplify;
    BulkRemoval cleared;       ///< sand removed in bulk before the contours (tin/bulk_removal.hpp)
    double enforce_ms = 0.0;   ///< placing the contours and steps 1-9
    double simplify_ms = 0.0;  ///< step 10
    double extrude_ms = 0.0;   ///< step 11

    void accumulate(const StampReport& o);
};

/// A sentence for the artist when extrusion lost more than 1 % of what it had to put back
/// (StampReport::undeposited_volume; the tools issue's bound on a stamp's volume change), for a
/// stamp or a stroke's accumulated report; nothing otherwise.
std::optional<std::string> lost_extrusion_warning(const StampReport& report);

/// Stamps `tool` at `at`. `motion` (any length) is the direction the tool moves in, which
/// shapes the extrusion ridge; without it the ridge surrounds the tool.
StampReport stamp(Tin& tin, const Tool& tool, const ToolPlacement& at, SculptContext& context,
                  std::optional<Vec2> motion = std::nullopt);

}  // namespace sandtin
