// Materials saved in a session's metadata: a round trip keeps every field (angles within
// rounding of the degree conversion), the reader agrees with the engine's own material-file
// reader (MaterialTable::load) on the shipped presets, metadata without materials gives
// nothing, and bad entries are errors that name the entry and field.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/scene_materials.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {

void expect_same(const MaterialTable& a, const MaterialTable& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Material& x = a.all()[i];
        const Material& y = b.all()[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_NEAR(x.repose_dry, y.repose_dry, 1e-12);
        EXPECT_NEAR(x.repose_wet, y.repose_wet, 1e-12);
        EXPECT_NEAR(x.repose_saturated, y.repose_saturated, 1e-12);
        EXPECT_DOUBLE_EQ(x.moisture_scale, y.moisture_scale);
        EXPECT_DOUBLE_EQ(x.slurry_start, y.slurry_start);
        EXPECT_DOUBLE_EQ(x.haptic_stiffness, y.haptic_stiffness);
        EXPECT_DOUBLE_EQ(x.haptic_friction, y.haptic_friction);
        EXPECT_EQ(x.default_moisture, y.default_moisture);
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(x.colour[c], y.colour[c]);
    }
}

TEST(SceneMaterials, RoundTripKeepsAnEditedTable) {
    std::vector<Material> all = MaterialTable::presets().all();
    all[1].repose_dry = 0.41;
    all[1].colour[2] = 0.9f;
    all[2].default_moisture = 0.25f;
    const MaterialTable edited(all);
    const std::string meta = session_metadata(edited);
    EXPECT_EQ(nlohmann::json::parse(meta).at("editor"), "sandtin-editor");
    const auto back = materials_from_metadata(meta);
    ASSERT_TRUE(back.has_value());
    expect_same(*back, edited);
}

// A scene imported by `sandtin import` carries its import record (grid, georeference) in the
// metadata; an editor save replaces the materials and keeps the rest.
TEST(SceneMaterials, SavingKeepsTheOtherKeysOfTheMetadata) {
    const std::string opened =
        R"({"import": {"georeference": {"west": 1005.0}}, "materials": [], "editor": "x"})";
    const nlohmann::json saved =
        nlohmann::json::parse(session_metadata(MaterialTable::presets(), opened));
    EXPECT_EQ(saved.at("/import/georeference/west"_json_pointer), 1005.0);
    EXPECT_EQ(saved.at("editor"), "sandtin-editor");
    EXPECT_EQ(saved.at("materials").size(), MaterialTable::presets().all().size());
    // Metadata that is not an object gives way to a fresh one.
    EXPECT_EQ(nlohmann::json::parse(session_metadata(MaterialTable::presets(), "[1]")).size(), 2u);
}

TEST(SceneMaterials, AgreesWithTheEngineReaderOnThePresetsFile) {
    const std::filesystem::path presets =
        std::filesystem::path(SANDTIN_SOURCE_DIR) / "assets" / "materials" / "presets.json";
    std::ifstream in(presets);
    ASSERT_TRUE(in) << presets;
    std::stringstream text;
    text << R"({"materials": )" << in.rdbuf() << "}";
    const auto mine = materials_from_metadata(text.str());
    ASSERT_TRUE(mine.has_value());
    expect_same(*mine, MaterialTable::load(presets));
}

TEST(SceneMaterials, NoTableIsNothingAndBadEntriesNameTheField) {
    EXPECT_FALSE(materials_from_metadata(R"({"editor": "sandtin-editor"})").has_value());
    EXPECT_FALSE(materials_from_metadata("{}").has_value());
    try {
        (void)materials_from_metadata(R"({"materials": [{"name": "a"}, {"repose_dry_deg": 95}]})");
        FAIL() << "an angle of 95 degrees was accepted";
    } catch (const JsonInputError& e) {
        EXPECT_NE(std::string(e.what()).find("material 1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("repose_dry_deg"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)materials_from_metadata(R"({"materials": []})"), JsonInputError);
    EXPECT_THROW((void)materials_from_metadata("{ not json"), JsonInputError);
}

}  // namespace
}  // namespace sandtin
