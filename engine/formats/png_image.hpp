#pragma once
// PNG reading and writing through libpng. Images are kept as 8- or 16-bit channels in row-major
// order, top row first, exactly as stored.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace sandtin {

struct PngImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int channels = 0;   ///< 1 gray, 2 gray+alpha, 3 RGB, 4 RGBA
    int bit_depth = 0;  ///< 8 or 16
    /// The file was indexed colour with colours in its palette (a palette of greys only is
    /// decoded as grey, with `channels` 1 or 2).
    bool indexed_colour = false;
    /// width * height * channels samples; 8-bit images use only the low byte range.
    std::vector<std::uint16_t> samples;
    /// tEXt key/value pairs (Latin-1), in file order: how sandtin records the height scale of
    /// an exported heightmap next to its samples.
    std::vector<std::pair<std::string, std::string>> text;

    std::uint16_t sample(std::uint32_t x, std::uint32_t y, int channel = 0) const {
        return samples[(static_cast<std::size_t>(y) * width + x) *
                           static_cast<std::size_t>(channels) +
                       static_cast<std::size_t>(channel)];
    }
    /// Largest sample value: 255 or 65535.
    double max_value() const { return bit_depth == 16 ? 65535.0 : 255.0; }
};

struct PngLimits {
    std::uint32_t max_width = 16384;
    std::uint32_t max_height = 16384;
};

/// Decodes a PNG (palette and gray below 8 bits are expanded to 8 bits). Throws
/// std::runtime_error naming `name` for anything that is not a complete, valid PNG within the
/// limits.
PngImage decode_png(std::span<const std::uint8_t> bytes, const std::string& name = "PNG",
                    const PngLimits& limits = {});
PngImage read_png(const std::filesystem::path& path, const PngLimits& limits = {});

/// Encodes an image (1-4 channels, 8 or 16 bits).
std::vector<std::uint8_t> encode_png(const PngImage& image);
/// Writes atomically (temp file + fsync + rename).
void write_png(const std::filesystem::path& path, const PngImage& image);

}  // namespace sandtin
