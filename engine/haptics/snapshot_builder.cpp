#include "haptics/snapshot_builder.hpp"

#include <algorithm>

namespace sandtin::haptics {

namespace {
Vec2 clamp_to(const Rect& d, Vec2 p) {
    return {std::clamp(p.x, d.min.x, d.max.x), std::clamp(p.y, d.min.y, d.max.y)};
}
}  // namespace

HapticSnapshot build_snapshot(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                              const MaterialTable& materials, LocateHint* hint) {
    const Rect domain = tin.domain();
    HapticSnapshot s;
    s.terrain = domain;
    // The centre and the control points stay where the tool is; the model gives no force where
    // they are off the terrain. Heights and material are taken at the nearest point of the
    // terrain, so every value in the snapshot stays finite and meaningful.
    s.centre = at.centre;
    const Location loc = tin.locate(clamp_to(domain, at.centre), hint);
    double centre_height = 0.0;
    std::uint16_t material = 0;
    if (loc.inside()) {
        std::size_t best = 0;
        for (std::size_t i = 0; i < 3; ++i) {
            centre_height += loc.barycentric[i] * tin.height(loc.corners[i]);
            if (loc.barycentric[i] > loc.barycentric[best]) best = i;
        }
        material = tin.vertices().material[loc.corners[best].index()];
    }
    s.centre_height = centre_height;
    const Material fallback;
    const Material& m = materials.size() > 0 ? materials.at(material) : fallback;
    s.stiffness = m.haptic_stiffness;
    s.friction = m.haptic_friction;

    const std::vector<Vec2>& ring = tool.shape().outer;
    const std::size_t n = std::min(ring.size(), kMaxControlPoints);
    s.control_count = static_cast<std::uint32_t>(n);
    const ToolFrame frame(tool, at);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 local = ring[i * ring.size() / n];
        const Vec2 p = frame.to_world(local);
        s.control[i] = p;
        s.control_height[i] = tin.height_at(clamp_to(domain, p), hint).value_or(centre_height);
    }
    return s;
}

}  // namespace sandtin::haptics
