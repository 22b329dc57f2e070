#pragma once
// A complete, CGAL-free copy of a TIN: what session files store and what undo restores.

#include <array>
#include <cstdint>
#include <vector>

#include "geom/rect.hpp"
#include "tin/ids.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {

/// Marks the corner of an unbounded (outside-the-domain) triangle in TinSnapshot::slots.
inline constexpr std::uint32_t kOutsideCorner = 0xFFFFFFFEu;

struct ConstraintRecord {
    std::uint32_t id = 0;  ///< ConstraintId value
    Generation generation = 0;
    std::vector<std::uint32_t> vertices;  ///< polyline through these VertexId values
    friend bool operator==(const ConstraintRecord&, const ConstraintRecord&) = default;
};

struct TinSnapshot {
    Rect domain;
    /// Per-vertex arrays of size vertex_capacity; lumped_area is recomputed on restore.
    VertexArrays vertices;
    std::vector<std::uint32_t> vertex_free_list;
    /// Per slot: corners as VertexId values, kOutsideCorner for the vertex at infinity of a
    /// triangle outside the domain, all kNoSlot for a free slot.
    std::vector<std::array<std::uint32_t, 3>> slots;
    std::vector<std::uint32_t> slot_free_list;
    std::vector<ConstraintRecord> constraints;  ///< sorted by id
    std::uint32_t constraint_capacity = 0;      ///< one past the largest ConstraintId used
    std::vector<std::uint32_t> constraint_free_list;
};

}  // namespace sandtin
