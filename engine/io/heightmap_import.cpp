#include "io/heightmap_import.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "io/esri_ascii_grid.hpp"
#include "io/geotiff_gdal.hpp"
#include "io/heightmap_exr.hpp"
#include "util/atomic_file.hpp"
#include "util/elapsed_ms.hpp"

namespace sandtin {

namespace {

enum class Format { Png, Tiff, Ascii, Exr, Unknown };

Format detect(std::span<const std::uint8_t> b) {
    auto starts = [&](std::initializer_list<std::uint8_t> magic) {
        return b.size() >= magic.size() && std::equal(magic.begin(), magic.end(), b.begin());
    };
    if (starts({0x89, 'P', 'N', 'G'})) return Format::Png;
    if (starts({'I', 'I', 42, 0}) || starts({'M', 'M', 0, 42}) || starts({'I', 'I', 43, 0}) ||
        starts({'M', 'M', 0, 43})) {
        return Format::Tiff;
    }
    if (starts({0x76, 0x2f, 0x31, 0x01})) return Format::Exr;
    // An ASCII grid opens with one of its header keys, after a UTF-8 byte-order mark if a
    // Windows editor saved it.
    std::size_t i = starts({0xEF, 0xBB, 0xBF}) ? 3 : 0;
    while (i < b.size() && std::isspace(b[i]))
        ++i;
    std::string word;
    while (i < b.size() && std::isalpha(b[i]) && word.size() < 16)
        word += static_cast<char>(std::tolower(b[i++]));
    for (const char* key : {"ncols", "nrows", "xllcorner", "yllcorner", "xllcenter", "yllcenter",
                            "xllcentre", "yllcentre", "cellsize", "nodata"}) {
        if (word == key) return Format::Ascii;
    }
    return Format::Unknown;
}

void check_option(std::optional<double> v, bool positive, const char* what) {
    if (v && (!std::isfinite(*v) || (positive && !(*v > 0.0)))) {
        throw std::invalid_argument(std::string(what) + " must be a finite" +
                                    (positive ? " positive" : "") + " number");
    }
}

}  // namespace

HeightRaster decode_heightmap(std::span<const std::uint8_t> bytes, const std::string& name,
                              const HeightmapReadOptions& options) {
    check_option(options.pixel_size, true, "the pixel size");
    check_option(options.z_scale, false, "the z-scale");
    check_option(options.z_offset, false, "the z-offset");
    if (bytes.empty()) throw std::runtime_error(name + ": file is empty");
    HeightRaster r;
    double z_scale = 1.0;
    double z_offset = 0.0;
    const Format format = detect(bytes);
    if (options.png_encoding != PngHeightEncoding::Auto && format != Format::Png &&
        format != Format::Unknown) {
        const char* kind = format == Format::Tiff    ? "a GeoTIFF"
                           : format == Format::Ascii ? "an ESRI ASCII grid"
                                                     : "an OpenEXR image";
        throw std::invalid_argument(name +
                                    ": a PNG height encoding applies to PNG heightmaps, "
                                    "and this is " +
                                    kind);
    }
    switch (format) {
        case Format::Png: {
            PngHeightmap png =
                decode_png_heightmap(bytes, name, options.png_encoding, options.limits);
            r = std::move(png.raster);
            // The scale is one statement in two keys. With one missing, the option for that
            // half must say it: a default would guess.
            if (png.z_range.has_value() != png.z_offset.has_value() &&
                !(png.z_range ? options.z_offset : options.z_scale)) {
                throw std::runtime_error(
                    name + ": the PNG gives '" + (png.z_range ? kPngKeyZRange : kPngKeyZOffset) +
                    "' without '" + (png.z_range ? kPngKeyZOffset : kPngKeyZRange) +
                    "', and sandtin's height scale needs both: give " +
                    (png.z_range ? "--z-offset" : "--z-scale") + " for the missing one");
            }
            z_scale = png.z_range.value_or(z_scale);
            z_offset = png.z_offset.value_or(z_offset);
            if (png.cell_size) r.cell_size = *png.cell_size;
            if (png.cell_height) r.cell_height = *png.cell_height;
            break;
        }
        case Format::Tiff:
            r = decode_geotiff(bytes, name, options.limits, options.nonfinite_as_nodata,
                               options.pixel_size.has_value(), options.z_scale.has_value());
            break;
        case Format::Ascii:
            r = parse_esri_ascii_grid(bytes, name, options.limits, options.nonfinite_as_nodata);
            break;
        case Format::Exr:
            r = decode_exr_heightmap(bytes, name, options.limits, options.nonfinite_as_nodata);
            break;
        case Format::Unknown:
            throw std::runtime_error(name +
                                     ": not a heightmap sandtin can read (expected PNG, "
                                     "GeoTIFF, ESRI ASCII grid or OpenEXR)");
    }
    if (options.pixel_size) {
        r.cell_size = *options.pixel_size;  // square pixels, as the user says
        r.cell_height = 0.0;
    }
    // Explicit options win over a sandtin PNG's own scale.
    z_scale = options.z_scale.value_or(z_scale);
    z_offset = options.z_offset.value_or(z_offset);
    if (z_scale != 1.0 || z_offset != 0.0) {
        for (std::size_t i = 0; i < r.size(); ++i) {
            if (r.is_valid(i)) r.heights[i] = r.heights[i] * z_scale + z_offset;
        }
    }
    check_raster(r, name, options.limits);
    return r;
}

HeightRaster read_heightmap(const std::filesystem::path& path,
                            const HeightmapReadOptions& options) {
    const std::vector<std::uint8_t> bytes = read_file(path);
    return decode_heightmap(bytes, path.string(), options);
}

ImportResult import_heightmap(const std::filesystem::path& path, const ImportOptions& options,
                              const ProgressCallback& progress) {
    const auto start = std::chrono::steady_clock::now();
    // Reading and filling no-data take a small share of an import; the insertion the rest.
    if (progress) progress({0.0, "reading the heightmap"});
    HeightRaster raster = read_heightmap(path, options.read);
    ImportReport report;
    report.source = path.string();
    report.format = raster.source_format;
    report.width = raster.width;
    report.height = raster.height;
    report.cell_size = raster.cell_size;
    report.cell_height = raster.row_spacing();
    report.georeference = raster.georeference;
    report.source_bands = raster.source_bands;
    if (progress) progress({0.04, "filling no-data samples"});
    report.nodata_samples = fill_nodata(raster);
    report.read_ms = elapsed_ms(start);
    report.greedy = options.greedy;
    // The raster's extent and heights (pixel size, z-scale and offset applied) must make a
    // terrain; when they do not, the file and the options that scaled it are named.
    GreedyResult result = [&] {
        try {
            return greedy_tin(raster, options.greedy, progress_part(progress, 0.05, 1.0));
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(
                path.string() + " (with its pixel size, z-scale and z-offset): " + e.what());
        }
    }();
    report.stats = result.stats;
    report.total_ms = elapsed_ms(start);
    return {std::move(result.tin), std::move(report)};
}

nlohmann::json to_json(const ImportReport& r) {
    nlohmann::json j;
    j["source"] = r.source;
    j["format"] = r.format;
    j["raster"] = {{"width", r.width},
                   {"height", r.height},
                   {"cell_size", r.cell_size},
                   {"cell_height", r.cell_height},
                   {"nodata_samples", r.nodata_samples},
                   {"bands", r.source_bands},
                   {"nodata_policy", "filled from the nearest valid sample; not measured"}};
    if (r.georeference.known) {
        j["georeference"] = {{"west", r.georeference.west},
                             {"south", r.georeference.south},
                             {"crs", r.georeference.crs},
                             {"horizontal_unit", r.georeference.horizontal_unit},
                             {"vertical_unit", r.georeference.vertical_unit},
                             {"count_scale", r.georeference.count_scale},
                             {"count_offset", r.georeference.count_offset}};
    }
    j["max_error_target"] = r.greedy.max_error;
    j["max_points"] = r.greedy.max_points;
    j["points"] = r.stats.points;
    j["triangles"] = r.stats.triangles;
    j["max_error"] = r.stats.max_error;
    j["rmsd"] = r.stats.rmsd;
    j["reached_error"] = r.stats.reached_error;
    j["fix_up_points"] = r.stats.fix_up_points;
    j["decimated_points"] = r.stats.decimated_points;
    j["read_ms"] = r.read_ms;
    j["build_ms"] = r.stats.build_ms;
    j["decimate_ms"] = r.stats.decimate_ms;
    j["measure_ms"] = r.stats.measure_ms;
    j["total_ms"] = r.total_ms;
    return j;
}

}  // namespace sandtin
