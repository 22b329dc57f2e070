// Height map export: a height PNG or EXR re-imports within its quantisation (against the TIN
// sampled by brute force), rows spaced unlike columns come back unstretched, the georeference
// travels with the map, a terrain flat up to rounding exports flat, and a terrain imported
// from a grid exports onto that grid's own samples while, and only while, it still lies on it.

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "export_fixture.hpp"
#include "formats/png_image.hpp"
#include "io/export_terrain.hpp"
#include "io/greedy_tin.hpp"
#include "io/heightmap_import.hpp"
#include "io/import_grid.hpp"
#include "support/tin_oracles.hpp"

namespace sandtin {
namespace {

using namespace export_test;

TEST_F(Export, HeightPngReimportsWithinTheQuantisation) {
    // An imported terrain: the export grid is the import grid, so every sample is a TIN point.
    HeightRaster raster;
    raster.width = 33;
    raster.height = 21;
    raster.cell_size = 0.5;
    for (std::uint32_t row = 0; row < raster.height; ++row) {
        for (std::uint32_t col = 0; col < raster.width; ++col)
            raster.heights.push_back(hills(raster.position(col, row)) * 10.0);
    }
    const Tin tin = greedy_tin(raster, {0.01, 0}).tin;
    ExportOptions o;
    o.cell_size = 0.5;
    run(tin, "h.png", o);
    EXPECT_EQ(report_.map_width, 33u);
    EXPECT_EQ(report_.map_height, 21u);
    const HeightRaster back = read_heightmap(dir_ / "h.png");
    ASSERT_EQ(back.width, 33u);
    ASSERT_EQ(back.height, 21u);
    EXPECT_EQ(back.cell_size, 0.5);
    EXPECT_EQ(back.domain(), tin.domain());
    const double step = report_.height_step;
    EXPECT_GT(step, 0.0);
    for (std::uint32_t row = 0; row < back.height; ++row) {
        for (std::uint32_t col = 0; col < back.width; ++col) {
            const double z = test::brute_force_height(tin, back.position(col, row));
            ASSERT_NEAR(back.at(col, row), z, 0.5 * step + 1e-9) << col << ", " << row;
        }
    }
    // EXR keeps float precision.
    run(tin, "h.exr", o);
    const HeightRaster exr = read_heightmap(dir_ / "h.exr");
    for (std::uint32_t row = 0; row < exr.height; ++row) {
        for (std::uint32_t col = 0; col < exr.width; ++col) {
            const double z = test::brute_force_height(tin, exr.position(col, row));
            ASSERT_NEAR(exr.at(col, row), z, 1e-6 * std::max(1.0, std::abs(z)));
        }
    }
}

TEST_F(Export, AHeightMapWithRowsSpacedUnlikeColumnsReimportsUnstretched) {
    // 1 x 0.5 m at 0.3 m cells: 4 columns 1/3 m apart, 3 rows 0.25 m apart. A plane, so the
    // baked samples are exact and a stretched re-import shows as a wrong height.
    const Rect domain = Rect::from_size(1.0, 0.5);
    const auto plane = [](Vec2 p) { return 1.0 + 0.4 * p.x + 0.8 * p.y; };
    const Tin tin = Tin::random_points(domain, 300, 611, plane);
    ExportOptions o;
    o.cell_size = 0.3;
    for (const char* file : {"rows.png", "rows.exr"}) {
        run(tin, file, o);
        ASSERT_EQ(report_.map_width, 4u);
        ASSERT_EQ(report_.map_height, 3u);
        const HeightRaster back = read_heightmap(dir_ / file);
        EXPECT_DOUBLE_EQ(back.cell_size, 1.0 / 3.0) << file;
        EXPECT_DOUBLE_EQ(back.row_spacing(), 0.25) << file;
        EXPECT_DOUBLE_EQ(report_.map_spacing.x, 1.0 / 3.0) << file;
        EXPECT_DOUBLE_EQ(report_.map_spacing.y, 0.25) << file;
        EXPECT_DOUBLE_EQ(back.domain().width(), 1.0) << file;
        EXPECT_DOUBLE_EQ(back.domain().height(), 0.5) << file;
        for (std::uint32_t row = 0; row < back.height; ++row) {
            for (std::uint32_t col = 0; col < back.width; ++col) {
                const Vec2 p = back.position(col, row);
                EXPECT_NEAR(back.at(col, row), plane(p), 1e-4)  // both origins at 0
                    << file << " " << col << ", " << row;
            }
        }
    }
    // Generic EXR readers take the samples' shape from the standard pixel aspect ratio
    // (width / height of a pixel): 1/3 m by 0.25 m.
    EXPECT_FLOAT_EQ(Imf::InputFile((dir_ / "rows.exr").c_str()).header().pixelAspectRatio(),
                    4.0f / 3.0f);
    // A square grid writes no row spacing of its own.
    o.cell_size = 0.25;
    run(tin, "square.png", o);
    EXPECT_EQ(read_heightmap(dir_ / "square.png").cell_height, 0.0);
}

// A terrain imported on 2 x 3 m cells and exported with both spacings re-imports onto the
// same samples; with the column spacing alone its rows would be resampled (a 10 m spike came
// back at 6.67 m).
// A terrain flat up to rounding exports as a flat map (every sample 0, range 1), not as noise
// stretched over the 16-bit range; a real relief of a micrometre at 5 m still shows.
// An imported terrain's georeference (the source coordinates of its south-west sample, its
// CRS and unit) travels in sandtin's height maps, so export followed by import keeps it.
TEST_F(Export, HeightMapsCarryTheGeoreference) {
    const Tin tin = Tin::random_points(Rect::from_size(30.0, 20.0), 100, 3, hills);
    ExportOptions o;
    o.cell_size = 2.0;
    o.georeference.known = true;
    o.georeference.west = 500015.25;
    o.georeference.south = 3999955.5;
    o.georeference.crs = "PROJCS[\"WGS 84 / UTM zone 33N\"]";
    o.georeference.horizontal_unit = "metre";
    for (const char* file : {"geo.png", "geo.exr"}) {
        run(tin, file, o);
        const HeightRaster back = read_heightmap(dir_ / file);
        EXPECT_TRUE(back.georeference.known) << file;
        EXPECT_EQ(back.georeference.west, 500015.25) << file;
        EXPECT_EQ(back.georeference.south, 3999955.5) << file;
        EXPECT_EQ(back.georeference.crs, o.georeference.crs) << file;
        EXPECT_EQ(back.georeference.horizontal_unit, "metre") << file;
    }
    // Meshes keep their vertices in the terrain frame and name the georeference in a comment.
    for (const char* file : {"geo.obj", "geo.ply"}) {
        const std::string header = text(run(tin, file, o)).substr(0, 400);
        EXPECT_NE(header.find("georeference: the terrain point (0, 0) m lies at west 500015.25, "
                              "south 3999955.5 (metre) in PROJCS"),
                  std::string::npos)
            << file << ": " << header;
    }
    EXPECT_EQ(text(run(tin, "plain.obj", {})).find("georeference"), std::string::npos);
    // Without one, none is invented.
    run(tin, "plain.png", {});
    EXPECT_FALSE(read_heightmap(dir_ / "plain.png").georeference.known);
    // The session's metadata is where the CLI and the editor take it from.
    const Georeference g = import_georeference_of(
        R"({"import": {"georeference": {"west": 1005.0, "south": 2000.5, "crs": "",
            "horizontal_unit": "", "vertical_unit": ""}}})");
    EXPECT_TRUE(g.known);
    EXPECT_EQ(g.west, 1005.0);
    EXPECT_EQ(g.south, 2000.5);
    EXPECT_FALSE(import_georeference_of(R"({"import": {"georeference": {"west": 1}}})").known);
}

TEST_F(Export, AHeightMapFlatUpToRoundingIsFlat) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(4.0, 4.0), 5.0);
    const std::vector<VertexId> ids = test::live_ids(tin);
    tin.set_height(ids[0], 5.0 - 2e-15);
    ExportOptions o;
    o.map_size = 9;
    run(tin, "flat.png", o);
    EXPECT_EQ(report_.height_step, 1.0 / 65535.0);  // the step the map was written with
    const PngImage flat = read_png(dir_ / "flat.png");
    for (const std::uint16_t v : flat.samples)
        ASSERT_EQ(v, 0u);
    const HeightRaster back = read_heightmap(dir_ / "flat.png");
    for (const double h : back.heights)
        EXPECT_NEAR(h, 5.0, 1e-14);
    tin.set_height(ids[0], 5.0 - 1e-6);
    run(tin, "micro.png", o);
    const PngImage micro = read_png(dir_ / "micro.png");
    EXPECT_EQ(*std::max_element(micro.samples.begin(), micro.samples.end()), 65535u);
}

TEST_F(Export, AnOblongImportGridExportsOntoItsOwnSamples) {
    HeightRaster raster;
    raster.width = 5;
    raster.height = 4;
    raster.cell_size = 2.0;
    raster.cell_height = 3.0;
    for (std::uint32_t i = 0; i < raster.size(); ++i)
        raster.heights.push_back(i == 7 ? 10.0 : 0.1 * static_cast<double>(i % 3));
    const Tin tin = greedy_tin(raster, {0.0, 0}).tin;
    const ImportGrid grid{2.0, 3.0};
    ASSERT_TRUE(tin_lies_on_grid(tin, grid));
    const DefaultSampling sampling = default_sampling(tin, grid, 0.01);
    EXPECT_FALSE(sampling.edited);
    ExportOptions o;
    o.cell_size = sampling.cell_size;
    o.cell_height = sampling.cell_height;
    run(tin, "oblong.exr", o);
    const HeightRaster back = read_heightmap(dir_ / "oblong.exr");
    ASSERT_EQ(back.width, 5u);
    ASSERT_EQ(back.height, 4u);
    EXPECT_DOUBLE_EQ(back.cell_size, 2.0);
    EXPECT_DOUBLE_EQ(back.row_spacing(), 3.0);
    for (std::size_t i = 0; i < raster.size(); ++i)
        EXPECT_NEAR(back.heights[i], raster.heights[i], 1e-6) << i;
    // A row spacing without a cell size has nothing to be relative to.
    ExportOptions rows_only;
    rows_only.cell_height = 3.0;
    EXPECT_THROW(run(tin, "bad.png", rows_only), std::invalid_argument);
}

// An edit that inserts a vertex between the import grid's samples makes the default sampling
// finer, so the edit is not sampled away; heights changed on grid vertices keep the grid.
TEST_F(Export, TheImportGridIsTheDefaultOnlyWhileTheTerrainLiesOnIt) {
    HeightRaster raster;
    raster.width = 11;
    raster.height = 11;
    raster.cell_size = 2.0;
    raster.heights.assign(raster.size(), 5.0);
    raster.heights[60] = 6.0;  // a bump, so the TIN keeps an inner vertex
    Tin tin = greedy_tin(raster, {0.0, 0}).tin;
    const std::optional<ImportGrid> grid = import_grid_of(
        R"({"import": {"raster": {"cell_size": 2.0, "cell_height": 0.0}}, "scene": "x"})");
    ASSERT_TRUE(grid.has_value());
    EXPECT_EQ(grid->cell_size, 2.0);
    EXPECT_EQ(grid->row_spacing(), 2.0);
    EXPECT_TRUE(tin_lies_on_grid(tin, *grid));
    VertexId bump = kInvalidVertex;
    for (const VertexId v : test::live_ids(tin))
        if (tin.position(v) == Vec2{10.0, 10.0}) bump = v;
    ASSERT_NE(bump, kInvalidVertex);
    tin.set_height(bump, 7.0);
    EXPECT_TRUE(tin_lies_on_grid(tin, *grid)) << "a height change keeps the vertex on the grid";
    // A 0.5 m pit between samples.
    const VertexId pit = tin.insert_point(Vec2{13.0, 9.0}, 4.5);
    ASSERT_TRUE(tin.is_alive(pit));
    EXPECT_FALSE(tin_lies_on_grid(tin, *grid));
    const DefaultSampling sampling = default_sampling(tin, *grid, 20.0 / 1023.0);
    EXPECT_TRUE(sampling.edited);
    EXPECT_DOUBLE_EQ(sampling.cell_size, 20.0 / 1023.0);
    ExportOptions o;
    o.cell_size = sampling.cell_size;
    run(tin, "edited.png", o);
    const HeightRaster back = read_heightmap(dir_ / "edited.png");
    double lowest = 1e300;
    for (const double h : back.heights)
        lowest = std::min(lowest, h);
    EXPECT_NEAR(lowest, 4.5, 0.01) << "the pit survives the export";
    // No import record, or one with no positive spacing: no import grid.
    EXPECT_FALSE(import_grid_of(R"({"scene": "x"})").has_value());
    EXPECT_FALSE(import_grid_of(R"({"import": {"raster": {"cell_size": 0}}})").has_value());
    EXPECT_FALSE(import_grid_of("not json").has_value());
}

}  // namespace
}  // namespace sandtin
