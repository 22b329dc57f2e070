#pragma once
// Automatic simplification (seed 000 §7.1.1, seed 003 §4 step 3): vertices whose height changed
// are queued, and at the end of an iteration each queued vertex is removed when it and all its
// neighbours lie within d_m of a common plane. Border vertices, vertices on constraints, and
// vertices under or beside water stay.
//
// The plane is the least-squares fit z = a x + b y + c through the vertex and its neighbours
// (vertical residuals, which is what decides the volume a removal changes); the seeds' plane
// through the vertex and two arbitrary neighbours depends on which two are picked.

#include <cstdint>
#include <span>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

struct SimplifySettings {
    /// d_m in metres. The seeds use 1 % of the terrain width, which on a sculpting scale erases
    /// tool marks; default_simplify_tolerance() gives 0.05 % of the larger domain side.
    double tolerance = 0.0005;
    VolumePolicy volume_policy = VolumePolicy::Conserve;
};

/// 0.05 % of the larger side of the domain: 0.5 mm on a 1 m sandbox, 5 mm on a 10 m one.
double default_simplify_tolerance(const Rect& domain);

struct SimplifyReport {
    std::size_t tested = 0;
    std::size_t removed = 0;
    double volume_change =
        0.0;  ///< m³: sum of the changes each removal caused (before compensation)
    double max_volume_change = 0.0;  ///< m³: largest |change| of a single removal
    void accumulate(const SimplifyReport& o);
};

/// Max vertical distance of v and its neighbours from their least-squares plane (m), or
/// +infinity when v is on the border, on a constraint, or holds water or borders a vertex
/// that does (its removal would change the water's volume).
double planarity_residual(const Tin& tin, VertexId v);

class Simplifier {
  public:
    void enqueue(VertexId v);
    void enqueue(std::span<const VertexId> vs);
    std::size_t queued() const { return queue_.size(); }
    void clear();
    /// Tests every queued vertex once and removes the redundant ones; empties the queue.
    SimplifyReport run(Tin& tin, const SimplifySettings& settings);

  private:
    std::vector<VertexId> queue_;
    std::vector<std::uint8_t> queued_flag_;
    /// By VertexId: a candidate of the current run not yet grouped. All 0 between runs, so a
    /// run costs its candidates and not the terrain.
    std::vector<std::uint8_t> candidate_flag_;
};

}  // namespace sandtin
