#pragma once
// The vertex graph the relaxation runs on: compressed rows (CSR) with per-row slack, so a
// local re-triangulation rewrites a few rows instead of the whole array. Each directed edge
// slot stores its target, its horizontal length (metres, fixed because vertices never move in
// the plane) and the slot of the opposite edge, which lets a vertex gather what its
// neighbours sent it without any atomic operation (the two-phase Jacobi step, on CPU threads
// and in the compute shader alike).
//
// Invariants (checked by matches()): for every live vertex v, the row of v lists exactly its
// TIN neighbours in counter-clockwise order; reverse(k) of the slot k = (v -> w) is the slot of
// (w -> v), and both slots hold the same length bit for bit (the Jacobi receiver recomputes
// what a sender computed along the opposite slot).
//
// Faces: slots k and k + 1 of a row (the last slot's next is the row's first) are the far
// corners of a face of v when across(k) > 0, the horizontal length (m) of the edge between
// them; across(k) == 0 where the pair spans the outside of the domain (the gap in a border
// vertex's ring), and for graphs given by assign() without faces.
//
// Rows and targets are in a VertexNumbering's local ids when one is given (the relaxation's
// locality order), else in TIN ids. Row v lists the neighbours of TIN vertex tin_id(v) in the
// same counter-clockwise order either way, so a kernel sums in the same order.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/face_kernel.hpp"
#include "physics/vertex_numbering.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Whether rebuilt rows get room to grow. Some: a local re-triangulation rewrites most rows in
/// place (the GPU mirror uploads only those). None: rebuilt rows are packed, so the kernels
/// stream no empty slots (measured: SandPhysics Jacobi at 10⁶ vertices in strip order 12.8 ->
/// 13.5 M updates per CPU-second); a row that grows moves to the end of the pool, with room
/// (where the terrain is being refined, it grows again).
enum class RowSlack : std::uint8_t { Some, None };

/// The 64-vertex words of a bitmap over the vertices that a row touches, v itself and its
/// neighbours: [lo, hi).
struct RowWords {
    std::uint32_t lo = 0, hi = 0;
};

/// Whether the graph keeps each slot's face shape (face_kernel.hpp's FaceCorner, 16 bytes a
/// slot) for the face rule's CPU kernel. Skip: a graph no CPU kernel relaxes (the GPU mirror's:
/// its shader works the shape out itself); a kernel given it works the shape out too.
enum class FaceShapes : std::uint8_t { Keep, Skip };

class AdjacencyGraph {
  public:
    AdjacencyGraph() = default;
    explicit AdjacencyGraph(RowSlack slack, FaceShapes shapes = FaceShapes::Keep)
        : slack_policy_(slack), keep_shapes_(shapes == FaceShapes::Keep) {}

    /// Builds the rows of every live vertex. With a numbering, every live vertex must be
    /// numbered, and the numbering must outlive the graph's next rebuild/update/matches call.
    void rebuild(const Tin& tin, const VertexNumbering* numbering = nullptr);
    /// Rewrites the rows of `changed` (TIN ids of vertices whose star changed, born or died)
    /// and fixes the reverse slots around them. Compacts when more than half the pool is
    /// slack. Pass the numbering the graph was built with.
    void update(const Tin& tin, std::span<const VertexId> changed,
                const VertexNumbering* numbering = nullptr);
    /// Builds a graph from explicit rows (regular grids). rows[v] lists v's neighbours. With
    /// `across`, rows are counter-clockwise and across[v][k] is across(k) of row v (see above:
    /// the length between the far corners of the face (v, k, k + 1), or 0 for no face); without
    /// it the graph carries no faces (the edge rule only). Throws std::invalid_argument when an
    /// edge has no opposite edge or a different length there, or an across length is negative
    /// or not finite.
    void assign(const std::vector<std::vector<std::uint32_t>>& rows,
                const std::vector<std::vector<double>>& lengths,
                const std::vector<std::vector<double>>* across = nullptr);

    std::uint32_t vertex_capacity() const { return static_cast<std::uint32_t>(offset_.size()); }
    std::uint32_t offset(std::uint32_t v) const { return offset_[v]; }
    std::uint32_t degree(std::uint32_t v) const { return v < degree_.size() ? degree_[v] : 0; }
    std::size_t slot_count() const { return target_.size(); }
    /// Slots the pool holds room for: slot_count() stays below this until the pool grows.
    std::size_t slot_capacity() const { return target_.capacity(); }
    /// Longest edge of v's row (m).
    double longest_edge(std::uint32_t v) const { return v < longest_.size() ? longest_[v] : 0.0; }

    const std::vector<std::uint32_t>& offsets() const { return offset_; }
    const std::vector<std::uint32_t>& degrees() const { return degree_; }
    const std::vector<std::uint32_t>& targets() const { return target_; }
    const std::vector<std::uint32_t>& reverses() const { return reverse_; }
    const std::vector<double>& lengths() const { return length_; }
    /// Per slot k: |target(k) target(next k)| (m) when v, target(k), target(next k) is a face
    /// (counter-clockwise), else 0. See above.
    const std::vector<double>& across() const { return across_; }
    /// Per slot: across() and the face's shape seen from the row's vertex (face_corner), for
    /// the face rule's kernel.
    FaceRows face_rows() const {
        return {across_.data(), keep_shapes_ ? corners_.data() : nullptr};
    }
    const std::vector<double>& longest_edges() const { return longest_; }
    /// Per vertex: the bitmap words its row touches. A kernel that marks v and some of its
    /// neighbours in a bitmap widens its word range once per row with this, not once per mark.
    const std::vector<RowWords>& row_words() const { return row_words_; }

    /// Rows whose slots moved or changed since the last call (GPU upload ranges).
    std::vector<std::uint32_t> take_dirty_rows();
    /// True when every row matches the TIN (tests and check paths).
    bool matches(const Tin& tin, const VertexNumbering* numbering = nullptr) const;

  private:
    void write_row(const Tin& tin, const VertexNumbering* numbering, std::uint32_t v,
                   std::vector<VertexId>& scratch);
    void fix_reverse(std::uint32_t v);
    /// Room in the slot pool for `slots` more at its end.
    void grow_pool(std::uint32_t slots);
    void ensure_vertices(std::uint32_t n);
    /// longest_, row_words_ and the face corners of v, from its row.
    void refresh_row_summary(std::uint32_t v);

    std::vector<std::uint32_t> offset_;
    std::vector<std::uint32_t> degree_;
    std::vector<std::uint32_t> capacity_;
    std::vector<std::uint32_t> target_;
    std::vector<std::uint32_t> reverse_;
    std::vector<double> length_;
    std::vector<double> across_;
    std::vector<FaceCorner> corners_;
    std::vector<double> longest_;
    std::vector<RowWords> row_words_;
    RowSlack slack_policy_ = RowSlack::Some;
    bool keep_shapes_ = true;  ///< corners_ is kept (FaceShapes::Keep)
    std::size_t slack_ = 0;
    std::vector<std::uint32_t> dirty_rows_;
    std::vector<std::uint8_t> dirty_flag_;
    std::vector<std::uint8_t> mark_;  ///< scratch for update(), all zero between calls
};

}  // namespace sandtin
