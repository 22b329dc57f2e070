#pragma once
// Rough synthetic elevation tiles for `sandtin bench import` (issue 41 item 6): fractional
// Brownian motion, a sum of octaves of smooth lattice noise, each twice as fine and `gain` times
// as strong as the last. With a gain near 0.6 most of the relief's detail sits at the finest
// octaves, which is what makes a tile expensive for any TIN to fit (a real mountain tile
// behaves alike; bay-hills is gentle by comparison). Deterministic: the seed fixes every value
// on every platform (integer hashing, no std:: distributions).

#include <cstdint>

#include "io/heightmap_raster.hpp"

namespace sandtin::bench {

struct FbmTileSpec {
    std::uint32_t size = 512;       ///< samples per side
    double cell_size = 30.0;        ///< metres between samples (a 1 arc-second DEM)
    double relief = 1500.0;         ///< metres: the coarsest octave's amplitude
    double gain = 0.6;              ///< amplitude ratio between consecutive octaves
    double coarsest_cells = 256.0;  ///< wavelength of the coarsest octave, in samples
    std::uint64_t seed = 1;
};

/// The tile: heights in metres, row-major, every sample valid.
HeightRaster fbm_tile(const FbmTileSpec& spec);

}  // namespace sandtin::bench
