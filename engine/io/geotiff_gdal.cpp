#include "io/geotiff_gdal.hpp"

#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sandtin {

namespace {

/// Collects GDAL's messages instead of letting it print them, for the life of the scope.
class GdalErrors {
  public:
    GdalErrors() { CPLPushErrorHandlerEx(&GdalErrors::handle, this); }
    ~GdalErrors() { CPLPopErrorHandler(); }
    GdalErrors(const GdalErrors&) = delete;
    GdalErrors& operator=(const GdalErrors&) = delete;
    std::string message() const { return last_.empty() ? "unknown GDAL error" : last_; }

  private:
    static void CPL_STDCALL handle(CPLErr level, CPLErrorNum, const char* message) {
        auto* self = static_cast<GdalErrors*>(CPLGetErrorHandlerUserData());
        if (self != nullptr && level >= CE_Failure && message != nullptr) self->last_ = message;
    }
    std::string last_;
};

struct DatasetCloser {
    void operator()(void* ds) const { GDALClose(ds); }
};

void register_drivers() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

/// A GDAL in-memory file over caller-owned bytes, unlinked on scope exit.
class MemoryFile {
  public:
    explicit MemoryFile(std::span<const std::uint8_t> bytes) {
        static std::atomic<std::uint64_t> counter{0};
        path_ = "/vsimem/sandtin-import-" + std::to_string(counter++) + ".tif";
        // GDAL takes a non-const pointer but, with take ownership off, only reads it.
        VSILFILE* f = VSIFileFromMemBuffer(path_.c_str(), const_cast<GByte*>(bytes.data()),
                                           static_cast<vsi_l_offset>(bytes.size()), FALSE);
        if (f != nullptr) VSIFCloseL(f);
    }
    ~MemoryFile() { VSIUnlink(path_.c_str()); }
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

/// Metres per unit for the names GDAL and GeoTIFF writers give lengths, in lower case ("metre",
/// "m", "ft", "US survey foot", "foot_us"...). Empty means metres. nullopt: a unit sandtin does
/// not know, which must not be guessed.
std::optional<double> metres_per_unit(std::string unit) {
    std::transform(unit.begin(), unit.end(), unit.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    std::replace(unit.begin(), unit.end(), '_', ' ');
    for (const char* metre : {"", "m", "metre", "meter", "metres", "meters"}) {
        if (unit == metre) return 1.0;
    }
    // The international foot is exactly 0.3048 m; the US survey foot 1200/3937 m.
    for (const char* foot : {"ft", "foot", "feet", "international foot", "foot international"}) {
        if (unit == foot) return 0.3048;
    }
    for (const char* foot :
         {"us survey foot", "us ft", "us-ft", "ftus", "foot us", "us foot", "survey foot"}) {
        if (unit == foot) return 1200.0 / 3937.0;
    }
    if (unit == "cm" || unit == "centimetre" || unit == "centimeter") return 0.01;
    if (unit == "mm" || unit == "millimetre" || unit == "millimeter") return 0.001;
    if (unit == "km" || unit == "kilometre" || unit == "kilometer") return 1000.0;
    return std::nullopt;
}

struct SpatialReferenceDeleter {
    void operator()(void* srs) const { OSRDestroySpatialReference(srs); }
};

/// Which way a raster's rows and columns run in its file (sandtin's rasters are north-up).
struct RasterOrientation {
    bool south_first = false;  ///< the first row is the southern one
    bool east_first = false;   ///< columns run west
};

/// Cell size, spacing of the rows and georeference from the dataset's geotransform.
RasterOrientation read_geotransform(GDALDatasetH ds, const std::string& name, int width, int height,
                                    bool pixel_size_override, HeightRaster& r) {
    RasterOrientation o;
    std::array<double, 6> gt{};
    // A raster whose first row is its southern one (gt[5] > 0), or whose columns run west
    // (gt[1] < 0), is read in file order and then mirrored.
    if (GDALGetGeoTransform(ds, gt.data()) == CE_None) {
        if (gt[2] != 0.0 || gt[4] != 0.0) {
            throw std::runtime_error(name +
                                     ": the GeoTIFF is rotated or sheared; sandtin needs "
                                     "a north-up raster");
        }
        const double dx = std::abs(gt[1]);
        const double dy = std::abs(gt[5]);
        if (!(dx > 0.0 && dy > 0.0 && std::isfinite(dx) && std::isfinite(dy)) &&
            !pixel_size_override) {
            throw std::runtime_error(name + ": the GeoTIFF's pixel size (" + std::to_string(dx) +
                                     " x " + std::to_string(dy) +
                                     ") is not positive; give the pixel size in metres");
        }
        r.cell_size = dx;
        // Rows spaced unlike columns (a 10 x 15 m grid) are kept as such: the raster, and the
        // TIN built from it, space them apart by their own size.
        if (std::abs(dx - dy) > 1e-9 * dx) r.cell_height = dy;
        o.south_first = gt[5] > 0.0;
        o.east_first = gt[1] < 0.0;
        // The centres of the westmost column and the southmost row.
        r.georeference.known = true;
        r.georeference.west = gt[0] + (o.east_first ? width - 0.5 : 0.5) * gt[1];
        r.georeference.south = gt[3] + (o.south_first ? 0.5 : height - 0.5) * gt[5];
    }
    return o;
}

/// The projection's units: the cell size in metres, and the heights' unit (the band's, else
/// the vertical CRS's). Throws for degrees without a pixel-size override.
std::string read_projection(GDALDatasetH ds, GDALRasterBandH band, const std::string& name,
                            bool pixel_size_override, HeightRaster& r) {
    // Heights in the unit the band names, else the one a compound CRS's vertical part names.
    std::string vertical_unit =
        GDALGetRasterUnitType(band) != nullptr ? GDALGetRasterUnitType(band) : std::string();
    if (const char* wkt = GDALGetProjectionRef(ds); wkt != nullptr && *wkt != '\0') {
        r.georeference.crs = wkt;
        const std::unique_ptr<void, SpatialReferenceDeleter> srs(OSRNewSpatialReference(wkt));
        if (srs && OSRIsGeographic(srs.get()) != 0 && !pixel_size_override) {
            throw std::runtime_error(name +
                                     ": the GeoTIFF is in geographic coordinates "
                                     "(degrees); give the pixel size in metres");
        }
        if (srs && OSRIsProjected(srs.get()) != 0) {
            // A state plane grid in US survey feet has 3.28 times the cell size in its numbers.
            char* unit_name = nullptr;
            const double metres = OSRGetLinearUnits(srs.get(), &unit_name);
            r.georeference.horizontal_unit = unit_name != nullptr ? unit_name : "";
            if (!(metres > 0.0) || !std::isfinite(metres)) {
                throw std::runtime_error(name + ": the GeoTIFF's projection has a linear unit ('" +
                                         r.georeference.horizontal_unit +
                                         "') of no length; give the pixel size in metres");
            }
            r.cell_size *= metres;
            r.cell_height *= metres;
        }
        if (vertical_unit.empty() && srs && OSRIsVertical(srs.get()) != 0) {
            char* unit_name = nullptr;
            OSRGetTargetLinearUnits(srs.get(), "VERT_CS", &unit_name);
            if (unit_name != nullptr) vertical_unit = unit_name;
        }
    }
    r.georeference.vertical_unit = vertical_unit;
    return vertical_unit;
}

/// The band's samples as heights in metres, north-up, with the no-data cells marked.
void read_samples(GDALRasterBandH band, const std::string& name, RasterOrientation orientation,
                  double height_metres, bool nonfinite_as_nodata, const GdalErrors& errors,
                  HeightRaster& r) {
    const int width = static_cast<int>(r.width);
    const int height = static_cast<int>(r.height);
    // Stored counts become heights in the band's unit through its scale and offset (an Int16
    // DEM in centimetres has scale 0.01). The no-data value is a stored count.
    int has_scale = 0;
    int has_offset = 0;
    const double scale = GDALGetRasterScale(band, &has_scale);
    const double offset = GDALGetRasterOffset(band, &has_offset);
    const double count_scale = has_scale != 0 ? scale : 1.0;
    const double count_offset = has_offset != 0 ? offset : 0.0;
    if (!(std::isfinite(count_scale) && count_scale != 0.0 && std::isfinite(count_offset))) {
        std::ostringstream what;
        what << name << ": the GeoTIFF's band scale (" << count_scale << ") and offset ("
             << count_offset << ") cannot turn its samples into heights";
        throw std::runtime_error(what.str());
    }
    r.georeference.count_scale = count_scale;
    r.georeference.count_offset = count_offset;

    int has_nodata = 0;
    const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    r.heights.resize(r.size());
    if (GDALRasterIO(band, GF_Read, 0, 0, width, height, r.heights.data(), width, height,
                     GDT_Float64, 0, 0) != CE_None) {
        throw std::runtime_error(name + ": cannot read the GeoTIFF's samples: " + errors.message());
    }
    if (orientation.south_first) {
        for (std::size_t y = 0; y < r.height / 2; ++y) {
            std::swap_ranges(
                r.heights.begin() + static_cast<std::ptrdiff_t>(y * r.width),
                r.heights.begin() + static_cast<std::ptrdiff_t>((y + 1) * r.width),
                r.heights.begin() + static_cast<std::ptrdiff_t>((r.height - 1 - y) * r.width));
        }
    }
    if (orientation.east_first) {
        for (std::size_t y = 0; y < r.height; ++y) {
            const auto row = r.heights.begin() + static_cast<std::ptrdiff_t>(y * r.width);
            std::reverse(row, row + r.width);
        }
    }
    const bool nan_nodata = has_nodata != 0 && std::isnan(nodata);
    std::vector<std::uint8_t> valid(r.size(), 1);
    bool any_nodata = false;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const double h = r.heights[i];
        const bool missing = (has_nodata != 0 && h == nodata) || (std::isnan(h) && nan_nodata) ||
                             (!std::isfinite(h) && nonfinite_as_nodata);
        if (missing) {
            valid[i] = 0;
            any_nodata = true;
            r.heights[i] = 0.0;
        } else if (!std::isfinite(h)) {
            throw std::runtime_error(
                name + ": the sample at row " + std::to_string(i / r.width) + ", column " +
                std::to_string(i % r.width) + " is not finite (" + std::to_string(h) +
                "); declare a no-data value or import with non-finite heights as no-data");
        } else {
            r.heights[i] = (h * count_scale + count_offset) * height_metres;
        }
    }
    if (any_nodata) r.valid = std::move(valid);
}

}  // namespace

HeightRaster decode_geotiff(std::span<const std::uint8_t> bytes, const std::string& name,
                            const RasterLimits& limits, bool nonfinite_as_nodata,
                            bool pixel_size_override, bool z_scale_override) {
    if (bytes.empty()) throw std::runtime_error(name + ": file is empty");
    register_drivers();
    GdalErrors errors;
    const MemoryFile file(bytes);
    const std::array<const char*, 3> drivers = {"GTiff", "COG", nullptr};
    std::unique_ptr<void, DatasetCloser> dataset(GDALOpenEx(
        file.path().c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers.data(), nullptr, nullptr));
    if (!dataset) {
        throw std::runtime_error(name + ": cannot read as GeoTIFF: " + errors.message());
    }
    GDALDatasetH ds = dataset.get();
    if (GDALGetRasterCount(ds) < 1) throw std::runtime_error(name + ": the GeoTIFF has no bands");
    const int width = GDALGetRasterXSize(ds);
    const int height = GDALGetRasterYSize(ds);
    check_raster_size(static_cast<std::uint64_t>(std::max(width, 0)),
                      static_cast<std::uint64_t>(std::max(height, 0)), name, limits);

    HeightRaster r;
    r.width = static_cast<std::uint32_t>(width);
    r.height = static_cast<std::uint32_t>(height);
    r.source_format = "geotiff";
    r.source_bands = static_cast<std::uint32_t>(GDALGetRasterCount(ds));
    const RasterOrientation orientation =
        read_geotransform(ds, name, width, height, pixel_size_override, r);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    const std::string vertical_unit = read_projection(ds, band, name, pixel_size_override, r);
    double height_metres = 1.0;
    if (!z_scale_override) {
        const std::optional<double> unit = metres_per_unit(vertical_unit);
        if (!unit) {
            throw std::runtime_error(name + ": the GeoTIFF's heights are in '" + vertical_unit +
                                     "', a unit sandtin does not know; give the z-scale that "
                                     "turns them into metres");
        }
        height_metres = *unit;
    }

    read_samples(band, name, orientation, height_metres, nonfinite_as_nodata, errors, r);
    return r;
}

}  // namespace sandtin
