#include "tools/refine.hpp"

#include <algorithm>

namespace sandtin {

SurfaceFence dab_fence(double radius, double simplify_tolerance, Generation next_generation) {
    SurfaceFence fence;
    fence.tolerance = std::min(0.01 * radius, simplify_tolerance);
    fence.generation = next_generation > 0 ? next_generation - 1 : 0;
    return fence;
}

bool coarse_for_dab(const Tin& tin, Vec2 centre, double radius, LocateHint* hint) {
    return tin.vertices_in_disc(centre, radius, hint).size() < 16;
}

namespace {

/// Fences the bent edges inserting `points` would remove; edges of any length (see dab_fence).
std::size_t fence_for(Tin& tin, std::span<const Vec2> points, const SurfaceFence& fence,
                      LocateHint* hint, EditReport* report = nullptr) {
    return tin.fence_bent_edges(points, {}, fence.tolerance, fence.generation, nullptr, hint,
                                report);
}

}  // namespace

std::size_t insert_points_fenced(Tin& tin, std::span<const Vec2> points, const SurfaceFence* fence,
                                 LocateHint* hint) {
    const std::size_t fenced =
        fence != nullptr && !points.empty() ? fence_for(tin, points, *fence, hint) : 0;
    tin.insert_points_on_surface(points, hint);
    return fenced;
}

std::vector<VertexId> simplifiable_after_dab(const Tin& tin, std::span<const VertexId> disc,
                                             Vec2 centre, double radius, double spacing,
                                             bool fenced) {
    if (!fenced) return {disc.begin(), disc.end()};
    std::vector<VertexId> inner;
    const double inside = radius - spacing;
    for (const VertexId v : disc)
        if (distance(tin.position(v), centre) <= inside) inner.push_back(v);
    return inner;
}

RefineResult refine_long_edges(Tin& tin, Vec2 centre, double radius, double max_length,
                               LocateHint* hint, std::size_t max_insertions, EditReport* report,
                               const SurfaceFence* fence) {
    RefineResult result;
    if (!(max_length > 0.0) || !(radius > 0.0)) return result;
    std::vector<EdgeSplit> midpoints;
    while (result.inserted < max_insertions) {
        const auto edges = tin.edges_longer_than(centre, radius, max_length, hint);
        if (edges.empty()) break;
        midpoints.clear();
        for (const auto& e : edges) {
            midpoints.push_back({e[0], e[1], 0.5});
            if (result.inserted + midpoints.size() >= max_insertions) break;
        }
        const std::size_t before = tin.vertex_count();
        if (fence != nullptr) {
            for (const EdgeSplit& s : midpoints) {
                const Vec2 p = lerp(tin.position(s.a), tin.position(s.b), s.t);
                result.fenced += fence_for(tin, std::span<const Vec2>(&p, 1), *fence, hint, report);
                tin.split_edges(std::span<const EdgeSplit>(&s, 1), VolumePolicy::Conserve, report);
            }
        } else {
            tin.split_edges(midpoints, VolumePolicy::Conserve, report);
        }
        const std::size_t added = tin.vertex_count() - before;
        if (added == 0) break;  // nothing new (degenerate): stop rather than loop
        result.inserted += added;
    }
    return result;
}

}  // namespace sandtin
