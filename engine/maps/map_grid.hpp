#pragma once
// Where a baked map samples the terrain. Row 0 is the north (max y) edge, as in images.
//
//  - Corners: samples on the domain's corners and edges, (W - 1) x (H - 1) cells; what a
//    heightmap needs so that re-importing it reproduces the domain exactly.
//  - Centres: samples at texel centres, W x H texels covering the domain; what a texture on a
//    mesh with u = (x - x0) / width, v = (y1 - y) / height needs.

#include <cstdint>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

enum class SampleAt : std::uint8_t { Corners, Centres };

struct MapGrid {
    Rect domain;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    SampleAt at = SampleAt::Centres;

    /// Throws std::invalid_argument for an empty domain or size (Corners needs >= 2 x 2) or
    /// more than 2^28 samples.
    MapGrid(Rect domain, std::uint32_t width, std::uint32_t height, SampleAt at);

    std::size_t size() const { return static_cast<std::size_t>(width) * height; }
    /// Position of sample (col, row), metres.
    Vec2 position(std::uint32_t col, std::uint32_t row) const;
    /// Continuous sample coordinates (col, row) of a point: the inverse of position().
    Vec2 to_grid(Vec2 p) const;
    /// Metres between neighbouring samples: (between columns, between rows).
    Vec2 spacing() const;
};

/// A baked map: `channels` doubles per sample, row-major, row 0 north.
struct MapImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int channels = 1;
    std::vector<double> values;

    double& at(std::uint32_t col, std::uint32_t row, int channel = 0) {
        return values[(static_cast<std::size_t>(row) * width + col) *
                          static_cast<std::size_t>(channels) +
                      static_cast<std::size_t>(channel)];
    }
    double at(std::uint32_t col, std::uint32_t row, int channel = 0) const {
        return values[(static_cast<std::size_t>(row) * width + col) *
                          static_cast<std::size_t>(channels) +
                      static_cast<std::size_t>(channel)];
    }
};

}  // namespace sandtin
