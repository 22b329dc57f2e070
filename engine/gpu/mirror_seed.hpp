#pragma once
// What a TinMirror's first sync computes on the CPU, computed beforehand on any thread: the CSR
// graph, the constrained flag of every directed edge, and the origins the GPU's floats are
// taken from. A scene opened or imported on a worker thread has its seed built there, so the
// UI thread's first sync only allocates and copies (issue 42: on a 10^6-vertex scene the graph
// took 1.9 s and the rows' upload with their flags 0.4 s of a 4.4 s install).
//
// A seed made by prepare_mirror_seed() carries a reader of the TIN's journal opened before the
// graph was built: whatever changes after that reaches the mirror's first sync through it, so
// a seed is never stale, only caught up.

#include <cstdint>
#include <memory>
#include <vector>

#include "geom/vec2.hpp"
#include "physics/adjacency_graph.hpp"
#include "tin/change_reader.hpp"
#include "tin/tin.hpp"

namespace sandtin::gpu {

struct MirrorSeed {
    /// The mirror's reader of the journal: opened, and its "everything" taken, before the rest
    /// was built. Null in a seed the mirror builds for itself.
    std::unique_ptr<ChangeReader> changes;
    AdjacencyGraph graph;  ///< every live vertex's row, all of them dirty
    /// Per pool slot of `graph`: 1 where the directed edge is constrained, else 0 (slack: 0).
    std::vector<std::uint32_t> edge_flags;
    Vec2 origin{};               ///< metres subtracted from positions on the GPU
    double height_origin = 0.0;  ///< metres subtracted from heights: the mean live height
};

/// Fills everything but the reader from `tin`'s present state. CPU only; `tin` is only read.
void build_mirror_seed(const Tin& tin, MirrorSeed& seed);

/// A reader of `tin`'s journal, then build_mirror_seed(). CPU only, any thread, but nothing
/// else may use `tin` meanwhile; `tin` must outlive the seed (and the mirror made from it) and
/// stay where it is.
MirrorSeed prepare_mirror_seed(Tin& tin);

}  // namespace sandtin::gpu
