#pragma once
// The workgroup grid of a direct dispatch. A device may cap the groups along x at 65 535
// (maxComputeWorkGroupCount[0]; lavapipe and Intel do), which one row of 64-thread groups
// passes at about 4.2 M threads: a bake over the triangle slots of a 1.9 M-vertex terrain.
// Larger counts go as rows of at most `max_x` groups, which the shaders flatten back with
// thread_index() (shaders/common.glsl) and bound by their own count.

#include <cstdint>
#include <optional>

namespace sandtin::gpu {

struct DispatchGrid {
    uint32_t x = 0;
    uint32_t y = 0;
};

/// The grid for `groups` workgroups with at most `max_x` along x and `max_y` along y: one
/// row when it fits, else full rows of `max_x` (the last row partly idle). Nothing when
/// `groups` exceeds max_x * max_y, or a limit is 0.
constexpr std::optional<DispatchGrid> dispatch_grid(uint32_t groups, uint32_t max_x,
                                                    uint32_t max_y) {
    if (max_x == 0 || max_y == 0) return std::nullopt;
    if (groups <= max_x) return DispatchGrid{groups, groups == 0 ? 0u : 1u};
    const uint64_t rows = (uint64_t{groups} + max_x - 1) / max_x;
    if (rows > max_y) return std::nullopt;
    return DispatchGrid{max_x, static_cast<uint32_t>(rows)};
}

}  // namespace sandtin::gpu
