#include "tin/detail/hole_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cstdint>

namespace sandtin::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>;
// Face info: reached from the infinite face without crossing the boundary (outside).
using Fb =
    CGAL::Triangulation_face_base_with_info_2<bool, K,
                                              CGAL::Constrained_triangulation_face_base_2<K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: crossing constraints become new (info-less) vertices instead of an
// exception, which is how a non-simple polygon is detected below.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

}  // namespace

std::vector<std::array<std::size_t, 3>> triangulate_simple_polygon(std::span<const Vec2> polygon) {
    const std::size_t n = polygon.size();
    if (n < 3) return {};
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> handles;
    handles.reserve(n);
    Cdt::Face_handle hint;
    for (std::size_t k = 0; k < n; ++k) {
        const Cdt::Vertex_handle v = cdt.insert(K::Point_2(polygon[k].x, polygon[k].y), hint);
        if (cdt.number_of_vertices() != k + 1) return {};  // a repeated point
        v->info() = k;
        hint = v->face();
        handles.push_back(v);
    }
    if (cdt.dimension() < 2) return {};  // all on one line: no area
    for (std::size_t k = 0; k < n; ++k)
        cdt.insert_constraint(handles[k], handles[(k + 1) % n]);
    // A crossing made a vertex; an edge through a boundary point was split in two.
    if (cdt.number_of_vertices() != n) return {};
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
        if (v->info() >= n) return {};
    }
    // Outside: everything reachable from the infinite face without crossing the boundary.
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
        f->info() = false;
    std::vector<Cdt::Face_handle> stack{cdt.infinite_face()};
    cdt.infinite_face()->info() = true;
    while (!stack.empty()) {
        const Cdt::Face_handle f = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
            const Cdt::Face_handle g = f->neighbor(i);
            if (f->is_constrained(i) || g->info()) continue;
            g->info() = true;
            stack.push_back(g);
        }
    }
    std::vector<std::array<std::size_t, 3>> triangles;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (f->info()) continue;
        triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    }
    if (triangles.size() != n - 2) return {};
    // Every boundary edge k -> k+1 must be an edge of an inside triangle with the inside on its
    // left; a clockwise polygon has its edges the other way round.
    std::vector<std::uint8_t> seen(n, 0);
    for (const auto& t : triangles) {
        for (int i = 0; i < 3; ++i) {
            const std::size_t a = t[static_cast<std::size_t>(i)];
            const std::size_t b = t[static_cast<std::size_t>((i + 1) % 3)];
            if ((a + 1) % n == b) seen[a] = 1;
        }
    }
    for (std::uint8_t s : seen) {
        if (!s) return {};
    }
    return triangles;
}

}  // namespace sandtin::detail
