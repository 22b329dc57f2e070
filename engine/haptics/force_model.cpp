#include "haptics/force_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin::haptics {

Vec3 clamp_magnitude(const Vec3& v, double limit) {
    const double l = length(v);
    if (!(l > limit)) return v;
    return v * (limit / l);
}

std::optional<double> ring_height_along(const HapticSnapshot& s, Vec2 d) {
    const std::uint32_t n = std::min<std::uint32_t>(s.control_count, kMaxControlPoints);
    if (n < 2 || !(length(d) > 0.0)) return std::nullopt;
    double best_t = std::numeric_limits<double>::infinity();
    std::optional<double> height;
    for (std::uint32_t j = 0; j < n; ++j) {
        const std::uint32_t k = (j + 1) % n;
        const Vec2 a = s.control[j];
        const Vec2 e = s.control[k] - a;
        // centre + t d = a + u e  =>  t = cross(a - c, e) / cross(d, e), u = cross(a - c, d) / ...
        const double denom = cross(d, e);
        if (denom == 0.0) continue;  // parallel to the edge
        const Vec2 ac = a - s.centre;
        const double t = cross(ac, e) / denom;
        const double u = cross(ac, d) / denom;
        if (!(t > 0.0) || u < 0.0 || u > 1.0 || !(t < best_t)) continue;
        best_t = t;
        height = s.control_height[j] + (s.control_height[k] - s.control_height[j]) * u;
    }
    return height;
}

PreparedSnapshot prepare_snapshot(const HapticSnapshot& s) {
    PreparedSnapshot p;
    p.snapshot = s;
    const std::uint32_t n = std::min<std::uint32_t>(s.control_count, kMaxControlPoints);
    for (std::uint32_t i = 0; i < n; ++i) {
        const Vec2 d = s.control[i] - s.centre;
        const double l = length(d);
        p.height_along[i] = s.control_height[i];
        if (!(l > 0.0)) continue;  // a control point at the centre has no direction
        p.direction[i] = d / l;
        p.height_along[i] = ring_height_along(s, d).value_or(s.control_height[i]);
    }
    return p;
}

ForceSample evaluate_force(const HapticSnapshot& s, const Vec3& position, const Vec3& velocity,
                           const ForceModelParams& p) {
    return evaluate_force(prepare_snapshot(s), position, velocity, p);
}

ForceSample evaluate_force(const PreparedSnapshot& prepared, const Vec3& position,
                           const Vec3& velocity, const ForceModelParams& p) {
    const HapticSnapshot& s = prepared.snapshot;
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
            const double m = prepared.height_along[i] - z + delta;
            if (!(m > 0.0)) continue;
            contact = true;
            lateral -= prepared.direction[i] * m;
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
