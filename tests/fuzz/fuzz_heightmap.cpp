// libFuzzer targets for every heightmap importer: 8/16-bit PNG and Mapbox Terrain-RGB PNG,
// ESRI ASCII grid, OpenEXR and GeoTIFF (through GDAL's in-memory files), selected at compile
// time by SANDTIN_FUZZ_FORMAT. Rasters are capped at 512 x 512 so the fuzzer explores the
// parsers rather than the allocator. Contract: a raster or std::runtime_error, nothing else.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <stdexcept>

#include "io/esri_ascii_grid.hpp"
#include "io/geotiff_gdal.hpp"
#include "io/heightmap_exr.hpp"
#include "io/heightmap_png.hpp"

namespace {

constexpr sandtin::RasterLimits kLimits{512, 512};

void check(const sandtin::HeightRaster& r) {
    // A decoded raster must be consistent: the sizes match the sample count and every
    // sample is finite or flagged as no-data.
    if (r.width == 0 || r.height == 0 || r.width > kLimits.max_width ||
        r.height > kLimits.max_height || r.heights.size() != r.size() ||
        !(r.valid.empty() || r.valid.size() == r.size()) || !std::isfinite(r.cell_size) ||
        !(r.cell_size > 0.0))
        std::abort();
    for (std::size_t i = 0; i < r.heights.size(); ++i) {
        if (r.is_valid(i) && !std::isfinite(r.heights[i])) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> bytes(data, size);
    try {
#if SANDTIN_FUZZ_FORMAT == 1
        const sandtin::PngHeightmap png = sandtin::decode_png_heightmap(
            bytes, "fuzz.png", sandtin::PngHeightEncoding::Auto, kLimits);
        check(png.raster);
#elif SANDTIN_FUZZ_FORMAT == 2
        check(sandtin::parse_esri_ascii_grid(bytes, "fuzz.asc", kLimits, size % 2 == 0));
#elif SANDTIN_FUZZ_FORMAT == 3
        check(sandtin::decode_exr_heightmap(bytes, "fuzz.exr", kLimits, size % 2 == 0));
#elif SANDTIN_FUZZ_FORMAT == 4
        check(sandtin::decode_geotiff(bytes, "fuzz.tif", kLimits, size % 2 == 0, size % 3 == 0,
                                      size % 5 == 0));
#else
#error "SANDTIN_FUZZ_FORMAT must be 1 (PNG), 2 (ESRI), 3 (EXR) or 4 (GeoTIFF)"
#endif
    } catch (const std::runtime_error&) {
    }
    return 0;
}
