// The editor's length settings follow the terrain's size (terrain_scale.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "editor_settings.hpp"
#include "terrain_scale.hpp"

namespace sandtin::editor {
namespace {

/// The defaults with every length times k and the pour times k³: what a terrain k times the
/// 1 m sandbox should get.
EditorSettings defaults_scaled(double k) {
    EditorSettings s;
    s.tool_radius *= k;
    s.tool_depth *= k;
    s.brush_strength *= k;
    s.relocation_radius *= k;
    s.simplify_tolerance *= k;
    s.pour_volume *= k * k * k;
    s.scene_size = k;
    return s;
}

TEST(TerrainScale, LengthsScaleWithTheSizeAndThePourWithItsCube) {
    EditorSettings s;
    s.tool = 3;  // not lengths: must not change
    s.erosion_steps = 31;
    s.settle_margin = 0.05;
    EXPECT_EQ(fit_settings_to_terrain(s, 250.0), 250.0);
    EditorSettings expected = defaults_scaled(250.0);
    expected.tool = 3;
    expected.erosion_steps = 31;
    expected.settle_margin = 0.05;
    EXPECT_EQ(s, expected);

    // From there to a 2 m terrain: relative to the size the settings were made for.
    EXPECT_DOUBLE_EQ(fit_settings_to_terrain(s, 2.0), 2.0 / 250.0);
    EXPECT_DOUBLE_EQ(s.tool_radius, EditorSettings{}.tool_radius * 2.0);
    EXPECT_DOUBLE_EQ(s.pour_volume, EditorSettings{}.pour_volume * 8.0);
    EXPECT_EQ(s.scene_size, 2.0);
}

TEST(TerrainScale, TheSameSizeChangesNothing) {
    EditorSettings s = defaults_scaled(3.0);
    s.tool_radius = 0.123;  // a value the artist chose
    const EditorSettings before = s;
    EXPECT_EQ(fit_settings_to_terrain(s, 3.0), 1.0);
    EXPECT_EQ(s, before);
}

TEST(TerrainScale, AnInvalidRememberedSizeCountsAsTheOneMetreSandbox) {
    for (double bad : {0.0, -4.0, std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
        SCOPED_TRACE(bad);
        EditorSettings s;
        s.scene_size = bad;
        EXPECT_EQ(fit_settings_to_terrain(s, 40.0), 40.0);
        EXPECT_EQ(s, defaults_scaled(40.0));
    }
}

TEST(TerrainScale, TerrainSizeIsTheLargerSide) {
    EXPECT_EQ(terrain_size(Rect{{-1.0, 2.0}, {2.0, 9.0}}), 7.0);
    EXPECT_EQ(terrain_size(Rect{{0.0, 0.0}, {5.0, 0.5}}), 5.0);
}

TEST(TerrainScale, SlidersReadAtLeastTenInTheirUnit) {
    // On the 1 m sandbox the panels keep the units they always had.
    EXPECT_EQ(std::string(length_unit(0.15).suffix), "cm");   // tool size up to 15 cm
    EXPECT_EQ(std::string(length_unit(0.04).suffix), "mm");   // depth up to 40 mm
    EXPECT_EQ(std::string(length_unit(0.005).suffix), "mm");  // simplify: nothing smaller
    EXPECT_EQ(std::string(volume_unit(2e-4).suffix), "cm3");  // pour up to 200 cm3
    // Larger terrains step up, and the unit's size is what its name says.
    EXPECT_EQ(std::string(length_unit(15.0).suffix), "m");
    EXPECT_EQ(length_unit(15.0).metres, 1.0);
    EXPECT_EQ(std::string(length_unit(4.0).suffix), "cm");
    EXPECT_EQ(length_unit(4.0).metres, 0.01);
    EXPECT_EQ(std::string(length_unit(150.0).suffix), "m");
    EXPECT_EQ(std::string(length_unit(15000.0).suffix), "km");
    EXPECT_EQ(length_unit(150000.0).metres, 1000.0);
    EXPECT_EQ(std::string(volume_unit(200.0).suffix), "m3");
    EXPECT_EQ(std::string(volume_unit(0.2).suffix), "L");
    EXPECT_EQ(volume_unit(0.2).metres, 1e-3);
    for (double largest : {1e-4, 0.003, 0.07, 0.9, 12.0, 3e3, 5e5}) {
        const DisplayUnit u = length_unit(largest);
        EXPECT_TRUE(largest / u.metres >= 10.0 || u.metres == 1e-3) << largest;
        EXPECT_TRUE(largest / u.metres < 10000.0 || u.metres == 1e3) << largest;
    }
}

}  // namespace
}  // namespace sandtin::editor
