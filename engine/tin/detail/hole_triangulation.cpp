#include "tin/detail/hole_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cstdint>

namespace sandtin::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>;
// Face info: -1 when reached from the infinite face without crossing the boundary (outside),
// else the index of the triangle in the result (-2 until numbered).
using Fb =
    CGAL::Triangulation_face_base_with_info_2<int, K,
                                              CGAL::Constrained_triangulation_face_base_2<K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: crossing constraints become new (info-less) vertices instead of an
// exception, which is how a non-simple polygon is detected below.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Dt = CGAL::Delaunay_triangulation_2<
    K, CGAL::Triangulation_data_structure_2<Vb, CGAL::Triangulation_face_base_with_info_2<int, K>>>;

/// Inserts the polygon's points in order, numbering the vertices; false on a repeated point or
/// when all points are on one line.
template <class Triangulation>
bool insert_points(Triangulation& t, std::span<const Vec2> polygon,
                   std::vector<typename Triangulation::Vertex_handle>& handles) {
    typename Triangulation::Face_handle hint;
    handles.reserve(polygon.size());
    for (std::size_t k = 0; k < polygon.size(); ++k) {
        const auto v = t.insert(K::Point_2(polygon[k].x, polygon[k].y), hint);
        if (t.number_of_vertices() != k + 1) return false;  // a repeated point
        v->info() = k;
        hint = v->face();
        handles.push_back(v);
    }
    return t.dimension() == 2;
}

/// The triangles inside the polygon's boundary (`on_boundary(face, i)`), numbered, with their
/// neighbours; empty unless they are the n - 2 triangles of a counter-clockwise polygon.
template <class Triangulation, class OnBoundary>
std::vector<std::array<std::size_t, 3>> inside_triangles(
    Triangulation& t, std::size_t n, OnBoundary&& on_boundary,
    std::vector<std::array<int, 3>>* neighbours) {
    using Fh = typename Triangulation::Face_handle;
    // Outside: everything reachable from the infinite face without crossing the boundary.
    for (auto f = t.all_faces_begin(); f != t.all_faces_end(); ++f)
        f->info() = -2;
    std::vector<Fh> stack{t.infinite_face()};
    t.infinite_face()->info() = -1;
    while (!stack.empty()) {
        const Fh f = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
            const Fh g = f->neighbor(i);
            if (on_boundary(f, i) || g->info() == -1) continue;
            g->info() = -1;
            stack.push_back(g);
        }
    }
    std::vector<std::array<std::size_t, 3>> triangles;
    std::vector<Fh> inside;
    for (auto f = t.finite_faces_begin(); f != t.finite_faces_end(); ++f) {
        if (f->info() == -1) continue;
        f->info() = static_cast<int>(triangles.size());
        inside.push_back(f);
        triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    }
    if (triangles.size() != n - 2) return {};
    // Every boundary edge k -> k+1 must be an edge of an inside triangle with the inside on its
    // left; a clockwise polygon has its edges the other way round.
    std::vector<std::uint8_t> seen(n, 0);
    for (const auto& tri : triangles) {
        for (int i = 0; i < 3; ++i) {
            const std::size_t a = tri[static_cast<std::size_t>(i)];
            const std::size_t b = tri[static_cast<std::size_t>((i + 1) % 3)];
            if ((a + 1) % n == b) seen[a] = 1;
        }
    }
    for (std::uint8_t s : seen) {
        if (!s) return {};
    }
    if (neighbours != nullptr) {
        neighbours->resize(triangles.size());
        for (std::size_t k = 0; k < inside.size(); ++k) {
            for (int i = 0; i < 3; ++i)
                (*neighbours)[k][static_cast<std::size_t>(i)] = inside[k]->neighbor(i)->info();
        }
    }
    return triangles;
}

}  // namespace

std::vector<std::array<std::size_t, 3>> triangulate_simple_polygon(
    std::span<const Vec2> polygon, std::vector<std::array<int, 3>>* neighbours) {
    const std::size_t n = polygon.size();
    if (n < 3) return {};
    // First the plain Delaunay triangulation of the points. A hole left by a patch removal is
    // bounded by edges of a Delaunay triangulation of a superset, which stay Delaunay edges of
    // the subset: then no constraint needs inserting, and the triangulation restricted to the
    // inside is the constrained one. Every boundary edge present also means the polygon is
    // simple (crossing or touching edges cannot all be edges of one triangulation).
    {
        // All at once: CGAL sorts them along a space-filling curve in randomised rounds. In ring
        // order nearly every point would land outside the hull built so far.
        std::vector<std::pair<K::Point_2, std::size_t>> points;
        points.reserve(n);
        for (std::size_t k = 0; k < n; ++k)
            points.emplace_back(K::Point_2(polygon[k].x, polygon[k].y), k);
        Dt dt;
        dt.insert(points.begin(), points.end());
        if (dt.number_of_vertices() != n || dt.dimension() < 2) return {};  // repeated; a line
        std::vector<Dt::Vertex_handle> handles(n);
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
            handles[v->info()] = v;
        bool all_edges = true;
        for (std::size_t k = 0; k < n && all_edges; ++k)
            all_edges = dt.is_edge(handles[k], handles[(k + 1) % n]);
        if (all_edges) {
            auto on_boundary = [&](Dt::Face_handle f, int i) {
                const Dt::Vertex_handle a = f->vertex(Dt::ccw(i));
                const Dt::Vertex_handle b = f->vertex(Dt::cw(i));
                if (dt.is_infinite(a) || dt.is_infinite(b)) return false;
                return (a->info() + 1) % n == b->info() || (b->info() + 1) % n == a->info();
            };
            return inside_triangles(dt, n, on_boundary, neighbours);
        }
    }
    // Otherwise the constrained Delaunay triangulation of the boundary.
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> handles;
    if (!insert_points(cdt, polygon, handles)) return {};
    for (std::size_t k = 0; k < n; ++k)
        cdt.insert_constraint(handles[k], handles[(k + 1) % n]);
    // A crossing made a vertex; an edge through a boundary point was split in two.
    if (cdt.number_of_vertices() != n) return {};
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
        if (v->info() >= n) return {};
    }
    return inside_triangles(
        cdt, n, [](Cdt::Face_handle f, int i) { return f->is_constrained(i); }, neighbours);
}

}  // namespace sandtin::detail
