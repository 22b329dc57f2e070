#include "tin/detail/triangle_soup.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

#include "tin/detail/half_edge_twins.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "util/prepare_for_writing.hpp"

namespace sandtin::detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_2 point(Vec2 p) {
    return {p.x, p.y};
}

/// The corner of triangle t that is v (the corners are distinct, so there is at most one).
int corner_of(const std::array<std::uint32_t, 3>& t, std::uint32_t v) {
    return t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : -1;
}

}  // namespace

TriangleSoup make_triangle_soup(std::span<const std::array<std::uint32_t, 3>> slots,
                                std::span<const std::uint8_t> slot_used, std::uint32_t vertex_count,
                                std::uint32_t outside_corner) {
    TriangleSoup soup;
    soup.vertex_count = vertex_count;
    std::size_t used = 0;
    for (std::uint8_t u : slot_used)
        used += u;
    reserve_for_writing(soup.corners, used);
    reserve_for_writing(soup.slot, used);
    reserve_for_writing(soup.fan_start, std::size_t{vertex_count} + 1);
    soup.fan_start.assign(std::size_t{vertex_count} + 1, kNoTriangle);
    reserve_for_writing(soup.references, std::size_t{vertex_count} + 1);
    soup.references.assign(std::size_t{vertex_count} + 1, 0);
    for (std::uint32_t s = 0; s < slots.size(); ++s) {
        if (!slot_used[s]) continue;
        const auto t = static_cast<std::uint32_t>(soup.corners.size());
        std::array<std::uint32_t, 3> c = slots[s];
        for (std::uint32_t& v : c) {
            if (v == outside_corner) v = vertex_count;
            soup.fan_start[v] = t;
            ++soup.references[v];
        }
        soup.corners.push_back(c);
        soup.slot.push_back(s);
    }
    return soup;
}

std::string pair_soup_twins(TriangleSoup& soup) {
    switch (pair_half_edges(soup.corners, soup.vertex_count + 1, soup.twin)) {
        case TwinProblem::RepeatedHalfEdge:
            return "two triangles share the same oriented edge";
        case TwinProblem::MissingTwin:
            return "the triangles do not close up (an edge has no twin)";
        case TwinProblem::CornerOutOfRange:  // make_triangle_soup's contract
            return "a triangle names an unknown vertex";
        case TwinProblem::None:
            break;
    }
    return {};
}

std::string check_fans(const TriangleSoup& soup, std::span<const std::uint8_t> alive,
                       std::span<const Vec2> position, std::uint32_t begin, std::uint32_t end,
                       std::span<double> lumped_area) {
    const std::uint32_t infinite = soup.vertex_count;
    const auto triangles = static_cast<std::uint32_t>(soup.size());
    for (std::uint32_t v = begin; v < end; ++v) {
        if (v != infinite && !alive[v]) continue;
        const std::uint32_t references = soup.references[v];
        if (references == 0) {
            if (v == infinite) return "the terrain border is not a single closed loop";
            return "vertex " + std::to_string(v) + " is in no triangle";
        }
        // Around the fan as CGAL's face circulator turns: from a triangle to its neighbour
        // across the edge opposite the corner after v's, adding areas in that order.
        const std::uint32_t start = soup.fan_start[v];
        std::uint32_t t = start;
        std::uint32_t count = 0;
        double area = 0.0;
        do {
            const auto& c = soup.corners[t];
            const int i = corner_of(c, v);
            if (i < 0 || ++count > triangles) break;  // the twins led off the fan
            if (c[0] != infinite && c[1] != infinite && c[2] != infinite) {
                area += triangle_area(position[c[0]], position[c[1]], position[c[2]]);
            }
            t = soup.twin[3 * t + static_cast<std::uint32_t>((i + 1) % 3)] / 3;
        } while (t != start);
        if (v == infinite) {
            if (count != references || references < 3)
                return "the terrain border is not a single closed loop";
            continue;
        }
        if (count != references)
            return "the triangles around vertex " + std::to_string(v) + " do not form one fan";
        // Positive for a vertex of counter-clockwise triangles, unless they are too thin for
        // their areas to be told from 0 in floating point (check_tiling's test is exact).
        if (!(area > 0.0) || !std::isfinite(area))
            return "vertex " + std::to_string(v) + " has no area around it";
        lumped_area[v] = area / 3.0;
    }
    return {};
}

std::string check_tiling(const TriangleSoup& soup, std::span<const Vec2> position,
                         const Rect& domain, std::size_t begin, std::size_t end,
                         CompensatedSum& area) {
    const std::uint32_t infinite = soup.vertex_count;
    const auto orientation = Kernel().orientation_2_object();
    for (std::size_t t = begin; t < end; ++t) {
        const auto& c = soup.corners[t];
        const int at_infinity = corner_of(c, infinite);
        if (at_infinity < 0) {
            const Vec2 a = position[c[0]], b = position[c[1]], d = position[c[2]];
            if (orientation(point(a), point(b), point(d)) != CGAL::LEFT_TURN) {
                return "triangle in slot " + std::to_string(soup.slot[t]) +
                       " is not counter-clockwise";
            }
            area.add(triangle_area(a, b, d));
        } else {
            const auto k = static_cast<std::size_t>(at_infinity);
            if (!domain.has_on_one_side(position[c[(k + 1) % 3]], position[c[(k + 2) % 3]]))
                return "a border edge does not lie on the domain rectangle";
        }
    }
    return {};
}

void find_non_delaunay_edges(const TriangleSoup& soup, std::span<const Vec2> position,
                             std::size_t begin, std::size_t end,
                             std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) {
    const std::uint32_t infinite = soup.vertex_count;
    const auto in_circle = Kernel().side_of_oriented_circle_2_object();
    for (std::size_t t = begin; t < end; ++t) {
        const auto& c = soup.corners[t];
        if (corner_of(c, infinite) >= 0) continue;
        for (std::size_t i = 0; i < 3; ++i) {
            const std::uint32_t h = static_cast<std::uint32_t>(3 * t + i);
            const std::uint32_t g = soup.twin[h];
            if (g < h) continue;  // seen from the other side
            const auto& other = soup.corners[g / 3];
            const std::uint32_t far = other[g % 3];
            if (far == infinite) continue;
            if (in_circle(point(position[c[0]]), point(position[c[1]]), point(position[c[2]]),
                          point(position[far])) == CGAL::ON_POSITIVE_SIDE) {
                out.emplace_back(c[(i + 2) % 3], c[(i + 1) % 3]);
            }
        }
    }
}

}  // namespace sandtin::detail
