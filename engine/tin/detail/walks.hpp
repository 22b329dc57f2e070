#pragma once
// Private to engine/tin: point location and walks over the faces of the triangulation. A walk
// starts from a LocateHint's vertex (vertices survive edits, faces do not) or, without one,
// from the nearest of a few sampled vertices.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "tin/detail/cgal_tin.hpp"
#include "tin/tin.hpp"
#include "util/visit_marks.hpp"

namespace sandtin::detail {

/// Where to start a walk to p: the hint's vertex when it is alive, else the closest of about
/// n^(1/3) sampled vertices (Mücke et al.'s jump-and-walk).
FaceHandle start_face(const Tin::Impl& m, Vec2 p, const LocateHint* hint);

/// A finite face containing the located point, with the point's barycentric coordinates.
struct FiniteLocation {
    FaceHandle face;
    std::array<std::uint32_t, 3> corners{};
    std::array<double, 3> weights{};
};

/// The finite face holding p from what CGAL's locate reported (f, lt, li): on the border the
/// walk may report the outer face, and a finite neighbour holds the point too.
FiniteLocation finite_location(const Tin::Impl& m, Vec2 p, CdtPlus::Locate_type lt, FaceHandle f,
                               int li);

/// Points the hint at the corner of `loc` nearest the located point (no-op without a hint).
void update_hint(LocateHint* hint, const FiniteLocation& loc);

/// CGAL's walk from `start` to p (in the domain), then the finite face holding it: nullopt
/// outside the triangulation. Reports the kind of location in `lt`.
std::optional<FiniteLocation> walk_to(const Tin::Impl& m, Vec2 p, FaceHandle start,
                                      CdtPlus::Locate_type& lt);

/// The finite face holding p, walking from the hint and updating it; a null handle outside the
/// triangulation.
FaceHandle face_at(const Tin::Impl& m, Vec2 p, LocateHint* hint);

/// Breadth-first walk over finite faces. `enter(face)` decides whether a face belongs to the
/// region; `cross(face, i)` whether the walk may step over edge i. Calls visit(face) once per
/// face in the region.
template <class Enter, class Cross, class Visit>
void walk_faces(const Tin::Impl& m, std::span<const FaceHandle> starts, Enter&& enter,
                Cross&& cross_edge, Visit&& visit) {
    static thread_local VisitMarks seen;
    static thread_local std::vector<FaceHandle> queue;
    seen.clear();
    seen.reserve_ids(m.events.face_of_slot.size());
    queue.clear();
    for (FaceHandle f : starts) {
        if (m.cdt.is_infinite(f) || seen.contains(f->slot) || !enter(f)) continue;
        seen.mark(f->slot);
        queue.push_back(f);
    }
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const FaceHandle f = queue[head];
        visit(f);
        for (int i = 0; i < 3; ++i) {
            const FaceHandle g = f->neighbor(i);
            if (m.cdt.is_infinite(g) || seen.contains(g->slot) || !cross_edge(f, i) || !enter(g)) {
                continue;
            }
            seen.mark(g->slot);
            queue.push_back(g);
        }
    }
}

/// Walks the finite faces the segment a-b crosses, from the one holding a, calling
/// visit(face) until it returns true (it has seen b) or the walk leaves the hull. Each face is
/// met at most once, so the walk is bounded by the face count.
template <class Visit>
void walk_faces_along(const Tin::Impl& m, Vec2 a, Vec2 b, LocateHint* hint, Visit&& visit) {
    auto lfc = m.cdt.line_walk(to_point(a), to_point(b), face_at(m, a, hint));
    if (lfc.is_empty()) return;
    const auto done = lfc;
    // The data structure's face count (infinite faces included) is a stored size; the
    // triangulation's finite count circulates the hull each time it is asked, which on a
    // terrain with a long border made this loop condition most of a section's cost.
    const std::size_t face_bound = m.cdt.tds().number_of_faces();
    for (std::size_t step = 0; step <= face_bound; ++step) {
        if (m.cdt.is_infinite(lfc)) return;
        if (visit(FaceHandle(lfc))) return;
        if (++lfc == done) return;
    }
}

}  // namespace sandtin::detail
