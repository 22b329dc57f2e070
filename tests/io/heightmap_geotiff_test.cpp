// GeoTIFF heightmaps, read through GDAL: samples, cell size, no-data and georeference; rasters
// stored south-first or east-first come in north-up; several bands (the first is read, and
// the count said), band scale and offset, heights in feet, oblong pixels, and an unknown
// height unit that asks for a z scale. The files are written through GDAL itself.

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "heightmap_test_files.hpp"
#include "io/heightmap_import.hpp"

namespace sandtin {
namespace {

using namespace heightmap_test;

TEST_F(HeightmapFiles, GeoTiffReadsSamplesCellSizeNoDataAndGeoreference) {
    const std::vector<float> v = {1, 2, 3, 4, -32768, 6};
    const auto bytes =
        geotiff(dir_ / "a.tif", 3, 2, v, {500000, 30, 0, 4000000, 0, -30}, kUtm33, -32768.0);
    const HeightRaster r = decode_heightmap(bytes, "a.tif");
    EXPECT_EQ(r.source_format, "geotiff");
    EXPECT_EQ(r.cell_size, 30.0);
    EXPECT_EQ(r.at(0, 0), 1.0);
    EXPECT_EQ(r.at(2, 1), 6.0);
    EXPECT_FALSE(r.is_valid(r.index(1, 1)));
    EXPECT_EQ(r.georeference.west, 500015.0);
    EXPECT_EQ(r.georeference.south, 4000000.0 - 45.0);
    EXPECT_NE(r.georeference.crs.find("UTM zone 33N"), std::string::npos);
    HeightmapReadOptions scaled;
    scaled.z_scale = 2.0;
    EXPECT_EQ(decode_heightmap(bytes, "a.tif", scaled).at(2, 1), 12.0);
}

// GDAL reports a raster stored south row first as gt[5] > 0, and one whose columns run west as
// gt[1] < 0. Read in file order they would import mirrored.
TEST_F(HeightmapFiles, GeoTiffStoredSouthFirstOrEastFirstImportsNorthUp) {
    // File rows: row 0 is the south row {1, 2, 3}, row 1 the north row {4, 5, 6}.
    const HeightRaster south_first =
        decode_heightmap(geotiff(dir_ / "s.tif", 3, 2, {1, 2, 3, 4, 5, 6},
                                 {500000, 30, 0, 4000000, 0, 30}, kUtm33, std::nullopt),
                         "s.tif");
    EXPECT_EQ(south_first.heights, (std::vector<double>{4, 5, 6, 1, 2, 3}));  // north row first
    EXPECT_EQ(south_first.georeference.west, 500015.0);
    EXPECT_EQ(south_first.georeference.south, 4000015.0);  // the centre of file row 0
    EXPECT_EQ(south_first.cell_size, 30.0);
    // File columns from east to west: the first sample lies at the east edge.
    const HeightRaster east_first =
        decode_heightmap(geotiff(dir_ / "e.tif", 3, 2, {1, 2, 3, 4, 5, 6},
                                 {500090, -30, 0, 4000000, 0, -30}, kUtm33, std::nullopt),
                         "e.tif");
    EXPECT_EQ(east_first.heights, (std::vector<double>{3, 2, 1, 6, 5, 4}));
    EXPECT_EQ(east_first.georeference.west, 500015.0);
    EXPECT_EQ(east_first.georeference.south, 4000000.0 - 45.0);
    // Both at once, with a no-data sample that must move with its height.
    const HeightRaster both =
        decode_heightmap(geotiff(dir_ / "b.tif", 3, 2, {1, 2, -9, 4, 5, 6},
                                 {500090, -30, 0, 4000000, 0, 30}, kUtm33, -9.0),
                         "b.tif");
    EXPECT_EQ(both.at(0, 0), 6.0);
    EXPECT_EQ(both.at(2, 1), 1.0);
    EXPECT_FALSE(both.is_valid(both.index(0, 1)));  // file (2, 0): east column, south row
    EXPECT_EQ(both.nodata_count(), 1u);
}

// A GeoTIFF of several bands (imagery, or a DEM with a quality band): heights come from the
// first, and the report says how many there were, so the CLI can warn.
TEST_F(HeightmapFiles, GeoTiffWithSeveralBandsReadsTheFirstAndSaysHowMany) {
    const fs::path path = dir_ / "rgb.tif";
    GDALDatasetH ds = create_utm_geotiff(path, 3, GDT_Float32);
    ASSERT_NE(ds, nullptr);
    for (int b = 1; b <= 3; ++b) {
        std::vector<float> v(4, static_cast<float>(100 * b));
        v[0] += 1.0f;
        ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b), GF_Write, 0, 0, 2, 2, v.data(), 2, 2,
                               GDT_Float32, 0, 0),
                  CE_None);
    }
    GDALClose(ds);
    const HeightRaster r = decode_heightmap(read_file(path), "rgb.tif");
    EXPECT_EQ(r.source_bands, 3u);
    EXPECT_EQ(r.heights, (std::vector<double>{101, 100, 100, 100}));
}

// A DEM stored as Int16 centimetres above a datum: height = count * scale + offset.
TEST_F(HeightmapFiles, GeoTiffBandScaleAndOffsetTurnCountsIntoHeights) {
    const fs::path path = dir_ / "scaled.tif";
    GDALDatasetH ds = create_utm_geotiff(path, 1, GDT_Int16);
    ASSERT_NE(ds, nullptr);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    GDALSetRasterScale(band, 0.01);
    GDALSetRasterOffset(band, 100.0);
    GDALSetRasterNoDataValue(band, -32768);
    std::vector<std::int16_t> counts = {0, 1000, 3000, -32768};
    ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, 2, 2, counts.data(), 2, 2, GDT_Int16, 0, 0),
              CE_None);
    GDALClose(ds);
    const HeightRaster r = decode_heightmap(read_file(path), "scaled.tif");
    EXPECT_DOUBLE_EQ(r.heights[0], 100.0);
    EXPECT_DOUBLE_EQ(r.heights[1], 110.0);
    EXPECT_DOUBLE_EQ(r.heights[2], 130.0);
    EXPECT_FALSE(r.is_valid(3));  // no-data is a count, compared before scaling
    EXPECT_EQ(r.georeference.count_scale, 0.01);
    EXPECT_EQ(r.georeference.count_offset, 100.0);
    // --z-scale replaces the height unit, not the encoding of the counts.
    HeightmapReadOptions o;
    o.z_scale = 2.0;
    EXPECT_DOUBLE_EQ(decode_heightmap(read_file(path), "scaled.tif", o).heights[1], 220.0);
}

TEST_F(HeightmapFiles, GeoTiffInFeetIsConvertedToMetres) {
    const std::vector<float> v = {100, 200, 300, 400};
    // A state plane grid: 10 US survey feet per pixel, heights declared in feet on the band.
    const auto state_plane = geotiff(dir_ / "ca.tif", 2, 2, v, {6000000, 10, 0, 2000000, 0, -10},
                                     kCaliforniaFeet, std::nullopt, "ft");
    const HeightRaster r = decode_heightmap(state_plane, "ca.tif");
    constexpr double kUsFoot = 1200.0 / 3937.0;
    EXPECT_NEAR(r.cell_size, 10.0 * kUsFoot, 1e-12);
    EXPECT_NEAR(r.at(1, 1), 400.0 * 0.3048, 1e-9);
    EXPECT_EQ(r.georeference.horizontal_unit, "US survey foot");
    EXPECT_EQ(r.georeference.vertical_unit, "ft");
    // The georeference stays in the source's own coordinates, the ones its CRS names.
    EXPECT_EQ(r.georeference.west, 6000005.0);
    // An explicit z-scale replaces the file's unit, as it replaces a sandtin PNG's scale.
    HeightmapReadOptions scaled;
    scaled.z_scale = 2.0;
    EXPECT_EQ(decode_heightmap(state_plane, "ca.tif", scaled).at(1, 1), 800.0);
    // An explicit pixel size wins over the projection's unit.
    HeightmapReadOptions pixel;
    pixel.pixel_size = 3.0;
    EXPECT_EQ(decode_heightmap(state_plane, "ca.tif", pixel).cell_size, 3.0);

    // A compound CRS, UTM 33N + NAVD88 height (ftUS) by its EPSG codes, as surveys publish
    // them: GDAL writes the vertical unit into the GeoTIFF's keys and reports it back.
    OGRSpatialReferenceH compound_srs = OSRNewSpatialReference(nullptr);
    ASSERT_EQ(OSRSetFromUserInput(compound_srs, "EPSG:32633+6360"), OGRERR_NONE);
    char* compound_wkt = nullptr;
    OSRExportToWkt(compound_srs, &compound_wkt);
    const auto compound = geotiff(dir_ / "c.tif", 2, 2, v, {500000, 30, 0, 4000000, 0, -30},
                                  compound_wkt, std::nullopt);
    CPLFree(compound_wkt);
    OSRDestroySpatialReference(compound_srs);
    const HeightRaster c = decode_heightmap(compound, "c.tif");
    EXPECT_EQ(c.cell_size, 30.0);
    EXPECT_NEAR(c.at(0, 0), 100.0 * kUsFoot, 1e-9);
    EXPECT_EQ(c.georeference.vertical_unit, "US survey foot");

    // A band in metres is left alone.
    const auto metres =
        geotiff(dir_ / "m.tif", 2, 2, v, {500000, 30, 0, 4000000, 0, -30}, kUtm33, {}, "metre");
    EXPECT_EQ(decode_heightmap(metres, "m.tif").at(1, 1), 400.0);
}

TEST_F(HeightmapFiles, GeoTiffWithOblongPixelsKeepsBothSpacings) {
    // 2 m between columns, 3 m between rows: a 4 x 3 grid spans 6 x 6 m.
    const std::vector<float> v(12, 1.0f);
    const auto bytes =
        geotiff(dir_ / "o.tif", 4, 3, v, {500000, 2, 0, 4000000, 0, -3}, kUtm33, std::nullopt);
    const HeightRaster r = decode_heightmap(bytes, "o.tif");
    EXPECT_EQ(r.cell_size, 2.0);
    EXPECT_EQ(r.row_spacing(), 3.0);
    EXPECT_EQ(r.domain().width(), 6.0);
    EXPECT_EQ(r.domain().height(), 6.0);
    // In feet, both spacings are converted.
    const auto feet = geotiff(dir_ / "of.tif", 4, 3, v, {6000000, 10, 0, 2000000, 0, -20},
                              kCaliforniaFeet, std::nullopt);
    const HeightRaster f = decode_heightmap(feet, "of.tif");
    EXPECT_NEAR(f.cell_size, 10.0 * 1200.0 / 3937.0, 1e-12);
    EXPECT_NEAR(f.row_spacing(), 20.0 * 1200.0 / 3937.0, 1e-12);
    // A given pixel size makes the pixels square.
    HeightmapReadOptions square;
    square.pixel_size = 5.0;
    EXPECT_EQ(decode_heightmap(bytes, "o.tif", square).row_spacing(), 5.0);
}

TEST_F(HeightmapFiles, GeoTiffWithAnUnknownHeightUnitAsksForAZScale) {
    const auto bytes = geotiff(dir_ / "f.tif", 2, 2, {1, 2, 3, 4}, {500000, 30, 0, 4000000, 0, -30},
                               kUtm33, std::nullopt, "furlong");
    try {
        decode_heightmap(bytes, "f.tif");
        ADD_FAILURE() << "an unknown unit was read as metres";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("'furlong'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("z-scale"), std::string::npos) << e.what();
    }
    HeightmapReadOptions scaled;
    scaled.z_scale = 201.168;
    EXPECT_DOUBLE_EQ(decode_heightmap(bytes, "f.tif", scaled).at(1, 1), 4 * 201.168);
}

}  // namespace
}  // namespace sandtin
