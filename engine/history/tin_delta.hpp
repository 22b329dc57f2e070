#pragma once
// A region-bounded difference between two states of a TIN: only the vertices and constraints
// that an edit touched, each with its value before and after. Undo applies the "before" side,
// redo the "after" side.
//
// Vertices are keyed by their position, not their VertexId: restoring a removed vertex through
// the Tin's public edits gives it a fresh id, so ids do not survive an undo, but positions do
// (a vertex's position is fixed for its life and no two live vertices share one). Constraints
// are recorded as polylines of positions with their generation, for the same reason.
//
// Exactness: the TIN is constrained-Delaunay, so once the vertex set, the attributes and the
// constraint polylines equal the recorded state, the triangulation does too, except where four
// or more vertices are cocircular (regular grids), where CGAL's choice of diagonal depends on
// the insertion history. apply_delta() reports vertices it could not restore (a vertex created
// on the domain border cannot be removed through the Tin API).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

/// Everything the TIN stores per vertex except derived data (lumped area).
struct VertexRecord {
    Vec2 position;                ///< metres
    double height = 0.0;          ///< metres
    double bedrock = kNoBedrock;  ///< metres
    std::uint16_t material = 0;
    float moisture = 0.0f;
    Vec2f slide;
    double water_depth = 0.0;  ///< metres
    friend bool operator==(const VertexRecord&, const VertexRecord&) = default;
};

/// A constrained polyline by the positions of its vertices.
struct ConstraintPolyline {
    Generation generation = 0;
    std::vector<Vec2> points;
    friend bool operator==(const ConstraintPolyline&, const ConstraintPolyline&) = default;
};

/// One vertex position whose content differs between the two states. An empty side means no
/// vertex stood there in that state.
struct VertexChange {
    std::optional<VertexRecord> before;
    std::optional<VertexRecord> after;
};

struct TinDelta {
    std::vector<VertexChange> vertices;
    std::vector<ConstraintPolyline> constraints_before;  ///< only in the before state
    std::vector<ConstraintPolyline> constraints_after;   ///< only in the after state

    bool empty() const {
        return vertices.empty() && constraints_before.empty() && constraints_after.empty();
    }
    /// Heap bytes held (for the history's memory budget).
    std::size_t bytes() const;
};

enum class DeltaSide : std::uint8_t { Before, After };

struct ApplyReport {
    std::size_t vertices_removed = 0;
    std::size_t vertices_inserted = 0;
    std::size_t vertices_updated = 0;
    std::size_t constraints_released = 0;
    std::size_t constraints_inserted = 0;
    /// Positions that could not be brought to the target state (see the header comment); the
    /// terrain is then equal to the target except there. Empty means exact.
    std::vector<Vec2> unrestored;
    bool exact() const { return unrestored.empty(); }
};

/// Brings the TIN from the other side of `delta` to `target`. The TIN must currently be in the
/// other side's state in the region the delta covers. Heights are written exactly (no volume
/// compensation: the recorded heights already are what they were).
ApplyReport apply_delta(Tin& tin, const TinDelta& delta, DeltaSide target);

}  // namespace sandtin
