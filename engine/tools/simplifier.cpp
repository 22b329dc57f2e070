#include "tools/simplifier.hpp"

#include "geom/plane_fit.hpp"
#include "tools/slivers.hpp"
#include "util/prepare_for_writing.hpp"
#include "util/visit_marks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin {

double default_simplify_tolerance(const Rect& domain) {
    return 0.0005 * std::max(domain.width(), domain.height());
}

void SimplifyReport::accumulate(const SimplifyReport& o) {
    tested += o.tested;
    removed += o.removed;
    volume_change += o.volume_change;
    max_volume_change = std::max(max_volume_change, o.max_volume_change);
}

double planarity_residual(const Tin& tin, VertexId v) {
    static thread_local std::vector<VertexId> ring;
    const Tin::VertexStar star = tin.star(v, ring);  // one walk for all three questions
    if (star.boundary || star.constrained) return std::numeric_limits<double>::infinity();
    const VertexArrays& va = tin.vertices();
    // Water stays where it needs its vertices: removing one under the water, or beside it
    // (whose removal changes the wet neighbours' areas), would change the water's volume.
    // Dry, planar ground is simplified as before (issue 40: detail goes once the terrain is
    // dry and planar).
    if (va.water_depth[v.value] > 0.0) return std::numeric_limits<double>::infinity();
    for (VertexId w : ring) {
        if (va.water_depth[w.value] > 0.0) return std::numeric_limits<double>::infinity();
    }
    const Vec2 origin = va.position[v.value];
    const double z0 = va.height[v.value];
    // Fast path: a level neighbourhood (the floor of a flat stamp) needs no fit.
    double spread = 0.0;
    for (VertexId w : ring)
        spread = std::max(spread, std::abs(va.height[w.value] - z0));
    if (spread == 0.0) return 0.0;
    static thread_local std::vector<Vec2> xy;
    static thread_local std::vector<double> dz;
    xy.assign(1, origin);
    dz.assign(1, 0.0);
    for (VertexId w : ring) {
        xy.push_back(va.position[w.value]);
        dz.push_back(va.height[w.value] - z0);
    }
    return plane_fit_residual(xy, dz, origin);
}

void Simplifier::enqueue(VertexId v) {
    if (!v.valid()) return;
    if (v.value >= queued_flag_.size())
        grow_zero_filled(queued_flag_,
                         static_cast<std::size_t>(v.value) + 1 + queued_flag_.size() / 2);
    if (queued_flag_[v.value]) return;
    queued_flag_[v.value] = 1;
    queue_.push_back(v);
}

void Simplifier::enqueue(std::span<const VertexId> vs) {
    for (VertexId v : vs)
        enqueue(v);
}

void Simplifier::clear() {
    for (VertexId v : queue_)
        queued_flag_[v.value] = 0;
    queue_.clear();
}

SimplifyReport Simplifier::run(Tin& tin, const SimplifySettings& settings) {
    SimplifyReport report;
    std::vector<VertexId> work;
    work.swap(queue_);
    for (VertexId v : work)
        queued_flag_[v.value] = 0;
    // Deterministic order regardless of how the queue was filled.
    std::sort(work.begin(), work.end());

    // Candidates: redundant with respect to their current neighbours.
    std::vector<VertexId> candidates;
    for (VertexId v : work) {
        if (!tin.is_alive(v)) continue;
        ++report.tested;
        if (planarity_residual(tin, v) <= settings.tolerance) candidates.push_back(v);
    }
    // The neighbourhoods the removals re-triangulate: a compensation shift there can part
    // vertices a rounding error apart (crossings of nearly coincident old rims), which are
    // levelled again at the end without moving volume.
    // Each ring vertex is kept once (neighbouring removals share most of their rings), so
    // the sort below costs the distinct vertices.
    std::vector<VertexId> rings, ring_of_one;
    static thread_local VisitMarks in_rings;
    in_rings.clear();
    auto remember_ring = [&](VertexId v) {
        if (settings.volume_policy != VolumePolicy::Conserve) return;
        tin.neighbours(v, ring_of_one);
        for (VertexId w : ring_of_one) {
            if (in_rings.insert(w.value)) rings.push_back(w);
        }
    };
    auto remove_one = [&](VertexId v) {
        EditReport edit;
        remember_ring(v);
        if (tin.remove_vertex(v, settings.volume_policy, &edit)) {
            ++report.removed;
            report.volume_change += edit.volume_change;
            report.max_volume_change =
                std::max(report.max_volume_change, std::abs(edit.volume_change));
        }
    };
    // Connected groups of candidates are removed as one planar patch when the whole patch is
    // planar within the tolerance (a stamp's floor): O(size) instead of one Delaunay hole fill
    // per vertex. Anything else goes one by one, each re-tested against its current
    // neighbourhood, so errors cannot pile up on curved sand.
    std::vector<std::uint8_t>& is_candidate = candidate_flag_;
    for (VertexId v : candidates) {
        if (v.value >= is_candidate.size())
            grow_zero_filled(is_candidate,
                             static_cast<std::size_t>(v.value) + 1 + is_candidate.size() / 2);
        is_candidate[v.value] = 1;
    }
    std::vector<VertexId> group, ring, stack;
    for (VertexId seed : candidates) {
        if (!is_candidate[seed.value]) continue;
        group.clear();
        stack.assign(1, seed);
        is_candidate[seed.value] = 0;
        while (!stack.empty()) {
            const VertexId v = stack.back();
            stack.pop_back();
            group.push_back(v);
            tin.neighbours(v, ring);
            for (VertexId w : ring) {
                if (w.value < is_candidate.size() && is_candidate[w.value]) {
                    is_candidate[w.value] = 0;
                    stack.push_back(w);
                }
            }
        }
        std::sort(group.begin(), group.end());
        if (group.size() > 1) {
            EditReport edit;
            for (VertexId v : group)
                remember_ring(v);
            if (tin.remove_planar_patch(group, settings.tolerance, settings.volume_policy, &edit)) {
                report.removed += group.size();
                report.volume_change += edit.volume_change;
                report.max_volume_change =
                    std::max(report.max_volume_change, std::abs(edit.volume_change));
                continue;
            }
        }
        for (VertexId v : group) {
            if (tin.is_alive(v) && planarity_residual(tin, v) <= settings.tolerance) remove_one(v);
        }
    }
    if (!rings.empty()) {
        std::sort(rings.begin(), rings.end());
        level_slivers_conserving(tin, rings);
    }
    return report;
}

}  // namespace sandtin
