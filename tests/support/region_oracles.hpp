#pragma once
// Regions of vertex sets, computed from Tin::triangles() only: the triangles a set's removal
// takes with it, their boundary, whether they form a disc (what Tin::remove_patch needs), and a
// way to grow a set until they do.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

/// Live vertices closer than `r` metres to `c`.
inline std::vector<VertexId> in_disc(const Tin& tin, Vec2 c, double r) {
    std::vector<VertexId> out;
    for (VertexId v : live_ids(tin)) {
        if (distance(tin.position(v), c) < r) out.push_back(v);
    }
    return out;
}

/// The region of a vertex set (every triangle with a corner in it) and its boundary: directed
/// edges with the region on the left, keyed by their start.
struct Region {
    std::vector<Tri> triangles;
    std::multimap<VertexId, VertexId> boundary;
    std::set<VertexId> corners;
};

inline Region region_of(const Tin& tin, const std::set<VertexId>& set) {
    Region out;
    std::set<std::pair<VertexId, VertexId>> region_edges;
    for (const Tri& t : tin.triangles()) {
        if (set.count(t[0]) || set.count(t[1]) || set.count(t[2])) {
            out.triangles.push_back(t);
            for (std::size_t i = 0; i < 3; ++i) {
                region_edges.insert({t[i], t[(i + 1) % 3]});
                out.corners.insert(t[i]);
            }
        }
    }
    for (const auto& [a, b] : region_edges) {
        if (!region_edges.count({b, a})) out.boundary.insert({a, b});
    }
    return out;
}

/// What makes a region a disc: every corner is in the set or on the boundary, no boundary
/// vertex in the set, each boundary vertex passed once, and one loop through all of them.
inline bool is_disc(const Region& r, const std::set<VertexId>& set) {
    for (VertexId v : r.corners) {
        if (!set.count(v) && !r.boundary.count(v)) return false;  // enclosed
        if (set.count(v) && r.boundary.count(v)) return false;    // the set touches the border
        if (r.boundary.count(v) > 1) return false;                // pinch
    }
    if (r.boundary.empty()) return false;
    std::size_t steps = 0;
    const VertexId start = r.boundary.begin()->first;
    VertexId at = start;
    do {
        at = r.boundary.find(at)->second;
        ++steps;
    } while (at != start && steps <= r.boundary.size());
    return steps == r.boundary.size();
}

/// Grows the set by enclosed corners and pinch vertices, and fills inner boundary loops, until
/// its region is a disc.
inline std::vector<VertexId> grow_to_disc(const Tin& tin, const std::vector<VertexId>& seed) {
    std::set<VertexId> set(seed.begin(), seed.end());
    for (int round = 0; round < 50; ++round) {
        const Region r = region_of(tin, set);
        if (is_disc(r, set)) return {set.begin(), set.end()};
        std::vector<VertexId> add;
        for (VertexId v : r.corners) {
            if (!set.count(v) && (!r.boundary.count(v) || r.boundary.count(v) > 1))
                add.push_back(v);
        }
        if (add.empty()) {
            // Several loops: keep the longest, fill the others.
            std::set<VertexId> seen;
            std::vector<std::vector<VertexId>> loops;
            for (const auto& [v, w] : r.boundary) {
                if (seen.count(v)) continue;
                std::vector<VertexId> loop;
                for (VertexId x = v; !seen.count(x); x = r.boundary.find(x)->second) {
                    seen.insert(x);
                    loop.push_back(x);
                }
                loops.push_back(loop);
            }
            std::sort(loops.begin(), loops.end(),
                      [](const auto& a, const auto& b) { return a.size() > b.size(); });
            for (std::size_t k = 1; k < loops.size(); ++k)
                add.insert(add.end(), loops[k].begin(), loops[k].end());
        }
        if (add.empty()) break;
        set.insert(add.begin(), add.end());
    }
    ADD_FAILURE() << "could not grow the set to a disc";
    return {set.begin(), set.end()};
}

inline bool region_is_disc(const Tin& tin, const std::vector<VertexId>& vertices) {
    const std::set<VertexId> set(vertices.begin(), vertices.end());
    return is_disc(region_of(tin, set), set);
}

}  // namespace sandtin::test
