#pragma once
// Terrains and helpers shared by the GPU tests.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu/vulkan_context.hpp"
#include "tin/tin.hpp"

namespace sandtin::gpu::testing {

inline const Rect kUnitSquare = Rect::from_size(1.0, 1.0);

// A steep cone (slope 2, far above tan 32° = 0.62) of radius `radius` on a gentle ramp:
// collapses for hundreds of iterations on a fine mesh while the rest of the terrain is at rest.
inline double collapsing_cone(Vec2 p, double radius = 0.25) {
    const double r = std::hypot(p.x - 0.45, p.y - 0.55);
    return 0.05 * p.x + std::max(0.0, 2.0 * (radius - r));
}

inline std::vector<uint32_t> live_ids(const Tin& tin) {
    std::vector<uint32_t> ids;
    const VertexArrays& va = tin.vertices();
    for (uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) ids.push_back(v);
    return ids;
}

template <class T>
std::vector<T> read_as(const VulkanContext& ctx, VkBuffer buffer, size_t count) {
    const auto bytes = read_buffer(ctx, buffer, 0, count * sizeof(T));
    std::vector<T> out(count);
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

}  // namespace sandtin::gpu::testing
