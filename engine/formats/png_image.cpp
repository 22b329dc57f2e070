#include "formats/png_image.hpp"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <stdexcept>

#include "util/atomic_file.hpp"

namespace sandtin {

namespace {

constexpr png_alloc_size_t kMaxAncillaryChunkBytes = 1u << 20;  ///< per chunk, decompressed
constexpr png_uint_32 kMaxAncillaryChunks = 64;

struct ReadState {
    std::span<const std::uint8_t> bytes;
    std::size_t offset = 0;
    std::string error;
};

void on_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<ReadState*>(png_get_error_ptr(png));
    if (state != nullptr && state->error.empty()) state->error = message;
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

void read_bytes(png_structp png, png_bytep out, png_size_t n) {
    auto* state = static_cast<ReadState*>(png_get_io_ptr(png));
    if (state->offset + n > state->bytes.size()) {
        png_error(png, "file is truncated");
    }
    std::memcpy(out, state->bytes.data() + state->offset, n);
    state->offset += n;
}

// Builds its message in its own frame: temporaries of the string concatenation must not live
// in decode_into's, which longjmp may leave.
[[gnu::noinline]] void report_oversize(ReadState& state, png_uint_32 w, png_uint_32 h,
                                       const PngLimits& limits) {
    state.error = "image of " + std::to_string(w) + " x " + std::to_string(h) +
                  " pixels exceeds the limit of " + std::to_string(limits.max_width) + " x " +
                  std::to_string(limits.max_height);
}

// An indexed image's palette and transparency, copied out of libpng's info struct. Plain data:
// it lives in decode_png's frame and is filled in decode_into's.
struct Palette {
    bool used = false;  ///< the image is indexed colour
    int entries = 0;
    png_color colours[PNG_MAX_PALETTE_LENGTH] = {};
    int transparent = 0;  ///< entries of `alpha` given by tRNS; the rest are opaque
    png_byte alpha[PNG_MAX_PALETTE_LENGTH] = {};
};

// libpng reports errors with longjmp, so no C++ object with a destructor may live in the frame
// that calls setjmp: the decode loop works on plain pointers owned by the caller.
bool decode_into(png_structp png, png_infop info, ReadState& state, const PngLimits& limits,
                 PngImage& image, Palette& palette, std::vector<png_bytep>& rows,
                 std::vector<std::uint8_t>& raw) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, &state, read_bytes);
    png_read_info(png, info);
    const png_uint_32 w = png_get_image_width(png, info);
    const png_uint_32 h = png_get_image_height(png, info);
    if (w == 0 || h == 0) {
        state.error = "image is empty (0 x 0)";
        return false;
    }
    if (w > limits.max_width || h > limits.max_height) {
        report_oversize(state, w, h, limits);
        return false;
    }
    const int color = png_get_color_type(png, info);
    int depth = png_get_bit_depth(png, info);
    if (color == PNG_COLOR_TYPE_PALETTE) {
        // Indices are read as they are, one byte each, and looked up by expand_palette: libpng's
        // own expansion turns an index past the palette into black without a word (its
        // palette-index check does not run on 8-bit images once expansion is on).
        png_set_packing(png);
        png_colorp colours = nullptr;
        png_get_PLTE(png, info, &colours, &palette.entries);
        palette.used = true;
        for (int i = 0; i < palette.entries && i < PNG_MAX_PALETTE_LENGTH; ++i)
            palette.colours[i] = colours[i];
        png_bytep alpha = nullptr;
        if (png_get_tRNS(png, info, &alpha, &palette.transparent, nullptr) == 0 ||
            alpha == nullptr) {
            palette.transparent = 0;
        }
        for (int i = 0; i < palette.transparent && i < PNG_MAX_PALETTE_LENGTH; ++i)
            palette.alpha[i] = alpha[i];
    } else {
        if (color == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
        if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
        if (depth == 16) png_set_swap(png);  // little-endian samples in memory
    }
    png_read_update_info(png, info);
    depth = png_get_bit_depth(png, info);
    const int channels = png_get_channels(png, info);
    const std::size_t row_bytes = png_get_rowbytes(png, info);
    raw.resize(row_bytes * h);
    rows.resize(h);
    for (png_uint_32 y = 0; y < h; ++y)
        rows[y] = raw.data() + row_bytes * y;
    png_read_image(png, rows.data());
    png_read_end(png, info);
    png_textp text = nullptr;
    const int text_count = png_get_text(png, info, &text, nullptr);
    for (int i = 0; i < text_count; ++i) {
        image.text.emplace_back(text[i].key, text[i].text != nullptr ? text[i].text : "");
    }
    image.width = w;
    image.height = h;
    image.channels = channels;
    image.bit_depth = depth;
    return true;
}

// Looks the indices in `raw` (one byte per pixel) up in the palette. A palette of greys is a
// grey image saved by an image editor as indexed colour: it becomes grey. tRNS adds alpha.
void expand_palette(const Palette& palette, const std::vector<std::uint8_t>& raw,
                    const std::string& name, PngImage& image) {
    bool grey = true;
    for (int i = 0; grey && i < palette.entries; ++i) {
        const png_color& c = palette.colours[i];
        grey = c.red == c.green && c.red == c.blue;
    }
    const bool alpha = palette.transparent > 0;
    image.indexed_colour = !grey;
    image.channels = (grey ? 1 : 3) + (alpha ? 1 : 0);
    image.bit_depth = 8;
    const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
    image.samples.resize(pixels * static_cast<std::size_t>(image.channels));
    std::uint16_t* out = image.samples.data();
    for (std::size_t p = 0; p < pixels; ++p) {
        const int index = raw[p];
        if (index >= palette.entries) {
            throw std::runtime_error(
                name + ": invalid PNG: pixel (" + std::to_string(p % image.width) + ", " +
                std::to_string(p / image.width) + ") uses palette index " + std::to_string(index) +
                ", but the palette has only " + std::to_string(palette.entries) + " entries");
        }
        const png_color& c = palette.colours[index];
        *out++ = c.red;
        if (!grey) {
            *out++ = c.green;
            *out++ = c.blue;
        }
        if (alpha) *out++ = index < palette.transparent ? palette.alpha[index] : 255;
    }
}

}  // namespace

PngImage decode_png(std::span<const std::uint8_t> bytes, const std::string& name,
                    const PngLimits& limits) {
    if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) {
        throw std::runtime_error(name + ": not a PNG file (bad signature)");
    }
    // The size from IHDR (always the first chunk) before libpng sees it: libpng reports an
    // empty or over-limit image only as "Invalid IHDR data".
    if (bytes.size() >= 24 && std::memcmp(bytes.data() + 12, "IHDR", 4) == 0) {
        const auto be32 = [&](std::size_t at) {
            return (std::uint32_t{bytes[at]} << 24) | (std::uint32_t{bytes[at + 1]} << 16) |
                   (std::uint32_t{bytes[at + 2]} << 8) | std::uint32_t{bytes[at + 3]};
        };
        const std::uint32_t w = be32(16);
        const std::uint32_t h = be32(20);
        if (w == 0 || h == 0) {
            throw std::runtime_error(name + ": invalid PNG: image is empty (" + std::to_string(w) +
                                     " x " + std::to_string(h) + ")");
        }
        if (w > limits.max_width || h > limits.max_height) {
            throw std::runtime_error(name + ": image of " + std::to_string(w) + " x " +
                                     std::to_string(h) + " pixels exceeds the limit of " +
                                     std::to_string(limits.max_width) + " x " +
                                     std::to_string(limits.max_height));
        }
    }
    // Every chunk must fit in the bytes we have: libpng allocates a chunk's buffer from its
    // length field before reading it (found by fuzzing: a 93-byte file made it ask for 553 MB).
    // The file is in memory, so no legitimate chunk is longer than what remains.
    {
        const auto be32 = [&](std::size_t at) {
            return (std::uint32_t{bytes[at]} << 24) | (std::uint32_t{bytes[at + 1]} << 16) |
                   (std::uint32_t{bytes[at + 2]} << 8) | std::uint32_t{bytes[at + 3]};
        };
        std::size_t at = 8;
        while (at + 8 <= bytes.size()) {
            const std::size_t length = be32(at);
            if (length > bytes.size() - at - 8) {
                throw std::runtime_error(
                    name + ": invalid PNG: chunk at byte " + std::to_string(at) + " claims " +
                    std::to_string(length) + " bytes but the file has only " +
                    std::to_string(bytes.size() - at - 8) + " left (truncated or corrupted)");
            }
            if (std::memcmp(bytes.data() + at + 4, "IEND", 4) == 0) break;
            at += 12 + length;
        }
    }
    ReadState state;
    state.bytes = bytes;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
    if (png == nullptr) throw std::runtime_error(name + ": cannot initialise libpng");
    png_infop info = png_create_info_struct(png);
    if (info == nullptr) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw std::runtime_error(name + ": cannot initialise libpng");
    }
    png_set_user_limits(png, limits.max_width, limits.max_height);
    // Ancillary chunks (our tEXt metadata, anything else) are tiny; without a cap libpng
    // allocates whatever a chunk's length field claims (found by fuzzing: a 93-byte file asked
    // for 553 MB), and a crafted zTXt could inflate without bound.
    png_set_chunk_malloc_max(png, kMaxAncillaryChunkBytes);
    png_set_chunk_cache_max(png, kMaxAncillaryChunks);
    PngImage image;
    Palette palette;
    std::vector<png_bytep> rows;
    std::vector<std::uint8_t> raw;
    const bool ok = decode_into(png, info, state, limits, image, palette, rows, raw);
    png_destroy_read_struct(&png, &info, nullptr);
    if (!ok) throw std::runtime_error(name + ": invalid PNG: " + state.error);
    if (palette.used) {
        expand_palette(palette, raw, name, image);
        return image;
    }
    const std::size_t n = static_cast<std::size_t>(image.width) * image.height *
                          static_cast<std::size_t>(image.channels);
    image.samples.resize(n);
    if (image.bit_depth == 16) {
        std::memcpy(image.samples.data(), raw.data(), n * 2);
    } else {
        for (std::size_t i = 0; i < n; ++i)
            image.samples[i] = raw[i];
    }
    return image;
}

PngImage read_png(const std::filesystem::path& path, const PngLimits& limits) {
    const std::vector<std::uint8_t> bytes = read_file(path, 1ull << 32);
    if (bytes.empty()) throw std::runtime_error(path.string() + ": file is empty");
    return decode_png(bytes, path.string(), limits);
}

namespace {

struct WriteState {
    std::vector<std::uint8_t> out;
    std::string error;
};

void write_bytes(png_structp png, png_bytep data, png_size_t n) {
    auto* state = static_cast<WriteState*>(png_get_io_ptr(png));
    state->out.insert(state->out.end(), data, data + n);
}

void flush_nothing(png_structp) {}

void on_write_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<WriteState*>(png_get_error_ptr(png));
    if (state != nullptr && state->error.empty()) state->error = message;
    png_longjmp(png, 1);
}

bool encode_into(png_structp png, png_infop info, WriteState& state, const PngImage& image,
                 std::vector<png_bytep>& rows, std::vector<png_text>& text) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_write_fn(png, &state, write_bytes, flush_nothing);
    const int type = image.channels == 1   ? PNG_COLOR_TYPE_GRAY
                     : image.channels == 2 ? PNG_COLOR_TYPE_GRAY_ALPHA
                     : image.channels == 3 ? PNG_COLOR_TYPE_RGB
                                           : PNG_COLOR_TYPE_RGBA;
    png_set_IHDR(png, info, image.width, image.height, image.bit_depth, type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!text.empty()) png_set_text(png, info, text.data(), static_cast<int>(text.size()));
    png_write_info(png, info);
    if (image.bit_depth == 16) png_set_swap(png);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    return true;
}

}  // namespace

std::vector<std::uint8_t> encode_png(const PngImage& image) {
    if (image.width == 0 || image.height == 0 || image.channels < 1 || image.channels > 4 ||
        (image.bit_depth != 8 && image.bit_depth != 16) ||
        image.samples.size() != static_cast<std::size_t>(image.width) * image.height *
                                    static_cast<std::size_t>(image.channels)) {
        throw std::invalid_argument("encode_png: inconsistent image description");
    }
    const std::size_t row_samples =
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.channels);
    const std::size_t bytes_per_sample = image.bit_depth == 16 ? 2 : 1;
    std::vector<std::uint8_t> raw(row_samples * bytes_per_sample * image.height);
    if (image.bit_depth == 16) {
        std::memcpy(raw.data(), image.samples.data(), raw.size());
    } else {
        for (std::size_t i = 0; i < image.samples.size(); ++i) {
            raw[i] = static_cast<std::uint8_t>(std::min<std::uint16_t>(image.samples[i], 255));
        }
    }
    std::vector<png_bytep> rows(image.height);
    for (std::uint32_t y = 0; y < image.height; ++y)
        rows[y] = raw.data() + row_samples * bytes_per_sample * y;
    // libpng takes non-const char pointers but does not write through them.
    std::vector<png_text> text(image.text.size());
    for (std::size_t i = 0; i < image.text.size(); ++i) {
        text[i].compression = PNG_TEXT_COMPRESSION_NONE;
        text[i].key = const_cast<char*>(image.text[i].first.c_str());
        text[i].text = const_cast<char*>(image.text[i].second.c_str());
        text[i].text_length = image.text[i].second.size();
    }
    WriteState state;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_write_error, on_warning);
    if (png == nullptr) throw std::runtime_error("encode_png: cannot initialise libpng");
    png_infop info = png_create_info_struct(png);
    const bool ok = info != nullptr && encode_into(png, info, state, image, rows, text);
    png_destroy_write_struct(&png, &info);
    if (!ok) throw std::runtime_error("encode_png: " + state.error);
    return std::move(state.out);
}

void write_png(const std::filesystem::path& path, const PngImage& image) {
    write_file_atomically(path, encode_png(image));
}

}  // namespace sandtin
