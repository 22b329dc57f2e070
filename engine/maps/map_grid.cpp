#include "maps/map_grid.hpp"

#include <stdexcept>
#include <string>

namespace sandtin {

MapGrid::MapGrid(Rect d, std::uint32_t w, std::uint32_t h, SampleAt a)
    : domain(d), width(w), height(h), at(a) {
    if (d.empty() || !(d.width() > 0.0 && d.height() > 0.0)) {
        throw std::invalid_argument("map grid: the domain has no area");
    }
    const std::uint32_t min_size = a == SampleAt::Corners ? 2 : 1;
    if (w < min_size || h < min_size) {
        throw std::invalid_argument("map grid: " + std::to_string(w) + " x " + std::to_string(h) +
                                    " is too small (at least " + std::to_string(min_size) +
                                    " samples a side)");
    }
    if (static_cast<std::uint64_t>(w) * h > (1ull << 28)) {
        throw std::invalid_argument("map grid: " + std::to_string(w) + " x " + std::to_string(h) +
                                    " exceeds 2^28 samples");
    }
}

Vec2 MapGrid::position(std::uint32_t col, std::uint32_t row) const {
    if (at == SampleAt::Corners) {
        // Exact border coordinates, so the outermost samples lie on the domain's edges.
        const double x =
            col + 1 == width ? domain.max.x : domain.min.x + domain.width() * col / (width - 1);
        const double y =
            row == 0 ? domain.max.y : domain.max.y - domain.height() * row / (height - 1);
        return {x, y};
    }
    return {domain.min.x + domain.width() * (col + 0.5) / width,
            domain.max.y - domain.height() * (row + 0.5) / height};
}

Vec2 MapGrid::to_grid(Vec2 p) const {
    if (at == SampleAt::Corners) {
        return {(p.x - domain.min.x) / domain.width() * (width - 1),
                (domain.max.y - p.y) / domain.height() * (height - 1)};
    }
    return {(p.x - domain.min.x) / domain.width() * width - 0.5,
            (domain.max.y - p.y) / domain.height() * height - 0.5};
}

Vec2 MapGrid::spacing() const {
    const std::uint32_t gaps_x = at == SampleAt::Corners ? width - 1 : width;
    const std::uint32_t gaps_y = at == SampleAt::Corners ? height - 1 : height;
    return {domain.width() / gaps_x, domain.height() / gaps_y};
}

}  // namespace sandtin
