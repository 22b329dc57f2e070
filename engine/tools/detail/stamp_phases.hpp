#pragma once
// Private to engine/tools: the phases of one stamp, in the order stamp() (tools/stamp.hpp)
// calls them. Each takes what it reads and returns what it found; the phases that edit the TIN
// add what they did to an EditReport. The first two only read the terrain as it was before the
// stamp (stamp_contours.cpp); the rest edit it (stamp_phases.cpp).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "tin/bulk_removal.hpp"
#include "tin/tin.hpp"
#include "tools/extrusion.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/simplifier.hpp"
#include "tools/tool.hpp"

namespace sandtin::detail {

/// The height a stamp leaves where the sand stood at a given height.
class Imprint {
  public:
    Imprint(const ToolFrame& frame, bool dig) : frame_(&frame), dig_(dig) {}

    /// Where the tool's underside is at height `u` (+infinity: no contact there).
    double under(double u, double terrain) const {
        if (!std::isfinite(u)) return terrain;
        return dig_ ? std::min(terrain, u) : u;
    }
    /// At p, under the tool there.
    double operator()(Vec2 p, double terrain) const { return under(frame_->underside(p), terrain); }

    const ToolFrame& frame() const { return *frame_; }
    bool dig() const { return dig_; }

  private:
    const ToolFrame* frame_;
    bool dig_;
};

/// The tool's contours in the world, subdivided to its rim spacing and clipped to the domain.
struct PlacedContours {
    std::vector<Vec2> outer;     ///< O
    std::vector<Vec2> inner;     ///< I
    bool inner_clipped = false;  ///< part of I lay outside the domain
};

/// The contours where `frame` puts them; nullopt when the tool misses the terrain.
std::optional<PlacedContours> place_contours(const Tin& tin, const Tool& tool,
                                             const ToolFrame& frame);

/// A curved profile's interior samples; empty for a flat one.
struct ProfileLattice {
    std::vector<Vec2> points;
    std::vector<double> underside;  ///< the tool's underside above each point
    std::vector<double> terrain;    ///< the sand there before the stamp (0 outside the domain)
};

/// Phase 1: the terrain along and inside the contours before the stamp.
struct ContourSamples {
    std::vector<Vec2> rim;          ///< O with the points it needs to follow the terrain
    std::vector<double> rim_h;      ///< the terrain's heights there
    std::size_t rim_crossings = 0;  ///< triangle edges O crosses: the density under it
    /// I with the points its chords need where the tool stands above the sand.
    std::vector<Vec2> inner;
    std::vector<double> inner_terrain;  ///< the terrain's heights at I's points
    std::vector<double> inner_h;        ///< the imprint's: the heights I is enforced at
    ProfileLattice lattice;
};

/// Samples the terrain along O (adaptively, within the tool's rim tolerance), at I and at a
/// curved profile's interior samples.
ContourSamples sample_contours(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                               const PlacedContours& contours, const Imprint& imprint,
                               double simplify_tolerance, LocateHint* hint);

/// Phase 2: which segments of the contours the stamp enforces; segment k runs from point k to
/// point k + 1 (wrapping).
struct ActiveSegments {
    std::vector<std::uint8_t> inner;
    std::vector<std::uint8_t> rim;
};

/// The segments of I that would move sand and the segments of O next to them or crossed by an
/// older constraint. nullopt when the stamp would change nothing: the terrain already holds its
/// imprint (re-working a trail), so the stamp adds no vertices, constraints or releases.
std::optional<ActiveSegments> find_active_segments(const Tin& tin, const Tool& tool, Vec2 centre,
                                                   const ContourSamples& samples,
                                                   const Imprint& imprint, double tolerance,
                                                   Generation generation, LocateHint* hint);

/// Phase 3, before anything changes: the bent edges that inserting O would re-triangulate are
/// constrained (Tin::fence_bent_edges), so the surface outside O stays as it was, and where O
/// crosses them it takes the terrain's own height there (after the bulk clearing, an edge across
/// the cleared sand would give it the cleared surface's height). Only on a terrain coarser than
/// the tool.
struct RimFence {
    bool coarse_terrain = false;  ///< the terrain was fenced: coarser than the tool
    std::size_t edges_fenced = 0;
};

RimFence fence_rim(Tin& tin, const Tool& tool, const std::vector<Vec2>& outer,
                   const ContourSamples& samples, const PolygonInclusion& in_outer,
                   double tolerance, Generation generation, const SculptSettings& settings,
                   LocateHint* hint, EditReport& edit);

/// Where a point between the contours sits relative to them (after phases 2 and 3, which decide
/// the active segments).
class Band {
  public:
    struct Position {
        NearestEdge to_inner;
        NearestEdge to_rim;
        bool both_active = false;  ///< the wall there is just the ramp from I to O
    };

    Band(const ContourSamples& samples, const ActiveSegments& active);
    Position position(Vec2 p) const;
    /// Whether p's nearest segments of I and O are both enforced.
    bool both_active_at(Vec2 p) const { return all_active_ || position(p).both_active; }

  private:
    const ContourSamples* samples_;
    const ActiveSegments* active_;
    bool all_active_;  ///< every segment of both contours: nothing to look up
};

/// Phase 4: sand the imprint is about to replace goes first, in bulk (tin/bulk_removal.hpp). The
/// contours then cross a few long triangles instead of every triangle of dense sand. Only
/// vertices that the stamp would remove anyway go, so the vertices left, and with them the
/// constrained Delaunay triangulation and the surface, are the same as without this step (a test
/// compares both paths; the terrain along the contours was sampled before):
/// - in the wall band next to enforced contours, every unconstrained vertex (see clean_band);
/// - under a flat profile, with simplification on, a vertex the imprint moves, when all its
///   neighbours end on the floor too or lie across an enforced part of I: its star is then flat
///   after the stamp, and the simplifier would remove it.
BulkRemoval clear_replaced_sand(Tin& tin, const Tool& tool, const std::vector<Vec2>& outer,
                                const ContourSamples& samples, const ActiveSegments& active,
                                const Band& band, const PolygonInclusion& in_outer,
                                const PolygonInclusion& in_inner, const Imprint& imprint,
                                const SculptSettings& settings, LocateHint* hint, EditReport& edit);

/// Inserts the endpoints of the active segments of a closed contour and constrains them: phase 7
/// (I at the imprint's heights) and, through enforce_rim, phase 5.
void enforce_contour(Tin& tin, const std::vector<Vec2>& points, const std::vector<double>& heights,
                     const std::vector<std::uint8_t>& active, Generation generation,
                     LocateHint* hint, EditReport& edit);

/// Phase 5: O at the terrain's heights. Returns the volume that changed: the re-triangulation's.
double enforce_rim(Tin& tin, const ContourSamples& samples, const ActiveSegments& active,
                   Generation generation, LocateHint* hint, EditReport& edit);

/// Phase 6: older constraints inside the footprint are released now that O is constrained: a
/// constraint crossing O was split where O crossed it, its outside part keeps its constraint,
/// and the Delaunay flips of the release stay inside O. Constraints past their lifetime go
/// wherever they are, but only where releasing them re-triangulates nothing.
struct Release {
    std::size_t constraints = 0;
    std::vector<VertexId> vertices;  ///< the released constraints' vertices: to simplify
};

Release release_under_footprint(Tin& tin, const std::vector<Vec2>& outer, Generation generation,
                                Generation keep_generations, EditReport& edit);

/// Phase 8: every vertex inside I follows the profile, and a curved profile's lattice adds
/// vertices where the surface strays from it. Returns the vertices it set or added: the region
/// to simplify.
std::vector<VertexId> imprint_inside(Tin& tin, const ContourSamples& samples,
                                     const PolygonInclusion& in_inner, const Imprint& imprint,
                                     double simplify_tolerance, LocateHint* hint, EditReport& edit);

/// Phase 9: the band between I and O emptied of old vertices where both contours are enforced
/// and, under a digging tool, brought down to the wall elsewhere; removed vertices leave
/// `region` too. Returns the footprint: the live vertices inside O.
std::vector<VertexId> clean_band(Tin& tin, const ContourSamples& samples,
                                 const ActiveSegments& active, const Band& band,
                                 const PolygonInclusion& in_outer, const PolygonInclusion& in_inner,
                                 const Imprint& imprint, std::vector<VertexId>& region,
                                 LocateHint* hint, EditReport& edit);

/// Phase 10: the region and the footprint simplified, with the rest of the simplifier's queue
/// (released rims, earlier edits): this is the end of the iteration. A flat tool's level floor
/// goes in one step first.
SimplifyReport simplify_footprint(Tin& tin, const Tool& tool, double bottom,
                                  const PolygonInclusion& in_inner,
                                  const std::vector<VertexId>& region,
                                  std::vector<VertexId> footprint, SculptContext& context);

/// Phase 11: the displaced volume pushed into a ridge beside the tool.
struct Extrusion {
    double deposited = 0.0;    ///< m³
    double undeposited = 0.0;  ///< m³ it had to put back but found no band in the domain for
    std::size_t edges_fenced = 0;
    std::vector<VertexId> ridge;  ///< vertices it touched: to simplify
};

Extrusion extrude(Tin& tin, const Tool& tool, const ContourSamples& samples,
                  const std::vector<Vec2>& outer, double displaced_volume,
                  double retriangulation_volume, std::optional<Vec2> motion,
                  const std::optional<RidgeFence>& fence, LocateHint* hint);

}  // namespace sandtin::detail
