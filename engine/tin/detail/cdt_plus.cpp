// CdtPlus: CGAL's constraint hierarchy with crossings and threadings that snap to nearby
// vertices (tin/detail/cgal_tin.hpp). Out of the header, so that the CGAL code these functions
// instantiate (and CdtPlus's virtual table) is compiled once, here, and not in every
// translation unit of engine/tin.

#include <utility>
#include <vector>

#include "tin/detail/cgal_tin.hpp"

namespace sandtin::detail {

CdtPlus::Vertex_handle CdtPlus::intersect(Face_handle f, int i, Vertex_handle vaa,
                                          Vertex_handle vbb) {
    const Vertex_handle vcc = f->vertex(cw(i));
    const Vertex_handle vdd = f->vertex(ccw(i));
    if (snap_distance > 0.0) {
        // Where a-b crosses c-d, in double precision: only to decide the snap.
        const Point& pa = vaa->point();
        const Point& pb = vbb->point();
        const Point& pc = vcc->point();
        const Point& pd = vdd->point();
        const double ax = pa.x(), ay = pa.y(), bx = pb.x(), by = pb.y();
        const double cx = pc.x(), cy = pc.y(), dx = pd.x(), dy = pd.y();
        const double denom = (bx - ax) * (dy - cy) - (by - ay) * (dx - cx);
        if (denom != 0.0) {
            const double t = ((cx - ax) * (dy - cy) - (cy - ay) * (dx - cx)) / denom;
            const double px = ax + t * (bx - ax);
            const double py = ay + t * (by - ay);
            const double s2 = snap_distance * snap_distance;
            auto near = [&](Vertex_handle v) {
                const double ex = v->point().x() - px;
                const double ey = v->point().y() - py;
                return ex * ex + ey * ey <= s2;
            };
            for (const Vertex_handle v : {vcc, vdd}) {
                if (near(v)) {
                    // As CGAL does when its rounded crossing falls on c or d.
                    insert_subconstraint(vcc, vdd);
                    return v;
                }
            }
            for (const Vertex_handle v : {vaa, vbb}) {
                if (near(v)) {
                    // An end of a-b lies on c-d up to rounding (a point inserted a hair off a
                    // constrained edge): c-d is split there, as CGAL does when its limit
                    // crossing is a or b. A new vertex at the crossing would sit an ulp from
                    // v, and the two would form a vertical step that sand cannot level.
                    Cdt::remove_constrained_edge(f, i);
                    hierarchy.split_constraint(vcc, vdd, v);
                    insert_subconstraint(vcc, v);
                    insert_subconstraint(v, vdd);
                    return v;
                }
            }
        }
    }
    return Base::intersect(f, i, vaa, vbb);
}

CdtPlus::Constraint_id CdtPlus::insert_polyline(const std::vector<Vertex_handle>& vs, bool thread) {
    Constraint_id id = hierarchy.insert_constraint(vs[0], vs[1]);
    insert_subconstraint(vs[0], vs[1]);
    for (std::size_t j = 1; j + 1 < vs.size(); ++j) {
        hierarchy.append_constraint(id, vs[j], vs[j + 1]);
        insert_subconstraint(vs[j], vs[j + 1]);
    }
    if (thread && snap_distance > 0.0) thread_through_near_vertices(id);
    return id;
}

CdtPlus::Vertex_handle CdtPlus::near_apex(Face_handle f, int i) const {
    const Vertex_handle c = f->vertex(i);
    if (is_infinite(c)) return {};
    const Point& pu = f->vertex(cw(i))->point();
    const Point& pw = f->vertex(ccw(i))->point();
    const Point& pc = c->point();
    const bool on = on_segment_up_to_snap(pw.x() - pu.x(), pw.y() - pu.y(), pc.x() - pu.x(),
                                          pc.y() - pu.y(), snap_distance * snap_distance);
    return on ? c : Vertex_handle();
}

void CdtPlus::thread_through_near_vertices(Constraint_id id) {
    std::vector<std::pair<Vertex_handle, Vertex_handle>> work;
    Vertex_handle previous;
    for (const Vertex_handle v : vertices_in_constraint(id)) {
        if (previous != Vertex_handle()) work.emplace_back(previous, v);
        previous = v;
    }
    while (!work.empty()) {
        const auto [u, w] = work.back();
        work.pop_back();
        Face_handle f;
        int i = 0;
        if (!is_edge(u, w, f, i) || !is_constrained(Edge(f, i))) continue;
        // On the domain's border the edge stays whatever happens to the constraint.
        if (is_infinite(f) || is_infinite(f->neighbor(i))) continue;
        Vertex_handle c = near_apex(f, i);
        if (c == Vertex_handle()) {
            const Face_handle g = f->neighbor(i);
            const int j = mirror_index(f, i);
            c = near_apex(g, j);
            if (c != Vertex_handle()) {
                f = g;
                i = j;
            }
        }
        if (c == Vertex_handle()) continue;
        Cdt::remove_constrained_edge(f, i);
        hierarchy.split_constraint(u, w, c);
        insert_subconstraint(u, c);
        insert_subconstraint(c, w);
        work.emplace_back(u, c);
        work.emplace_back(c, w);
    }
}

}  // namespace sandtin::detail
