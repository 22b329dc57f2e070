#pragma once
// Bulk removal of vertices an edit is about to overwrite. A stamp on dense sand would otherwise
// enforce its contours through every triangle of that sand (CGAL flips each crossed edge),
// set every vertex under the imprint to the profile, and then test and remove each one again.
// Removing them first, a connected patch at a time, makes the contours cross a few long
// triangles instead, so the stamp's cost follows the number of vertices it replaces, not the
// density of what it crosses.

#include <cstddef>
#include <functional>
#include <span>

#include "tin/tin.hpp"

namespace sandtin {

struct PatchClearing {
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
PatchClearing remove_in_patches(
    Tin& tin, std::span<const VertexId> vertices, EditReport* report,
    const std::function<bool(VertexId v, VertexId w)>& may_border = nullptr);

}  // namespace sandtin
