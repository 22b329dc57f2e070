#include "physics/grid_erosion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/project_out_of_repose.hpp"
#include "tin/vertex_arrays.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin {

namespace {

/// Neighbour directions counter-clockwise from +x: all eight, or the four along the axes.
constexpr int kDi[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDj[8] = {0, 1, 1, 1, 0, -1, -1, -1};

}  // namespace

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
    if (rule() == SlopeRule::Face)
        build_triangulated_graph();
    else
        build_moore_graph();
}

void GridErosion::build_moore_graph() {
    const std::size_t n = height_.size();
    std::vector<std::vector<std::uint32_t>> rows(n);
    std::vector<std::vector<double>> lengths(n);
    for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) {
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

void GridErosion::build_triangulated_graph() {
    const std::size_t n = height_.size();
    std::vector<std::vector<std::uint32_t>> rows(n);
    std::vector<std::vector<double>> lengths(n), across(n);
    const auto inside = [&](int a, int b) { return a >= 0 && b >= 0 && a < nx_ && b < ny_; };
    const double triangle_area = 0.5 * dx_ * dy_;
    for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) {
            // A centre on its own quad's diagonal lies on all four quads' diagonals (the
            // alternation), and has 8 neighbours; the others have the 4 along the axes.
            const int step = diagonal_from_origin(i, j) ? 1 : 2;
            const std::size_t v = index(i, j);
            int faces = 0;
            for (int k = 0; k < 8; k += step) {
                if (!inside(i + kDi[k], j + kDj[k])) continue;
                const int next = (k + step) % 8;
                rows[v].push_back(static_cast<std::uint32_t>(index(i + kDi[k], j + kDj[k])));
                lengths[v].push_back(std::hypot(kDi[k] * dx_, kDj[k] * dy_));
                // Consecutive directions bound a triangle of the quad between them, unless the
                // next neighbour is outside (the gap in a border centre's ring).
                const bool face = inside(i + kDi[next], j + kDj[next]);
                across[v].push_back(
                    face ? std::hypot((kDi[next] - kDi[k]) * dx_, (kDj[next] - kDj[k]) * dy_)
                         : 0.0);
                faces += face ? 1 : 0;
            }
            area_[v] = faces * triangle_area / 3.0;
        }
    }
    graph_.assign(rows, lengths, &across);
}

std::vector<std::array<std::uint32_t, 3>> GridErosion::triangles() const {
    std::vector<std::array<std::uint32_t, 3>> out;
    out.reserve(2 * static_cast<std::size_t>(nx_ - 1) * static_cast<std::size_t>(ny_ - 1));
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(index(i, j)); };
    for (int j = 0; j + 1 < ny_; ++j) {
        for (int i = 0; i + 1 < nx_; ++i) {
            if (diagonal_from_origin(i, j)) {  // diagonal (i, j)-(i + 1, j + 1)
                out.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                out.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            } else {  // diagonal (i + 1, j)-(i, j + 1)
                out.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
                out.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        }
    }
    return out;
}

std::vector<SlopeFace> GridErosion::faces() const {
    std::vector<SlopeFace> out;
    const std::vector<std::array<std::uint32_t, 3>> tris = triangles();
    out.reserve(tris.size());
    for (const auto& t : tris) {
        Vec3 p[3];
        double tan_sum = 0.0;
        bool sand = false;
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = t[k];
            const Vec2 c = centre(static_cast<int>(v % static_cast<std::size_t>(nx_)),
                                  static_cast<int>(v / static_cast<std::size_t>(nx_)));
            p[k] = {c.x, c.y, height_[v]};
            tan_sum += tan_[v];
            sand = sand || height_[v] > bedrock_[v];
        }
        out.push_back({p[0], p[1], p[2], tan_sum / 3.0, sand});
    }
    return out;
}

ReposeProjection GridErosion::settle_by_projection(const ReposeProjectionOptions& options) {
    // The TIN's settle_by_projection, on this mesh: the same solver, where the sand is out of
    // repose only, so the bench compares two discretisations and not two solvers.
    ProjectionInput in;
    in.faces = triangles();
    in.face_tan_alpha.resize(in.faces.size());
    for (std::size_t f = 0; f < in.faces.size(); ++f) {
        const auto& t = in.faces[f];
        in.face_tan_alpha[f] = (tan_[t[0]] + tan_[t[1]] + tan_[t[2]]) / 3.0;
    }
    in.position.resize(height_.size());
    in.bedrock.resize(height_.size());
    for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) {
            in.position[index(i, j)] = centre(i, j);
            const double b = bedrock_[index(i, j)];
            in.bedrock[index(i, j)] =
                b > 0.5 * kNoBedrock ? b : -std::numeric_limits<double>::infinity();
        }
    }
    in.area = area_;
    in.height = height_;
    in.alive.assign(height_.size(), 1);
    ReposeProjection p = project_out_of_repose(in, options);
    height_ = p.height;
    activate_all();
    return p;
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
    const double h00 = height(i, j), h10 = height(i + 1, j), h01 = height(i, j + 1),
                 h11 = height(i + 1, j + 1);
    if (rule() != SlopeRule::Face)
        return (1 - ty) * ((1 - tx) * h00 + tx * h10) + ty * ((1 - tx) * h01 + tx * h11);
    // Linear on the quad's triangle holding p (faces()).
    if (diagonal_from_origin(i, j)) {
        return tx >= ty ? h00 + tx * (h10 - h00) + ty * (h11 - h10)
                        : h00 + ty * (h01 - h00) + tx * (h11 - h01);
    }
    return tx + ty <= 1.0 ? h00 + tx * (h10 - h00) + ty * (h01 - h00)
                          : h11 + (1 - tx) * (h01 - h11) + (1 - ty) * (h10 - h11);
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
