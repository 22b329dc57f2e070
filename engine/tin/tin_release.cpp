// Tin: release and expiry of constraints. A footprint releases the constraints under it (only
// the pieces inside it), and old constraints expire where releasing them re-triangulates
// nothing.

#include <algorithm>
#include <iterator>
#include <span>
#include <vector>

#include "geom/polygon.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/edit_finisher.hpp"

namespace sandtin {

using detail::EditFinisher, detail::kNoId;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

namespace {

/// Whether releasing the constrained edge a-b would flip nothing: the vertex opposite it in
/// one triangle lies outside the circumcircle of the other (exact predicate).
bool edge_is_delaunay(const Tin::Impl& m, Vh a, Vh b) {
    Fh f;
    int i = 0;
    if (!m.cdt.is_edge(a, b, f, i)) return true;
    const Fh g = f->neighbor(i);
    if (m.cdt.is_infinite(f) || m.cdt.is_infinite(g)) return true;
    const Vh d = g->vertex(m.cdt.mirror_index(f, i));
    const auto in_circle = detail::Kernel().side_of_oriented_circle_2_object();
    return in_circle(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(),
                     d->point()) != CGAL::ON_POSITIVE_SIDE;
}

/// Whether releasing the whole constraint would flip nothing.
bool constraint_is_delaunay(const Tin::Impl& m, const detail::ConstraintEntry& e) {
    Vh previous;
    bool first = true;
    for (const Vh v : m.cdt.vertices_in_constraint(e.cgal_id)) {
        if (!first && !edge_is_delaunay(m, previous, v)) return false;
        previous = v;
        first = false;
    }
    return true;
}

/// Unconstrains the listed constraints in one edit (Delaunay flips follow).
std::size_t release_doomed(Tin::Impl& m, std::span<const std::uint32_t> doomed, VolumePolicy policy,
                           EditReport* report, std::vector<VertexId>* released_vertices) {
    if (doomed.empty()) return 0;
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    for (std::uint32_t id : doomed) {
        detail::ConstraintEntry& e = m.constraints[id];
        if (released_vertices != nullptr) {
            for (Vh v : m.cdt.vertices_in_constraint(e.cgal_id))
                released_vertices->push_back(VertexId{v->id});
        }
        m.constraint_of_cgal.erase(e.cgal_id.vl_ptr());
        m.cdt.remove_constraint(e.cgal_id);
        m.unfile_constraint(id);
        e = {};
        m.constraint_ids.release(id);
    }
    finisher.finish(policy, {}, report);
    return doomed.size();
}

/// Dooms the pieces of constraint `id` inside the closed polygon (ReleaseFilter::inside_polygon):
/// the constraint is split at its vertices between runs of pieces inside and outside, and the
/// inside runs go into `doomed`.
void doom_inside_pieces(Tin::Impl& m, std::uint32_t id, std::span<const Vec2> inside_polygon,
                        std::vector<std::uint32_t>& doomed) {
    // Classify the pieces, then split the constraint between runs inside and outside.
    std::vector<Vh> vs;
    for (const Vh v : m.cdt.vertices_in_constraint(m.constraints[id].cgal_id))
        vs.push_back(v);
    std::vector<std::uint8_t> inside(vs.size() - 1);
    bool any_in = false;
    bool any_out = false;
    for (std::size_t k = 0; k + 1 < vs.size(); ++k) {
        const Vec2 mid = (m.va.position[vs[k]->id] + m.va.position[vs[k + 1]->id]) * 0.5;
        // A piece along the border counts as inside (a box stroked along a side puts its
        // rim on the line of the rim before): kept, it would run a hair beside the new
        // border's constraint, and between the two only triangles without area would fit.
        inside[k] = point_in_polygon(mid, inside_polygon) ||
                            nearest_edge(mid, inside_polygon).distance <= m.snap_distance
                        ? 1
                        : 0;
        (inside[k] ? any_in : any_out) = true;
    }
    if (!any_in) return;
    if (!any_out) {
        doomed.push_back(id);
        return;
    }
    std::uint32_t current = id;
    std::size_t run_start = 0;
    for (std::size_t k = 1; k <= inside.size(); ++k) {
        if (k < inside.size() && inside[k] == inside[run_start]) continue;
        if (k == inside.size()) {
            if (inside[run_start]) doomed.push_back(current);
            break;
        }
        // Split at vertex k: the current constraint keeps [.., vs[k]], a new one takes
        // [vs[k], ..]. Only the hierarchy changes; the triangulation does not.
        auto it = m.cdt.vertices_in_constraint_begin(m.constraints[current].cgal_id);
        std::advance(it, static_cast<std::ptrdiff_t>(k - run_start));
        const detail::CgalConstraintId second = m.cdt.split(m.constraints[current].cgal_id, it);
        const std::uint32_t nid = m.constraint_ids.allocate();
        if (nid >= m.constraints.size()) m.constraints.resize(static_cast<std::size_t>(nid) + 1);
        Rect first_box;
        Rect second_box;
        for (std::size_t j = run_start; j <= k; ++j)
            first_box.expand(m.va.position[vs[j]->id]);
        for (std::size_t j = k; j < vs.size(); ++j)
            second_box.expand(m.va.position[vs[j]->id]);
        m.unfile_constraint(current);
        m.constraints[current].bounds = first_box;
        m.file_constraint(current);
        m.constraints[nid] = {second, m.constraints[current].generation, true, second_box};
        m.file_constraint(nid);
        m.constraint_of_cgal[second.vl_ptr()] = nid;
        m.note_constraint(nid);
        if (inside[run_start]) doomed.push_back(current);
        current = nid;
        run_start = k;
    }
}

}  // namespace

std::size_t Tin::release_constraints(const ReleaseFilter& filter, VolumePolicy policy,
                                     EditReport* report, std::vector<VertexId>* released_vertices) {
    Impl& m = *impl_;
    std::vector<std::uint32_t> doomed;
    const Rect touch_box = bounding_box(filter.touching_polygon);
    const Rect inside_box = bounding_box(filter.inside_polygon);
    // Ids alive before this call: pieces split off below get new ids (possibly recycled ones)
    // and must not be visited again.
    // A spatial filter only needs the constraints whose bounds meet its polygon's box (with
    // both polygons, both must hold: the inside box picks the candidates, the touching box is
    // tested below); otherwise every live constraint is a candidate.
    std::vector<std::uint32_t> candidates;
    if (!filter.inside_polygon.empty() || !filter.touching_polygon.empty()) {
        candidates =
            m.constraints_meeting_box(filter.inside_polygon.empty() ? touch_box : inside_box);
    } else {
        for (std::uint32_t id = 0; id < m.constraints.size(); ++id) {
            if (m.constraints[id].alive) candidates.push_back(id);
        }
    }
    for (const std::uint32_t id : candidates) {
        const detail::ConstraintEntry& e = m.constraints[id];
        if (filter.generation && e.generation != *filter.generation) continue;
        if (filter.older_than && e.generation >= *filter.older_than) continue;
        if (!filter.touching_polygon.empty()) {
            if (!e.bounds.intersects(touch_box)) continue;
            bool touches = false;
            std::uint32_t previous = kNoId;
            for (const Vh v : m.cdt.vertices_in_constraint(e.cgal_id)) {
                if (previous != kNoId &&
                    segment_touches_polygon(m.va.position[previous], m.va.position[v->id],
                                            filter.touching_polygon)) {
                    touches = true;
                    break;
                }
                previous = v->id;
            }
            if (!touches) continue;
        }
        if (filter.only_if_delaunay && !constraint_is_delaunay(m, e)) continue;
        if (filter.inside_polygon.empty()) {
            doomed.push_back(id);
            continue;
        }
        doom_inside_pieces(m, id, filter.inside_polygon, doomed);
    }
    return release_doomed(m, doomed, policy, report, released_vertices);
}

std::size_t Tin::expire_constraints(Generation older_than, VolumePolicy policy, EditReport* report,
                                    std::vector<VertexId>* released_vertices) {
    Impl& m = *impl_;
    std::vector<std::uint32_t> doomed;
    std::vector<Impl::Expiry> later;
    while (!m.expiry.empty() && m.expiry.top().due < older_than) {
        const Impl::Expiry next = m.expiry.top();
        m.expiry.pop();
        if (next.id >= m.constraints.size()) continue;
        const detail::ConstraintEntry& e = m.constraints[next.id];
        if (!e.alive || e.generation != next.generation) continue;  // stale entry
        if (constraint_is_delaunay(m, e)) {
            doomed.push_back(next.id);
        } else {
            // Its neighbourhood may relax later (a stroke re-working it): look again after a
            // wait that doubles, so a constraint that never qualifies costs O(log n) looks.
            later.push_back({older_than + next.wait, next.generation,
                             std::min<Generation>(2 * next.wait, Generation{1} << 40), next.id});
        }
    }
    for (const Impl::Expiry& x : later)
        m.expiry.push(x);
    std::sort(doomed.begin(), doomed.end());
    doomed.erase(std::unique(doomed.begin(), doomed.end()), doomed.end());
    return release_doomed(m, doomed, policy, report, released_vertices);
}

bool Tin::release_constraint(ConstraintId id, VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    if (!id.valid() || id.value >= m.constraints.size() || !m.constraints[id.value].alive) {
        return false;
    }
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    detail::ConstraintEntry& e = m.constraints[id.value];
    m.constraint_of_cgal.erase(e.cgal_id.vl_ptr());
    m.cdt.remove_constraint(e.cgal_id);
    m.unfile_constraint(id.value);
    e = {};
    m.constraint_ids.release(id.value);
    finisher.finish(policy, {}, report);
    return true;
}

}  // namespace sandtin
