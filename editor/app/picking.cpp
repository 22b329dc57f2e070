#include "picking.hpp"

#include <cmath>

namespace sandtin::editor {

std::optional<Pick> pick_terrain(const Tin& tin, const Ray& ray, Vec2 offset, double step,
                                 double max_distance) {
    LocateHint hint;
    auto above = [&](double t, bool& inside) {
        const Vec2 p{ray.origin.x + t * ray.direction.x + offset.x,
                     ray.origin.y + t * ray.direction.y + offset.y};
        const std::optional<double> h = tin.height_at(p, &hint);
        inside = h.has_value();
        return inside ? ray.origin.z + t * ray.direction.z - *h : 1.0;
    };
    double prev_t = 0.0;
    bool inside = false;
    double prev = above(0.0, inside);
    bool prev_inside = inside;
    for (double t = step; t <= max_distance; t += step) {
        const double cur = above(t, inside);
        if (inside && prev_inside && cur <= 0.0 && prev > 0.0) {
            double lo = prev_t, hi = t;
            for (int i = 0; i < 40 && hi - lo > step * 1e-7; ++i) {
                const double mid = 0.5 * (lo + hi);
                bool in = false;
                (above(mid, in) > 0.0 ? lo : hi) = mid;
            }
            const double tt = 0.5 * (lo + hi);
            const Vec3 p{ray.origin.x + tt * ray.direction.x + offset.x,
                         ray.origin.y + tt * ray.direction.y + offset.y,
                         ray.origin.z + tt * ray.direction.z};
            return Pick{p, tt};
        }
        if (inside && !prev_inside && cur <= 0.0) {
            // Entered the domain below the surface (looking in through a side wall).
            return std::nullopt;
        }
        prev = cur;
        prev_inside = inside;
        prev_t = t;
    }
    return std::nullopt;
}

}  // namespace sandtin::editor
