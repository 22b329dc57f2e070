#include "tools/imprint_activity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "geom/polygon.hpp"

namespace sandtin {

ImprintActivity inner_contour_activity(const Tin& tin, std::span<const Vec2> inner,
                                       const ImprintHeight& imprint, double tolerance,
                                       double lateral, LocateHint* hint) {
    ImprintActivity out;
    const std::size_t n = inner.size();
    out.inner_active.assign(n, 0);
    const double inward_sign = signed_area(inner) > 0.0 ? 1.0 : -1.0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = inner[i];
        const Vec2 b = inner[(i + 1) % n];
        const double len = distance(a, b);
        const Vec2 inward =
            len > 0.0 ? Vec2{-(b.y - a.y), b.x - a.x} * (inward_sign / len) : Vec2{};
        for (const auto& [t, z] : tin.section(a, b, hint)) {
            const Vec2 p = lerp(a, b, t);
            const double off = std::abs(z - imprint(p, z));
            if (!(off > tolerance)) continue;
            const Vec2 q = p + inward * lateral;
            const std::optional<double> zq = tin.height_at(q, hint);
            if (!zq || std::abs(*zq - imprint(q, *zq)) > std::max(tolerance, 0.5 * off)) {
                out.inner_active[i] = 1;
                out.any_segment = true;
                break;
            }
        }
    }
    return out;
}

bool interior_stands_off(const Tin& tin, std::span<const Vec2> inner, const ImprintHeight& imprint,
                         double tolerance, double lateral, Vec2 centre, double radius,
                         LocateHint* hint) {
    const VertexArrays& va = tin.vertices();
    const std::size_t n = inner.size();
    for (VertexId v : tin.vertices_in_disc(centre, radius, hint)) {
        const Vec2 p = va.position[v.value];
        const double z = va.height[v.value];
        if (!point_in_polygon(p, inner) || !(std::abs(z - imprint(p, z)) > tolerance)) continue;
        // Within `lateral` of the contour it is a wall the contour grazes.
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < n && d > lateral; ++i)
            d = std::min(d, distance_to_segment(p, inner[i], inner[(i + 1) % n]));
        if (d > lateral) return true;
    }
    return false;
}

}  // namespace sandtin
