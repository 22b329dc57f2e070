#pragma once
// A snapshot's triangles as flat arrays, and the checks that make them a triangulation CGAL may
// hold: every half-edge paired with its twin, every vertex's triangles one fan, the finite
// triangles counter-clockwise and tiling the domain, and the edges locally Delaunay.
//
// Loading a session runs them here rather than on CGAL's faces: the arrays take 12 bytes a
// triangle against a face's 80, and vertex and triangle ranges are independent, so each check
// takes a range and the caller spreads the ranges over the cores. Every function reports the
// first problem it finds as a sentence (empty: none) and never throws, so that it can run on a
// worker thread.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin::detail {

inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;

struct TriangleSoup {
    /// Vertex ids are below it; the vertex at infinity is numbered vertex_count.
    std::uint32_t vertex_count = 0;
    /// The used slots' corners, in slot order, counter-clockwise as saved.
    std::vector<std::array<std::uint32_t, 3>> corners;
    std::vector<std::uint32_t> slot;  ///< each triangle's slot
    /// twin[3 t + i]: the half-edge paired with the one opposite corner i of triangle t
    /// (detail::pair_half_edges' numbering).
    std::vector<std::uint32_t> twin;
    /// Per vertex (vertex_count + 1 entries): the last triangle naming it, where its fan walk
    /// starts (the face CGAL's vertex keeps after a restore, so that sums around a vertex add
    /// in CGAL's order), and how many triangles name it.
    std::vector<std::uint32_t> fan_start;
    std::vector<std::uint32_t> references;

    std::size_t size() const { return corners.size(); }
};

/// The used slots (`slot_used[t]`) of `slots` as a soup, the corner `outside_corner`
/// renumbered `vertex_count`; twins not yet paired. Corners must be below vertex_count or
/// outside_corner (check_snapshot_slots has made sure).
TriangleSoup make_triangle_soup(std::span<const std::array<std::uint32_t, 3>> slots,
                                std::span<const std::uint8_t> slot_used, std::uint32_t vertex_count,
                                std::uint32_t outside_corner);

/// Fills soup.twin; a problem when an oriented edge repeats or an edge has one triangle only.
std::string pair_soup_twins(TriangleSoup& soup);

/// For the vertices in [begin, end) (the vertex at infinity is vertex_count): each live one is
/// named by a triangle, and the triangles naming it form one fan (else CGAL's circulators
/// would loop or skip); the one at infinity has a fan of three or more (the border is one
/// loop). Writes each live finite vertex's lumped area (a third of its finite triangles' areas,
/// added around the fan as Tin's incremental updates add them) into lumped_area[v]. Needs the
/// twins.
std::string check_fans(const TriangleSoup& soup, std::span<const std::uint8_t> alive,
                       std::span<const Vec2> position, std::uint32_t begin, std::uint32_t end,
                       std::span<double> lumped_area);

/// For the triangles in [begin, end): each finite one counter-clockwise (exact predicate), its
/// area added to `area`; each border edge (a triangle with the vertex at infinity) on a side
/// of `domain`.
std::string check_tiling(const TriangleSoup& soup, std::span<const Vec2> position,
                         const Rect& domain, std::size_t begin, std::size_t end,
                         CompensatedSum& area);

/// For the triangles in [begin, end), each edge shared by two finite triangles and seen from
/// its lower-numbered half-edge: appended to `out` as its two vertex ids when the far corner
/// lies strictly inside the triangle's circumcircle (exact predicate). Such an edge is fine
/// only if it is constrained, which the caller learns from CGAL once the constraints are in.
void find_non_delaunay_edges(const TriangleSoup& soup, std::span<const Vec2> position,
                             std::size_t begin, std::size_t end,
                             std::vector<std::pair<std::uint32_t, std::uint32_t>>& out);

}  // namespace sandtin::detail
