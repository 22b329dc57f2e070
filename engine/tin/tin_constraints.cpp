// Tin: constraints and their registry. A constrained polyline that crosses older constraints
// splits them at new vertices, which take the height of the constraint they split.

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/edit_finisher.hpp"
#include "tin/detail/impl_helpers.hpp"

namespace sandtin {

using detail::CdtPlus, detail::EditFinisher, detail::kNoId, detail::require;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

namespace {

/// Gives the vertices CGAL created at constraint crossings the height of the constraint they
/// split: linear along it between the nearest vertices of known height. Constraints other than
/// `inserted` are preferred, because they were already part of the surface.
void interpolate_crossing_heights(Tin::Impl& m, detail::CgalConstraintId inserted) {
    for (std::uint32_t id : m.events.born_vertices) {
        if (m.events.vertex_of_id[id] == nullptr || std::isfinite(m.va.height[id])) continue;
        const Vh x = m.handle(id);
        double best_height = std::numeric_limits<double>::quiet_NaN();
        bool best_is_old = false;
        std::array<std::uint32_t, 2> best_sources{};
        std::array<double, 2> best_weights{};
        auto ec = m.cdt.incident_edges(x);
        const auto done = ec;
        do {
            if (!m.cdt.is_constrained(*ec)) continue;
            const Fh f = ec->first;
            const int i = ec->second;
            const Vh a = f->vertex(CdtPlus::cw(i));
            const Vh b = f->vertex(CdtPlus::ccw(i));
            const Vh y = a == x ? b : a;
            for (auto ctx : m.cdt.contexts(x, y)) {
                const bool is_old = ctx.id() != inserted;
                if (std::isfinite(best_height) && (best_is_old || !is_old)) continue;
                // Walk to known heights on both sides of x along this constraint.
                auto here = ctx.current();
                if (*here != x) {
                    // current() names the subconstraint's first vertex, which may be y.
                    auto next = here;
                    ++next;
                    if (next != ctx.vertices_end() && *next == x) here = next;
                }
                if (*here != x) continue;
                auto back = here;
                std::uint32_t lo = kNoId;
                while (back != ctx.vertices_begin()) {
                    --back;
                    if (std::isfinite(m.va.height[(*back)->id])) {
                        lo = (*back)->id;
                        break;
                    }
                }
                auto fwd = here;
                std::uint32_t hi = kNoId;
                for (++fwd; fwd != ctx.vertices_end(); ++fwd) {
                    if (std::isfinite(m.va.height[(*fwd)->id])) {
                        hi = (*fwd)->id;
                        break;
                    }
                }
                if (lo == kNoId || hi == kNoId) continue;
                const Vec2 px = m.va.position[id];
                const double da = distance(px, m.va.position[lo]);
                const double db = distance(px, m.va.position[hi]);
                const double t = da + db > 0.0 ? da / (da + db) : 0.5;
                best_height = (1.0 - t) * m.va.height[lo] + t * m.va.height[hi];
                best_is_old = is_old;
                best_sources = {lo, hi};
                best_weights = {1.0 - t, t};
            }
        } while (++ec != done);
        if (std::isfinite(best_height)) {
            m.va.height[id] = best_height;
            EditFinisher(m).inherit(id, best_sources, best_weights);
        }
    }
}

/// Where nearly coincident constraints are crossed, CGAL can make crossing vertices a rounding
/// error from each other or from an old vertex. They cannot be merged inside CGAL's insertion,
/// but each such cluster can share one height (an old member's, when it has one), so the
/// slivers between them carry no spike.
void level_crossing_clusters(Tin::Impl& m) {
    std::vector<Vh> cluster;
    for (std::uint32_t id : m.events.born_vertices) {
        if (m.events.vertex_of_id[id] == nullptr) continue;
        cluster.assign(1, m.handle(id));
        for (std::size_t k = 0; k < cluster.size() && cluster.size() < 16; ++k) {
            auto vc = m.cdt.incident_vertices(cluster[k]);
            const auto done = vc;
            do {
                if (m.cdt.is_infinite(vc)) continue;
                const Vh w = vc;
                if (std::find(cluster.begin(), cluster.end(), w) != cluster.end()) continue;
                if (distance(m.va.position[w->id], m.va.position[cluster[k]->id]) <=
                    m.snap_distance) {
                    cluster.push_back(w);
                }
            } while (++vc != done);
        }
        if (cluster.size() < 2) continue;
        double reference = m.va.height[id];
        for (const Vh w : cluster) {
            const bool born =
                std::find(m.events.born_vertices.begin(), m.events.born_vertices.end(), w->id) !=
                m.events.born_vertices.end();
            if (!born && std::isfinite(m.va.height[w->id])) {
                reference = m.va.height[w->id];
                break;
            }
        }
        for (const Vh w : cluster) {
            const bool born =
                std::find(m.events.born_vertices.begin(), m.events.born_vertices.end(), w->id) !=
                m.events.born_vertices.end();
            if (born) m.va.height[w->id] = reference;
        }
    }
}

/// The heights of the vertices CGAL created while constraining `inserted`.
void resolve_crossing_heights(Tin::Impl& m, detail::CgalConstraintId inserted) {
    interpolate_crossing_heights(m, inserted);
    level_crossing_clusters(m);
}

/// Constrains one polyline inside an edit (no finish) and registers it.
ConstraintId constrain_one(Tin::Impl& m, std::span<const VertexId> polyline, bool closed,
                           Generation generation) {
    if (polyline.size() == 2 && !closed) {
        // CGAL would add a second, overlapping constraint: refresh the existing one instead.
        const Vh a = m.handle(polyline[0]);
        const Vh b = m.handle(polyline[1]);
        if (m.cdt.is_subconstraint(a, b)) {
            for (auto ctx : m.cdt.contexts(a, b)) {
                if (ctx.number_of_vertices() != 2) continue;
                const auto it = m.constraint_of_cgal.find(ctx.id().vl_ptr());
                if (it == m.constraint_of_cgal.end()) continue;
                auto& entry = m.constraints[it->second];
                if (generation > entry.generation) {
                    entry.generation = generation;
                    m.note_constraint(it->second);
                }
                return ConstraintId{it->second};
            }
        }
    }
    std::vector<Vh> handles;
    handles.reserve(polyline.size() + 1);
    for (VertexId v : polyline)
        handles.push_back(m.handle(v));
    if (closed && polyline.front() != polyline.back()) handles.push_back(handles.front());
    const detail::CgalConstraintId cid = m.cdt.insert_polyline(handles);
    EditFinisher(m).prepare_born();
    const std::uint32_t id = m.constraint_ids.allocate();
    if (id >= m.constraints.size()) m.constraints.resize(static_cast<std::size_t>(id) + 1);
    Rect bounds;
    for (VertexId v : polyline)
        bounds.expand(m.va.position[v.value]);
    m.constraints[id] = {cid, generation, true, bounds};
    m.file_constraint(id);
    m.constraint_of_cgal[cid.vl_ptr()] = id;
    m.note_constraint(id);
    resolve_crossing_heights(m, cid);
    return ConstraintId{id};
}

}  // namespace

ConstraintId Tin::insert_constraint(VertexId a, VertexId b, Generation generation,
                                    VolumePolicy policy, EditReport* report) {
    const std::array<VertexId, 2> polyline = {a, b};
    return insert_constraint(polyline, false, generation, policy, report);
}

ConstraintId Tin::insert_constraint(std::span<const VertexId> polyline, bool closed,
                                    Generation generation, VolumePolicy policy,
                                    EditReport* report) {
    Impl& m = *impl_;
    require(polyline.size() >= 2, "insert_constraint: a constraint needs at least two vertices");
    for (VertexId v : polyline) {
        if (!is_alive(v)) {
            throw std::invalid_argument("insert_constraint: vertex id " + std::to_string(v.value) +
                                        " is not alive");
        }
    }
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        require(polyline[i] != polyline[i + 1],
                "insert_constraint: consecutive vertices are the same (zero-length segment)");
    }
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    const ConstraintId result = constrain_one(m, polyline, closed, generation);
    finisher.finish(policy, {}, report);
    return result;
}

std::vector<ConstraintId> Tin::insert_constraints(std::span<const std::array<VertexId, 2>> segments,
                                                  Generation generation, VolumePolicy policy,
                                                  EditReport* report) {
    Impl& m = *impl_;
    for (const auto& s : segments) {
        for (VertexId v : s) {
            if (!is_alive(v)) {
                throw std::invalid_argument("insert_constraints: vertex id " +
                                            std::to_string(v.value) + " is not alive");
            }
        }
    }
    std::vector<ConstraintId> ids;
    ids.reserve(segments.size());
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    for (const auto& s : segments) {
        // An earlier segment may have killed nothing, but a crossing can never remove a vertex;
        // still, stay defensive about ids that died inside this edit.
        if (s[0] == s[1] || !m.alive(s[0]) || !m.alive(s[1])) {
            ids.push_back(ConstraintId{});
            continue;
        }
        ids.push_back(constrain_one(m, s, false, generation));
    }
    finisher.finish(policy, {}, report);
    return ids;
}

// ---- The registry -------------------------------------------------------------------------

std::optional<ConstraintInfo> Tin::constraint(ConstraintId id) const {
    const Impl& m = *impl_;
    if (!id.valid() || id.value >= m.constraints.size() || !m.constraints[id.value].alive) {
        return std::nullopt;
    }
    const detail::ConstraintEntry& e = m.constraints[id.value];
    ConstraintInfo info;
    info.id = id;
    info.generation = e.generation;
    for (Vh v : m.cdt.vertices_in_constraint(e.cgal_id))
        info.vertices.push_back(VertexId{v->id});
    return info;
}

std::vector<std::array<Vec2, 2>> Tin::constrained_segments(const Rect& box,
                                                           Generation older_than) const {
    const Impl& m = *impl_;
    std::vector<std::array<Vec2, 2>> out;
    for (const std::uint32_t id : m.constraints_meeting_box(box)) {
        const detail::ConstraintEntry& e = m.constraints[id];
        if (e.generation >= older_than) continue;
        std::uint32_t previous = kNoId;
        for (const Vh v : m.cdt.vertices_in_constraint(e.cgal_id)) {
            if (previous != kNoId) out.push_back({m.va.position[previous], m.va.position[v->id]});
            previous = v->id;
        }
    }
    return out;
}

std::optional<Generation> Tin::newest_constraint_generation() const {
    std::optional<Generation> newest;
    for (const detail::ConstraintEntry& e : impl_->constraints) {
        if (e.alive && (!newest || e.generation > *newest)) newest = e.generation;
    }
    return newest;
}

std::vector<ConstraintInfo> Tin::constraints() const {
    std::vector<ConstraintInfo> out;
    for (std::uint32_t i = 0; i < impl_->constraints.size(); ++i) {
        if (auto c = constraint(ConstraintId{i})) out.push_back(std::move(*c));
    }
    return out;
}

}  // namespace sandtin
