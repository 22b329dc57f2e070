#include "fbm_tile.hpp"

#include <cmath>

#include "physics/talus_kernel.hpp"

namespace sandtin::bench {

namespace {

/// The lattice value at (x, y) of an octave, in [-1, 1): the relaxation's own hash
/// (physics/talus_kernel.hpp), with the octave folded into the seed.
double lattice_value(std::uint64_t seed, std::int64_t x, std::int64_t y, int octave) {
    return signed_unit_hash(seed ^ (static_cast<std::uint64_t>(octave) * 0x165667B19E3779F9ull),
                            static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y));
}

/// Smooth (C1) value noise at (x, y) in lattice units.
double value_noise(std::uint64_t seed, double x, double y, int octave) {
    const double fx = std::floor(x), fy = std::floor(y);
    const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
    const double tx = x - fx, ty = y - fy;
    const double sx = tx * tx * (3.0 - 2.0 * tx), sy = ty * ty * (3.0 - 2.0 * ty);
    const double a = lattice_value(seed, ix, iy, octave);
    const double b = lattice_value(seed, ix + 1, iy, octave);
    const double c = lattice_value(seed, ix, iy + 1, octave);
    const double d = lattice_value(seed, ix + 1, iy + 1, octave);
    return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

}  // namespace

HeightRaster fbm_tile(const FbmTileSpec& spec) {
    HeightRaster r;
    r.width = spec.size;
    r.height = spec.size;
    r.cell_size = spec.cell_size;
    r.source_format = "fbm";
    r.heights.resize(r.size());
    // Octaves down to a wavelength of two samples: finer ones would alias.
    int octaves = 0;
    for (double w = spec.coarsest_cells; w >= 2.0; w *= 0.5)
        ++octaves;
    for (std::uint32_t row = 0; row < spec.size; ++row) {
        for (std::uint32_t col = 0; col < spec.size; ++col) {
            double h = 0.0, amplitude = spec.relief, wavelength = spec.coarsest_cells;
            for (int o = 0; o < octaves; ++o) {
                h += amplitude * value_noise(spec.seed, col / wavelength, row / wavelength, o);
                amplitude *= spec.gain;
                wavelength *= 0.5;
            }
            r.heights[r.index(col, row)] = h;
        }
    }
    return r;
}

}  // namespace sandtin::bench
