#pragma once
// Stable handles into the TIN. A VertexId indexes the per-vertex SoA arrays and the GPU vertex
// buffers; a TriangleSlot indexes the triangle (index) buffer. Both are reused after the owner
// dies, but never before the change journal has reported the death (see ChangeJournal).

#include <compare>
#include <cstdint>
#include <functional>
#include <limits>

namespace sandtin {

struct VertexId {
    std::uint32_t value = std::numeric_limits<std::uint32_t>::max();

    constexpr VertexId() = default;
    constexpr explicit VertexId(std::uint32_t v) : value(v) {}
    constexpr bool valid() const { return value != std::numeric_limits<std::uint32_t>::max(); }
    constexpr std::size_t index() const { return value; }
    friend constexpr auto operator<=>(VertexId, VertexId) = default;
};

inline constexpr VertexId kInvalidVertex{};

using TriangleSlot = std::uint32_t;
inline constexpr TriangleSlot kNoSlot = std::numeric_limits<std::uint32_t>::max();

/// Tool stamps number their constraints with an increasing generation, so that older
/// constraints can be released as new stamps cover them.
using Generation = std::uint64_t;

/// Handle of a constraint (a constrained polyline) in the TIN's registry.
struct ConstraintId {
    std::uint32_t value = std::numeric_limits<std::uint32_t>::max();

    constexpr ConstraintId() = default;
    constexpr explicit ConstraintId(std::uint32_t v) : value(v) {}
    constexpr bool valid() const { return value != std::numeric_limits<std::uint32_t>::max(); }
    friend constexpr auto operator<=>(ConstraintId, ConstraintId) = default;
};

}  // namespace sandtin

template <>
struct std::hash<sandtin::VertexId> {
    std::size_t operator()(sandtin::VertexId v) const noexcept {
        return std::hash<std::uint32_t>{}(v.value);
    }
};
