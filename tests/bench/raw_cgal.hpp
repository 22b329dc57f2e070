#pragma once
// The baseline: the same operations on a plain CGAL constrained Delaunay triangulation (default
// vertex and face bases, Epick, Exact_predicates_tag), with no ids, attributes or journal.

#include <memory>
#include <span>
#include <vector>

#include "geom/vec2.hpp"

namespace sandtin::bench {

class RawCgalTin {
  public:
    RawCgalTin();
    ~RawCgalTin();
    RawCgalTin(const RawCgalTin&) = delete;
    RawCgalTin& operator=(const RawCgalTin&) = delete;

    /// Bulk insertion with CGAL's own spatial sort.
    void insert(std::span<const Vec2> points);
    /// Point location from CGAL's default start; returns a checksum so it is not optimised away.
    std::size_t locate_all(std::span<const Vec2> queries) const;
    /// Inserts the ring's points and constrains its closed polygon, segment by segment.
    void constrain_ring(std::span<const Vec2> ring);
    std::size_t vertex_count() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The same triangulation with CGAL's constraint hierarchy on top
/// (Constrained_triangulation_plus_2), as sandtin's TIN keeps it: constraints with ids, their
/// crossings split into sub-constraints. It tells how much of the TIN's cost over RawCgalTin is the
/// hierarchy and how much is the TIN's own bookkeeping (ids, slots, lumped areas, the journal).
class RawCgalPlusTin {
  public:
    RawCgalPlusTin();
    ~RawCgalPlusTin();
    RawCgalPlusTin(const RawCgalPlusTin&) = delete;
    RawCgalPlusTin& operator=(const RawCgalPlusTin&) = delete;

    void insert(std::span<const Vec2> points);
    /// Inserts the ring's points and constrains its closed polygon, segment by segment.
    void constrain_ring(std::span<const Vec2> ring);
    std::size_t vertex_count() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace sandtin::bench
