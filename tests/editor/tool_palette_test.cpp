// The editor's tool palette against what it must offer: every tool shipped in assets/tools
// (read from the folder, not from a list), every brush the engine has, and keys that pick
// exactly one tool without taking the keys the editor uses for other things.

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <set>
#include <string>

#include "tool_palette.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::editor {
namespace {

TEST(ToolPalette, OffersEveryShippedToolAndEveryBrush) {
    const std::filesystem::path dir = std::filesystem::path(SANDTIN_SOURCE_DIR) / "assets/tools";
    std::set<std::string> shipped;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().extension() == ".json") shipped.insert(e.path().stem().string());
    }
    ASSERT_GE(shipped.size(), 6u) << dir;
    std::set<std::string> stamps;
    std::set<BrushKind> brushes;
    bool pour = false, remove = false, water = false, rain = false;
    for (const ToolEntry& t : kTools) {
        if (t.kind == ToolKind::Stamp) {
            stamps.insert(t.asset);
            // The asset loads and builds: its contour and profile are valid.
            EXPECT_NO_THROW(Tool::build(load_tool_asset(t.asset))) << t.label;
        }
        if (t.kind == ToolKind::Brush) brushes.insert(t.brush);
        pour |= t.kind == ToolKind::Pour;
        remove |= t.kind == ToolKind::Remove;
        water |= t.kind == ToolKind::Water;
        rain |= t.kind == ToolKind::Rain;
    }
    EXPECT_EQ(stamps, shipped);
    for (const BrushKind b : {BrushKind::Raise, BrushKind::Lower, BrushKind::Smooth,
                              BrushKind::Flatten, BrushKind::PaintMaterial, BrushKind::Weather}) {
        EXPECT_EQ(brushes.count(b), 1u) << "brush kind " << static_cast<int>(b);
    }
    EXPECT_TRUE(pour);
    EXPECT_TRUE(remove);
    EXPECT_TRUE(water);
    EXPECT_TRUE(rain);
}

// The Tools panel shows Size and Depth only for the tools they act on. Size: the circle and
// the ball take the slider's radius, while the box, rake, letter and foot keep their asset's
// shape whatever the radius (checked on the built tools, not assumed); Depth: stamps, and
// every tool while the haptic pen rests in the sand. Both sliders used to show for every tool.
TEST(ToolPalette, SizeAndDepthShowOnlyForTheToolsTheyActOn) {
    for (const ToolEntry& t : kTools) {
        bool round = false;
        if (t.kind == ToolKind::Stamp) {
            ToolSpec small = load_tool_asset(t.asset), large = small;
            round = sized_by_slider(small);
            small.radius = 0.01;
            large.radius = 0.15;
            const bool radius_matters =
                Tool::build(small).shape().inner != Tool::build(large).shape().inner;
            EXPECT_EQ(round, radius_matters) << t.label;
        }
        const ToolSliders alone = sliders_for(t, round, false);
        const ToolSliders with_pen = sliders_for(t, round, true);
        const std::string label = t.label;
        // The Water tool's nozzle is a point: no size.
        const bool sized = label == "Circle" || label == "Ball" ||
                           (t.kind != ToolKind::Stamp && t.kind != ToolKind::Water);
        EXPECT_EQ(alone.size, sized) << label;
        EXPECT_EQ(alone.depth, t.kind == ToolKind::Stamp) << label;
        EXPECT_TRUE(with_pen.depth) << label;
    }
}

TEST(ToolPalette, EachKeyAndLabelPicksOneTool) {
    std::set<char> keys;
    std::set<std::string> labels;
    for (int i = 0; i < kToolCount; ++i) {
        const ToolEntry& t = kTools[i];
        // A digit or an upper-case letter: GLFW's key code for that key.
        EXPECT_TRUE(std::isdigit(t.key) || std::isupper(t.key)) << t.label;
        // F frames the terrain.
        EXPECT_NE(t.key, 'F') << t.label;
        EXPECT_TRUE(keys.insert(t.key).second) << "key " << t.key << " twice";
        EXPECT_TRUE(labels.insert(t.label).second) << t.label << " twice";
        EXPECT_EQ(tool_for_key(t.key), i) << t.label;
        EXPECT_EQ(tool_named(t.label), i) << t.label;
        // The tooltip tells the artist the key.
        EXPECT_NE(std::string(t.help).find(std::string("(key ") + t.key + ")"), std::string::npos)
            << t.label << ": " << t.help;
    }
    EXPECT_FALSE(tool_for_key('F').has_value());
    EXPECT_FALSE(tool_for_key('X').has_value());
    EXPECT_FALSE(tool_named("circle").has_value());  // labels are matched exactly
}

}  // namespace
}  // namespace sandtin::editor
