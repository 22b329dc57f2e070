#include "water/water_borders.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <type_traits>
#include <utility>
#include <vector>

namespace sandtin {

std::vector<double> outflow_widths(const WaterMesh& m, Rect domain, OpenSides sides) {
    const double tolerance =
        1e-9 * std::max(domain.max.x - domain.min.x, domain.max.y - domain.min.y);
    const auto on_open_side = [&](Vec2 p) {
        return (sides.west && std::abs(p.x - domain.min.x) <= tolerance) ||
               (sides.east && std::abs(p.x - domain.max.x) <= tolerance) ||
               (sides.south && std::abs(p.y - domain.min.y) <= tolerance) ||
               (sides.north && std::abs(p.y - domain.max.y) <= tolerance);
    };
    // Border edges: those of one face.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> faces_of_edge;
    for (const auto& f : m.faces) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[k], b = f[(k + 1) % 3];
            ++faces_of_edge[{std::min(a, b), std::max(a, b)}];
        }
    }
    std::vector<double> width(m.position.size(), 0.0);
    for (const auto& [edge, count] : faces_of_edge) {
        if (count != 1) continue;
        const Vec2 a = m.position[edge.first], b = m.position[edge.second];
        // Both ends on one open side (a corner edge of two sides counts once).
        const Vec2 mid = 0.5 * (a + b);
        if (!on_open_side(a) || !on_open_side(b) || !on_open_side(mid)) continue;
        const double half = 0.5 * length(b - a);
        width[edge.first] += half;
        width[edge.second] += half;
    }
    return width;
}

template <class Water>
double open_borders(Water& water, Rect domain, OpenSides sides) {
    const std::vector<double> width = outflow_widths(water.mesh(), domain, sides);
    double total = 0.0;
    for (std::size_t v = 0; v < width.size(); ++v) {
        total += width[v];
        if constexpr (std::is_same_v<Water, ShallowWater>) {
            water.set_open_border(v, width[v] > 0.0);
        } else {
            water.set_outflow_width(v, width[v]);
        }
    }
    return total;
}

template double open_borders(VirtualPipes&, Rect, OpenSides);
template double open_borders(ShallowWater&, Rect, OpenSides);

}  // namespace sandtin
