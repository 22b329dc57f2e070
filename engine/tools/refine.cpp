#include "tools/refine.hpp"

#include <algorithm>

namespace sandtin {

std::size_t refine_long_edges(Tin& tin, Vec2 centre, double radius, double max_length,
                              LocateHint* hint, std::size_t max_insertions, EditReport* report) {
    if (!(max_length > 0.0) || !(radius > 0.0)) return 0;
    std::size_t inserted = 0;
    std::vector<EdgeSplit> midpoints;
    while (inserted < max_insertions) {
        const auto edges = tin.edges_longer_than(centre, radius, max_length, hint);
        if (edges.empty()) break;
        midpoints.clear();
        for (const auto& e : edges) {
            midpoints.push_back({e[0], e[1], 0.5});
            if (inserted + midpoints.size() >= max_insertions) break;
        }
        const std::size_t before = tin.vertex_count();
        tin.split_edges(midpoints, VolumePolicy::Conserve, report);
        const std::size_t added = tin.vertex_count() - before;
        if (added == 0) break;  // nothing new (degenerate): stop rather than loop
        inserted += added;
    }
    return inserted;
}

}  // namespace sandtin
