#pragma once
// Rasters sampled from height functions, the import tests' fixtures.

#include <cstdint>

#include "geom/vec2.hpp"
#include "io/heightmap_raster.hpp"

namespace sandtin::test {

/// A w x h raster of 1 m cells whose sample at (x, y) metres is f(x, y).
template <class HeightAt>
HeightRaster raster_of(std::uint32_t w, std::uint32_t h, HeightAt&& f) {
    HeightRaster r;
    r.width = w;
    r.height = h;
    r.heights.resize(r.size());
    for (std::uint32_t row = 0; row < h; ++row) {
        for (std::uint32_t col = 0; col < w; ++col) {
            const Vec2 p = r.position(col, row);
            r.heights[r.index(col, row)] = f(p.x, p.y);
        }
    }
    return r;
}

}  // namespace sandtin::test
