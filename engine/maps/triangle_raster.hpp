#pragma once
// Visits every sample of a map grid once, with the TIN triangle that contains it and the
// sample's barycentric weights there: the one rasteriser all CPU bakes share.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Calls visit(sample_index, corners, weights) exactly once per sample (index = row * width +
/// col), where corners are a TIN triangle containing the sample and weights (summing to 1)
/// interpolate it. Samples on shared edges go to the first triangle found; a sample that
/// rounding keeps out of every triangle is located in the TIN instead. The grid's domain must
/// lie inside the TIN's (throws std::invalid_argument otherwise).
template <class Visit>
void for_each_sample(const Tin& tin, const MapGrid& grid, Visit&& visit) {
    std::vector<std::uint8_t> seen(grid.size(), 0);
    const VertexArrays& va = tin.vertices();
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        std::array<Vec2, 3> g;
        for (std::size_t k = 0; k < 3; ++k)
            g[k] = grid.to_grid(va.position[t[k].index()]);
        const double area = cross(g[1] - g[0], g[2] - g[0]);
        if (area == 0.0) continue;
        const double eps = 1e-12 * std::abs(area);
        const auto lo = [](double v) { return static_cast<std::int64_t>(std::ceil(v - 1e-9)); };
        const auto hi = [](double v) { return static_cast<std::int64_t>(std::floor(v + 1e-9)); };
        const std::int64_t c0 = std::max<std::int64_t>(0, lo(std::min({g[0].x, g[1].x, g[2].x})));
        const std::int64_t c1 =
            std::min<std::int64_t>(grid.width - 1, hi(std::max({g[0].x, g[1].x, g[2].x})));
        const std::int64_t r0 = std::max<std::int64_t>(0, lo(std::min({g[0].y, g[1].y, g[2].y})));
        const std::int64_t r1 =
            std::min<std::int64_t>(grid.height - 1, hi(std::max({g[0].y, g[1].y, g[2].y})));
        for (std::int64_t r = r0; r <= r1; ++r) {
            for (std::int64_t c = c0; c <= c1; ++c) {
                const std::size_t index =
                    static_cast<std::size_t>(r) * grid.width + static_cast<std::size_t>(c);
                if (seen[index]) continue;
                const Vec2 s{static_cast<double>(c), static_cast<double>(r)};
                std::array<double, 3> w = {cross(g[1] - s, g[2] - s), cross(g[2] - s, g[0] - s),
                                           cross(g[0] - s, g[1] - s)};
                if (area < 0.0) w = {-w[0], -w[1], -w[2]};
                if (w[0] < -eps || w[1] < -eps || w[2] < -eps) continue;
                const double sum = w[0] + w[1] + w[2];
                seen[index] = 1;
                visit(index, t, std::array<double, 3>{w[0] / sum, w[1] / sum, w[2] / sum});
            }
        }
    }
    LocateHint hint;
    for (std::size_t index = 0; index < seen.size(); ++index) {
        if (seen[index]) continue;
        const auto col = static_cast<std::uint32_t>(index % grid.width);
        const auto row = static_cast<std::uint32_t>(index / grid.width);
        const Location loc = tin.locate(grid.position(col, row), &hint);
        if (!loc.inside()) {
            throw std::invalid_argument("map bake: the map grid reaches outside the terrain");
        }
        visit(index, loc.corners, loc.barycentric);
    }
}

/// One channel: `per_vertex` (indexed by VertexId) interpolated linearly at every sample, so
/// exact for any field linear over each triangle (the surface's heights, the water's depths).
inline MapImage interpolate_per_vertex(const Tin& tin, const MapGrid& grid,
                                       const std::vector<double>& per_vertex) {
    MapImage map{grid.width, grid.height, 1, std::vector<double>(grid.size())};
    for_each_sample(
        tin, grid,
        [&](std::size_t i, const std::array<VertexId, 3>& t, const std::array<double, 3>& w) {
            map.values[i] = w[0] * per_vertex[t[0].index()] + w[1] * per_vertex[t[1].index()] +
                            w[2] * per_vertex[t[2].index()];
        });
    return map;
}

}  // namespace sandtin
