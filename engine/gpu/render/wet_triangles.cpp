#include "gpu/render/wet_triangles.hpp"

namespace sandtin::render {

namespace {

bool wet(const VertexArrays& va, std::uint32_t v) {
    return v < va.size() && va.alive[v] && va.water_depth[v] > 0.0;
}

}  // namespace

void WetTriangles::refan(const Tin& tin, std::uint32_t v, std::span<const VertexId> ring) {
    const VertexArrays& va = tin.vertices();
    if (!wet(va, v)) {
        forget(v);
        return;
    }
    scratch_.clear();
    const Vec2 p = va.position[v];
    for (std::size_t k = 0; ring.size() >= 2 && k < ring.size(); ++k) {
        const std::uint32_t a = ring[k].value, b = ring[(k + 1) % ring.size()].value;
        // Around a border vertex the ring has a gap (the outside): that pair is no face.
        if (cross(va.position[a] - p, va.position[b] - p) <= 0.0) continue;
        if ((a < v && wet(va, a)) || (b < v && wet(va, b))) continue;  // a lower wet corner owns it
        scratch_.insert(scratch_.end(), {v, a, b});
    }
    if (scratch_.empty()) {
        forget(v);
        return;
    }
    std::vector<std::uint32_t>& fan = fans_[v];
    if (fan == scratch_) return;
    triangles_ = triangles_ - fan.size() / 3 + scratch_.size() / 3;
    fan.swap(scratch_);
    stale_ = true;
    ++version_;
}

void WetTriangles::forget(std::uint32_t v) {
    const auto it = fans_.find(v);
    if (it == fans_.end()) return;
    triangles_ -= it->second.size() / 3;
    fans_.erase(it);
    stale_ = true;
    ++version_;
}

void WetTriangles::clear() {
    if (fans_.empty() && indices_.empty()) return;
    fans_.clear();
    indices_.clear();
    triangles_ = 0;
    stale_ = false;
    ++version_;
}

void WetTriangles::settle() {
    if (!stale_) return;
    indices_.clear();
    indices_.reserve(triangles_ * 3);
    for (const auto& [owner, fan] : fans_)
        indices_.insert(indices_.end(), fan.begin(), fan.end());
    stale_ = false;
}

}  // namespace sandtin::render
