#pragma once
// What one step of a terrain solver did (physics/terrain_solver.hpp).

#include <cstddef>

namespace sandtin {

struct PhysicsStepReport {
    int iterations = 0;              ///< iterations actually run (fewer when the sand came to rest)
    std::size_t vertex_updates = 0;  ///< sum over iterations of the vertices processed
    std::size_t changed = 0;         ///< sum over iterations of the vertices whose height changed
    std::size_t refined = 0;         ///< vertices inserted to split long edges
    double volume_moved = 0.0;       ///< m³
    double ms = 0.0;
    bool at_rest = false;
    /// Adds `o`'s counts and time; at_rest becomes `o`'s (the later step's).
    void accumulate(const PhysicsStepReport& o);
};

}  // namespace sandtin
