#include "physics/grid_erosion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tin/vertex_arrays.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin {

GridErosion::GridErosion(Rect domain, int cells_x, int cells_y, double tan_alpha,
                         TalusSettings settings)
    : domain_(domain), nx_(cells_x), ny_(cells_y), solver_(settings) {
    if (cells_x < 2 || cells_y < 2)
        throw std::invalid_argument("grid erosion: needs at least 2 x 2 cells");
    dx_ = domain.width() / cells_x;
    dy_ = domain.height() / cells_y;
    const std::size_t n = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
    height_.assign(n, 0.0);
    area_.assign(n, dx_ * dy_);
    bedrock_.assign(n, kNoBedrock);
    tan_.assign(n, tan_alpha);
    std::vector<std::vector<std::uint32_t>> rows(n);
    std::vector<std::vector<double>> lengths(n);
    for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) {
            // Moore neighbourhood, counter-clockwise from +x.
            static constexpr int kDi[8] = {1, 1, 0, -1, -1, -1, 0, 1};
            static constexpr int kDj[8] = {0, 1, 1, 1, 0, -1, -1, -1};
            for (int k = 0; k < 8; ++k) {
                const int a = i + kDi[k];
                const int b = j + kDj[k];
                if (a < 0 || b < 0 || a >= nx_ || b >= ny_) continue;
                rows[index(i, j)].push_back(static_cast<std::uint32_t>(index(a, b)));
                lengths[index(i, j)].push_back(std::hypot(kDi[k] * dx_, kDj[k] * dy_));
            }
        }
    }
    graph_.assign(rows, lengths);
}

Vec2 GridErosion::centre(int i, int j) const {
    return {domain_.min.x + (i + 0.5) * dx_, domain_.min.y + (j + 0.5) * dy_};
}

double GridErosion::volume() const {
    CompensatedSum s;
    for (std::size_t k = 0; k < height_.size(); ++k)
        s.add(area_[k] * height_[k]);
    return s.value();
}

double GridErosion::height_at(Vec2 p) const {
    const double fx = std::clamp((p.x - domain_.min.x) / dx_ - 0.5, 0.0, nx_ - 1.0);
    const double fy = std::clamp((p.y - domain_.min.y) / dy_ - 0.5, 0.0, ny_ - 1.0);
    const int i = std::min(static_cast<int>(fx), nx_ - 2);
    const int j = std::min(static_cast<int>(fy), ny_ - 2);
    const double tx = fx - i;
    const double ty = fy - j;
    return (1 - ty) * ((1 - tx) * height(i, j) + tx * height(i + 1, j)) +
           ty * ((1 - tx) * height(i, j + 1) + tx * height(i + 1, j + 1));
}

void GridErosion::pour(Vec2 p, double volume) {
    const int i = std::clamp(static_cast<int>((p.x - domain_.min.x) / dx_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((p.y - domain_.min.y) / dy_), 0, ny_ - 1);
    height(i, j) += volume / area_[index(i, j)];
    active_.activate(static_cast<std::uint32_t>(index(i, j)));
}

void GridErosion::activate_all() {
    for (std::uint32_t k = 0; k < height_.size(); ++k)
        active_.activate(k);
}

int GridErosion::run_to_rest(int max_iterations) {
    const TalusArrays arrays{height_.data(), area_.data(), bedrock_.data(), tan_.data(),
                             height_.size()};
    int it = 0;
    for (; it < max_iterations && !active_.empty(); ++it) {
        updates_ += solver_.iterate(graph_, arrays, active_).processed;
    }
    return it;
}

}  // namespace sandtin
