#include "tools/tool_profile.hpp"

#include "geom/polygon.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

namespace sandtin {

ToolProfile ToolProfile::flat() {
    return ToolProfile{};
}

ToolProfile ToolProfile::half_sphere(double radius) {
    if (!(radius > 0.0) || !std::isfinite(radius)) {
        throw std::invalid_argument("half-sphere profile: radius must be positive");
    }
    ToolProfile p;
    p.kind_ = Kind::HalfSphere;
    p.radius_ = radius;
    p.sample_spacing_ = radius / 16.0;
    return p;
}

ToolProfile ToolProfile::heightfield(const PngImage& image, const Rect& extent, double relief) {
    if (image.width < 2 || image.height < 2) {
        throw std::invalid_argument("heightfield profile: the image needs at least 2 x 2 pixels");
    }
    if (extent.empty() || !(extent.width() > 0.0) || !(extent.height() > 0.0)) {
        throw std::invalid_argument("heightfield profile: the extent must have positive size");
    }
    if (!(relief >= 0.0) || !std::isfinite(relief)) {
        throw std::invalid_argument(
            "heightfield profile: relief must be a non-negative number of metres");
    }
    ToolProfile p;
    p.kind_ = Kind::Grid;
    p.extent_ = extent;
    p.nx_ = static_cast<int>(image.width);
    p.ny_ = static_cast<int>(image.height);
    p.grid_.resize(static_cast<std::size_t>(p.nx_) * static_cast<std::size_t>(p.ny_));
    const int luminance_channels = image.channels >= 3 ? 3 : 1;
    for (int y = 0; y < p.ny_; ++y) {
        for (int x = 0; x < p.nx_; ++x) {
            double v = 0.0;
            for (int c = 0; c < luminance_channels; ++c) {
                v += image.sample(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), c);
            }
            v /= luminance_channels * image.max_value();
            // Image row 0 is the top (max y) of the extent.
            p.grid_[static_cast<std::size_t>(p.ny_ - 1 - y) * static_cast<std::size_t>(p.nx_) +
                    static_cast<std::size_t>(x)] = v * relief;
        }
    }
    const double lowest = *std::min_element(p.grid_.begin(), p.grid_.end());
    for (double& v : p.grid_)
        v -= lowest;
    p.sample_spacing_ = std::max(extent.width() / (p.nx_ - 1), extent.height() / (p.ny_ - 1)) * 2.0;
    return p;
}

namespace {

/// A mesh triangle seen from below: its corners in the plane (tool metres) and their heights.
struct Triangle {
    std::array<Vec2, 3> q;
    std::array<double, 3> z{};
};

std::size_t grid_index(int gx, int gy, int resolution) {
    return static_cast<std::size_t>(gy) * static_cast<std::size_t>(resolution) +
           static_cast<std::size_t>(gx);
}

/// The grid points a box covers, widened by `margin` cells: [x0, x1] x [y0, y1].
std::array<int, 4> grid_span(const Rect& box, const Rect& extent, int resolution, double dx,
                             double dy, int margin) {
    const int x0 =
        std::max(0, static_cast<int>(std::floor((box.min.x - extent.min.x) / dx)) - margin);
    const int x1 = std::min(resolution - 1,
                            static_cast<int>(std::ceil((box.max.x - extent.min.x) / dx)) + margin);
    const int y0 =
        std::max(0, static_cast<int>(std::floor((box.min.y - extent.min.y) / dy)) - margin);
    const int y1 = std::min(resolution - 1,
                            static_cast<int>(std::ceil((box.max.y - extent.min.y) / dy)) + margin);
    return {x0, x1, y0, y1};
}

/// Each triangle's height over the grid points it covers: the lowest wins. Points no triangle
/// covers stay +infinity.
void rasterise_envelope(std::span<const Triangle> triangles, const Rect& extent, int resolution,
                        double dx, double dy, std::vector<double>& grid) {
    for (const Triangle& t : triangles) {
        const double area2 = cross(t.q[1] - t.q[0], t.q[2] - t.q[0]);
        const auto [x0, x1, y0, y1] =
            grid_span(bounding_box(std::span<const Vec2>(t.q)), extent, resolution, dx, dy, 0);
        for (int gy = y0; gy <= y1; ++gy) {
            for (int gx = x0; gx <= x1; ++gx) {
                const Vec2 g{extent.min.x + gx * dx, extent.min.y + gy * dy};
                const double w0 = cross(t.q[1] - g, t.q[2] - g) / area2;
                const double w1 = cross(t.q[2] - g, t.q[0] - g) / area2;
                const double w2 = 1.0 - w0 - w1;
                const double eps = -1e-9;
                if (w0 < eps || w1 < eps || w2 < eps) continue;
                double& cell = grid[grid_index(gx, gy, resolution)];
                cell = std::min(cell, w0 * t.z[0] + w1 * t.z[1] + w2 * t.z[2]);
            }
        }
    }
}

/// Grid points outside the mesh but within a cell's diagonal of it take the height of its
/// nearest point (a skirt): then the four samples around any point of the mesh all have
/// contact, and the interpolated underside holds up to the mesh's own outline. Without it a
/// point on the outline (every point of a contour_from_mesh tool's inner contour) often fell
/// in a cell with no-contact corners.
void add_skirt(std::span<const Triangle> triangles, const Rect& extent, int resolution, double dx,
               double dy, std::vector<double>& grid) {
    const double reach = std::hypot(dx, dy);
    std::vector<double> skirt(grid.size(), std::numeric_limits<double>::infinity());
    std::vector<double> skirt_distance(grid.size(), std::numeric_limits<double>::infinity());
    for (const Triangle& t : triangles) {
        const auto [x0, x1, y0, y1] =
            grid_span(bounding_box(std::span<const Vec2>(t.q)), extent, resolution, dx, dy, 2);
        for (int gy = y0; gy <= y1; ++gy) {
            for (int gx = x0; gx <= x1; ++gx) {
                const std::size_t i = grid_index(gx, gy, resolution);
                if (std::isfinite(grid[i])) continue;  // on the mesh
                const Vec2 g{extent.min.x + gx * dx, extent.min.y + gy * dy};
                for (std::size_t k = 0; k < 3; ++k) {
                    const Vec2 a = t.q[k];
                    const Vec2 b = t.q[(k + 1) % 3];
                    const double len2 = length_squared(b - a);
                    const double u =
                        len2 > 0.0 ? std::clamp(dot(g - a, b - a) / len2, 0.0, 1.0) : 0.0;
                    const double d = distance(g, lerp(a, b, u));
                    const double z = (1.0 - u) * t.z[k] + u * t.z[(k + 1) % 3];
                    if (d > reach || d > skirt_distance[i]) continue;
                    skirt[i] = d < skirt_distance[i] ? z : std::min(skirt[i], z);
                    skirt_distance[i] = d;
                }
            }
        }
    }
    for (std::size_t i = 0; i < grid.size(); ++i) {
        if (!std::isfinite(grid[i])) grid[i] = skirt[i];
    }
}

}  // namespace

ToolProfile ToolProfile::mesh_imprint(const TriangleMesh& mesh, double scale, int resolution) {
    if (mesh.triangles.empty())
        throw std::invalid_argument("mesh imprint: the mesh has no triangles");
    if (!(scale > 0.0) || !std::isfinite(scale))
        throw std::invalid_argument("mesh imprint: scale must be positive");
    if (resolution < 8 || resolution > 4096)
        throw std::invalid_argument("mesh imprint: resolution must lie in 8..4096");
    Rect box;
    for (const auto& v : mesh.vertices)
        box.expand(Vec2{v[0], v[1]});
    if (!(box.width() > 0.0) || !(box.height() > 0.0)) {
        throw std::invalid_argument("mesh imprint: the mesh has no extent in x and y");
    }
    const Vec2 centre = box.centre();
    ToolProfile p;
    p.kind_ = Kind::Grid;
    p.extent_ = Rect{(box.min - centre) * scale, (box.max - centre) * scale};
    p.nx_ = resolution;
    p.ny_ = resolution;
    p.grid_.assign(static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution),
                   std::numeric_limits<double>::infinity());
    const double dx = p.extent_.width() / (resolution - 1);
    const double dy = p.extent_.height() / (resolution - 1);
    std::vector<Triangle> projected;
    projected.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        Triangle tri;
        for (std::size_t k = 0; k < 3; ++k) {
            const auto& v = mesh.vertices[t[k]];
            tri.q[k] = (Vec2{v[0], v[1]} - centre) * scale;
            tri.z[k] = v[2] * scale;
        }
        // A vertical triangle is invisible from below.
        if (std::abs(cross(tri.q[1] - tri.q[0], tri.q[2] - tri.q[0])) >= 1e-300)
            projected.push_back(tri);
    }
    rasterise_envelope(projected, p.extent_, resolution, dx, dy, p.grid_);
    add_skirt(projected, p.extent_, resolution, dx, dy, p.grid_);
    double lowest = std::numeric_limits<double>::infinity();
    for (double v : p.grid_)
        lowest = std::min(lowest, v);
    if (!std::isfinite(lowest))
        throw std::invalid_argument("mesh imprint: the mesh covers no grid point");
    for (double& v : p.grid_)
        v = std::isfinite(v) ? v - lowest : std::numeric_limits<double>::quiet_NaN();
    p.sample_spacing_ = 2.0 * std::max(dx, dy);
    return p;
}

double ToolProfile::offset(Vec2 q) const {
    switch (kind_) {
        case Kind::Flat:
            return 0.0;
        case Kind::HalfSphere: {
            const double r2 = radius_ * radius_ - length_squared(q);
            return r2 > 0.0 ? radius_ - std::sqrt(r2) : radius_;
        }
        case Kind::Grid:
            break;
    }
    // Bilinear interpolation, clamped to the grid; no-contact cells poison their neighbourhood.
    const double fx =
        std::clamp((q.x - extent_.min.x) / extent_.width() * (nx_ - 1), 0.0, nx_ - 1.0);
    const double fy =
        std::clamp((q.y - extent_.min.y) / extent_.height() * (ny_ - 1), 0.0, ny_ - 1.0);
    const int x0 = std::min(static_cast<int>(fx), nx_ - 2);
    const int y0 = std::min(static_cast<int>(fy), ny_ - 2);
    const double tx = fx - x0;
    const double ty = fy - y0;
    auto at = [&](int x, int y) {
        return grid_[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) +
                     static_cast<std::size_t>(x)];
    };
    const double v00 = at(x0, y0), v10 = at(x0 + 1, y0), v01 = at(x0, y0 + 1),
                 v11 = at(x0 + 1, y0 + 1);
    if (std::isnan(v00) || std::isnan(v10) || std::isnan(v01) || std::isnan(v11)) {
        // A cell the edge of a mesh imprint crosses: the bilinear blend of the samples that
        // have contact, re-weighted. The nearest sample alone (which it was) said "no contact"
        // at 39 of the shipped foot's 72 outline points, whose nearest sample lay just outside
        // the sole, and extrusion, which weights the ridge by the cut at each outline point,
        // heaped the sand in radial stripes beside the other 33. Each weight is kept above a
        // hair, so a point on the cell's side away from those samples (the sole's tip, on the
        // side of its bounding box) still gets their blend along that side.
        constexpr double kHair = 1e-9;
        const std::array<double, 2> wx = {std::max(1.0 - tx, kHair), std::max(tx, kHair)};
        const std::array<double, 2> wy = {std::max(1.0 - ty, kHair), std::max(ty, kHair)};
        const std::array<double, 4> value = {v00, v10, v01, v11};
        double sum = 0.0;
        double total = 0.0;
        for (std::size_t k = 0; k < 4; ++k) {
            if (std::isnan(value[k])) continue;
            const double w = wx[k % 2] * wy[k / 2];
            sum += w * value[k];
            total += w;
        }
        return total > 0.0 ? sum / total : std::numeric_limits<double>::infinity();
    }
    return (1 - ty) * ((1 - tx) * v00 + tx * v10) + ty * ((1 - tx) * v01 + tx * v11);
}

double ToolProfile::tip_length() const {
    if (kind_ != Kind::Grid) return std::numeric_limits<double>::infinity();
    double relief = 0.0;
    for (double v : grid_) {
        if (!std::isnan(v)) relief = std::max(relief, v);
    }
    const double band = kTipBand * relief;
    const auto nx = static_cast<std::size_t>(nx_);
    const std::size_t cells = grid_.size();
    auto in_tip = [&](std::size_t i) { return !std::isnan(grid_[i]) && grid_[i] <= band; };
    // Label the tips (4-connected), then measure each one's longest run along x.
    std::vector<std::int32_t> tip(cells, -1);
    std::int32_t tips = 0;
    std::vector<std::size_t> stack;
    for (std::size_t start = 0; start < cells; ++start) {
        if (tip[start] >= 0 || !in_tip(start)) continue;
        tip[start] = tips;
        stack.assign(1, start);
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            const std::size_t x = i % nx;
            const std::array<std::size_t, 4> next = {x > 0 ? i - 1 : i, x + 1 < nx ? i + 1 : i,
                                                     i >= nx ? i - nx : i,
                                                     i + nx < cells ? i + nx : i};
            for (std::size_t j : next) {
                if (tip[j] < 0 && in_tip(j)) {
                    tip[j] = tips;
                    stack.push_back(j);
                }
            }
        }
        ++tips;
    }
    std::vector<std::size_t> longest(static_cast<std::size_t>(tips), 0);
    for (std::size_t row = 0; row < cells; row += nx) {
        std::size_t run = 0;
        for (std::size_t x = 0; x < nx; ++x) {
            const std::int32_t t = tip[row + x];
            run = t >= 0 && x > 0 && tip[row + x - 1] == t ? run + 1 : (t >= 0 ? 1 : 0);
            if (t >= 0) {
                std::size_t& l = longest[static_cast<std::size_t>(t)];
                l = std::max(l, run);
            }
        }
    }
    const double dx = extent_.width() / (nx_ - 1);
    double shortest = std::numeric_limits<double>::infinity();
    for (std::size_t l : longest)
        shortest = std::min(shortest, static_cast<double>(l) * dx);
    return shortest;
}

}  // namespace sandtin
