#include "history/change_recorder.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace sandtin {

namespace {

ConstraintPolyline polyline_of(const Tin& tin, const ConstraintInfo& info) {
    ConstraintPolyline c{info.generation, {}};
    c.points.reserve(info.vertices.size());
    for (VertexId v : info.vertices)
        c.points.push_back(tin.position(v));
    return c;
}

/// Orders positions so that a vertex that moved ids still pairs with itself.
struct PositionLess {
    bool operator()(Vec2 a, Vec2 b) const { return a.x < b.x || (a.x == b.x && a.y < b.y); }
};

}  // namespace

ChangeRecorder::ChangeRecorder(Tin& tin) : tin_(tin), changes_(tin) {
    const VertexArrays& va = tin.vertices();
    records_.resize(va.size());
    alive_.assign(va.alive.begin(), va.alive.end());
    for (std::uint32_t i = 0; i < va.size(); ++i) {
        if (alive_[i]) records_[i] = current(VertexId{i});
    }
    for (const ConstraintInfo& info : tin.constraints())
        constraints_.emplace(info.id.value, polyline_of(tin, info));
}

ChangeRecorder::~ChangeRecorder() = default;

VertexRecord ChangeRecorder::current(VertexId v) const {
    const VertexArrays& va = tin_.vertices();
    const std::size_t i = v.index();
    return VertexRecord{va.position[i], va.height[i], va.bedrock[i],    va.material[i],
                        va.moisture[i], va.slide[i],  va.water_depth[i]};
}

bool ChangeRecorder::has_vertex_changes() {
    VertexChanges changes = changes_.take();
    pending_.insert(pending_.end(), changes.attributes.begin(), changes.attributes.end());
    return !pending_.empty();
}

TinDelta ChangeRecorder::take() {
    has_vertex_changes();
    std::vector<VertexId> ids;
    ids.swap(pending_);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());

    // Pair old and new records by position: an id may have died and been reused elsewhere, and
    // a position may have lost its vertex and regained one under another id.
    std::map<Vec2, VertexChange, PositionLess> by_position;
    const VertexArrays& va = tin_.vertices();
    for (VertexId v : ids) {
        const std::size_t i = v.index();
        if (i < alive_.size() && alive_[i]) by_position[records_[i].position].before = records_[i];
        if (i < va.size() && va.alive[i]) {
            const VertexRecord now = current(v);
            by_position[now.position].after = now;
        }
    }
    TinDelta delta;
    delta.vertices.reserve(by_position.size());
    for (auto& [position, change] : by_position) {
        if (change.before == change.after) continue;
        delta.vertices.push_back(std::move(change));
    }

    // Move the vertex mirror forward.
    if (records_.size() < va.size()) {
        records_.resize(va.size());
        alive_.resize(va.size(), 0);
    }
    for (VertexId v : ids) {
        const std::size_t i = v.index();
        if (i >= va.size()) continue;
        alive_[i] = va.alive[i];
        if (alive_[i]) records_[i] = current(v);
    }

    // Constraints: compare every live one with the mirror (their count stays bounded: stamps
    // release old generations).
    std::map<std::uint32_t, ConstraintPolyline> now;
    for (const ConstraintInfo& info : tin_.constraints())
        now.emplace(info.id.value, polyline_of(tin_, info));
    for (auto& [id, old] : constraints_) {
        const auto it = now.find(id);
        if (it == now.end() || !(it->second == old)) delta.constraints_before.push_back(old);
    }
    for (auto& [id, c] : now) {
        const auto it = constraints_.find(id);
        if (it == constraints_.end() || !(it->second == c)) delta.constraints_after.push_back(c);
    }
    constraints_ = std::move(now);
    return delta;
}

}  // namespace sandtin
