// The editor's settings file: a round trip, bad files, and the fields checked on load.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "editor_settings.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {
namespace {

TEST(Settings, RoundTripAndBadFiles) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-editor-settings-test";
    std::filesystem::remove_all(dir);
    const auto path = dir / "nested" / "editor.json";
    EditorSettings s;
    EXPECT_EQ(load_settings(path), s);  // missing: defaults
    s.tool = 4;
    s.tool_radius = 0.07;
    s.overlay_slope = true;
    s.vsync = false;
    s.erosion_steps = 77;
    s.erosion_gpu = true;
    s.settle_margin = 0.05;
    save_settings(path, s);
    std::string problem;
    EXPECT_EQ(load_settings(path, &problem), s);
    EXPECT_TRUE(problem.empty());

    std::ofstream(path) << "{ not json";
    EXPECT_EQ(load_settings(path, &problem), EditorSettings{});
    EXPECT_NE(problem.find("editor.json"), std::string::npos);
    std::ofstream(path) << R"({"tool_radius": "big"})";
    problem.clear();
    EXPECT_EQ(load_settings(path, &problem), EditorSettings{});
    EXPECT_FALSE(problem.empty());
    std::filesystem::remove_all(dir);
}

TEST(Settings, TheToolIsSavedByItsLabelAndBrushSettingsAreChecked) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-editor-settings-tool";
    std::filesystem::remove_all(dir);
    const auto path = dir / "editor.json";
    EditorSettings s;
    s.tool = *tool_named("Flatten");
    s.brush_blend = 0.25;
    s.brush_falloff = "gaussian";
    save_settings(path, s);
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("tool"), "Flatten");  // by label, so a new palette order keeps the choice
    std::string problem;
    EXPECT_EQ(load_settings(path, &problem), s);
    EXPECT_TRUE(problem.empty()) << problem;

    // An index from an older palette, or a label this one lacks: the first tool, and the rest
    // of the file still counts.
    std::ofstream(path) << R"({"tool": 7, "tool_radius": 0.03})";
    EXPECT_EQ(load_settings(path, &problem).tool, 0);
    EXPECT_EQ(load_settings(path, &problem).tool_radius, 0.03);
    std::ofstream(path) << R"({"tool": "Chisel", "tool_radius": 0.03})";
    EXPECT_EQ(load_settings(path, &problem).tool, 0);
    EXPECT_EQ(load_settings(path, &problem).tool_radius, 0.03);
    EXPECT_TRUE(problem.empty()) << problem;

    // Values a brush would refuse are refused here, with the field named.
    for (const char* bad :
         {R"({"brush_falloff": "cubic"})", R"({"brush_blend": 1.5})", R"({"brush_blend": -0.1})"}) {
        std::ofstream(path) << bad;
        problem.clear();
        EXPECT_EQ(load_settings(path, &problem), EditorSettings{}) << bad;
        EXPECT_NE(problem.find("brush_"), std::string::npos) << bad << ": " << problem;
    }
    // A stroke spacing of zero would never finish a stroke; one past the slider's range is no
    // setting the panel could have written.
    for (const char* bad : {R"({"stroke_spacing_ratio": 0})", R"({"stroke_spacing_ratio": -0.5})",
                            R"({"stroke_spacing_ratio": 50})"}) {
        std::ofstream(path) << bad;
        problem.clear();
        EXPECT_EQ(load_settings(path, &problem), EditorSettings{}) << bad;
        EXPECT_NE(problem.find("stroke_spacing_ratio"), std::string::npos)
            << bad << ": " << problem;
    }
    // The metres of earlier versions' "stroke_spacing" are not a fraction: the key is ignored,
    // and the rest of the file counts.
    std::ofstream(path) << R"({"stroke_spacing": 0.01, "tool_radius": 0.03})";
    problem.clear();
    EXPECT_EQ(load_settings(path, &problem).stroke_spacing_ratio, 0.25);
    EXPECT_EQ(load_settings(path, &problem).tool_radius, 0.03);
    EXPECT_TRUE(problem.empty()) << problem;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sandtin::editor
