#pragma once
// The triangles the water surface is drawn on: every triangle with at least one wet corner,
// each exactly once. A triangle belongs to its lowest-id wet corner, which lists it in its
// fan; a vertex's fan is recomputed from its ring when it or a neighbour changes (the render
// mesh's update already visits exactly those vertices), so keeping the list costs what the
// water's front costs, and a dry terrain holds nothing.

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin::render {

class WetTriangles {
  public:
    /// Recomputes the fan of `v` from `ring` (its counter-clockwise neighbours, as
    /// Tin::neighbours gives them): the faces (v, a, b) of consecutive neighbours, when v is wet
    /// and no wet corner has a lower id. A dead or dry vertex owns nothing.
    void refan(const Tin& tin, std::uint32_t v, std::span<const VertexId> ring);
    /// `v` owns nothing (it died).
    void forget(std::uint32_t v);
    void clear();

    /// Brings indices() up to date with the fans (after a batch of refans).
    void settle();
    /// Three VertexIds per wet triangle (counter-clockwise), as of the last settle().
    const std::vector<std::uint32_t>& indices() const { return indices_; }
    std::size_t triangle_count() const { return triangles_; }
    /// Bumped whenever the list changes, so a GPU copy knows when it is stale.
    std::uint64_t version() const { return version_; }

  private:
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> fans_;
    std::vector<std::uint32_t> indices_;
    std::vector<std::uint32_t> scratch_;
    std::size_t triangles_ = 0;
    std::uint64_t version_ = 0;
    bool stale_ = false;
};

}  // namespace sandtin::render
