#include "io/heightmap_png.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace sandtin {

namespace {

/// The text sandtin recorded under `key`. A key given twice with different values is an
/// error: the file was edited by hand or by a tool that appended, and which value holds is a guess.
std::optional<std::string> text_value(const PngImage& image, const char* key,
                                      const std::string& name) {
    const std::string* value = nullptr;
    for (const auto& [k, v] : image.text) {
        if (k != key) continue;
        if (value != nullptr && *value != v) {
            throw std::runtime_error(name + ": the PNG text chunk '" + k +
                                     "' is given twice, as '" + *value + "' and as '" + v +
                                     "'; only one can count");
        }
        value = &v;
    }
    if (value == nullptr) return std::nullopt;
    return *value;
}

/// The number sandtin recorded under `key`.
std::optional<double> text_number(const PngImage& image, const char* key, const std::string& name) {
    const std::optional<std::string> value = text_value(image, key, name);
    if (!value) return std::nullopt;
    double x = 0.0;
    const auto [end, ec] = std::from_chars(value->data(), value->data() + value->size(), x);
    if (ec != std::errc() || end != value->data() + value->size() || !std::isfinite(x)) {
        throw std::runtime_error(name + ": the PNG text chunk '" + std::string(key) + "' holds '" +
                                 *value + "', not a finite number");
    }
    return x;
}

/// Whether an RGB(A) image has R = G = B in every pixel.
bool every_pixel_is_grey(const PngImage& image) {
    const auto channels = static_cast<std::size_t>(image.channels);
    for (std::size_t i = 0; i < image.samples.size(); i += channels) {
        const std::uint16_t* px = image.samples.data() + i;
        if (px[0] != px[1] || px[0] != px[2]) return false;
    }
    return true;
}

}  // namespace

PngHeightmap decode_png_heightmap(std::span<const std::uint8_t> bytes, const std::string& name,
                                  PngHeightEncoding encoding, const RasterLimits& limits) {
    if (bytes.empty()) throw std::runtime_error(name + ": file is empty");
    PngLimits png_limits;
    png_limits.max_width = limits.max_width;
    png_limits.max_height = limits.max_height;
    const PngImage image = decode_png(bytes, name, png_limits);
    check_raster_size(image.width, image.height, name, limits);

    // A grey heightmap that an image editor saved as RGB(A) has R = G = B in every pixel. Read
    // as Terrain-RGB it would span kilometres; no real Terrain-RGB tile is grey throughout.
    const bool neutral_colour = image.channels >= 3 && encoding != PngHeightEncoding::TerrainRgb &&
                                every_pixel_is_grey(image);
    const bool gray = image.channels <= 2 || neutral_colour;
    if (encoding == PngHeightEncoding::Gray && !gray) {
        throw std::runtime_error(name + ": a grayscale heightmap was expected, but the PNG has " +
                                 std::to_string(image.channels) +
                                 " channels whose pixels are not all grey (R = G = B)");
    }
    if (encoding == PngHeightEncoding::TerrainRgb &&
        (image.channels <= 2 || image.bit_depth != 8)) {
        throw std::runtime_error(name +
                                 ": Terrain-RGB needs an 8-bit RGB or RGBA PNG, but this one has " +
                                 std::to_string(image.channels) + " channel(s) of " +
                                 std::to_string(image.bit_depth) + " bits");
    }
    if (encoding == PngHeightEncoding::Auto && image.indexed_colour && !gray) {
        throw std::runtime_error(name +
                                 ": an indexed-colour PNG with colours in its palette is not a "
                                 "heightmap encoding sandtin knows (use grey, or force "
                                 "Terrain-RGB if its colours are Terrain-RGB codes)");
    }
    if (!gray && image.bit_depth != 8) {
        throw std::runtime_error(name +
                                 ": a 16-bit colour PNG is not a heightmap encoding "
                                 "sandtin knows (use 8/16-bit gray or 8-bit Terrain-RGB)");
    }

    PngHeightmap out;
    HeightRaster& r = out.raster;
    r.width = image.width;
    r.height = image.height;
    r.heights.resize(r.size());
    const bool has_alpha = image.channels == 2 || image.channels == 4;
    if (has_alpha) r.valid.assign(r.size(), 1);

    if (gray) {
        out.z_offset = text_number(image, kPngKeyZOffset, name);
        out.z_range = text_number(image, kPngKeyZRange, name);
    }
    out.cell_size = text_number(image, kPngKeyCellSize, name);
    if (out.cell_size && !(*out.cell_size > 0.0)) {
        throw std::runtime_error(name + ": the PNG's cell size must be positive");
    }
    // Both coordinates or neither: one alone places nothing.
    const std::optional<double> west = text_number(image, kPngKeyWest, name);
    const std::optional<double> south = text_number(image, kPngKeySouth, name);
    if (west.has_value() != south.has_value()) {
        throw std::runtime_error(name + ": the PNG gives '" + (west ? kPngKeyWest : kPngKeySouth) +
                                 "' without '" + (west ? kPngKeySouth : kPngKeyWest) + "'");
    }
    if (west) {
        r.georeference.known = true;
        r.georeference.west = *west;
        r.georeference.south = *south;
        r.georeference.crs = text_value(image, kPngKeyCrs, name).value_or("");
        r.georeference.horizontal_unit =
            text_value(image, kPngKeyHorizontalUnit, name).value_or("");
    }
    out.cell_height = text_number(image, kPngKeyCellHeight, name);
    if (out.cell_height && !(*out.cell_height > 0.0)) {
        throw std::runtime_error(name + ": the PNG's cell height must be positive");
    }

    const auto channels = static_cast<std::size_t>(image.channels);
    const double max_value = image.max_value();
    for (std::size_t i = 0; i < r.size(); ++i) {
        const std::uint16_t* px = image.samples.data() + i * channels;
        if (has_alpha && px[channels - 1] == 0) r.valid[i] = 0;
        if (gray) {
            r.heights[i] = px[0] / max_value;
        } else {
            const double code = px[0] * 65536.0 + px[1] * 256.0 + px[2];
            r.heights[i] = -10000.0 + code * 0.1;
        }
    }
    r.source_format = gray ? (image.bit_depth == 16 ? "png-gray16" : "png-gray8") : "terrain-rgb";
    return out;
}

}  // namespace sandtin
