#pragma once
// Removal of many vertices at once, a connected patch at a time (Tin::remove_patch), where
// removing them one by one would fill a hole and re-flip its neighbourhood per vertex. Used by
// a stamp to clear the dense sand its imprint replaces before enforcing its contours through
// it, and by redo to take out the vertices an edit removed.

#include <cstddef>
#include <functional>
#include <span>

#include "tin/tin.hpp"

namespace sandtin {

struct BulkRemoval {
    std::size_t candidates = 0;  ///< vertices offered
    std::size_t removed = 0;     ///< vertices removed
    std::size_t patches = 0;     ///< connected patches removed in one step each
    std::size_t refused = 0;     ///< pieces left alone (not a disc even after halving)
};

/// Removes the given vertices, grouped into connected patches (edges of the TIN), each in one
/// Tin::remove_patch step with VolumePolicy::Report, so the volume the removal changes is in
/// `report` and in the TIN's ledger. Vertices next to a constrained vertex, or around a vertex
/// that stays and would lose all its triangles, stay. A patch that still does not qualify (a
/// ring around vertices that stay) is halved and its pieces tried again, a few levels deep;
/// what is left counts as refused, and the caller's ordinary path deals with those vertices.
/// Dead ids, border vertices and vertices on constraints
/// are skipped. `may_border(v, w)`, when given, says whether vertex v of the set may go while
/// its neighbour w stays: the caller's condition for the removal to leave the surface it would
/// have made anyway (a vertex that fails it stays, and so may its neighbours in turn).
BulkRemoval remove_in_patches(
    Tin& tin, std::span<const VertexId> vertices, EditReport* report,
    const std::function<bool(VertexId v, VertexId w)>& may_border = nullptr);

}  // namespace sandtin
