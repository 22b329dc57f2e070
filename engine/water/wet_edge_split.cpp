#include "water/wet_edge_split.hpp"

#include <algorithm>

#include "water/water_summary.hpp"

namespace sandtin {

namespace {

/// Calls visit(a, b) for each edge a < b longer than max_length with `film` of water at both
/// ends by `depth` (m per vertex id), in order of a, until visit returns false.
template <class Visit>
void for_long_wet_edges(const Tin& tin, std::span<const double> depth, double max_length,
                        double film, Visit visit) {
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> ring;
    const auto n = static_cast<std::uint32_t>(std::min(va.size(), depth.size()));
    for (std::uint32_t a = 0; a < n; ++a) {
        if (!va.alive[a] || depth[a] < film) continue;
        tin.neighbours(VertexId{a}, ring);
        for (const VertexId b : ring) {
            if (b.value < a || b.value >= n || depth[b.index()] < film) continue;
            if (length(va.position[a] - va.position[b.index()]) <= max_length) continue;
            if (!visit(VertexId{a}, b)) return;
        }
    }
}

}  // namespace

bool has_long_wet_edge(const Tin& tin, std::span<const double> depth, double max_length,
                       double film) {
    bool found = false;
    for_long_wet_edges(tin, depth, max_length, film, [&](VertexId, VertexId) {
        found = true;
        return false;
    });
    return found;
}

std::vector<VertexId> split_wet_edges(Tin& tin, double max_length, std::size_t max_splits,
                                      double film) {
    std::vector<EdgeSplit> splits;
    for_long_wet_edges(tin, tin.vertices().water_depth, max_length, film,
                       [&](VertexId a, VertexId b) {
                           splits.push_back({a, b, 0.5});
                           return splits.size() < max_splits;
                       });
    if (splits.empty()) return {};
    const double before = measure_water(tin).volume;
    std::vector<VertexId> born = tin.split_edges(splits, VolumePolicy::Conserve);
    std::erase_if(born, [](VertexId v) { return !v.valid(); });
    const VertexArrays& va = tin.vertices();
    double area = 0.0;
    for (const VertexId v : born)
        area += va.lumped_area[v.index()];
    const double missing = before - measure_water(tin).volume;
    if (area > 0.0 && missing != 0.0) {
        for (const VertexId v : born)
            tin.set_water_depth(v, std::max(0.0, va.water_depth[v.index()] + missing / area));
    }
    return born;
}

}  // namespace sandtin
