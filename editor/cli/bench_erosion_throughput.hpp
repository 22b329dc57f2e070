#pragma once
// sandtin bench erosion --throughput: CPU Jacobi vertex-updates per second on about 10⁶ vertices
// (200 x 200 with --quick), of the solver alone on three numberings of one graph and of
// SandPhysics in TIN and strip order, each at 1 and 2 threads and under both slope rules (the
// face rule's rows always branch; issue 39 asks for it at >= 0.5x the edge rule's rate).

#include <nlohmann/json.hpp>

namespace sandtin::cli {

/// The solver alone (TalusSolver on an AdjacencyGraph), median of `runs` runs per row.
nlohmann::json jacobi_throughputs(bool quick, int runs);
/// SandPhysics::step in TIN and strip order, median of `runs` runs per row.
nlohmann::json sand_physics_throughputs(bool quick, int runs);

}  // namespace sandtin::cli
