#include "io/export_maps.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>

#include "formats/png_image.hpp"
#include "io/heightmap_exr.hpp"
#include "io/heightmap_png.hpp"

namespace sandtin {

namespace {

std::string exact(double v) {
    std::array<char, 32> buf{};
    const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    return {buf.data(), end};
}

void add_georeference(PngImage& image, const Georeference& georeference) {
    if (!georeference.known) return;
    image.text.emplace_back(kPngKeyWest, exact(georeference.west));
    image.text.emplace_back(kPngKeySouth, exact(georeference.south));
    if (!georeference.crs.empty()) image.text.emplace_back(kPngKeyCrs, georeference.crs);
    if (!georeference.horizontal_unit.empty())
        image.text.emplace_back(kPngKeyHorizontalUnit, georeference.horizontal_unit);
}

std::vector<std::uint8_t> encode_rgb8(const MapImage& map, double offset, double scale,
                                      const TexelFrame& frame) {
    PngImage image;
    image.width = map.width;
    image.height = map.height;
    image.channels = 3;
    image.bit_depth = 8;
    image.samples.resize(map.values.size());
    for (std::size_t i = 0; i < map.values.size(); ++i) {
        const double v = std::clamp((map.values[i] + offset) * scale, 0.0, 1.0);
        image.samples[i] = static_cast<std::uint16_t>(std::lround(v * 255.0));
    }
    if (frame.texel.x > 0.0) {
        image.text.emplace_back(kPngKeyTexelSize, exact(frame.texel.x));
        if (frame.texel.y > 0.0 && frame.texel.y != frame.texel.x)
            image.text.emplace_back(kPngKeyTexelHeight, exact(frame.texel.y));
    }
    add_georeference(image, frame.georeference);
    return encode_png(image);
}

}  // namespace

double height_png_range(const MapImage& heights) {
    const auto [lo, hi] = std::minmax_element(heights.values.begin(), heights.values.end());
    // A flat map still round-trips, with range 1. So does one flat up to rounding (a sculpted
    // floor at 4.999999999999998 and 5): stretching 1e-15 m of noise over 65535 grey levels
    // would show as noise in any viewer, and re-import would follow it.
    const double magnitude = std::max(std::abs(*lo), std::abs(*hi));
    return *hi - *lo > 1e-12 * magnitude ? *hi - *lo : 1.0;
}

namespace {

/// 16-bit gray from z_min (black) over `range` metres (white), with the keys that let
/// `sandtin import` restore metres.
std::vector<std::uint8_t> encode_gray16(const MapImage& heights, double z_min, double range,
                                        double cell_size, double cell_height,
                                        const Georeference& georeference) {
    PngImage image;
    image.width = heights.width;
    image.height = heights.height;
    image.channels = 1;
    image.bit_depth = 16;
    image.samples.resize(heights.values.size());
    for (std::size_t i = 0; i < heights.values.size(); ++i) {
        const double unit = std::clamp((heights.values[i] - z_min) / range, 0.0, 1.0);
        image.samples[i] = static_cast<std::uint16_t>(std::lround(unit * 65535.0));
    }
    image.text = {{kPngKeyZOffset, exact(z_min)},
                  {kPngKeyZRange, exact(range)},
                  {kPngKeyCellSize, exact(cell_size)}};
    if (cell_height > 0.0 && cell_height != cell_size) {
        image.text.emplace_back(kPngKeyCellHeight, exact(cell_height));
    }
    add_georeference(image, georeference);
    return encode_png(image);
}

}  // namespace

std::vector<std::uint8_t> encode_height_png(const MapImage& heights, double cell_size,
                                            double cell_height, const Georeference& georeference) {
    const double z_min = *std::min_element(heights.values.begin(), heights.values.end());
    return encode_gray16(heights, z_min, height_png_range(heights), cell_size, cell_height,
                         georeference);
}

double water_depth_png_range(const MapImage& depths) {
    const double deepest = *std::max_element(depths.values.begin(), depths.values.end());
    return deepest > 0.0 ? deepest : 1.0;
}

std::vector<std::uint8_t> encode_water_depth_png(const MapImage& depths, double cell_size,
                                                 double cell_height,
                                                 const Georeference& georeference) {
    return encode_gray16(depths, 0.0, water_depth_png_range(depths), cell_size, cell_height,
                         georeference);
}

std::vector<std::uint8_t> encode_height_exr(const MapImage& heights, double cell_size,
                                            double cell_height, const Georeference& georeference) {
    HeightRaster raster;
    raster.georeference = georeference;
    raster.width = heights.width;
    raster.height = heights.height;
    raster.cell_size = cell_size;
    raster.cell_height = cell_height;  // encode_exr_heightmap stores it only when it differs
    raster.heights = heights.values;
    return encode_exr_heightmap(raster);
}

std::vector<std::uint8_t> encode_normal_png(const MapImage& normals, const TexelFrame& frame) {
    return encode_rgb8(normals, 1.0, 0.5, frame);
}

namespace {

/// The 8-bit sRGB code of a linear value (IEC 61966-2-1, rounded to the nearest code): the
/// number of codes whose upper half-step lies at or below it, found in a table of those
/// half-steps decoded to linear. One pow per code once, not one per texel and channel (which
/// made a 1024-texel glTF export a fifth slower).
double srgb8(double linear) {
    static const std::array<double, 255> kUpperHalfStep = [] {
        std::array<double, 255> t{};
        for (std::size_t k = 0; k < t.size(); ++k) {
            const double c = (static_cast<double>(k) + 0.5) / 255.0;
            t[k] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        }
        return t;
    }();
    const auto code = std::upper_bound(kUpperHalfStep.begin(), kUpperHalfStep.end(), linear) -
                      kUpperHalfStep.begin();
    return static_cast<double>(code) / 255.0;
}

}  // namespace

std::vector<std::uint8_t> encode_albedo_png(const MapImage& colours, const TexelFrame& frame) {
    MapImage encoded = colours;
    for (double& v : encoded.values)
        v = srgb8(v);
    return encode_rgb8(encoded, 0.0, 1.0, frame);
}

}  // namespace sandtin
