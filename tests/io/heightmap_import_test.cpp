// Heightmap readers: every format decodes what it should (GeoTIFF: heightmap_geotiff_test.cpp),
// and every kind of bad input is rejected with a message that names the problem, never a crash.

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <gtest/gtest.h>

#include <zlib.h>
#include <algorithm>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "formats/png_image.hpp"
#include "heightmap_test_files.hpp"
#include "io/heightmap_exr.hpp"
#include "io/heightmap_import.hpp"
#include "io/heightmap_png.hpp"

namespace sandtin {
namespace {

using namespace heightmap_test;

std::vector<std::uint8_t> bytes_of(const std::string& s) {
    return {s.begin(), s.end()};
}

/// Expects decode_heightmap to throw std::runtime_error (not crash, not another type) with a
/// message holding every keyword (case-sensitive) and the input's name.
void expect_rejected(const std::vector<std::uint8_t>& bytes, const std::vector<std::string>& words,
                     const HeightmapReadOptions& options = {}) {
    try {
        (void)decode_heightmap(bytes, "input.xyz", options);
        ADD_FAILURE() << "accepted; expected an error with '" << words.front() << "'";
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("input.xyz"), std::string::npos) << "message lacks the file: " << msg;
        for (const std::string& w : words)
            EXPECT_NE(msg.find(w), std::string::npos) << "message lacks '" << w << "': " << msg;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
}

PngImage gray_image(std::uint32_t w, std::uint32_t h, int depth, int channels = 1) {
    PngImage image;
    image.width = w;
    image.height = h;
    image.bit_depth = depth;
    image.channels = channels;
    image.samples.resize(static_cast<std::size_t>(w) * h * static_cast<std::size_t>(channels));
    for (std::size_t i = 0; i < image.samples.size(); ++i)
        image.samples[i] = static_cast<std::uint16_t>((i * 37) % (depth == 16 ? 65536 : 256));
    return image;
}

void put_be32(std::vector<std::uint8_t>& b, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8)
        b.push_back(static_cast<std::uint8_t>(v >> s));
}

/// A PNG of the given chunks, each with its length and a valid CRC.
std::vector<std::uint8_t> png_of_chunks(
    const std::vector<std::pair<const char*, std::vector<std::uint8_t>>>& chunks) {
    std::vector<std::uint8_t> b = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    for (const auto& [type, data] : chunks) {
        put_be32(b, static_cast<std::uint32_t>(data.size()));
        const std::size_t start = b.size();
        b.insert(b.end(), type, type + 4);
        b.insert(b.end(), data.begin(), data.end());
        put_be32(b, static_cast<std::uint32_t>(
                        crc32(0, b.data() + start, static_cast<uInt>(b.size() - start))));
    }
    return b;
}

std::vector<std::uint8_t> ihdr(std::uint32_t width, std::uint32_t height, std::uint8_t colour_type,
                               std::uint8_t depth = 8) {
    std::vector<std::uint8_t> data;
    put_be32(data, width);
    put_be32(data, height);
    data.insert(data.end(), {depth, colour_type, 0, 0, 0});
    return data;
}

/// A PNG whose IHDR declares width x height (CRCs valid), with no image data after it.
std::vector<std::uint8_t> png_with_header(std::uint32_t width, std::uint32_t height) {
    return png_of_chunks({{"IHDR", ihdr(width, height, 0)}, {"IEND", {}}});
}

/// An indexed-colour PNG: `palette` holds RGB triples, `indices` one per pixel, packed at
/// `depth` bits (1, 2, 4 or 8) from the high bits of each byte; `alpha` is its tRNS chunk.
std::vector<std::uint8_t> indexed_png(std::uint32_t width, std::uint32_t height,
                                      const std::vector<std::uint8_t>& palette,
                                      const std::vector<std::uint8_t>& indices,
                                      std::uint8_t depth = 8,
                                      const std::vector<std::uint8_t>& alpha = {}) {
    std::vector<std::uint8_t> rows;
    for (std::uint32_t y = 0; y < height; ++y) {
        rows.push_back(0);  // filter: none
        int bits = 0;
        for (std::uint32_t x = 0; x < width; ++x) {
            if (bits == 0) rows.push_back(0);
            bits += depth;
            rows.back() =
                static_cast<std::uint8_t>(rows.back() | (indices[y * width + x] << (8 - bits)));
            if (bits == 8) bits = 0;
        }
    }
    std::vector<std::uint8_t> idat(compressBound(static_cast<uLong>(rows.size())));
    uLongf size = static_cast<uLongf>(idat.size());
    EXPECT_EQ(compress(idat.data(), &size, rows.data(), static_cast<uLong>(rows.size())), Z_OK);
    idat.resize(size);
    if (alpha.empty()) {
        return png_of_chunks({{"IHDR", ihdr(width, height, 3, depth)},
                              {"PLTE", palette},
                              {"IDAT", idat},
                              {"IEND", {}}});
    }
    return png_of_chunks({{"IHDR", ihdr(width, height, 3, depth)},
                          {"PLTE", palette},
                          {"tRNS", alpha},
                          {"IDAT", idat},
                          {"IEND", {}}});
}

// ---- What each format decodes ----------------------------------------------------------------

TEST(HeightmapImport, TerrainRgbFollowsTheMapboxFormula) {
    PngImage image;
    image.width = 2;
    image.height = 2;
    image.channels = 3;
    image.bit_depth = 8;
    image.samples = {1, 134, 160, 0, 0, 0, 255, 255, 255, 1, 135, 0};
    const HeightRaster r = decode_heightmap(encode_png(image), "rgb.png");
    EXPECT_EQ(r.source_format, "terrain-rgb");
    EXPECT_DOUBLE_EQ(r.at(0, 0), -10000.0 + (1 * 65536 + 134 * 256 + 160) * 0.1);  // 0 m
    EXPECT_DOUBLE_EQ(r.at(1, 0), -10000.0);
    EXPECT_DOUBLE_EQ(r.at(0, 1), -10000.0 + 16777215 * 0.1);
    EXPECT_NEAR(r.at(0, 0), 0.0, 1e-9);
}

TEST(HeightmapImport, GrayPngScalesToMetres) {
    PngImage image = gray_image(3, 2, 16);
    image.samples = {0, 65535, 32768, 1, 2, 3};
    HeightmapReadOptions o;
    o.z_scale = 100.0;
    o.z_offset = -5.0;
    o.pixel_size = 2.5;
    const HeightRaster r = decode_heightmap(encode_png(image), "g16.png", o);
    EXPECT_EQ(r.source_format, "png-gray16");
    EXPECT_DOUBLE_EQ(r.at(0, 0), -5.0);
    EXPECT_DOUBLE_EQ(r.at(1, 0), 95.0);
    EXPECT_DOUBLE_EQ(r.at(2, 0), -5.0 + 100.0 * 32768.0 / 65535.0);
    EXPECT_EQ(r.cell_size, 2.5);
    EXPECT_EQ(r.domain(), (Rect{{0, 0}, {5.0, 2.5}}));
    // 8-bit: full white is z_scale.
    PngImage g8 = gray_image(2, 2, 8);
    g8.samples = {255, 0, 51, 102};
    const HeightRaster r8 = decode_heightmap(encode_png(g8), "g8.png", o);
    EXPECT_DOUBLE_EQ(r8.at(0, 0), 95.0);
    EXPECT_DOUBLE_EQ(r8.at(0, 1), -5.0 + 20.0);
}

TEST(HeightmapImport, AlphaZeroIsNoData) {
    PngImage image = gray_image(3, 3, 8, 2);
    for (std::size_t i = 0; i < 9; ++i)
        image.samples[2 * i + 1] = i == 4 ? 0 : 255;
    HeightRaster r = decode_heightmap(encode_png(image), "ga.png");
    EXPECT_EQ(r.nodata_count(), 1u);
    EXPECT_FALSE(r.is_valid(4));
    EXPECT_EQ(fill_nodata(r), 1u);
    EXPECT_EQ(r.heights[4], r.heights[1]) << "filled from a nearest neighbour";
}

TEST(HeightmapImport, EncodingCanBeForced) {
    expect_rejected(encode_png(gray_image(4, 4, 8)), {"Terrain-RGB"},
                    {{}, {}, {}, {}, false, PngHeightEncoding::TerrainRgb});
    PngImage rgb = gray_image(4, 4, 8, 3);
    expect_rejected(encode_png(rgb), {"grayscale"},
                    {{}, {}, {}, {}, false, PngHeightEncoding::Gray});
    PngImage rgb16 = gray_image(4, 4, 16, 3);
    expect_rejected(encode_png(rgb16), {"16-bit colour"});
}

// Image editors and terrain generators often save a grey heightmap as RGB(A), R = G = B. Read
// as Terrain-RGB, 0..255 greys would span -10 km to +1668 km.
TEST(HeightmapImport, GreyStoredAsColourIsAGreyHeightmap) {
    const std::vector<std::uint16_t> greys = {0, 51, 255, 102, 204, 0};
    const auto colour = [&](int channels, int depth, std::uint16_t alpha_of_last) {
        PngImage image = gray_image(3, 2, depth, channels);
        for (std::size_t i = 0; i < greys.size(); ++i) {
            const std::uint16_t v =
                depth == 16 ? static_cast<std::uint16_t>(greys[i] * 257) : greys[i];
            for (int c = 0; c < 3; ++c)
                image
                    .samples[i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)] =
                    v;
            if (channels == 4)
                image.samples[i * 4 + 3] = i + 1 == greys.size() ? alpha_of_last : 255;
        }
        return encode_png(image);
    };
    const std::vector<double> expected = {0.0, 0.2, 1.0, 0.4, 0.8, 0.0};
    for (const PngHeightEncoding e : {PngHeightEncoding::Auto, PngHeightEncoding::Gray}) {
        HeightmapReadOptions o;
        o.png_encoding = e;
        EXPECT_EQ(decode_heightmap(colour(3, 8, 255), "rgb.png", o).heights, expected);
        EXPECT_EQ(decode_heightmap(colour(3, 16, 255), "rgb16.png", o).heights, expected);
        const HeightRaster rgba = decode_heightmap(colour(4, 8, 0), "rgba.png", o);
        EXPECT_EQ(rgba.valid, (std::vector<std::uint8_t>{1, 1, 1, 1, 1, 0}));
        EXPECT_NEAR(rgba.heights[4], 0.8, 1e-15);
    }
    // Forced, the same pixels are Terrain-RGB codes: 51 grey is -10000 + 51 * 65793 * 0.1 m.
    HeightmapReadOptions terrain_rgb;
    terrain_rgb.png_encoding = PngHeightEncoding::TerrainRgb;
    EXPECT_NEAR(decode_heightmap(colour(3, 8, 255), "rgb.png", terrain_rgb).heights[1],
                -10000.0 + 51 * 65793 * 0.1, 1e-6);
    // One coloured pixel makes it colour again.
    PngImage tinted = gray_image(3, 2, 8, 3);
    for (std::size_t i = 0; i < tinted.samples.size(); ++i)
        tinted.samples[i] = 100;
    tinted.samples[16] = 101;
    EXPECT_EQ(decode_heightmap(encode_png(tinted), "t.png").source_format, "terrain-rgb");
    expect_rejected(encode_png(tinted), {"not all grey"},
                    {{}, {}, {}, {}, false, PngHeightEncoding::Gray});
}

TEST(HeightmapImport, IndexedPngWithAGreyPaletteIsAGreyHeightmap) {
    // Image editors save a grey heightmap of few levels as indexed colour. The palette here is
    // in a shuffled order, so reading the index instead of the grey level would show.
    const std::vector<std::uint8_t> palette = {255, 255, 255, 0, 0, 0, 51, 51, 51, 204, 204, 204};
    const std::vector<std::uint8_t> indices = {1, 2, 3, 0};
    const HeightRaster r = decode_heightmap(indexed_png(2, 2, palette, indices), "idx.png");
    EXPECT_EQ(r.source_format, "png-gray8");
    EXPECT_EQ(r.heights, (std::vector<double>{0.0, 0.2, 0.8, 1.0}));

    // A palette with colours is no heightmap encoding; forcing Terrain-RGB still reads it.
    const std::vector<std::uint8_t> colours = {1, 134, 160, 1, 134, 170, 1, 134, 180, 1, 134, 190};
    expect_rejected(indexed_png(2, 2, colours, indices), {"indexed-colour", "Terrain-RGB"});
    HeightmapReadOptions terrain_rgb;
    terrain_rgb.png_encoding = PngHeightEncoding::TerrainRgb;
    const HeightRaster forced =
        decode_heightmap(indexed_png(2, 2, colours, indices), "idx.png", terrain_rgb);
    // Mapbox's formula on (1, 134, 170): -10000 + (65536 + 134 * 256 + 170) * 0.1.
    EXPECT_NEAR(forced.at(0, 0), -10000.0 + (65536 + 134 * 256 + 170) * 0.1, 1e-9);
}

// libpng expands an index past the end of the palette to black without a word, which would
// import as the lowest height. Such a file is broken; the error names the pixel.
TEST(HeightmapImport, AnIndexPastThePaletteIsAnErrorNamingThePixel) {
    const std::vector<std::uint8_t> greys = {0, 0, 0, 128, 128, 128, 255, 255, 255};  // 3 entries
    expect_rejected(indexed_png(2, 2, greys, {0, 1, 2, 3}),
                    {"pixel (1, 1)", "palette index 3", "only 3 entries"});
    // Packed at 2 bits per pixel, where 3 is the largest index the file can hold.
    expect_rejected(indexed_png(3, 2, greys, {2, 2, 0, 2, 3, 0}, 2),
                    {"pixel (1, 1)", "palette index 3"});
    // A two-entry palette, every index inside it, at 1, 2, 4 and 8 bits: the grey levels. Nine
    // pixels a row, so that packed rows end part-way through a byte.
    const std::vector<std::uint8_t> two = {0, 0, 0, 255, 255, 255};
    const std::vector<std::uint8_t> bits = {1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 0, 1, 1, 1, 0, 1};
    for (const std::uint8_t depth : {1, 2, 4, 8}) {
        const HeightRaster r = decode_heightmap(indexed_png(9, 2, two, bits, depth), "i.png");
        EXPECT_EQ(r.heights, std::vector<double>(bits.begin(), bits.end())) << int{depth};
    }
}

// tRNS gives the first entries an alpha, the rest stay opaque: a transparent pixel is no data.
TEST(HeightmapImport, IndexedTransparencyMarksPixelsWithoutData) {
    const std::vector<std::uint8_t> greys = {0, 0, 0, 51, 51, 51, 255, 255, 255};
    const HeightRaster r =
        decode_heightmap(indexed_png(3, 2, greys, {0, 1, 2, 2, 1, 1}, 8, {0}), "transparent.png");
    ASSERT_EQ(r.valid.size(), 6u);
    EXPECT_EQ(r.valid, (std::vector<std::uint8_t>{0, 1, 1, 1, 1, 1}));
    EXPECT_NEAR(r.heights[1], 0.2, 1e-12);
    EXPECT_NEAR(r.heights[2], 1.0, 1e-12);
}

TEST(HeightmapImport, AsciiGridReadsHeaderAndValues) {
    const std::string text =
        "NCOLS 3\nnrows 2\nxllcorner 1000\nyllcenter 2000.5\ncellsize 10\nNODATA_value -9999\n"
        "1 2 3\n4 -9999 +6e0\n";
    const HeightRaster r = decode_heightmap(bytes_of(text), "g.asc");
    EXPECT_EQ(r.width, 3u);
    EXPECT_EQ(r.height, 2u);
    EXPECT_EQ(r.cell_size, 10.0);
    EXPECT_EQ(r.at(2, 0), 3.0);
    EXPECT_EQ(r.at(2, 1), 6.0);
    EXPECT_FALSE(r.is_valid(r.index(1, 1)));
    EXPECT_EQ(r.nodata_count(), 1u);
    EXPECT_TRUE(r.georeference.known);
    EXPECT_EQ(r.georeference.west, 1005.0);   // corner + half a cell
    EXPECT_EQ(r.georeference.south, 2000.5);  // already a centre
}

// ESRI's format description makes NODATA_value optional with a default of -9999: a grid written
// without the line still marks its holes that way. GDAL writes "nan" for a NaN no-data value.
TEST(HeightmapImport, AsciiGridNoDataDefaultsToMinus9999AndMayBeNaN) {
    const std::string header = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    const HeightRaster implicit =
        decode_heightmap(bytes_of(header + "5 5 5\n5 -9999 5\n"), "g.asc");
    EXPECT_EQ(implicit.nodata_count(), 1u);
    EXPECT_FALSE(implicit.is_valid(implicit.index(1, 1)));
    // A declared value replaces the default: -9999 is then a height like any other.
    const HeightRaster declared =
        decode_heightmap(bytes_of(header + "NODATA_value -1\n5 -1 5\n5 -9999 5\n"), "g.asc");
    EXPECT_EQ(declared.nodata_count(), 1u);
    EXPECT_EQ(declared.at(1, 1), -9999.0);
    const HeightRaster nan =
        decode_heightmap(bytes_of(header + "NODATA_value nan\n5 nan 5\n5 5 5\n"), "g.asc");
    EXPECT_EQ(nan.nodata_count(), 1u);
    EXPECT_FALSE(nan.is_valid(nan.index(1, 0)));
    // Other header keys still need finite numbers.
    expect_rejected(
        bytes_of("ncols 3\nnrows 2\nxllcorner nan\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n"),
        {"finite number"});
}

// GDAL's AAIGrid writer gives oblong cells as dx and dy instead of cellsize.
// An EXR with an alpha channel beside its heights: alpha 0 is no-data, as in a PNG. Written
// through OpenEXR itself.
TEST(HeightmapImport, ExrAlphaZeroIsNoData) {
    const int w = 3, h = 2;
    std::vector<float> heights = {1, 2, 3, 4, 5, 6};
    std::vector<float> alpha = {1, 1, 0, 1, 0.5f, 1};
    Imf::Header header(w, h);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.channels().insert("A", Imf::Channel(Imf::FLOAT));
    Imf::StdOSStream stream;
    {
        Imf::OutputFile file(stream, header);
        Imf::FrameBuffer fb;
        fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(heights.data()),
                                  sizeof(float), sizeof(float) * w));
        fb.insert("A", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(alpha.data()), sizeof(float),
                                  sizeof(float) * w));
        file.setFrameBuffer(fb);
        file.writePixels(h);
    }
    const std::string text = stream.str();
    const HeightRaster r =
        decode_heightmap(std::vector<std::uint8_t>(text.begin(), text.end()), "a.exr");
    EXPECT_EQ(r.nodata_count(), 1u);
    EXPECT_FALSE(r.is_valid(2));
    EXPECT_EQ(r.at(1, 1), 5.0);  // alpha 0.5 is data
}

TEST(HeightmapImport, AsciiGridWithDxAndDyKeepsBothSpacings) {
    const HeightRaster r = decode_heightmap(
        bytes_of("ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ndx 2\ndy 3\n1 2 3\n4 5 6\n"),
        "o.asc");
    EXPECT_EQ(r.cell_size, 2.0);
    EXPECT_EQ(r.row_spacing(), 3.0);
    EXPECT_EQ(r.domain().width(), 4.0);
    EXPECT_EQ(r.domain().height(), 3.0);
    EXPECT_EQ(r.georeference.west, 101.0);   // half a column
    EXPECT_EQ(r.georeference.south, 201.5);  // half a row
    EXPECT_EQ(r.at(2, 1), 6.0);
    const std::string grid = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n";
    expect_rejected(bytes_of(grid + "dx 2\n1 2\n3 4\n"), {"both 'dx' and 'dy'"});
    expect_rejected(bytes_of(grid + "cellsize 1\ndx 2\ndy 2\n1 2\n3 4\n"),
                    {"either 'cellsize' or both"});
    expect_rejected(bytes_of(grid + "dx 2\ndy 0\n1 2\n3 4\n"), {"must be positive"});
}

TEST(HeightmapImport, AsciiGridSavedWithAByteOrderMarkReadsLikeWithout) {
    // Notepad and Excel save UTF-8 text with EF BB BF in front; CRLF line ends come with it.
    const std::string text =
        "ncols 2\r\nnrows 2\r\nxllcorner 0\r\nyllcorner 0\r\n"
        "cellsize 5\r\n7 8\r\n9 10\r\n";
    const HeightRaster plain = decode_heightmap(bytes_of(text), "g.asc");
    const HeightRaster marked = decode_heightmap(bytes_of("\xEF\xBB\xBF" + text), "g.asc");
    EXPECT_EQ(marked.width, 2u);
    EXPECT_EQ(marked.cell_size, 5.0);
    EXPECT_EQ(marked.heights, plain.heights);
    EXPECT_EQ(marked.heights, (std::vector<double>{7, 8, 9, 10}));
    // Only a whole mark is skipped: a stray byte of one is still not a grid.
    EXPECT_THROW(decode_heightmap(bytes_of("\xEF\xBB" + text), "g.asc"), std::runtime_error);
}

TEST(HeightmapImport, ExrRoundTripsFloatHeights) {
    HeightRaster r;
    r.width = 5;
    r.height = 3;
    r.cell_size = 0.25;
    for (int i = 0; i < 15; ++i)
        r.heights.push_back(std::sin(i) * 1000.0);
    const HeightRaster back = decode_heightmap(encode_exr_heightmap(r), "h.exr");
    EXPECT_EQ(back.cell_size, 0.25);
    for (std::size_t i = 0; i < 15; ++i)
        EXPECT_EQ(back.heights[i], static_cast<double>(static_cast<float>(r.heights[i])));
}

// ---- Bad input ---------------------------------------------------------------------------------

TEST(BadHeightmap, EmptyFile) {
    expect_rejected({}, {"empty"});
}

TEST_F(HeightmapFiles, MissingFileAndDirectory) {
    EXPECT_THROW((void)read_heightmap(dir_ / "none.png"), std::runtime_error);
    EXPECT_THROW((void)read_heightmap(dir_), std::runtime_error);
}

TEST(BadHeightmap, NotAHeightmapAtAll) {
    expect_rejected(bytes_of("hello, this is a text file\n"), {"not a heightmap"});
    std::vector<std::uint8_t> noise(4096);
    for (std::size_t i = 0; i < noise.size(); ++i)
        noise[i] = static_cast<std::uint8_t>((i * 7919) >> 3);
    expect_rejected(noise, {"not a heightmap"});
    // PNG magic but garbage after it.
    std::vector<std::uint8_t> fake = {0x89, 'P', 'N', 'G', 1, 2, 3, 4, 5, 6, 7, 8, 9};
    expect_rejected(fake, {"PNG"});
}

TEST(BadHeightmap, TruncatedPng) {
    const std::vector<std::uint8_t> good = encode_png(gray_image(64, 64, 16));
    for (std::size_t cut : {std::size_t{8}, std::size_t{20}, std::size_t{40}, good.size() / 2,
                            good.size() - 13, good.size() - 1}) {
        expect_rejected({good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut)}, {"PNG"});
    }
}

TEST(BadHeightmap, ZeroByZeroRasters) {
    expect_rejected(png_with_header(0, 0), {"PNG"});
    expect_rejected(bytes_of("ncols 0\nnrows 0\nxllcorner 0\nyllcorner 0\ncellsize 1\n"),
                    {"empty", "0 x 0"});
    // One row or column spans no area.
    expect_rejected(encode_png(gray_image(1, 5, 8)), {"at least 2 x 2"});
    expect_rejected(bytes_of("ncols 4\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3 4\n"),
                    {"at least 2 x 2"});
}

/// A little-endian TIFF whose only IFD declares width x height float samples, no strips.
std::vector<std::uint8_t> tiff_with_size(std::uint16_t width, std::uint16_t height) {
    std::vector<std::uint8_t> b = {'I', 'I', 42, 0, 8, 0, 0, 0};
    const std::vector<std::array<std::uint16_t, 2>> entries = {
        {256, width}, {257, height}, {258, 32}, {277, 1}, {339, 3}};
    b.push_back(static_cast<std::uint8_t>(entries.size()));
    b.push_back(0);
    for (const auto& [tag, value] : entries) {
        for (std::uint16_t v : {tag, std::uint16_t{3}}) {  // type SHORT
            b.push_back(static_cast<std::uint8_t>(v));
            b.push_back(static_cast<std::uint8_t>(v >> 8));
        }
        b.insert(b.end(), {1, 0, 0, 0});  // count 1
        b.push_back(static_cast<std::uint8_t>(value));
        b.push_back(static_cast<std::uint8_t>(value >> 8));
        b.insert(b.end(), {0, 0});
    }
    b.insert(b.end(), {0, 0, 0, 0});  // no next IFD
    return b;
}

TEST(BadHeightmap, ZeroByZeroGeoTiff) {
    try {
        (void)decode_heightmap(tiff_with_size(0, 0), "input.xyz");
        ADD_FAILURE() << "a 0 x 0 TIFF was accepted";
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_TRUE(msg.find("GeoTIFF") != std::string::npos ||
                    msg.find("empty") != std::string::npos)
            << msg;
    }
}

TEST(BadHeightmap, TruncatedExr) {
    HeightRaster r;
    r.width = 2;
    r.height = 2;
    r.heights = {1, 2, 3, 4};
    const std::vector<std::uint8_t> exr = encode_exr_heightmap(r);
    for (std::size_t cut : {std::size_t{4}, std::size_t{40}, exr.size() / 2, exr.size() - 1}) {
        expect_rejected({exr.begin(), exr.begin() + static_cast<std::ptrdiff_t>(cut)}, {"EXR"});
    }
}

TEST_F(HeightmapFiles, LargerThanTheLimit) {
    // The default limit is 16k x 16k: one sample more is refused before the samples are read.
    expect_rejected(encode_png(gray_image(16385, 2, 8)), {"exceeds the limit of 16384 x 16384"});
    expect_rejected(bytes_of("ncols 20000\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1\n"),
                    {"exceeds the limit"});
    const auto tif = geotiff(dir_ / "wide.tif", 16385, 2, std::vector<float>(16385 * 2, 1.0f),
                             {0, 1, 0, 0, 0, -1}, kUtm33, std::nullopt);
    expect_rejected(tif, {"exceeds the limit"});
    // The limit is configurable.
    HeightmapReadOptions small;
    small.limits = {100, 50};
    expect_rejected(encode_png(gray_image(101, 10, 8)), {"exceeds the limit of 100 x 50"}, small);
    expect_rejected(encode_png(gray_image(10, 51, 16)), {"exceeds the limit"}, small);
    HeightRaster r;
    r.width = 60;
    r.height = 60;
    r.heights.assign(3600, 1.0);
    expect_rejected(encode_exr_heightmap(r), {"exceeds the limit"}, small);
    EXPECT_NO_THROW((void)decode_heightmap(encode_png(gray_image(100, 50, 8)), "ok.png", small));
}

// Found by fuzz_exr: a header whose data window is 33 million pixels wide made OpenEXR's
// InputFile allocate 2 GB for its line buffers before the size could be checked. The header
// is now read alone first, so the size is rejected before OpenEXR allocates anything.
TEST_F(HeightmapFiles, ExrHeaderWithAHugeDataWindowIsRejectedBeforeDecoding) {
    HeightRaster r;
    r.width = 4;
    r.height = 4;
    r.heights.assign(16, 1.0);
    std::vector<std::uint8_t> exr = encode_exr_heightmap(r);
    const std::string key = "dataWindow";
    const auto at = std::search(exr.begin(), exr.end(), key.begin(), key.end());
    ASSERT_NE(at, exr.end());
    // Name, "box2i", the 4-byte size, then min.x min.y max.x max.y (little-endian int32).
    const auto max_x = at + static_cast<std::ptrdiff_t>(key.size() + 1 + 6 + 4 + 8);
    const std::uint32_t huge = 0x01ffff05u;
    for (int b = 0; b < 4; ++b)
        max_x[b] = static_cast<std::uint8_t>(huge >> (8 * b));
    expect_rejected(exr, {"exceeds the limit"});
    // Too short to hold the magic number and version.
    expect_rejected({exr.begin(), exr.begin() + 6}, {"EXR"});
}

TEST_F(HeightmapFiles, NanAndInfHeights) {
    // ASCII grid: rejected with the sample named, or no-data on request.
    const std::string nan_grid =
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 nan 6\n";
    expect_rejected(bytes_of(nan_grid), {"row 1, column 1", "not finite"});
    const std::string inf_grid =
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 -inf 3\n4 5 6\n";
    expect_rejected(bytes_of(inf_grid), {"row 0, column 1", "not finite"});
    HeightmapReadOptions as_nodata;
    as_nodata.nonfinite_as_nodata = true;
    EXPECT_EQ(decode_heightmap(bytes_of(nan_grid), "g.asc", as_nodata).nodata_count(), 1u);
    EXPECT_EQ(decode_heightmap(bytes_of(inf_grid), "g.asc", as_nodata).nodata_count(), 1u);
    // GeoTIFF: NaN without a NaN no-data value is an error; declared NaN no-data is masked.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const auto t1 =
        geotiff(dir_ / "n.tif", 2, 2, {1, nan, 3, 4}, {0, 1, 0, 2, 0, -1}, kUtm33, std::nullopt);
    expect_rejected(t1, {"not finite"});
    const auto t2 =
        geotiff(dir_ / "i.tif", 2, 2, {1, 2, inf, 4}, {0, 1, 0, 2, 0, -1}, kUtm33, std::nullopt);
    expect_rejected(t2, {"not finite"});
    const auto t3 =
        geotiff(dir_ / "d.tif", 2, 2, {1, nan, 3, 4}, {0, 1, 0, 2, 0, -1}, kUtm33, std::nan(""));
    EXPECT_EQ(decode_heightmap(t3, "d.tif").nodata_count(), 1u);
    EXPECT_EQ(decode_heightmap(t2, "i.tif", as_nodata).nodata_count(), 1u);
    // EXR.
    HeightRaster r;
    r.width = 2;
    r.height = 2;
    r.heights = {1, 2, 3, 4};
    r.valid = {1, 1, 0, 1};  // written as NaN
    const auto exr = encode_exr_heightmap(r);
    expect_rejected(exr, {"NaN"});
    EXPECT_EQ(decode_heightmap(exr, "n.exr", as_nodata).nodata_count(), 1u);
    // Every sample no-data: nothing to mesh.
    const std::string all_nodata =
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nnodata_value 0\n0 0\n0 0\n";
    expect_rejected(bytes_of(all_nodata), {"every sample is no-data"});
    // Non-finite scale options.
    HeightmapReadOptions bad_scale;
    bad_scale.z_scale = std::numeric_limits<double>::infinity();
    EXPECT_THROW((void)decode_heightmap(encode_png(gray_image(2, 2, 8)), "s.png", bad_scale),
                 std::invalid_argument);
}

TEST(BadHeightmap, WrongAsciiHeaders) {
    const std::string values = "1 2\n3 4\n";
    struct Case {
        std::string header;
        std::vector<std::string> words;
    };
    const std::vector<Case> cases = {
        {"nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", {"lacks 'ncols'"}},
        {"ncols 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", {"lacks 'nrows'"}},
        {"ncols 2\nnrows 2\nyllcorner 0\ncellsize 1\n", {"lacks 'xllcorner or xllcenter'"}},
        {"ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n", {"lacks 'cellsize'"}},
        {"ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\ncolour blue\n",
         {"line 6", "'colour' is not an ESRI ASCII grid header key"}},
        {"ncols 2\nncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", {"given twice"}},
        {"ncols two\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n",
         {"line 1", "'ncols' needs a finite number"}},
        {"ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", {"whole number"}},
        {"ncols -2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", {"whole number"}},
        {"ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -1\n",
         {"'cellsize' must be positive"}},
        {"ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\n",
         {"'cellsize' must be positive"}},
        {"ncols 2\nnrows 2\nxllcorner nan\nyllcorner 0\ncellsize 1\n", {"finite number"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.header);
        expect_rejected(bytes_of(c.header + values), c.words);
    }
    const std::string header = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    expect_rejected(bytes_of(header + "1 2\n3\n"), {"truncated", "expected 4 heights", "found 3"});
    // A header that asks for the largest raster and holds one value is refused by its size,
    // before 2 GB of heights would be allocated.
    expect_rejected(bytes_of("ncols 16384\nnrows 16384\nxllcorner 0\nyllcorner 0\ncellsize 1\n0\n"),
                    {"truncated", "expected 268435456 heights", "only 3 bytes follow the header"});
    expect_rejected(bytes_of(header + "1 2\n3 4 5\n"), {"more heights"});
    expect_rejected(bytes_of(header + "1 2\n3 x4\n"), {"row 1, column 1", "not a number"});
}

TEST_F(HeightmapFiles, BadGeoTiffs) {
    const std::vector<float> v(16, 1.0f);
    const auto good = geotiff(dir_ / "g.tif", 4, 4, v, {0, 2, 0, 8, 0, -2}, kUtm33, std::nullopt);
    expect_rejected({good.begin(), good.begin() + 16}, {"GeoTIFF"});
    expect_rejected({good.begin(), good.begin() + static_cast<std::ptrdiff_t>(good.size() / 2)},
                    {"GeoTIFF"});
    const auto rotated =
        geotiff(dir_ / "r.tif", 4, 4, v, {0, 2, 0.5, 8, 0.5, -2}, kUtm33, std::nullopt);
    expect_rejected(rotated, {"rotated"});
    const auto degrees =
        geotiff(dir_ / "d.tif", 4, 4, v, {10, 0.001, 0, 50, 0, -0.001}, kWgs84, std::nullopt);
    expect_rejected(degrees, {"degrees"});
    HeightmapReadOptions metres;
    metres.pixel_size = 90.0;
    EXPECT_EQ(decode_heightmap(degrees, "d.tif", metres).cell_size, 90.0);
}

TEST_F(HeightmapFiles, HeightmapExportImportRoundTripsWithinTheQuantisation) {
    // Covered end to end (TIN -> 16-bit PNG -> raster) in export_test; here the PNG tEXt
    // scale alone: explicit options override it.
    PngImage image = gray_image(3, 3, 16);
    image.text = {{kPngKeyZOffset, "-12.5"}, {kPngKeyZRange, "200"}, {kPngKeyCellSize, "0.5"}};
    image.samples[0] = 65535;
    const HeightRaster r = decode_heightmap(encode_png(image), "t.png");
    EXPECT_DOUBLE_EQ(r.at(0, 0), 187.5);
    EXPECT_EQ(r.cell_size, 0.5);
    HeightmapReadOptions o;
    o.z_scale = 1.0;
    EXPECT_DOUBLE_EQ(decode_heightmap(encode_png(image), "t.png", o).at(0, 0), -12.5 + 1.0);
    image.text = {{kPngKeyZOffset, "lots"}};
    expect_rejected(encode_png(image), {"not a finite number"});
    // A key given twice: the same value is one statement, two values are a contradiction.
    image.text = {{kPngKeyZRange, "200"}, {kPngKeyZOffset, "-12.5"}, {kPngKeyZRange, "200"}};
    EXPECT_DOUBLE_EQ(decode_heightmap(encode_png(image), "t.png").at(0, 0), 187.5);
    image.text = {{kPngKeyZRange, "200"}, {kPngKeyZOffset, "-12.5"}, {kPngKeyZRange, "20"}};
    expect_rejected(encode_png(image), {"'sandtin:z_range' is given twice", "'200'", "'20'"});
    // Half a scale is refused unless the option for the missing half is given.
    image.text = {{kPngKeyZRange, "200"}};
    expect_rejected(encode_png(image),
                    {"'sandtin:z_range' without 'sandtin:z_offset'", "--z-offset"});
    HeightmapReadOptions offset;
    offset.z_offset = 1.0;
    EXPECT_DOUBLE_EQ(decode_heightmap(encode_png(image), "t.png", offset).at(0, 0), 201.0);
    image.text = {{kPngKeyZOffset, "3"}};
    expect_rejected(encode_png(image), {"without 'sandtin:z_range'", "--z-scale"});
    // A georeference needs both coordinates.
    image.text = {{kPngKeyWest, "1000"}};
    expect_rejected(encode_png(image), {"'sandtin:west' without 'sandtin:south'"});
}

}  // namespace
}  // namespace sandtin

namespace sandtin {
namespace {

// Found by fuzzing (tests/fuzz/corpus/fuzz_png/regression-oom-chunk-length): a chunk whose
// length field exceeds the file made libpng allocate hundreds of megabytes. It must be
// rejected as corrupted before libpng sees it.
TEST(HeightmapImportRegression, ChunkLongerThanTheFileIsRejectedWithoutAllocating) {
    std::vector<std::uint8_t>
        png = {0x89, 'P',  'N',  'G',  0x0d, 0x0a, 0x1a, 0x0a, 0,    0, 0, 13,
               'I',  'H',  'D',  'R',  0,    0,    0,    5,    0,    0, 0, 5,
               16,   0,    0,    0,    0,    0xf8, 0x94, 0xa5, 0x7a,  // CRC (not checked first)
               0x21, 0x00, 0x00, 0x13, 't',  'E',  'X',  't'};
    png.resize(png.size() + 20, 0);
    try {
        decode_png_heightmap(png, "crafted.png", PngHeightEncoding::Auto, RasterLimits{});
        FAIL() << "accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("claims"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("crafted.png"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sandtin
