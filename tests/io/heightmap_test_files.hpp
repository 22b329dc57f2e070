#pragma once
// What the heightmap import tests share: a fixture with a scratch folder of its own per test,
// GeoTIFFs written through GDAL itself (an independent writer for the reader under test), and
// the coordinate systems they are georeferenced in.

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "support/scratch_folder.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::heightmap_test {

namespace fs = std::filesystem;

class HeightmapFiles : public test::ScratchFolderTest {
  protected:
    HeightmapFiles() : ScratchFolderTest("import") {}
};

/// A GeoTIFF of float samples written through GDAL itself.
inline std::vector<std::uint8_t> geotiff(const fs::path& path, int w, int h,
                                         const std::vector<float>& v,
                                         std::array<double, 6> transform, const char* wkt,
                                         std::optional<double> nodata,
                                         const char* unit_type = nullptr) {
    GDALAllRegister();
    GDALDriverH driver = GDALGetDriverByName("GTiff");
    GDALDatasetH ds = GDALCreate(driver, path.c_str(), w, h, 1, GDT_Float32, nullptr);
    EXPECT_NE(ds, nullptr);
    GDALSetGeoTransform(ds, transform.data());
    if (wkt != nullptr) GDALSetProjection(ds, wkt);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    if (nodata) GDALSetRasterNoDataValue(band, *nodata);
    if (unit_type != nullptr) GDALSetRasterUnitType(band, unit_type);
    std::vector<float> copy = v;
    EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, w, h, copy.data(), w, h, GDT_Float32, 0, 0),
              CE_None);
    GDALClose(ds);
    return read_file(path);
}

inline constexpr const char* kUtm33 =
    R"(PROJCS["WGS 84 / UTM zone 33N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",15],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1]])";
// NAD83 / California zone 3 (ftUS), EPSG 2227: a state plane grid in US survey feet.
inline constexpr const char* kCaliforniaFeet =
    R"wkt(PROJCS["NAD83 / California zone 3 (ftUS)",GEOGCS["NAD83",DATUM["North_American_Datum_1983",SPHEROID["GRS 1980",6378137,298.257222101]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Lambert_Conformal_Conic_2SP"],PARAMETER["latitude_of_origin",36.5],PARAMETER["central_meridian",-120.5],PARAMETER["standard_parallel_1",38.4333333333333],PARAMETER["standard_parallel_2",37.0666666666667],PARAMETER["false_easting",6561666.667],PARAMETER["false_northing",1640416.667],UNIT["US survey foot",0.304800609601219]])wkt";
inline constexpr const char* kWgs84 =
    R"(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]])";

/// A 2 x 2 GeoTIFF of `bands` bands of `type` at 10 m in UTM zone 33N, open for writing
/// through GDAL; the caller writes the bands and closes it.
inline GDALDatasetH create_utm_geotiff(const fs::path& path, int bands, GDALDataType type) {
    GDALAllRegister();
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), 2, 2, bands, type, nullptr);
    if (ds == nullptr) return ds;
    std::array<double, 6> transform = {500000, 10, 0, 4000000, 0, -10};
    GDALSetGeoTransform(ds, transform.data());
    GDALSetProjection(ds, kUtm33);
    return ds;
}

}  // namespace sandtin::heightmap_test
