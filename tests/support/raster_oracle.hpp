#pragma once
// Independent oracles for heightmap import: a Terrain-RGB decoder on libpng's simplified API
// (not engine/formats), and a brute-force check of a TIN against every raster sample in long
// double, sharing no code with the greedy insertion it checks.

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin::test {

struct OracleRaster {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    double cell = 1.0;
    std::vector<double> heights;      ///< row-major, row 0 north
    std::vector<std::uint8_t> valid;  ///< empty: all valid
    double at(std::uint32_t col, std::uint32_t row) const {
        return heights[static_cast<std::size_t>(row) * width + col];
    }
};

/// height = -10000 + (R * 65536 + G * 256 + B) * 0.1 (Mapbox Terrain-RGB).
inline OracleRaster read_terrain_rgb(const std::string& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
        throw std::runtime_error("oracle: cannot read " + path + ": " + image.message);
    }
    image.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr)) {
        throw std::runtime_error("oracle: cannot decode " + path + ": " + image.message);
    }
    OracleRaster r;
    r.width = image.width;
    r.height = image.height;
    r.heights.resize(static_cast<std::size_t>(r.width) * r.height);
    for (std::size_t i = 0; i < r.heights.size(); ++i) {
        const double code = rgb[3 * i] * 65536.0 + rgb[3 * i + 1] * 256.0 + rgb[3 * i + 2];
        r.heights[i] = -10000.0 + code * 0.1;
    }
    return r;
}

struct RasterCheck {
    double max_error = 0.0;
    std::size_t uncovered = 0;  ///< samples no triangle contains
    std::size_t samples = 0;    ///< valid samples checked
};

/// Every valid sample (col, row) at (col * cell, (height - 1 - row) * cell) against the TIN
/// surface in the triangle(s) containing it; the error of a sample is the largest over the
/// triangles that contain it (on an edge: both).
inline RasterCheck check_tin_against_raster(const Tin& tin, const OracleRaster& r) {
    using L = long double;
    std::vector<double> worst(r.heights.size(), -1.0);
    const VertexArrays& va = tin.vertices();
    for (const auto& t : tin.triangles()) {
        std::array<L, 3> x{};
        std::array<L, 3> y{};
        std::array<L, 3> z{};
        for (std::size_t k = 0; k < 3; ++k) {
            x[k] = static_cast<L>(va.position[t[k].index()].x) / r.cell;
            y[k] = static_cast<L>(va.position[t[k].index()].y) / r.cell;
            z[k] = va.height[t[k].index()];
        }
        const L area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        const L eps = 1e-12L * std::abs(area);
        const auto c0 = static_cast<long>(std::floor(std::min({x[0], x[1], x[2]})));
        const auto c1 = static_cast<long>(std::ceil(std::max({x[0], x[1], x[2]})));
        const auto j0 = static_cast<long>(std::floor(std::min({y[0], y[1], y[2]})));
        const auto j1 = static_cast<long>(std::ceil(std::max({y[0], y[1], y[2]})));
        for (long j = std::max(0L, j0); j <= std::min<long>(r.height - 1, j1); ++j) {
            for (long c = std::max(0L, c0); c <= std::min<long>(r.width - 1, c1); ++c) {
                const L px = c;
                const L py = j;
                const L w0 = ((x[1] - px) * (y[2] - py) - (y[1] - py) * (x[2] - px)) / area;
                const L w1 = ((x[2] - px) * (y[0] - py) - (y[2] - py) * (x[0] - px)) / area;
                const L w2 = 1.0L - w0 - w1;
                if (w0 * area < -eps || w1 * area < -eps || w2 * std::abs(area) < -eps) continue;
                const std::size_t k = static_cast<std::size_t>(r.height - 1 - j) * r.width +
                                      static_cast<std::size_t>(c);
                const double e =
                    static_cast<double>(std::abs(w0 * z[0] + w1 * z[1] + w2 * z[2] - r.heights[k]));
                worst[k] = std::max(worst[k], e);
            }
        }
    }
    RasterCheck check;
    for (std::size_t k = 0; k < worst.size(); ++k) {
        if (!r.valid.empty() && !r.valid[k]) continue;
        ++check.samples;
        if (worst[k] < 0.0) {
            ++check.uncovered;
            continue;
        }
        check.max_error = std::max(check.max_error, worst[k]);
    }
    return check;
}

}  // namespace sandtin::test
