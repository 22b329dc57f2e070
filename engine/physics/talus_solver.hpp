#pragma once
// Talus relaxation over an AdjacencyGraph, in one of two schedules:
//  - Sequential (the seeds' Gauss-Seidel over the active list): each vertex sees the heights
//    its predecessors in the list just wrote. The CPU default.
//  - Jacobi: phase 1 computes every active vertex's outflow per directed edge from the old
//    heights, phase 2 lets every vertex gather what its neighbours sent. Deterministic and
//    independent of the thread count (each vertex sums in its fixed row order); the exact CPU
//    twin of the compute shader.
// Both move volume, never height: what leaves a vertex is exactly what its neighbours receive.

#include <cstdint>
#include <vector>

#include "physics/active_set.hpp"
#include "physics/adjacency_graph.hpp"
#include "physics/talus_kernel.hpp"
#include "util/thread_pool.hpp"

namespace sandtin {

enum class Schedule : std::uint8_t { Sequential, Jacobi };

struct TalusSettings {
    Schedule schedule = Schedule::Sequential;
    TalusParameters parameters;
    int quiet_iterations = 3;  ///< K: a vertex leaves the active set after K still iterations
    double randomness = 0.0;   ///< relative jitter of each outflow, in [0, 1); 0 = none
    std::uint64_t seed = 1;    ///< seed of the jitter (results depend on it deterministically)
    int threads = 1;           ///< Jacobi worker threads
};

/// The per-vertex arrays a relaxation reads and writes, indexed by vertex id.
struct TalusArrays {
    double* height = nullptr;           ///< m, updated in place
    const double* area = nullptr;       ///< m², lumped
    const double* bedrock = nullptr;    ///< m
    const double* tan_alpha = nullptr;  ///< tan of the angle of repose
    std::size_t size = 0;
};

struct IterationStats {
    std::size_t processed = 0;  ///< vertices whose outflow was computed
    std::size_t changed = 0;    ///< vertices whose height changed
    double volume_moved = 0.0;  ///< m³ that left their vertices
};

class TalusSolver {
  public:
    explicit TalusSolver(TalusSettings settings);

    TalusSettings& settings() { return settings_; }
    const TalusSettings& settings() const { return settings_; }
    std::uint64_t iteration() const { return iteration_; }

    /// One iteration over the active set. Appends to `split_around` the vertices whose edges
    /// longer than the relocation radius kept material from moving (duplicates possible).
    /// Updates the active set (changed vertices and their neighbours stay or become active).
    IterationStats iterate(const AdjacencyGraph& graph, const TalusArrays& arrays,
                           ActiveSet& active, std::vector<std::uint32_t>* split_around = nullptr);

    /// Ids whose height changed in the last iteration.
    const std::vector<std::uint32_t>& changed() const { return changed_list_; }

  private:
    IterationStats sequential(const AdjacencyGraph& g, const TalusArrays& a, ActiveSet& active,
                              std::vector<std::uint32_t>* split_around);
    IterationStats jacobi(const AdjacencyGraph& g, const TalusArrays& a, ActiveSet& active,
                          std::vector<std::uint32_t>* split_around);
    double random_factor(std::uint32_t v) const;
    void ensure(const AdjacencyGraph& g, std::size_t vertices);

    TalusSettings settings_;
    std::uint64_t iteration_ = 0;
    std::unique_ptr<ThreadPool> pool_;
    std::vector<double> q_;             ///< per slot: volume sent along the directed edge
    std::vector<double> out_;           ///< per vertex: total sent this iteration
    std::vector<double> new_height_;    ///< per receiver (Jacobi)
    std::vector<std::uint8_t> source_;  ///< per vertex: computed an outflow this iteration
    std::vector<std::uint8_t> receiver_flag_;
    std::vector<std::uint32_t> receivers_;
    std::vector<std::uint8_t> changed_;
    std::vector<std::uint32_t> changed_list_;
    std::vector<std::vector<std::uint32_t>> split_per_thread_;
    std::vector<double> moved_per_thread_;
};

}  // namespace sandtin
