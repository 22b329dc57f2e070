#include "haptics/force_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin::haptics {

Vec3 clamp_magnitude(const Vec3& v, double limit) {
    const double l = length(v);
    if (!std::isinf(l)) {  // finite, or NaN (left as it is)
        if (!(l > limit)) return v;
        return v * (limit / l);
    }
    // |v|² overflowed. Measured relative to its largest component, v has a length in [1, √3].
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (std::isinf(largest)) {
        // An infinite component: the direction is along the infinite components.
        const auto unit = [](double c) { return std::isinf(c) ? std::copysign(1.0, c) : 0.0; };
        const Vec3 d{unit(v.x), unit(v.y), unit(v.z)};
        return d * (limit / length(d));
    }
    const Vec3 u = v * (1.0 / largest);
    return u * (limit / length(u));
}

namespace {

struct RingCrossing {
    double t = 0.0;       ///< the crossing is centre + t d
    double height = 0.0;  ///< interpolated along the crossed edge (m)
};

// The first crossing of the ray centre + t d (t > 0) with the control-point ring.
std::optional<RingCrossing> ring_crossing(const HapticSnapshot& s, Vec2 d) {
    const std::uint32_t n = std::min<std::uint32_t>(s.control_count, kMaxControlPoints);
    if (n < 2 || !(length(d) > 0.0)) return std::nullopt;
    double best_t = std::numeric_limits<double>::infinity();
    std::optional<RingCrossing> crossing;
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
        crossing =
            RingCrossing{t, s.control_height[j] + (s.control_height[k] - s.control_height[j]) * u};
    }
    return crossing;
}

}  // namespace

std::optional<double> ring_height_along(const HapticSnapshot& s, Vec2 d) {
    const std::optional<RingCrossing> c = ring_crossing(s, d);
    if (!c) return std::nullopt;
    return c->height;
}

PreparedSnapshot prepare_snapshot(const HapticSnapshot& s) {
    PreparedSnapshot p;
    p.snapshot = s;
    p.centre_on_terrain = s.terrain.contains(s.centre);
    const std::uint32_t n = std::min<std::uint32_t>(s.control_count, kMaxControlPoints);
    for (std::uint32_t i = 0; i < n; ++i) {
        const Vec2 d = s.control[i] - s.centre;
        const double l = length(d);
        p.height_along[i] = s.control_height[i];
        p.on_terrain[i] = s.terrain.contains(s.control[i]);
        if (!(l > 0.0)) continue;  // a control point at the centre has no direction
        p.direction[i] = d / l;
        if (const std::optional<RingCrossing> c = ring_crossing(s, d)) {
            p.height_along[i] = c->height;
            // A concave ring can hide c_i behind a nearer edge: the material in this direction
            // is at that crossing, which must be over the terrain too. It lies between the
            // centre and c_i, so it is when both are (the terrain is a rectangle): only a centre
            // off the terrain needs the test (which rounding could tip for a crossing at c_i).
            if (!p.centre_on_terrain)
                p.on_terrain[i] = p.on_terrain[i] && s.terrain.contains(s.centre + d * c->t);
        }
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

    // Off the terrain there is no surface to touch (header comment, rule 5).
    out.immersion =
        prepared.centre_on_terrain ? s.centre_height - z : -std::numeric_limits<double>::infinity();
    bool contact = out.immersion > -delta;
    Vec3 f;
    if (contact) f.z = k * (out.immersion + delta);

    const std::uint32_t n = std::min<std::uint32_t>(s.control_count, kMaxControlPoints);
    if (n > 0) {
        Vec2 lateral;
        for (std::uint32_t i = 0; i < n; ++i) {
            if (!prepared.on_terrain[i]) continue;
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
