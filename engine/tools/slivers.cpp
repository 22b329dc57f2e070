#include "tools/slivers.hpp"

#include <algorithm>

namespace sandtin {

namespace {

enum class Level { Lower, Higher, Mean };

void level_clusters(Tin& tin, std::span<const VertexId> vertices, Level level) {
    // Clusters, not pairs: three crossings a rounding error apart levelled pair by pair in
    // one pass can leave the first pair apart again (the third raises the second).
    std::vector<VertexId> ring;
    std::vector<VertexId> cluster;
    std::vector<VertexId> done;
    // Squared: every neighbour of every vertex offered is tested, and hypot is slow.
    const double snap2 = tin.snap_distance() * tin.snap_distance();
    const VertexArrays& va = tin.vertices();
    for (VertexId start : vertices) {
        if (!tin.is_alive(start) || std::find(done.begin(), done.end(), start) != done.end())
            continue;
        cluster.assign(1, start);
        for (std::size_t head = 0; head < cluster.size(); ++head) {
            const VertexId v = cluster[head];
            tin.neighbours(v, ring);
            for (VertexId w : ring) {
                if (length_squared(va.position[w.value] - va.position[v.value]) > snap2) continue;
                if (std::find(cluster.begin(), cluster.end(), w) == cluster.end())
                    cluster.push_back(w);
            }
        }
        if (cluster.size() == 1) continue;
        double h = va.height[cluster.front().value];
        if (level == Level::Mean) {
            double area = 0.0;
            double moment = 0.0;
            for (VertexId v : cluster) {
                area += va.lumped_area[v.value];
                moment += va.lumped_area[v.value] * va.height[v.value];
            }
            if (area > 0.0) h = moment / area;
        } else {
            for (VertexId v : cluster) {
                h = level == Level::Lower ? std::min(h, va.height[v.value])
                                          : std::max(h, va.height[v.value]);
            }
        }
        for (VertexId v : cluster) {
            if (va.height[v.value] != h) tin.set_height(v, h);
            done.push_back(v);
        }
    }
}

}  // namespace

void equalise_slivers(Tin& tin, std::span<const VertexId> vertices, bool take_lower) {
    level_clusters(tin, vertices, take_lower ? Level::Lower : Level::Higher);
}

void level_slivers_conserving(Tin& tin, std::span<const VertexId> vertices) {
    level_clusters(tin, vertices, Level::Mean);
}

}  // namespace sandtin
