// Tin: queries. Counts, point location and heights, a vertex's star, the volume, and the
// vertices and edges a region of the plane meets (walks over faces, tin/detail/walks.hpp).

#include <algorithm>
#include <cmath>
#include <limits>

#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "tin/detail/walks.hpp"
#include "util/compensated_sum.hpp"
#include "util/prepare_for_writing.hpp"
#include "util/visit_marks.hpp"

namespace sandtin {

using detail::CdtPlus, detail::face_at, detail::finite_location, detail::FiniteLocation,
    detail::require, detail::SlotRecord, detail::start_face, detail::to_point, detail::update_hint,
    detail::walk_faces, detail::walk_faces_along, detail::walk_to;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

Rect Tin::domain() const {
    return impl_->domain;
}
std::size_t Tin::vertex_count() const {
    return impl_->events.vertex_ids.live();
}
std::size_t Tin::triangle_count() const {
    return impl_->live_triangles;
}
std::size_t Tin::constrained_edge_count() const {
    // number_of_subconstraints() only reads a map size but is not declared const.
    return const_cast<CdtPlus&>(impl_->cdt).number_of_subconstraints();
}
std::size_t Tin::constraint_count() const {
    return impl_->constraint_ids.live();
}
std::uint32_t Tin::vertex_capacity() const {
    return impl_->events.vertex_ids.capacity();
}
std::uint32_t Tin::slot_capacity() const {
    return impl_->events.slots.capacity();
}
bool Tin::is_alive(VertexId v) const {
    return impl_->alive(v);
}
const VertexArrays& Tin::vertices() const {
    return impl_->va;
}

Vec2 Tin::position(VertexId v) const {
    require(is_alive(v), "position: vertex id is not alive");
    return impl_->va.position[v.value];
}

double Tin::height(VertexId v) const {
    require(is_alive(v), "height: vertex id is not alive");
    return impl_->va.height[v.value];
}

std::array<VertexId, 3> Tin::slot_triangle(TriangleSlot slot) const {
    if (slot >= impl_->slot_cache.size()) return {};
    const SlotRecord& r = impl_->slot_cache[slot];
    if (!r.finite()) return {};
    return {VertexId{r.corners[0]}, VertexId{r.corners[1]}, VertexId{r.corners[2]}};
}

std::uint8_t Tin::slot_constraint_mask(TriangleSlot slot) const {
    if (slot >= impl_->slot_cache.size()) return 0;
    return impl_->slot_cache[slot].constraint_mask;
}

std::vector<std::array<VertexId, 3>> Tin::triangles() const {
    std::vector<std::array<VertexId, 3>> out;
    out.reserve(impl_->live_triangles);
    for (const SlotRecord& r : impl_->slot_cache) {
        if (r.finite()) {
            out.push_back({VertexId{r.corners[0]}, VertexId{r.corners[1]}, VertexId{r.corners[2]}});
        }
    }
    return out;
}

Location Tin::locate(Vec2 p, LocateHint* hint) const {
    Location out;
    const Impl& m = *impl_;
    if (!is_finite(p) || !m.domain.contains(p)) return out;
    CdtPlus::Locate_type lt;
    const std::optional<FiniteLocation> found = walk_to(m, p, start_face(m, p, hint), lt);
    if (!found) return out;
    const FiniteLocation& loc = *found;
    out.kind = lt == CdtPlus::VERTEX ? Location::Kind::OnVertex
               : lt == CdtPlus::EDGE ? Location::Kind::OnEdge
                                     : Location::Kind::InTriangle;
    out.slot = loc.face->slot;
    for (std::size_t i = 0; i < 3; ++i) {
        out.corners[i] = VertexId{loc.corners[i]};
        out.barycentric[i] = loc.weights[i];
    }
    update_hint(hint, loc);
    return out;
}

namespace {

/// True when p lies strictly inside finite face f (exact predicates): then f is the face any
/// walk would locate p in.
bool strictly_inside(const Tin::Impl& m, Fh f, const detail::Point& p) {
    if (m.cdt.is_infinite(f)) return false;
    const auto orientation = detail::Kernel().orientation_2_object();
    for (int i = 0; i < 3; ++i) {
        if (orientation(f->vertex(CdtPlus::ccw(i))->point(), f->vertex(CdtPlus::cw(i))->point(),
                        p) != CGAL::LEFT_TURN) {
            return false;
        }
    }
    return true;
}

double interpolate(const Tin::Impl& m, const FiniteLocation& loc) {
    return loc.weights[0] * m.va.height[loc.corners[0]] +
           loc.weights[1] * m.va.height[loc.corners[1]] +
           loc.weights[2] * m.va.height[loc.corners[2]];
}

}  // namespace

void Tin::heights_at(std::span<const Vec2> points, std::span<double> out, LocateHint* hint,
                     std::span<std::array<VertexId, 3>> corners) const {
    require(points.size() == out.size(), "heights_at: one output per point");
    require(corners.empty() || corners.size() == points.size(),
            "heights_at: one corner triple per point, or none");
    const auto record = [&](std::size_t k, const FiniteLocation& loc) {
        if (corners.empty()) return;
        for (std::size_t i = 0; i < 3; ++i)
            corners[k][i] = VertexId{loc.corners[i]};
    };
    const Impl& m = *impl_;
    Fh last;  // the finite face of the point before, if any
    for (std::size_t k = 0; k < points.size(); ++k) {
        const Vec2 p = points[k];
        out[k] = std::numeric_limits<double>::quiet_NaN();
        if (!corners.empty()) corners[k] = {};
        if (!is_finite(p) || !m.domain.contains(p)) continue;
        const detail::Point cp = to_point(p);
        Fh f;
        if (last != Fh()) {
            if (strictly_inside(m, last, cp)) {
                f = last;
            } else {
                for (int i = 0; i < 3 && f == Fh(); ++i) {
                    if (strictly_inside(m, last->neighbor(i), cp)) f = last->neighbor(i);
                }
            }
        }
        if (f != Fh()) {
            // The face locate() would return, with the same weights: the same height.
            const FiniteLocation loc = finite_location(m, p, CdtPlus::FACE, f, 0);
            out[k] = interpolate(m, loc);
            record(k, loc);
            last = f;
            continue;
        }
        CdtPlus::Locate_type lt;
        const std::optional<FiniteLocation> found = walk_to(m, p, start_face(m, p, hint), lt);
        if (!found) continue;
        out[k] = interpolate(m, *found);
        record(k, *found);
        update_hint(hint, *found);
        last = found->face;
    }
}

std::optional<double> Tin::height_at(Vec2 p, LocateHint* hint) const {
    double h = 0.0;
    heights_at(std::span<const Vec2>(&p, 1), std::span<double>(&h, 1), hint);
    if (std::isnan(h)) return std::nullopt;
    return h;
}

void Tin::neighbours(VertexId v, std::vector<VertexId>& out) const {
    out.clear();
    require(is_alive(v), "neighbours: vertex id is not alive");
    const Impl& m = *impl_;
    auto vc = m.cdt.incident_vertices(m.handle(v));
    const auto done = vc;
    do {
        if (!m.cdt.is_infinite(vc)) out.push_back(VertexId{vc->id});
    } while (++vc != done);
}

Tin::VertexStar Tin::star(VertexId v, std::vector<VertexId>& out) const {
    out.clear();
    require(is_alive(v), "star: vertex id is not alive");
    const Impl& m = *impl_;
    const Vh vh = m.handle(v);
    VertexStar result;
    auto fc = m.cdt.incident_faces(vh);
    const auto done = fc;
    do {
        const int j = fc->index(vh);
        const Vh w = fc->vertex(CdtPlus::ccw(j));
        // The edge v-w is opposite the third corner; each edge is seen once, from the face
        // where w follows v counter-clockwise.
        if (fc->is_constrained(CdtPlus::cw(j))) result.constrained = true;
        if (m.cdt.is_infinite(w)) {
            result.boundary = true;
        } else {
            out.push_back(VertexId{w->id});
        }
    } while (++fc != done);
    return result;
}

bool Tin::is_boundary(VertexId v) const {
    require(is_alive(v), "is_boundary: vertex id is not alive");
    const Impl& m = *impl_;
    auto vc = m.cdt.incident_vertices(m.handle(v));
    const auto done = vc;
    do {
        if (m.cdt.is_infinite(vc)) return true;
    } while (++vc != done);
    return false;
}

bool Tin::is_on_constraint(VertexId v) const {
    require(is_alive(v), "is_on_constraint: vertex id is not alive");
    return impl_->cdt.are_there_incident_constraints(impl_->handle(v));
}

bool Tin::is_constrained_edge(VertexId a, VertexId b) const {
    if (!is_alive(a) || !is_alive(b)) return false;
    Fh f;
    int i = 0;
    if (!impl_->cdt.is_edge(impl_->handle(a), impl_->handle(b), f, i)) return false;
    return f->is_constrained(i);
}

double Tin::volume(double datum) const {
    const VertexArrays& va = impl_->va;
    CompensatedSum sum;
    for (std::size_t id = 0; id < va.size(); ++id) {
        if (va.alive[id]) sum.add(va.lumped_area[id] * (va.height[id] - datum));
    }
    return sum.value();
}

double Tin::volume_ledger() const {
    return impl_->volume_ledger.value();
}

namespace {

bool triangle_meets_disc(Vec2 a, Vec2 b, Vec2 c, Vec2 centre, double radius) {
    // Most faces of a walk have a corner in the disc; only those along its edge need the rest.
    const double r2 = radius * radius;
    if (length_squared(a - centre) <= r2 || length_squared(b - centre) <= r2 ||
        length_squared(c - centre) <= r2) {
        return true;
    }
    const double d1 = cross(b - a, centre - a);
    const double d2 = cross(c - b, centre - b);
    const double d3 = cross(a - c, centre - c);
    if (d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) return true;
    return distance_to_segment(centre, a, b) <= radius ||
           distance_to_segment(centre, b, c) <= radius ||
           distance_to_segment(centre, c, a) <= radius;
}

bool face_meets_disc(const Tin::Impl& m, Fh f, Vec2 centre, double radius) {
    return triangle_meets_disc(m.va.position[f->vertex(0)->id], m.va.position[f->vertex(1)->id],
                               m.va.position[f->vertex(2)->id], centre, radius);
}

/// Calls visit(face) once for each finite face that meets the disc (constrained edges do not
/// stop the walk). The walk starts from the face under the centre clamped into the domain, so
/// discs overlapping the border still find their faces.
template <class Visit>
void walk_disc(const Tin::Impl& m, Vec2 centre, double radius, LocateHint* hint, Visit&& visit) {
    const Vec2 start{std::clamp(centre.x, m.domain.min.x, m.domain.max.x),
                     std::clamp(centre.y, m.domain.min.y, m.domain.max.y)};
    if (distance(start, centre) > radius) return;
    const Fh f = face_at(m, start, hint);
    if (f == Fh()) return;
    const std::array<Fh, 1> starts = {f};
    walk_faces(
        m, starts, [&](Fh g) { return face_meets_disc(m, g, centre, radius); },
        [](Fh, int) { return true; }, visit);
}

}  // namespace

std::vector<VertexId> Tin::vertices_in_disc(Vec2 centre, double radius, LocateHint* hint) const {
    const Impl& m = *impl_;
    std::vector<VertexId> out;
    if (!is_finite(centre) || !(radius >= 0.0)) return out;
    const double r2 = radius * radius;
    static thread_local VisitMarks taken;
    taken.clear();
    taken.reserve_ids(m.events.vertex_of_id.size());
    walk_disc(m, centre, radius, hint, [&](Fh g) {
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t id = g->vertex(i)->id;
            if (!taken.contains(id) && length_squared(m.va.position[id] - centre) <= r2) {
                taken.mark(id);
                out.push_back(VertexId{id});
            }
        }
    });
    return out;
}

std::vector<VertexId> Tin::vertices_in_polygon(const PolygonInclusion& region,
                                               LocateHint* hint) const {
    const Impl& m = *impl_;
    std::vector<VertexId> out;
    const std::span<const Vec2> polygon = region.polygon();
    if (polygon.size() < 3) return out;
    // Start at up to four of the polygon's own vertices that lie in the domain: the face under
    // a border point meets the region.
    std::vector<Fh> starts;
    const std::size_t step = std::max<std::size_t>(polygon.size() / 4, 1);
    for (std::size_t i = 0; i < polygon.size(); i += step) {
        if (!is_finite(polygon[i]) || !m.domain.contains(polygon[i])) continue;
        const Fh f = face_at(m, polygon[i], hint);
        if (f != Fh()) starts.push_back(f);
    }
    if (starts.empty()) {
        // No vertex in the domain (a polygon around or across it): test every vertex.
        for (auto v = m.cdt.finite_vertices_begin(); v != m.cdt.finite_vertices_end(); ++v) {
            if (region.contains(m.va.position[v->id])) out.push_back(VertexId{v->id});
        }
        return out;
    }
    // Each vertex's answer once: a walk meets a vertex from each of its faces, and a face's
    // test asks about its three corners.
    static thread_local VisitMarks decided;
    static thread_local std::vector<std::uint8_t> inside;
    decided.clear();
    decided.reserve_ids(m.events.vertex_of_id.size());
    grow_zero_filled(inside, m.events.vertex_of_id.size());
    const auto is_inside = [&](std::uint32_t id) {
        if (!decided.contains(id)) {
            decided.mark(id);
            const bool in = region.contains(m.va.position[id]);
            inside[id] = in ? 1 : 0;
            if (in) out.push_back(VertexId{id});
        }
        return inside[id] != 0;
    };
    walk_faces(
        m, starts,
        [&](Fh g) {
            const std::uint32_t a = g->vertex(0)->id, b = g->vertex(1)->id, c = g->vertex(2)->id;
            // Every corner decided (and each inside one collected) before the border test.
            const bool in_a = is_inside(a);
            const bool in_b = is_inside(b);
            const bool in_c = is_inside(c);
            return in_a || in_b || in_c ||
                   region.border_meets_triangle(m.va.position[a], m.va.position[b],
                                                m.va.position[c]);
        },
        [](Fh, int) { return true; }, [](Fh) {});
    return out;
}

std::vector<VertexId> Tin::vertices_in_region(std::span<const Vec2> seeds,
                                              std::span<const Vec2> bound, LocateHint* hint) const {
    const Impl& m = *impl_;
    std::vector<VertexId> out;
    std::vector<Fh> starts;
    for (Vec2 s : seeds) {
        if (!is_finite(s) || !m.domain.contains(s)) continue;
        const Fh f = face_at(m, s, hint);
        if (f != Fh()) starts.push_back(f);
    }
    // Seen from the first seed: the walk tests a centroid per face, and a tool's subdivided
    // contour has hundreds of edges (PolygonInclusion gives point_in_polygon's answers).
    const PolygonInclusion inside(bound, seeds.empty() ? Vec2{} : seeds.front());
    auto centroid_inside = [&](Fh g) {
        const Vec2 c = (m.va.position[g->vertex(0)->id] + m.va.position[g->vertex(1)->id] +
                        m.va.position[g->vertex(2)->id]) /
                       3.0;
        return inside.contains(c);
    };
    static thread_local VisitMarks taken;
    taken.clear();
    taken.reserve_ids(m.events.vertex_of_id.size());
    walk_faces(
        m, starts, centroid_inside, [](Fh g, int i) { return !g->is_constrained(i); },
        [&](Fh g) {
            for (int i = 0; i < 3; ++i) {
                const std::uint32_t id = g->vertex(i)->id;
                if (!taken.contains(id)) {
                    taken.mark(id);
                    out.push_back(VertexId{id});
                }
            }
        });
    return out;
}

std::vector<std::pair<double, double>> Tin::section(Vec2 a, Vec2 b, LocateHint* hint) const {
    const Impl& m = *impl_;
    const Rect& d = m.domain;
    a = {std::clamp(a.x, d.min.x, d.max.x), std::clamp(a.y, d.min.y, d.max.y)};
    b = {std::clamp(b.x, d.min.x, d.max.x), std::clamp(b.y, d.min.y, d.max.y)};
    std::vector<std::pair<double, double>> out;
    if (!is_finite(a) || !is_finite(b)) return out;
    out.emplace_back(0.0, height_at(a, hint).value_or(0.0));
    if (a == b) return out;
    std::vector<std::pair<double, double>> crossings;
    const Vec2 ab = b - a;
    walk_faces_along(m, a, b, hint, [&](Fh f) {
        double t_exit = 0.0;
        bool contains_b = true;
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t iu = f->vertex(CdtPlus::ccw(i))->id;
            const std::uint32_t iw = f->vertex(CdtPlus::cw(i))->id;
            const Vec2 u = m.va.position[iu];
            const Vec2 w = m.va.position[iw];
            if (cross(w - u, b - u) < 0.0) contains_b = false;
            const double denom = cross(ab, w - u);
            if (denom == 0.0) continue;  // parallel: the crossings are at its ends
            const double t = cross(u - a, w - u) / denom;
            const double sp = cross(u - a, ab) / denom;
            if (sp < -1e-12 || sp > 1.0 + 1e-12) continue;
            t_exit = std::max(t_exit, t);
            if (t > 0.0 && t < 1.0) {
                const double c = std::clamp(sp, 0.0, 1.0);
                crossings.emplace_back(t, (1.0 - c) * m.va.height[iu] + c * m.va.height[iw]);
            }
        }
        return contains_b || t_exit >= 1.0;
    });
    std::sort(crossings.begin(), crossings.end());
    for (const auto& c : crossings) {
        // Each interior edge is met from both of its faces.
        if (c.first - out.back().first > 1e-12) out.push_back(c);
    }
    const double hb = height_at(b, hint).value_or(out.back().second);
    if (1.0 - out.back().first <= 1e-12 && out.size() > 1) out.pop_back();
    out.emplace_back(1.0, hb);
    return out;
}

std::vector<std::array<VertexId, 2>> Tin::edges_longer_than(Vec2 centre, double radius,
                                                            double max_length,
                                                            LocateHint* hint) const {
    const Impl& m = *impl_;
    std::vector<std::array<VertexId, 2>> out;
    if (!is_finite(centre) || !(radius >= 0.0) || !(max_length > 0.0)) return out;
    const double l2 = max_length * max_length;
    walk_disc(m, centre, radius, hint, [&](Fh g) {
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = g->vertex(CdtPlus::ccw(i))->id;
            const std::uint32_t b = g->vertex(CdtPlus::cw(i))->id;
            // Each interior edge is seen from both faces; report it from the face whose slot is
            // smaller (or from its only finite face).
            const Fh n = g->neighbor(i);
            if (!m.cdt.is_infinite(n) && n->slot < g->slot && face_meets_disc(m, n, centre, radius))
                continue;
            if (length_squared(m.va.position[a] - m.va.position[b]) > l2) {
                out.push_back({VertexId{a}, VertexId{b}});
            }
        }
    });
    return out;
}

}  // namespace sandtin
