// The editor's settings file: a round trip, bad files, and the fields checked on load.

#include <gtest/gtest.h>

#include <cmath>
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
    s.physics = "gpu";
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

TEST(Settings, ABadFieldFallsBackAloneAndIsNamedWithItsRange) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-editor-settings-fields";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto path = dir / "editor.json";
    const EditorSettings defaults;
    // Values a typed slider once let in (issue 43): each falls back to its default, the good
    // fields count, and the problem names each bad field with its value and range.
    std::ofstream(path) << R"({"tool_radius": -2, "pour_volume": -5, "erosion_steps": 0,
        "tool_depth": -0.01, "contrast": 0.7, "vsync": false, "settle_margin": "lots"})";
    std::string problem;
    const EditorSettings s = load_settings(path, &problem);
    EXPECT_EQ(s.tool_radius, defaults.tool_radius);
    EXPECT_EQ(s.pour_volume, defaults.pour_volume);
    EXPECT_EQ(s.erosion_steps, defaults.erosion_steps);
    EXPECT_EQ(s.tool_depth, defaults.tool_depth);
    EXPECT_EQ(s.settle_margin, defaults.settle_margin);
    EXPECT_EQ(s.contrast, 0.7);
    EXPECT_FALSE(s.vsync);
    for (const char* named : {"tool_radius -2 is outside [0.005, 0.15]", "pour_volume -5",
                              "erosion_steps 0", "tool_depth -0.01", "settle_margin \"lots\""})
        EXPECT_NE(problem.find(named), std::string::npos) << named << " in " << problem;
    EXPECT_EQ(problem.find("contrast"), std::string::npos) << problem;

    // The ranges are those of the terrain the file was written for: on a 100 m terrain a 4 m
    // tool is in range and a 40 m one is not.
    std::ofstream(path) << R"({"scene_size": 100, "tool_radius": 4, "relocation_radius": 40})";
    problem.clear();
    const EditorSettings big = load_settings(path, &problem);
    EXPECT_EQ(big.scene_size, 100.0);
    EXPECT_EQ(big.tool_radius, 4.0);
    EXPECT_EQ(big.relocation_radius, defaults.relocation_radius);
    EXPECT_NE(problem.find("relocation_radius 40 is outside [0.1, 5]"), std::string::npos)
        << problem;
    std::filesystem::remove_all(dir);
}

TEST(Settings, ThePhysicsChoiceIsAutoByDefaultAndAnOldGpuFlagStaysAChoiceOfTheGpu) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-editor-settings-physics";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto path = dir / "editor.json";
    EXPECT_EQ(EditorSettings{}.physics, "auto");
    std::string problem;
    std::ofstream(path) << R"({"erosion_gpu": true})";
    EXPECT_EQ(load_settings(path, &problem).physics, "gpu");
    std::ofstream(path) << R"({"erosion_gpu": false})";
    EXPECT_EQ(load_settings(path, &problem).physics, "auto");
    std::ofstream(path) << R"({"physics": "cpu", "erosion_gpu": true})";
    EXPECT_EQ(load_settings(path, &problem).physics, "cpu");
    EXPECT_TRUE(problem.empty()) << problem;
    std::ofstream(path) << R"({"physics": "quantum"})";
    EXPECT_EQ(load_settings(path, &problem).physics, "auto");
    EXPECT_NE(problem.find("physics 'quantum'"), std::string::npos) << problem;
    std::filesystem::remove_all(dir);
}

TEST(Settings, TheFileDialogChoiceAndTheLastFolderSurviveAndABadChoiceFallsBack) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-editor-settings-dialog";
    std::filesystem::remove_all(dir);
    const auto path = dir / "editor.json";
    EXPECT_EQ(EditorSettings{}.file_dialog, "auto");
    EXPECT_EQ(EditorSettings{}.last_folder, "");
    EditorSettings s;
    s.file_dialog = "imgui";
    s.last_folder = "/data/dunes and hills";
    save_settings(path, s);
    std::string problem;
    const EditorSettings loaded = load_settings(path, &problem);
    EXPECT_EQ(loaded.file_dialog, "imgui");
    EXPECT_EQ(loaded.last_folder, "/data/dunes and hills");
    EXPECT_TRUE(problem.empty()) << problem;
    std::ofstream(path) << R"({"file_dialog": "gtk", "last_folder": "/data"})";
    const EditorSettings bad = load_settings(path, &problem);
    EXPECT_EQ(bad.file_dialog, "auto");
    EXPECT_EQ(bad.last_folder, "/data") << "the rest of the file still counts";
    EXPECT_NE(problem.find("file_dialog 'gtk'"), std::string::npos) << problem;
    std::filesystem::remove_all(dir);
}

TEST(Settings, TheSlopeRuleIsFacesByDefaultSurvivesAndABadOneFallsBack) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-editor-settings-rule";
    std::filesystem::remove_all(dir);
    const auto path = dir / "editor.json";
    EXPECT_EQ(EditorSettings{}.slope_rule, "face");
    EditorSettings s;
    s.slope_rule = "edge";
    save_settings(path, s);
    std::string problem;
    EXPECT_EQ(load_settings(path, &problem).slope_rule, "edge");
    EXPECT_TRUE(problem.empty()) << problem;
    std::ofstream(path) << R"({"slope_rule": "vertex", "settle_margin": 0.01})";
    const EditorSettings bad = load_settings(path, &problem);
    EXPECT_EQ(bad.slope_rule, "face");
    EXPECT_EQ(bad.settle_margin, 0.01) << "the rest of the file still counts";
    EXPECT_NE(problem.find("slope_rule 'vertex'"), std::string::npos) << problem;
    std::filesystem::remove_all(dir);
}

TEST(Settings, RangesClampWhatIsTypedAndScaleWithTheTerrain) {
    EXPECT_EQ(kToolRadiusRange.clamp(-2.0, 1.0), 0.005);
    EXPECT_EQ(kToolRadiusRange.clamp(1e9, 1.0), 0.15);
    EXPECT_EQ(kToolRadiusRange.clamp(0.05, 1.0), 0.05);
    EXPECT_EQ(kToolRadiusRange.clamp(std::nan(""), 1.0), 0.005);
    EXPECT_DOUBLE_EQ(kToolRadiusRange.hi_at(200.0), 30.0);
    EXPECT_DOUBLE_EQ(kPourVolumeRange.hi_at(10.0), 2e-4 * 1000.0);
    EXPECT_EQ(kStrokeSpacingRange.hi_at(500.0), 2.0);  // a share of the radius: not scaled
    // The defaults lie in their ranges (a fresh install must pass its own check).
    const EditorSettings d;
    EXPECT_TRUE(kToolRadiusRange.contains(d.tool_radius, 1.0));
    EXPECT_TRUE(kToolDepthRange.contains(d.tool_depth, 1.0));
    EXPECT_TRUE(kStrokeSpacingRange.contains(d.stroke_spacing_ratio, 1.0));
    EXPECT_TRUE(kBrushStrengthRange.contains(d.brush_strength, 1.0));
    EXPECT_TRUE(kBrushBlendRange.contains(d.brush_blend, 1.0));
    EXPECT_TRUE(kPourVolumeRange.contains(d.pour_volume, 1.0));
    EXPECT_TRUE(kErosionStepsRange.contains(d.erosion_steps, 1.0));
    EXPECT_TRUE(kSimplifyToleranceRange.contains(d.simplify_tolerance, 1.0));
    EXPECT_TRUE(kRelocationRadiusRange.contains(d.relocation_radius, 1.0));
    EXPECT_TRUE(kSettleMarginRange.contains(d.settle_margin, 1.0));
    EXPECT_TRUE(kContrastRange.contains(d.contrast, 1.0));
}

}  // namespace
}  // namespace sandtin::editor
