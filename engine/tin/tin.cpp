// Tin: construction, queries and edits over CGAL's constrained Delaunay triangulation.
// See tin/detail/cgal_tin.hpp for how CGAL object lifetimes feed the change journal.

#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "geom/plane_fit.hpp"
#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/edit_finisher.hpp"
#include "tin/detail/hole_triangulation.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "tin/detail/walks.hpp"
#include "util/compensated_sum.hpp"
#include "util/visit_marks.hpp"

namespace sandtin {

using detail::CdtPlus;
using detail::describe;
using detail::EditFinisher;
using detail::face_at;
using detail::finite_location;
using detail::FiniteLocation;
using detail::kNoId;
using detail::near_line;
using detail::NoEventScope;
using detail::require;
using detail::require_inside;
using detail::SlotRecord;
using detail::start_face;
using detail::to_point;
using detail::triangle_area;
using detail::update_hint;
using detail::walk_faces;
using detail::walk_faces_along;
using detail::walk_to;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

std::string ValidationReport::summary() const {
    std::string s;
    for (const std::string& p : problems) {
        s += p;
        s += '\n';
    }
    return s;
}

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
        // Classify the pieces, then split the constraint between runs inside and outside.
        std::vector<Vh> vs;
        for (const Vh v : m.cdt.vertices_in_constraint(e.cgal_id))
            vs.push_back(v);
        std::vector<std::uint8_t> inside(vs.size() - 1);
        bool any_in = false;
        bool any_out = false;
        for (std::size_t k = 0; k + 1 < vs.size(); ++k) {
            const Vec2 mid = (m.va.position[vs[k]->id] + m.va.position[vs[k + 1]->id]) * 0.5;
            // A piece along the border counts as inside (a box stroked along a side puts its
            // rim on the line of the rim before): kept, it would run a hair beside the new
            // border's constraint, and between the two only triangles without area would fit.
            inside[k] = point_in_polygon(mid, filter.inside_polygon) ||
                                nearest_edge(mid, filter.inside_polygon).distance <= m.snap_distance
                            ? 1
                            : 0;
            (inside[k] ? any_in : any_out) = true;
        }
        if (!any_in) continue;
        if (!any_out) {
            doomed.push_back(id);
            continue;
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
            if (nid >= m.constraints.size())
                m.constraints.resize(static_cast<std::size_t>(nid) + 1);
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

// ---- Attributes ---------------------------------------------------------------------------

namespace {

template <class T>
void set_attribute(Tin::Impl& m, VertexId v, std::vector<T>& array, T value, const char* what) {
    if (!m.alive(v)) {
        throw std::invalid_argument(std::string(what) + ": vertex id " + std::to_string(v.value) +
                                    " is not alive");
    }
    if (array[v.value] == value) return;
    array[v.value] = value;
    m.note_attribute(v.value);
}

}  // namespace

void Tin::set_height(VertexId v, double height) {
    require(std::isfinite(height), "set_height: height is not finite");
    Impl& m = *impl_;
    const double before = m.alive(v) ? m.va.height[v.value] : 0.0;
    set_attribute(m, v, m.va.height, height, "set_height");
    m.volume_ledger.add(m.va.lumped_area[v.value] * (height - before));
    if (m.va.bedrock[v.value] > height) set_attribute(m, v, m.va.bedrock, height, "set_height");
}

void Tin::set_bedrock(VertexId v, double bedrock) {
    require(std::isfinite(bedrock), "set_bedrock: bedrock is not finite");
    if (is_alive(v) && bedrock > impl_->va.height[v.value]) {
        throw std::invalid_argument("set_bedrock: bedrock " + std::to_string(bedrock) +
                                    " m would lie above the surface at " +
                                    std::to_string(impl_->va.height[v.value]) + " m");
    }
    set_attribute(*impl_, v, impl_->va.bedrock, bedrock, "set_bedrock");
}

void Tin::set_material(VertexId v, std::uint16_t material) {
    set_attribute(*impl_, v, impl_->va.material, material, "set_material");
}

void Tin::set_moisture(VertexId v, float moisture) {
    require(std::isfinite(moisture) && moisture >= 0.0f && moisture <= 1.0f,
            "set_moisture: moisture must lie in [0, 1]");
    set_attribute(*impl_, v, impl_->va.moisture, moisture, "set_moisture");
}

void Tin::set_slide(VertexId v, Vec2f slide) {
    require(std::isfinite(slide.x) && std::isfinite(slide.y), "set_slide: offset is not finite");
    set_attribute(*impl_, v, impl_->va.slide, slide, "set_slide");
}

// ---- Journal ------------------------------------------------------------------------------

ChangeSet Tin::take_changes() {
    Impl& m = *impl_;
    ChangeSet cs;
    cs.vertices = merge_into_ranges(m.journal_vertices.take());
    cs.triangles = merge_into_ranges(m.journal_slots.take());
    cs.vertex_capacity = m.events.vertex_ids.capacity();
    cs.slot_capacity = m.events.slots.capacity();
    cs.live_vertices = m.events.vertex_ids.live();
    cs.live_slots = m.live_triangles;
    cs.dead_slots = cs.slot_capacity - cs.live_slots;
    // The deaths are reported: their ids and slots may now be reused.
    m.events.vertex_ids.flush_deferred();
    m.events.slots.flush_deferred();
    return cs;
}

bool Tin::tracks_changes() const {
    return impl_->options.track_changes;
}

std::uint32_t Tin::subscribe_vertex_changes() {
    Impl& m = *impl_;
    for (std::uint32_t i = 0; i < m.feeds.size(); ++i) {
        if (!m.feeds[i].active) {
            m.feeds[i].active = true;
            return i;
        }
    }
    m.feeds.emplace_back();
    m.feeds.back().active = true;
    return static_cast<std::uint32_t>(m.feeds.size() - 1);
}

void Tin::unsubscribe_vertex_changes(std::uint32_t subscription) {
    Impl& m = *impl_;
    if (subscription >= m.feeds.size()) return;
    m.feeds[subscription].active = false;
    m.feeds[subscription].attributes.clear();
    m.feeds[subscription].topology.clear();
}

VertexChanges Tin::take_vertex_changes(std::uint32_t subscription) {
    Impl& m = *impl_;
    VertexChanges out;
    if (subscription >= m.feeds.size() || !m.feeds[subscription].active) return out;
    Impl::VertexFeed& f = m.feeds[subscription];
    for (std::uint32_t id : f.attributes.take())
        out.attributes.push_back(VertexId{id});
    for (std::uint32_t id : f.topology.take())
        out.topology.push_back(VertexId{id});
    return out;
}

void Tin::set_heights(std::span<const VertexId> vertices, std::span<const double> heights) {
    Impl& m = *impl_;
    require(vertices.size() == heights.size(),
            "set_heights: vertices and heights differ in length");
    VertexArrays& va = m.va;
    CompensatedSum change;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const std::uint32_t id = vertices[i].value;
        const double h = heights[i];
        if (!m.alive(vertices[i]) || !std::isfinite(h)) {
            throw std::invalid_argument("set_heights: dead vertex or non-finite height at entry " +
                                        std::to_string(i));
        }
        if (va.height[id] == h) continue;
        change.add(va.lumped_area[id] * (h - va.height[id]));
        va.height[id] = h;
        if (va.bedrock[id] > h) va.bedrock[id] = h;
        m.note_attribute(id);
    }
    m.volume_ledger.add(change.value());
}

}  // namespace sandtin
