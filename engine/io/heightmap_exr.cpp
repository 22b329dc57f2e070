#include "io/heightmap_exr.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTileDescription.h>
#include <OpenEXR/ImfVersion.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sandtin {

namespace {

constexpr const char* kCellSizeAttribute = "sandtin:cell_size";
constexpr const char* kCellHeightAttribute = "sandtin:cell_height";  ///< when not cell_size
// The georeference of the south-west sample (Georeference), as in sandtin's height PNGs.
constexpr const char* kWestAttribute = "sandtin:west";
constexpr const char* kSouthAttribute = "sandtin:south";
constexpr const char* kCrsAttribute = "sandtin:crs";
constexpr const char* kHorizontalUnitAttribute = "sandtin:horizontal_unit";

/// Reads the header alone and checks its data window (and tile size) against the limits.
/// OpenEXR's InputFile sizes its line and tile buffers from the header before a caller can
/// look: a damaged data window 33 million pixels wide made it allocate 2 GB (found by
/// fuzz_exr).
void check_header_sizes(std::span<const std::uint8_t> bytes, const std::string& name,
                        const RasterLimits& limits) {
    if (bytes.size() < 8) throw std::runtime_error(name + ": too short for an OpenEXR file");
    if (!Imf::isImfMagic(reinterpret_cast<const char*>(bytes.data())))
        throw std::runtime_error(name + ": not an OpenEXR file (bad magic number)");
    // The version field follows the magic number, little-endian like the whole format.
    auto version = static_cast<int>(static_cast<std::uint32_t>(bytes[4]) |
                                    (static_cast<std::uint32_t>(bytes[5]) << 8) |
                                    (static_cast<std::uint32_t>(bytes[6]) << 16) |
                                    (static_cast<std::uint32_t>(bytes[7]) << 24));
    Imf::StdISStream stream;
    stream.str(std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    stream.seekg(8);
    Imf::Header header;
    header.readFrom(stream, version);
    const Imath::Box2i window = header.dataWindow();
    const std::int64_t w = static_cast<std::int64_t>(window.max.x) - window.min.x + 1;
    const std::int64_t h = static_cast<std::int64_t>(window.max.y) - window.min.y + 1;
    check_raster_size(static_cast<std::uint64_t>(std::max<std::int64_t>(w, 0)),
                      static_cast<std::uint64_t>(std::max<std::int64_t>(h, 0)), name, limits);
    if (header.hasTileDescription()) {
        const Imf::TileDescription& tiles = header.tileDescription();
        check_raster_size(tiles.xSize, tiles.ySize, name + " (tile size)", limits);
    }
}

}  // namespace

std::vector<std::uint8_t> encode_exr_heightmap(const HeightRaster& raster) {
    const auto w = static_cast<int>(raster.width);
    const auto h = static_cast<int>(raster.height);
    std::vector<float> pixels(raster.size());
    for (std::size_t i = 0; i < raster.size(); ++i) {
        pixels[i] = raster.is_valid(i) ? static_cast<float>(raster.heights[i])
                                       : std::numeric_limits<float>::quiet_NaN();
    }
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.insert(kCellSizeAttribute, Imf::DoubleAttribute(raster.cell_size));
    if (raster.cell_height > 0.0 && raster.cell_height != raster.cell_size) {
        header.insert(kCellHeightAttribute, Imf::DoubleAttribute(raster.cell_height));
        // Oblong samples: generic viewers read the shape from the standard attribute (width /
        // height of a pixel), which OpenEXR bounds to [1e-6, 1e6].
        const double aspect = raster.cell_size / raster.cell_height;
        if (aspect >= 1e-6 && aspect <= 1e6) header.pixelAspectRatio() = static_cast<float>(aspect);
    }
    if (raster.georeference.known) {
        header.insert(kWestAttribute, Imf::DoubleAttribute(raster.georeference.west));
        header.insert(kSouthAttribute, Imf::DoubleAttribute(raster.georeference.south));
        if (!raster.georeference.crs.empty())
            header.insert(kCrsAttribute, Imf::StringAttribute(raster.georeference.crs));
        if (!raster.georeference.horizontal_unit.empty()) {
            header.insert(kHorizontalUnitAttribute,
                          Imf::StringAttribute(raster.georeference.horizontal_unit));
        }
    }
    Imf::StdOSStream stream;
    {
        Imf::OutputFile file(stream, header);
        Imf::FrameBuffer fb;
        fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data()), sizeof(float),
                                  sizeof(float) * raster.width));
        file.setFrameBuffer(fb);
        file.writePixels(h);
    }
    const std::string bytes = stream.str();
    return {bytes.begin(), bytes.end()};
}

HeightRaster decode_exr_heightmap(std::span<const std::uint8_t> bytes, const std::string& name,
                                  const RasterLimits& limits, bool nonfinite_as_nodata) {
    if (bytes.empty()) throw std::runtime_error(name + ": file is empty");
    HeightRaster r;
    std::vector<float> alpha;  ///< empty: no alpha channel
    try {
        check_header_sizes(bytes, name, limits);
        Imf::StdISStream stream;
        stream.str(std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
        Imf::InputFile file(stream);
        const Imath::Box2i window = file.header().dataWindow();
        const std::int64_t w = static_cast<std::int64_t>(window.max.x) - window.min.x + 1;
        const std::int64_t h = static_cast<std::int64_t>(window.max.y) - window.min.y + 1;
        check_raster_size(static_cast<std::uint64_t>(std::max<std::int64_t>(w, 0)),
                          static_cast<std::uint64_t>(std::max<std::int64_t>(h, 0)), name, limits);
        const Imf::ChannelList& channels = file.header().channels();
        std::string channel;
        for (const char* c : {"Y", "Z", "R", "height"}) {
            if (channels.findChannel(c) != nullptr) {
                channel = c;
                break;
            }
        }
        if (channel.empty()) {
            auto it = channels.begin();
            if (it == channels.end() || ++channels.begin() != channels.end()) {
                throw std::runtime_error(name +
                                         ": the EXR has no Y, Z, R or height channel and "
                                         "not exactly one channel");
            }
            channel = channels.begin().name();
        }
        r.width = static_cast<std::uint32_t>(w);
        r.height = static_cast<std::uint32_t>(h);
        std::vector<float> pixels(r.size());
        Imf::FrameBuffer fb;
        // Slices address pixel (x, y) at base + x * xStride + y * yStride over the data window.
        char* base = reinterpret_cast<char*>(pixels.data()) -
                     (static_cast<std::ptrdiff_t>(window.min.x) +
                      static_cast<std::ptrdiff_t>(window.min.y) * w) *
                         static_cast<std::ptrdiff_t>(sizeof(float));
        fb.insert(channel, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                      sizeof(float) * static_cast<std::size_t>(w)));
        // An alpha channel beside the heights marks no-data where it is 0, as in PNG.
        if (channel != "A" && channels.findChannel("A") != nullptr) {
            alpha.assign(r.size(), 1.0f);
            char* alpha_base = reinterpret_cast<char*>(alpha.data()) -
                               (static_cast<std::ptrdiff_t>(window.min.x) +
                                static_cast<std::ptrdiff_t>(window.min.y) * w) *
                                   static_cast<std::ptrdiff_t>(sizeof(float));
            fb.insert("A", Imf::Slice(Imf::FLOAT, alpha_base, sizeof(float),
                                      sizeof(float) * static_cast<std::size_t>(w)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(window.min.y, window.max.y);
        if (const auto* cs =
                file.header().findTypedAttribute<Imf::DoubleAttribute>(kCellSizeAttribute);
            cs != nullptr && std::isfinite(cs->value()) && cs->value() > 0.0) {
            r.cell_size = cs->value();
        }
        if (const auto* ch =
                file.header().findTypedAttribute<Imf::DoubleAttribute>(kCellHeightAttribute);
            ch != nullptr && std::isfinite(ch->value()) && ch->value() > 0.0) {
            r.cell_height = ch->value();
        }
        const auto* west = file.header().findTypedAttribute<Imf::DoubleAttribute>(kWestAttribute);
        const auto* south = file.header().findTypedAttribute<Imf::DoubleAttribute>(kSouthAttribute);
        if ((west == nullptr) != (south == nullptr)) {
            throw std::runtime_error(name + ": the EXR gives '" +
                                     (west ? kWestAttribute : kSouthAttribute) + "' without '" +
                                     (west ? kSouthAttribute : kWestAttribute) + "'");
        }
        if (west != nullptr) {
            if (!std::isfinite(west->value()) || !std::isfinite(south->value())) {
                throw std::runtime_error(name + ": the EXR's georeference is not finite");
            }
            r.georeference.known = true;
            r.georeference.west = west->value();
            r.georeference.south = south->value();
            if (const auto* crs =
                    file.header().findTypedAttribute<Imf::StringAttribute>(kCrsAttribute)) {
                r.georeference.crs = crs->value();
            }
            if (const auto* unit = file.header().findTypedAttribute<Imf::StringAttribute>(
                    kHorizontalUnitAttribute)) {
                r.georeference.horizontal_unit = unit->value();
            }
        }
        r.heights.assign(pixels.begin(), pixels.end());
    } catch (const std::runtime_error&) {
        throw;
    } catch (const std::exception& e) {
        throw std::runtime_error(name + ": cannot read as OpenEXR: " + e.what());
    }
    r.source_format = "exr";
    std::vector<std::uint8_t> valid(r.size(), 1);
    bool any_nodata = false;
    for (std::size_t i = 0; i < r.size(); ++i) {
        if (!alpha.empty() && alpha[i] == 0.0f) {
            valid[i] = 0;
            any_nodata = true;
            r.heights[i] = 0.0;
            continue;
        }
        if (std::isfinite(r.heights[i])) continue;
        if (!nonfinite_as_nodata) {
            throw std::runtime_error(name + ": the sample at row " + std::to_string(i / r.width) +
                                     ", column " + std::to_string(i % r.width) + " is " +
                                     (std::isnan(r.heights[i]) ? "NaN" : "infinite") +
                                     "; import with non-finite heights as no-data");
        }
        valid[i] = 0;
        any_nodata = true;
        r.heights[i] = 0.0;
    }
    if (any_nodata) r.valid = std::move(valid);
    return r;
}

}  // namespace sandtin
