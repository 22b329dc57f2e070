// Tin: removal of vertices. One vertex at a time (CGAL fills the hole), a vertex on a straight
// stretch of the border, and a connected patch in one step: the hole around the patch is
// re-triangulated from its boundary and made constrained-Delaunay again.

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "geom/plane_fit.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/edit_finisher.hpp"
#include "tin/detail/hole_triangulation.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "util/prepare_for_writing.hpp"
#include "util/visit_marks.hpp"

namespace sandtin {

using detail::CdtPlus, detail::EditFinisher, detail::require;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

bool Tin::remove_vertex(VertexId v, VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    require(is_alive(v), "remove_vertex: vertex id is not alive");
    if (is_boundary(v) || is_on_constraint(v)) return false;
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    m.cdt.remove(m.handle(v));
    finisher.finish(policy, {}, report);
    return true;
}

bool Tin::remove_border_vertex(VertexId v, VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    require(is_alive(v), "remove_border_vertex: vertex id is not alive");
    if (is_on_constraint(v)) return false;
    // The two border neighbours: the finite ends of the infinite faces around v.
    const Vh vh = m.handle(v);
    std::array<Vh, 2> ends{};
    int found = 0;
    auto fc = m.cdt.incident_faces(vh);
    const auto done = fc;
    do {
        if (!m.cdt.is_infinite(fc)) continue;
        const int j = fc->index(vh);
        for (int k : {CdtPlus::ccw(j), CdtPlus::cw(j)}) {
            const Vh w = fc->vertex(k);
            if (!m.cdt.is_infinite(w) && found < 2 && (found == 0 || ends[0] != w)) {
                ends[static_cast<std::size_t>(found++)] = w;
            }
        }
    } while (++fc != done);
    if (found != 2) return false;  // not on the border
    // On one side of the rectangle with both neighbours: then removing v leaves that side
    // straight (a corner, or a vertex between two sides, would cut the domain).
    const Vec2 p = m.va.position[v.value];
    const Vec2 a = m.va.position[ends[0]->id];
    const Vec2 b = m.va.position[ends[1]->id];
    const Rect& d = m.domain;
    auto same_side = [&](auto coordinate, double side) {
        return coordinate(p) == side && coordinate(a) == side && coordinate(b) == side;
    };
    const bool straight = same_side([](Vec2 q) { return q.x; }, d.min.x) ||
                          same_side([](Vec2 q) { return q.x; }, d.max.x) ||
                          same_side([](Vec2 q) { return q.y; }, d.min.y) ||
                          same_side([](Vec2 q) { return q.y; }, d.max.y);
    if (!straight) return false;
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    m.cdt.remove(vh);
    finisher.finish(policy, {}, report);
    return true;
}

bool Tin::remove_patch(std::span<const VertexId> vertices, VolumePolicy policy,
                       EditReport* report) {
    return remove_planar_patch(vertices, std::numeric_limits<double>::infinity(), policy, report);
}

namespace {

/// An edge of the boundary of a patch's region, directed with the region on its left.
struct BoundaryEdge {
    Vh from, to;
    Fh outside;
    int outside_index;
    bool constrained;
};

/// The faces around a set of vertices to remove, and the boundary of their union as one loop
/// of directed edges. Per-vertex marks are reused between calls and cleared entry by entry, so
/// a patch costs its own size and not the terrain's: in the set, and 1 + the index of the
/// boundary edge that starts at the vertex (0: none).
class PatchRegion {
  public:
    PatchRegion(const Tin::Impl& m, std::span<const VertexId> vertices);
    ~PatchRegion() {
        if (!cleared_) clear_marks();
    }
    PatchRegion(const PatchRegion&) = delete;
    PatchRegion& operator=(const PatchRegion&) = delete;

    /// Finds the region and its boundary loop. False when the set does not qualify: a dead or
    /// repeated vertex, a vertex on the border or on a constraint, a constrained chord across
    /// the region, a boundary that touches the set or itself or forms several loops, or a
    /// vertex that is not in the set but would be left without faces.
    bool find() {
        return mark_set() && collect_faces() && collect_boundary() && close_loop() &&
               covers_its_corners();
    }
    /// Whether the set and its boundary lie within `tolerance` metres of one plane.
    bool planar(double tolerance) const;
    /// Clears the marks (the faces and the loop stay readable).
    void clear_marks();

    const std::vector<Fh>& faces() const { return faces_; }
    const std::vector<BoundaryEdge>& loop() const { return loop_; }

  private:
    bool mark_set();
    bool collect_faces();
    bool collect_boundary();
    bool close_loop();
    bool covers_its_corners() const;

    const Tin::Impl& m_;
    std::span<const VertexId> vertices_;
    std::vector<Fh> faces_;
    std::vector<BoundaryEdge> edges_;  ///< in the order found
    std::vector<BoundaryEdge> loop_;   ///< in order around the region
    bool cleared_ = false;
    static thread_local std::vector<std::uint8_t> in_set_;
    static thread_local std::vector<std::uint32_t> edge_from_;
    static thread_local VisitMarks face_in_region_;
};

thread_local std::vector<std::uint8_t> PatchRegion::in_set_;
thread_local std::vector<std::uint32_t> PatchRegion::edge_from_;
thread_local VisitMarks PatchRegion::face_in_region_;

PatchRegion::PatchRegion(const Tin::Impl& m, std::span<const VertexId> vertices)
    : m_(m), vertices_(vertices) {
    grow_zero_filled(in_set_, m.va.size());
    grow_zero_filled(edge_from_, m.va.size());
    face_in_region_.clear();  // O(1): marks of earlier calls no longer count
    face_in_region_.reserve_ids(m.events.face_of_slot.size());
}

void PatchRegion::clear_marks() {
    for (VertexId v : vertices_) {
        if (v.value < in_set_.size()) in_set_[v.value] = 0;
    }
    for (const BoundaryEdge& e : edges_)
        edge_from_[e.from->id] = 0;
    cleared_ = true;
}

bool PatchRegion::mark_set() {
    for (VertexId v : vertices_) {
        if (!m_.alive(v) || in_set_[v.value]) return false;
        in_set_[v.value] = 1;
    }
    return true;
}

/// The faces around the set.
bool PatchRegion::collect_faces() {
    for (VertexId v : vertices_) {
        const Vh vh = m_.handle(v);
        auto fc = m_.cdt.incident_faces(vh);
        const auto done = fc;
        do {
            const Fh f = fc;
            // A vertex on the border (an infinite face) or on a constraint (each edge at v is
            // opposite cw of v in one face) is not removable.
            if (m_.cdt.is_infinite(f) || f->is_constrained(CdtPlus::cw(f->index(vh)))) {
                return false;
            }
            if (!face_in_region_.contains(f->slot)) {
                face_in_region_.mark(f->slot);
                faces_.push_back(f);
            }
        } while (++fc != done);
    }
    return true;
}

/// The boundary of the faces as directed edges with the region on the left.
bool PatchRegion::collect_boundary() {
    for (const Fh f : faces_) {
        for (int i = 0; i < 3; ++i) {
            const Fh g = f->neighbor(i);
            if (face_in_region_.contains(g->slot)) {
                // A constrained chord across the region would not survive the re-fill.
                if (f->is_constrained(i)) return false;
                continue;
            }
            const Vh from = f->vertex(CdtPlus::ccw(i));
            const Vh to = f->vertex(CdtPlus::cw(i));
            if (m_.cdt.is_infinite(from) || m_.cdt.is_infinite(to) || in_set_[from->id] ||
                in_set_[to->id]) {
                return false;
            }
            if (edge_from_[from->id] != 0) return false;  // the boundary touches itself: not a disc
            edges_.push_back({from, to, g, m_.cdt.mirror_index(f, i), f->is_constrained(i)});
            edge_from_[from->id] = static_cast<std::uint32_t>(edges_.size());
        }
    }
    return true;
}

/// The boundary edges in order around the region: false when they form several loops (the set
/// surrounds something it does not remove).
bool PatchRegion::close_loop() {
    if (!edges_.empty()) {
        const std::uint32_t start = edges_.front().from->id;
        std::uint32_t at = start;
        for (std::size_t k = 0; k <= edges_.size(); ++k) {
            if (edge_from_[at] == 0) break;
            const BoundaryEdge& e = edges_[edge_from_[at] - 1];
            loop_.push_back(e);
            at = e.to->id;
            if (at == start) break;
        }
    }
    return loop_.size() == edges_.size() && loop_.size() >= 3;
}

/// Whether every corner of the region is removed or on its boundary; a vertex whose whole star
/// lies in the region but which is not in the set would be left without faces.
bool PatchRegion::covers_its_corners() const {
    for (const Fh f : faces_) {
        for (int i = 0; i < 3; ++i) {
            const Vh v = f->vertex(i);
            if (!in_set_[v->id] && edge_from_[v->id] == 0) return false;
        }
    }
    return true;
}

bool PatchRegion::planar(double tolerance) const {
    std::vector<Vec2> xy;
    std::vector<double> z;
    for (const BoundaryEdge& e : loop_) {
        xy.push_back(m_.va.position[e.from->id]);
        z.push_back(m_.va.height[e.from->id]);
    }
    for (VertexId v : vertices_) {
        xy.push_back(m_.va.position[v.value]);
        z.push_back(m_.va.height[v.value]);
    }
    return plane_fit_residual(xy, z, xy.front()) <= tolerance;
}

/// Surgery on the data structure: deletes the region, glues the hole's triangles (`ears` over
/// the loop's vertices, `across` their neighbours among each other) in, and flips to
/// constrained Delaunay.
void refill_hole(Tin::Impl& m, std::span<const VertexId> vertices, PatchRegion& region,
                 const std::vector<std::array<std::size_t, 3>>& ears,
                 const std::vector<std::array<int, 3>>& across, VolumePolicy policy,
                 EditReport* report) {
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    detail::Tds& tds = m.cdt.tds();
    const std::vector<BoundaryEdge>& loop = region.loop();
    std::vector<Vh> doomed;
    for (VertexId v : vertices)
        doomed.push_back(m.handle(v));
    region.clear_marks();
    for (const Fh f : region.faces())
        tds.delete_face(f);
    for (const Vh v : doomed)
        tds.delete_vertex(v);
    std::vector<Fh> created(ears.size());
    for (std::size_t t = 0; t < ears.size(); ++t) {
        const auto& ear = ears[t];
        created[t] = tds.create_face(loop[ear[0]].from, loop[ear[1]].from, loop[ear[2]].from);
    }
    CdtPlus::List_edges to_check;
    for (std::size_t t = 0; t < ears.size(); ++t) {
        const auto& ear = ears[t];
        const Fh f = created[t];
        for (int i = 0; i < 3; ++i) {
            const auto corner = static_cast<std::size_t>(i);
            f->vertex(i)->set_face(f);
            if (across[t][corner] >= 0) {
                f->set_neighbor(i, created[static_cast<std::size_t>(across[t][corner])]);
            } else {
                // On the hole's boundary: the edge from corner ccw(i) to corner cw(i) is
                // boundary edge number ear[ccw(i)].
                const BoundaryEdge& e = loop[ear[static_cast<std::size_t>(CdtPlus::ccw(i))]];
                f->set_neighbor(i, e.outside);
                e.outside->set_neighbor(e.outside_index, f);
                if (e.constrained) f->set_constraint(i, true);
            }
            to_check.emplace_back(f, i);
        }
    }
    m.cdt.propagating_flip(to_check);
    finisher.finish(policy, {}, report);
}

}  // namespace

bool Tin::remove_planar_patch(std::span<const VertexId> vertices, double tolerance,
                              VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    if (vertices.empty()) return true;
    PatchRegion region(m, vertices);
    if (!region.find()) return false;
    // Planarity of the whole patch (none asked for with an infinite tolerance).
    if (std::isfinite(tolerance) && !region.planar(tolerance)) return false;
    // The hole's triangles (constrained Delaunay inside its boundary), before anything changes.
    const std::vector<BoundaryEdge>& loop = region.loop();
    std::vector<Vec2> ring(loop.size());
    for (std::size_t k = 0; k < loop.size(); ++k)
        ring[k] = m.va.position[loop[k].from->id];
    std::vector<std::array<int, 3>> across;
    const std::vector<std::array<std::size_t, 3>> ears =
        detail::triangulate_simple_polygon(ring, &across);
    if (ears.empty()) return false;
    refill_hole(m, vertices, region, ears, across, policy, report);
    return true;
}

}  // namespace sandtin
