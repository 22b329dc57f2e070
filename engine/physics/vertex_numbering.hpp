#pragma once
// The numbering the relaxation runs in: a bijection between the TIN's vertex ids and dense
// "local" ids, so the solver's per-vertex arrays, graph rows and active-set bitmap can be laid
// out for locality instead of in the TIN's order.
//
// Why: at 10⁶ active vertices the Jacobi kernels are memory-bound, and the order of the ids
// decides how many of a vertex's neighbours' data is already in cache. Measured with
// `sandtin bench erosion --throughput` (M vertex updates per CPU-second, one thread, same
// graph, with the kernel's branch-free passes; medians of five runs on a 2-core VM whose other
// tenants add about 10 % of noise): the TIN's bulk-build ids (CGAL's multiscale spatial sort)
// 8.3, a Hilbert curve 14.5, strips two spacings tall in x order 20.2. Strips win because a
// vertex's neighbours lie in its own strip or the next one, so the kernels read a few nearly
// sequential streams that the hardware prefetchers follow.
//
// Identity numbering: local id == TIN id for every id (dead ones included), i.e. no
// renumbering. Strip numbering: the live vertices sorted by (floor(y / (2 s)), x, id), s the
// mean spacing sqrt(domain area / live vertices). Vertices born later are appended (add());
// the owner renumbers when enough have been appended (appended()).
//
// Invariants: tin_id(local(t)) == t for every numbered TIN id t; local(tin_id(l)) == l for
// every local id l.

#include <cstdint>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

class VertexNumbering {
  public:
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

    /// Local id = TIN id for every id below tin.vertex_capacity().
    void assign_identity(const Tin& tin);
    /// The live vertices in strips two mean spacings tall, each in x order.
    void assign_strips(const Tin& tin);

    bool identity() const { return identity_; }
    /// Local id of TIN id t, or kNone when t is not numbered.
    std::uint32_t local(std::uint32_t t) const {
        return t < to_local_.size() ? to_local_[t] : kNone;
    }
    /// TIN id of local id l (l < size()).
    std::uint32_t tin_id(std::uint32_t l) const { return to_tin_[l]; }
    /// Numbers TIN id t if it is not yet (identity: every id up to t; strips: t at the end).
    /// Returns its local id.
    std::uint32_t add(std::uint32_t t);
    /// Number of local ids.
    std::uint32_t size() const { return static_cast<std::uint32_t>(to_tin_.size()); }
    /// Local ids given out by add() since the last assign (strip numbering only).
    std::size_t appended() const { return appended_; }
    /// TIN id of each local id.
    const std::vector<std::uint32_t>& tin_ids() const { return to_tin_; }

  private:
    bool identity_ = true;
    std::vector<std::uint32_t> to_tin_;
    std::vector<std::uint32_t> to_local_;
    std::size_t appended_ = 0;
};

}  // namespace sandtin
