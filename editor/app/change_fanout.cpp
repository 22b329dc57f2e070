#include "change_fanout.hpp"

#include <algorithm>
#include <utility>

namespace sandtin::editor {

std::vector<IdRange> union_of_ranges(const std::vector<IdRange>& a, const std::vector<IdRange>& b) {
    std::vector<IdRange> all;
    all.reserve(a.size() + b.size());
    std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(all),
               [](IdRange x, IdRange y) { return x.begin < y.begin; });
    std::vector<IdRange> out;
    for (const IdRange r : all) {
        if (r.size() == 0) continue;
        if (!out.empty() && r.begin <= out.back().end)
            out.back().end = std::max(out.back().end, r.end);
        else
            out.push_back(r);
    }
    return out;
}

void ChangeFanout::pull() {
    const ChangeSet fresh = tin_.take_changes();
    for (ChangeSet& p : pending_) {
        p.vertices = union_of_ranges(p.vertices, fresh.vertices);
        p.triangles = union_of_ranges(p.triangles, fresh.triangles);
        // Capacities and counts describe the TIN now: the newest take's.
        p.vertex_capacity = fresh.vertex_capacity;
        p.slot_capacity = fresh.slot_capacity;
        p.live_vertices = fresh.live_vertices;
        p.live_slots = fresh.live_slots;
        p.dead_slots = fresh.dead_slots;
    }
}

ChangeSet ChangeFanout::take(Channel channel) {
    pull();
    ChangeSet out = std::move(pending_[channel]);
    pending_[channel] = ChangeSet{};
    return out;
}

}  // namespace sandtin::editor
