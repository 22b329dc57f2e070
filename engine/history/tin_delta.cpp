// Applying a TinDelta through the Tin's public edits, in the order that keeps every step legal:
// constraints of the source state go first (a vertex on a constraint cannot be removed), then
// vertices that must disappear, then vertices that must appear, then attributes, and the
// target's constraints last, when all their vertices exist.

#include "history/tin_delta.hpp"

#include "tin/bulk_removal.hpp"

#include <algorithm>
#include <map>
#include <span>
#include <stdexcept>
#include <utility>

namespace sandtin {

std::size_t TinDelta::bytes() const {
    std::size_t total = vertices.capacity() * sizeof(VertexChange);
    for (const auto* list : {&constraints_before, &constraints_after}) {
        total += list->capacity() * sizeof(ConstraintPolyline);
        for (const ConstraintPolyline& c : *list)
            total += c.points.capacity() * sizeof(Vec2);
    }
    return total;
}

namespace {

/// The live vertex exactly at p, or an invalid id.
VertexId vertex_at(const Tin& tin, Vec2 p, LocateHint& hint) {
    const Location loc = tin.locate(p, &hint);
    if (loc.kind != Location::Kind::OnVertex) return kInvalidVertex;
    for (VertexId v : loc.corners) {
        if (v.valid() && tin.is_alive(v) && tin.position(v) == p) return v;
    }
    return kInvalidVertex;
}

/// Turns the TIN's snapping off for a scope.
class SnapOff {
  public:
    explicit SnapOff(Tin& tin) : tin_(tin), saved_(tin.snap_distance()) {
        tin.set_snap_distance(0.0);
    }
    ~SnapOff() { tin_.set_snap_distance(saved_); }
    SnapOff(const SnapOff&) = delete;
    SnapOff& operator=(const SnapOff&) = delete;

  private:
    Tin& tin_;
    double saved_;
};

/// Interleaves the bits of two 21-bit integers (a Morton / Z-order code).
std::uint64_t morton(std::uint32_t x, std::uint32_t y) {
    auto spread = [](std::uint64_t v) {
        v &= 0x1FFFFF;
        v = (v | v << 32) & 0x1F00000000FFFFull;
        v = (v | v << 16) & 0x1F0000FF0000FFull;
        v = (v | v << 8) & 0x100F00F00F00F00Full;
        v = (v | v << 4) & 0x10C30C30C30C30C3ull;
        v = (v | v << 2) & 0x1249249249249249ull;
        return v;
    };
    return spread(x) | spread(y) << 1;
}

/// Orders points along a Z-order curve over their bounding box. Delaunay insertion in such an
/// order walks a few steps per point and flips little; in the delta's lexicographic order it
/// builds long slivers first and costs several times more.
void sort_along_curve(std::vector<Vec2>& points, std::vector<double>& heights) {
    Rect box;
    for (Vec2 p : points)
        box.expand(p);
    const double sx = box.width() > 0.0 ? 2097151.0 / box.width() : 0.0;
    const double sy = box.height() > 0.0 ? 2097151.0 / box.height() : 0.0;
    std::vector<std::pair<std::uint64_t, std::size_t>> order(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto x = static_cast<std::uint32_t>((points[i].x - box.min.x) * sx);
        const auto y = static_cast<std::uint32_t>((points[i].y - box.min.y) * sy);
        order[i] = {morton(x, y), i};
    }
    std::sort(order.begin(), order.end());
    std::vector<Vec2> p2(points.size());
    std::vector<double> h2(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        p2[i] = points[order[i].second];
        h2[i] = heights[order[i].second];
    }
    points.swap(p2);
    heights.swap(h2);
}

using PolylineKey = std::pair<Generation, std::vector<std::pair<double, double>>>;

PolylineKey key_of(const ConstraintPolyline& c) {
    PolylineKey k{c.generation, {}};
    k.second.reserve(c.points.size());
    for (Vec2 p : c.points)
        k.second.emplace_back(p.x, p.y);
    return k;
}

void write_attributes(Tin& tin, VertexId v, const VertexRecord& r, ApplyReport& report) {
    const VertexArrays& va = tin.vertices();
    const std::size_t i = v.index();
    bool changed = false;
    if (va.height[i] != r.height) {
        tin.set_height(v, r.height);
        changed = true;
    }
    // set_height may have lowered the bedrock with the surface; write the recorded value.
    if (va.bedrock[i] != r.bedrock) {
        tin.set_bedrock(v, r.bedrock);
        changed = true;
    }
    if (va.material[i] != r.material) {
        tin.set_material(v, r.material);
        changed = true;
    }
    if (va.moisture[i] != r.moisture) {
        tin.set_moisture(v, r.moisture);
        changed = true;
    }
    if (!(va.slide[i] == r.slide)) {
        tin.set_slide(v, r.slide);
        changed = true;
    }
    if (va.water_depth[i] != r.water_depth) {
        tin.set_water_depth(v, r.water_depth);
        changed = true;
    }
    if (changed) ++report.vertices_updated;
}

}  // namespace

ApplyReport apply_delta(Tin& tin, const TinDelta& delta, DeltaSide target) {
    const bool to_before = target == DeltaSide::Before;
    const auto& source_constraints = to_before ? delta.constraints_after : delta.constraints_before;
    const auto& target_constraints = to_before ? delta.constraints_before : delta.constraints_after;
    auto target_of = [&](const VertexChange& c) -> const std::optional<VertexRecord>& {
        return to_before ? c.before : c.after;
    };
    auto source_of = [&](const VertexChange& c) -> const std::optional<VertexRecord>& {
        return to_before ? c.after : c.before;
    };

    ApplyReport report;
    LocateHint hint;
    // Recorded vertices may lie closer together than the snap distance (CGAL places constraint
    // crossings where they fall); snapping would merge them, so it is off while restoring.
    const SnapOff snap_off(tin);

    // 1. Release the source state's constraints that the target does not have.
    if (!source_constraints.empty()) {
        std::multimap<PolylineKey, ConstraintId> live;
        for (const ConstraintInfo& info : tin.constraints()) {
            ConstraintPolyline c{info.generation, {}};
            c.points.reserve(info.vertices.size());
            for (VertexId v : info.vertices)
                c.points.push_back(tin.position(v));
            live.emplace(key_of(c), info.id);
        }
        for (const ConstraintPolyline& c : source_constraints) {
            const auto it = live.find(key_of(c));
            if (it == live.end()) continue;  // already gone (e.g. released by a later flip)
            if (tin.release_constraint(it->second, VolumePolicy::Report))
                ++report.constraints_released;
            live.erase(it);
        }
    }

    // 2. Remove vertices that only the source state has: in connected patches first (a stroke's
    //    worth of vertices one by one took most of a redo), then one by one for what a patch
    //    could not take (next to a constraint, or around a vertex that stays), and those an
    //    edit created on the domain border (a stroke across the edge).
    std::vector<VertexId> doomed;
    for (const VertexChange& c : delta.vertices) {
        if (!source_of(c) || target_of(c)) continue;
        const VertexId v = vertex_at(tin, source_of(c)->position, hint);
        if (v.valid()) doomed.push_back(v);
    }
    report.vertices_removed += remove_in_patches(tin, doomed, nullptr).removed;
    for (VertexId v : doomed) {
        if (!tin.is_alive(v)) continue;
        if (tin.remove_vertex(v, VolumePolicy::Report) ||
            tin.remove_border_vertex(v, VolumePolicy::Report)) {
            ++report.vertices_removed;
        } else {
            report.unrestored.push_back(tin.position(v));
        }
    }

    // 3. Insert vertices that only the target state has, at their recorded heights.
    std::vector<Vec2> points;
    std::vector<double> heights;
    for (const VertexChange& c : delta.vertices) {
        if (source_of(c) || !target_of(c)) continue;
        if (vertex_at(tin, target_of(c)->position, hint).valid()) continue;
        points.push_back(target_of(c)->position);
        heights.push_back(target_of(c)->height);
    }
    if (!points.empty()) {
        sort_along_curve(points, heights);
        // In chunks: the Tin's per-insertion bookkeeping walks the edit's list of new
        // vertices, which makes one huge batch quadratic.
        constexpr std::size_t kChunk = 256;
        for (std::size_t i = 0; i < points.size(); i += kChunk) {
            const std::size_t n = std::min(kChunk, points.size() - i);
            tin.insert_points(std::span<const Vec2>(points).subspan(i, n),
                              std::span<const double>(heights).subspan(i, n), &hint);
        }
        report.vertices_inserted = points.size();
    }

    // 4. Every vertex of the target state in the delta gets its recorded attributes.
    for (const VertexChange& c : delta.vertices) {
        const auto& t = target_of(c);
        if (!t) continue;
        const VertexId v = vertex_at(tin, t->position, hint);
        if (!v.valid()) {
            report.unrestored.push_back(t->position);
            continue;
        }
        write_attributes(tin, v, *t, report);
    }

    // 5. Constrain the target state's polylines.
    // In generation order, as the tools created them: a constraint overlapping an existing one
    // is only registered separately when it comes second, so the order decides the registry.
    std::vector<const ConstraintPolyline*> order;
    for (const ConstraintPolyline& c : target_constraints)
        order.push_back(&c);
    std::stable_sort(order.begin(), order.end(),
                     [](const ConstraintPolyline* a, const ConstraintPolyline* b) {
                         return a->generation < b->generation;
                     });
    std::vector<VertexId> ids;
    for (const ConstraintPolyline* cp : order) {
        const ConstraintPolyline& c = *cp;
        ids.clear();
        bool complete = true;
        for (Vec2 p : c.points) {
            const VertexId v = vertex_at(tin, p, hint);
            if (!v.valid()) {
                report.unrestored.push_back(p);
                complete = false;
                break;
            }
            ids.push_back(v);
        }
        if (!complete || ids.size() < 2) continue;
        tin.insert_constraint(ids, false, c.generation, VolumePolicy::Report);
        ++report.constraints_inserted;
    }
    return report;
}

}  // namespace sandtin
