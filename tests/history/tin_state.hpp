#pragma once
// An id-free picture of a TIN's complete state, built from Tin::snapshot() and the public
// queries, independently of engine/history: vertices by position with all attributes,
// triangles as position triples with their constrained edges, constraints as position
// polylines with generations. Two TINs with equal pictures are the same terrain.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin::test {

using Point = std::pair<double, double>;

struct VertexState {
    double height, bedrock;
    std::uint16_t material;
    float moisture, slide_x, slide_y;
    double water_depth;
    friend bool operator==(const VertexState&, const VertexState&) = default;
};

struct TinState {
    std::map<Point, VertexState> vertices;
    /// Corners rotated so the smallest position comes first (orientation kept), plus the
    /// constraint flags of the edges opposite each corner.
    std::set<std::tuple<Point, Point, Point, int>> triangles;
    /// Constrained polylines and their generation. Two registry entries over the same
    /// polyline (a rim segment stamped twice) count once with the newer generation: the Tin
    /// merges such duplicates when a two-point constraint is re-inserted, and they constrain
    /// the same edges, so the terrain cannot tell them apart.
    std::map<std::vector<Point>, Generation> constraints;
};

inline Point key(Vec2 p) {
    return {p.x, p.y};
}

inline TinState capture(const Tin& tin) {
    TinState s;
    const TinSnapshot snap = tin.snapshot();
    const VertexArrays& va = snap.vertices;
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        s.vertices[key(va.position[i])] =
            VertexState{va.height[i],  va.bedrock[i], va.material[i],   va.moisture[i],
                        va.slide[i].x, va.slide[i].y, va.water_depth[i]};
    }
    for (TriangleSlot slot = 0; slot < snap.slots.size(); ++slot) {
        const auto c = tin.slot_triangle(slot);
        if (!c[0].valid()) continue;
        const std::uint8_t mask = tin.slot_constraint_mask(slot);
        std::array<Point, 3> p{key(tin.position(c[0])), key(tin.position(c[1])),
                               key(tin.position(c[2]))};
        std::array<int, 3> bit{mask & 1, (mask >> 1) & 1, (mask >> 2) & 1};
        const int r = static_cast<int>(std::min_element(p.begin(), p.end()) - p.begin());
        std::rotate(p.begin(), p.begin() + r, p.end());
        std::rotate(bit.begin(), bit.begin() + r, bit.end());
        s.triangles.emplace(p[0], p[1], p[2], bit[0] | (bit[1] << 1) | (bit[2] << 2));
    }
    for (const ConstraintRecord& c : snap.constraints) {
        std::vector<Point> pts;
        for (std::uint32_t v : c.vertices)
            pts.push_back(key(va.position[v]));
        Generation& g = s.constraints[std::move(pts)];
        g = std::max(g, c.generation);
    }
    return s;
}

/// Number of triangles in one picture and not in the other.
inline std::size_t triangle_difference(const TinState& a, const TinState& b) {
    std::vector<std::tuple<Point, Point, Point, int>> diff;
    std::set_symmetric_difference(a.triangles.begin(), a.triangles.end(), b.triangles.begin(),
                                  b.triangles.end(), std::back_inserter(diff));
    return diff.size();
}

/// Vertices and constraints equal exactly; triangles equal exactly.
inline ::testing::AssertionResult same_state(const TinState& a, const TinState& b) {
    if (a.vertices.size() != b.vertices.size()) {
        return ::testing::AssertionFailure()
               << "vertex counts differ: " << a.vertices.size() << " vs " << b.vertices.size();
    }
    std::size_t differing = 0;
    for (const auto& [p, v] : a.vertices) {
        const auto it = b.vertices.find(p);
        if (it == b.vertices.end() || !(it->second == v)) ++differing;
    }
    if (differing > 0) return ::testing::AssertionFailure() << differing << " vertices differ";
    if (a.constraints != b.constraints) {
        return ::testing::AssertionFailure()
               << "constraints differ: " << a.constraints.size() << " vs " << b.constraints.size();
    }
    const std::size_t t = triangle_difference(a, b);
    if (t > 0) return ::testing::AssertionFailure() << t << " triangles differ";
    return ::testing::AssertionSuccess();
}

}  // namespace sandtin::test
