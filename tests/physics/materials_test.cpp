// Materials: the moisture model (documented in physics/material.hpp) and the shipped presets.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "physics/material.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Moisture, CapillaryRiseThenSlurry) {
    const Material dry = MaterialTable::presets().at(0);
    EXPECT_NEAR(dry.repose(0.0), 32.0 * kDeg, 1e-12);
    // The pendular rise: monotone, most of it by a few per cent of saturation.
    double last = dry.repose(0.0);
    for (double m = 0.01; m <= dry.slurry_start; m += 0.01) {
        EXPECT_GE(dry.repose(m), last);
        last = dry.repose(m);
    }
    EXPECT_GT(dry.repose(3.0 * dry.moisture_scale), 31.0 * kDeg + 0.9 * 12.0 * kDeg);
    EXPECT_LT(dry.repose(dry.slurry_start), 44.0 * kDeg + 1e-12);
    // Past slurry_start, bridges merge and the slope collapses to the saturated angle.
    EXPECT_NEAR(dry.repose(1.0), 12.0 * kDeg, 1e-12);
    EXPECT_LT(dry.repose(0.95), dry.repose(dry.slurry_start));
    EXPECT_NEAR(dry.talus_slope(0.0), std::tan(32.0 * kDeg), 1e-12);
    // Out-of-range saturation is clamped, never NaN.
    EXPECT_EQ(dry.repose(-1.0), dry.repose(0.0));
    EXPECT_EQ(dry.repose(2.0), dry.repose(1.0));
}

TEST(Presets, FileMatchesBuiltInTable) {
    const MaterialTable file = MaterialTable::load(SANDTIN_ASSET_DIR "/materials/presets.json");
    const MaterialTable built = MaterialTable::presets();
    ASSERT_EQ(file.size(), built.size());
    ASSERT_GE(file.size(), 3u);
    for (std::size_t i = 0; i < file.size(); ++i) {
        const Material& a = file.all()[i];
        const Material& b = built.all()[i];
        EXPECT_EQ(a.name, b.name);
        for (double m : {0.0, 0.02, 0.25, 0.9, 1.0})
            EXPECT_NEAR(a.repose(m), b.repose(m), 1e-12) << a.name << " at " << m;
        EXPECT_EQ(a.haptic_stiffness, b.haptic_stiffness);
        EXPECT_EQ(a.haptic_friction, b.haptic_friction);
        EXPECT_EQ(a.default_moisture, b.default_moisture);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(a.colour[k], b.colour[k], 1e-6);
    }
    EXPECT_EQ(built.at(0).name, "dry_sand");
    EXPECT_EQ(built.at(1).name, "moist_sand");
    EXPECT_EQ(built.at(2).name, "gravel");
    // Dry sand 30-34°, moist sand steeper at its default moisture, gravel steeper than dry sand.
    EXPECT_GE(built.at(0).repose(0.0), 30.0 * kDeg);
    EXPECT_LE(built.at(0).repose(0.0), 34.0 * kDeg);
    EXPECT_GT(built.at(1).repose(built.at(1).default_moisture), built.at(0).repose(0.0) + 5 * kDeg);
    EXPECT_GT(built.at(2).repose(0.0), built.at(0).repose(0.0));
    // Unknown ids fall back to the first material instead of crashing.
    EXPECT_EQ(built.at(999).name, "dry_sand");
}

TEST(Presets, BadFileNamesTheProblem) {
    const std::string path = ::testing::TempDir() + "bad_materials.json";
    {
        std::ofstream out(path);
        out << R"([{"name": "x", "repose_dry_deg": 95}])";
    }
    try {
        MaterialTable::load(path);
        FAIL() << "expected an error";
    } catch (const JsonInputError& e) {
        EXPECT_NE(std::string(e.what()).find("repose_dry_deg"), std::string::npos) << e.what();
    }
    EXPECT_THROW(MaterialTable::load(::testing::TempDir() + "missing.json"), JsonInputError);
}

}  // namespace
}  // namespace sandtin
