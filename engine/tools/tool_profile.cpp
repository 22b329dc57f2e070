#include "tools/tool_profile.hpp"

#include "geom/polygon.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

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
    // Rasterise each triangle's height over the grid points it covers: the lowest wins.
    for (const auto& t : mesh.triangles) {
        std::array<Vec2, 3> q;
        std::array<double, 3> z{};
        for (std::size_t k = 0; k < 3; ++k) {
            const auto& v = mesh.vertices[t[k]];
            q[k] = (Vec2{v[0], v[1]} - centre) * scale;
            z[k] = v[2] * scale;
        }
        const double area2 = cross(q[1] - q[0], q[2] - q[0]);
        if (std::abs(area2) < 1e-300) continue;  // vertical triangle: invisible from below
        const Rect tb = bounding_box(std::span<const Vec2>(q));
        const int x0 = std::max(0, static_cast<int>(std::floor((tb.min.x - p.extent_.min.x) / dx)));
        const int x1 = std::min(resolution - 1,
                                static_cast<int>(std::ceil((tb.max.x - p.extent_.min.x) / dx)));
        const int y0 = std::max(0, static_cast<int>(std::floor((tb.min.y - p.extent_.min.y) / dy)));
        const int y1 = std::min(resolution - 1,
                                static_cast<int>(std::ceil((tb.max.y - p.extent_.min.y) / dy)));
        for (int gy = y0; gy <= y1; ++gy) {
            for (int gx = x0; gx <= x1; ++gx) {
                const Vec2 g{p.extent_.min.x + gx * dx, p.extent_.min.y + gy * dy};
                const double w0 = cross(q[1] - g, q[2] - g) / area2;
                const double w1 = cross(q[2] - g, q[0] - g) / area2;
                const double w2 = 1.0 - w0 - w1;
                const double eps = -1e-9;
                if (w0 < eps || w1 < eps || w2 < eps) continue;
                double& cell =
                    p.grid_[static_cast<std::size_t>(gy) * static_cast<std::size_t>(resolution) +
                            static_cast<std::size_t>(gx)];
                cell = std::min(cell, w0 * z[0] + w1 * z[1] + w2 * z[2]);
            }
        }
    }
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
        // Near the edge of a mesh imprint: use the nearest sample that has contact.
        const int nxi = static_cast<int>(std::lround(fx));
        const int nyi = static_cast<int>(std::lround(fy));
        const double v = at(nxi, nyi);
        return std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
    }
    return (1 - ty) * ((1 - tx) * v00 + tx * v10) + ty * ((1 - tx) * v01 + tx * v11);
}

}  // namespace sandtin
