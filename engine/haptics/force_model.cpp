#include "haptics/force_model.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin::haptics {

Vec3 clamp_magnitude(const Vec3& v, double limit) {
    const double l = length(v);
    if (!(l > limit)) return v;
    return v * (limit / l);
}

ForceSample evaluate_force(const HapticSnapshot& s, const Vec3& position, const Vec3& velocity,
                           const ForceModelParams& p) {
    ForceSample out;
    if (s.sequence == 0) return out;
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z) ||
        !std::isfinite(velocity.x) || !std::isfinite(velocity.y) || !std::isfinite(velocity.z)) {
        return out;
    }
    const double delta = p.contact_offset;
    const double k = s.stiffness;
    const double z = position.z;

    out.immersion = s.centre_height - z;
    bool contact = out.immersion > -delta;
    Vec3 f;
    if (contact) f.z = k * (out.immersion + delta);

    const std::uint32_t n = std::min<std::uint32_t>(s.control_count, kMaxControlPoints);
    if (n > 0) {
        Vec2 lateral;
        for (std::uint32_t i = 0; i < n; ++i) {
            const double m = s.control_height[i] - z + delta;
            if (!(m > 0.0)) continue;
            contact = true;
            const Vec2 d = s.control[i] - s.centre;
            const double l = length(d);
            if (!(l > 0.0)) continue;  // a control point at the centre has no direction
            lateral -= d * (m / l);
        }
        const double gain = s.friction * k / static_cast<double>(n);
        f.x += lateral.x * gain;
        f.y += lateral.y * gain;
    }
    if (!contact) return out;
    out.contact = true;

    f.x -= p.gel_damping * velocity.x;
    f.y -= p.gel_damping * velocity.y;

    const double magnitude = length(f);
    if (magnitude < p.gel_force) {
        f = magnitude > 0.0 ? f * (p.gel_force / magnitude) : Vec3{0.0, 0.0, p.gel_force};
    }
    out.force = clamp_magnitude(f, p.max_force);
    return out;
}

}  // namespace sandtin::haptics
