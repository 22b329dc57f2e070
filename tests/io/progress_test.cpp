// Progress callbacks of the long engine work (io/progress.hpp): greedy insertion, heightmap
// import, export and script runs. Each must report fractions in [0, 1] that never decrease and
// end at exactly 1, report between its ends (not only 0 and 1), and give a result bit for bit
// the same as without a listener.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/export_terrain.hpp"
#include "io/greedy_tin.hpp"
#include "io/heightmap_import.hpp"
#include "io/progress.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
#include "support/height_fields.hpp"

namespace sandtin {
namespace {

/// Every report a job made.
struct Recorder {
    std::vector<double> fractions;
    std::vector<std::string> stages;

    ProgressCallback callback() {
        return [this](const Progress& p) {
            fractions.push_back(p.fraction);
            stages.emplace_back(p.stage);
        };
    }

    /// In [0, 1], never decreasing, ending at 1, with at least `inner` reports strictly between.
    void expect_well_formed(std::size_t inner) const {
        ASSERT_FALSE(fractions.empty()) << "no progress reported";
        for (std::size_t k = 0; k < fractions.size(); ++k) {
            EXPECT_GE(fractions[k], 0.0) << "report " << k;
            EXPECT_LE(fractions[k], 1.0) << "report " << k;
            if (k > 0) {
                EXPECT_GE(fractions[k], fractions[k - 1])
                    << "report " << k << " (" << stages[k] << ") went back from " << stages[k - 1];
            }
        }
        EXPECT_EQ(fractions.back(), 1.0);
        std::size_t between = 0;
        for (double f : fractions)
            between += f > 0.0 && f < 1.0 ? 1 : 0;
        EXPECT_GE(between, inner) << "too few reports between the start and the end";
    }

    bool has_stage(const std::string& text) const {
        for (const std::string& s : stages) {
            if (s.find(text) != std::string::npos) return true;
        }
        return false;
    }
};

/// The terrain as the bytes of a session: equal bytes, bit-identical terrains.
std::vector<std::uint8_t> bytes_of(const Tin& tin) {
    Session session;
    session.terrain = tin.snapshot();
    return encode_session(session);
}

std::vector<char> file_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Rolling hills with fine ripples on 1 m cells: many insertions before a 1 cm bound.
HeightRaster hills(std::uint32_t n) {
    return test::raster_of(n, n, [](double x, double y) {
        return 5.0 * std::sin(0.05 * x) * std::cos(0.07 * y) + 0.3 * std::sin(0.9 * x + 0.4 * y);
    });
}

TEST(Progress, GreedyInsertionRisesToOneAndBuildsTheSameTin) {
    const HeightRaster raster = hills(200);
    const GreedyOptions options{0.01, 0};
    const GreedyResult quiet = greedy_tin(raster, options);
    Recorder recorder;
    const GreedyResult heard = greedy_tin(raster, options, recorder.callback());
    recorder.expect_well_formed(5);
    EXPECT_TRUE(recorder.has_stage("refining"));
    EXPECT_TRUE(recorder.has_stage("measuring"));
    EXPECT_EQ(bytes_of(heard.tin), bytes_of(quiet.tin));
    EXPECT_EQ(heard.stats.points, quiet.stats.points);
    EXPECT_EQ(heard.stats.max_error, quiet.stats.max_error);
    EXPECT_EQ(heard.stats.rmsd, quiet.stats.rmsd);
}

TEST(Progress, APointLimitedInsertionStillEndsAtOne) {
    const HeightRaster raster = hills(120);
    const GreedyOptions options{0.0, 2000};
    Recorder recorder;
    const GreedyResult heard = greedy_tin(raster, options, recorder.callback());
    recorder.expect_well_formed(3);
    EXPECT_FALSE(heard.stats.reached_error);
    EXPECT_EQ(bytes_of(heard.tin), bytes_of(greedy_tin(raster, options).tin));
}

TEST(Progress, ImportReadsThenRefinesAndImportsTheSameTerrain) {
    const std::string tile = std::string(SANDTIN_TEST_DATA_DIR) + "/bay-hills-terrain-rgb.png";
    const ImportOptions options{{}, {1.0, 0}};
    Recorder recorder;
    const ImportResult heard = import_heightmap(tile, options, recorder.callback());
    recorder.expect_well_formed(5);
    EXPECT_EQ(recorder.stages.front(), "reading the heightmap");
    EXPECT_EQ(bytes_of(heard.tin), bytes_of(import_heightmap(tile, options).tin));
}

class ExportProgress : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("sandtin_progress_test_" +
                std::to_string(::testing::UnitTest::GetInstance()->current_test_info()->line()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(ExportProgress, ATexturedSimplifiedMeshReportsEveryStageAndWritesTheSameBytes) {
    const Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 2000, 3, [](Vec2 p) {
        return 0.1 * std::sin(6.0 * p.x) * std::cos(4.0 * p.y);
    });
    ExportOptions options;
    options.max_error = 0.002;
    options.map_size = 128;
    const std::filesystem::path quiet = dir_ / "quiet.glb";
    const std::filesystem::path heard = dir_ / "heard.glb";
    export_terrain(tin, quiet, ExportFormat::Glb, options);
    Recorder recorder;
    export_terrain(tin, heard, ExportFormat::Glb, options, recorder.callback());
    recorder.expect_well_formed(4);
    for (const char* stage : {"refining", "building the mesh", "baking the albedo texture",
                              "baking the normal texture", "encoding and writing"}) {
        EXPECT_TRUE(recorder.has_stage(stage)) << stage;
    }
    EXPECT_EQ(file_bytes(heard), file_bytes(quiet));
}

TEST_F(ExportProgress, AMapReportsBakingAndEncoding) {
    const Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 500, 5,
                                       [](Vec2 p) { return 0.05 * p.x * p.y; });
    ExportOptions options;
    options.map_size = 64;
    Recorder recorder;
    export_terrain(tin, dir_ / "h.png", ExportFormat::HeightPng, options, recorder.callback());
    recorder.expect_well_formed(1);
    EXPECT_TRUE(recorder.has_stage("baking the map"));
    EXPECT_TRUE(recorder.has_stage("encoding and writing the map"));
}

TEST(Progress, AScriptReportsEachOperationAndLeavesTheSameTerrain) {
    const std::string text = R"({"version": 1,
      "terrain": {"size": [1, 1], "points": 3000, "seed": 2, "height": 0.1},
      "operations": [
        {"op": "stroke", "tool": {"radius": 0.03}, "path": [[0.2, 0.5], [0.8, 0.5]],
         "spacing": 0.02, "depth": 0.01, "erode": true, "erode_iterations": 2},
        {"op": "pour", "path": [[0.3, 0.3], [0.7, 0.3]], "volume": 1e-4, "radius": 0.03},
        {"op": "brush", "kind": "smooth", "path": [[0.3, 0.7], [0.7, 0.7]]},
        {"op": "erode", "iterations": 3}]})";
    const Script script = parse_script(text, "progress", ".");
    const auto run = [&](const ProgressCallback& progress) {
        Tin tin = make_script_terrain(*script.terrain);
        SculptContext context(tin.domain());
        run_script(script, tin, context, {}, nullptr, progress);
        return bytes_of(tin);
    };
    const std::vector<std::uint8_t> quiet = run({});
    Recorder recorder;
    const std::vector<std::uint8_t> heard = run(recorder.callback());
    // The stroke's 31 stamps, the pour's and the brush's points: far more than 4 steps.
    recorder.expect_well_formed(20);
    EXPECT_TRUE(recorder.has_stage("operation 1 of 4 (stroke)"));
    EXPECT_TRUE(recorder.has_stage("operation 4 of 4 (erode)"));
    EXPECT_EQ(heard, quiet);
}

TEST(Progress, APartMapsItsFractionsIntoTheWhole) {
    Recorder recorder;
    const ProgressCallback part = progress_part(recorder.callback(), 0.25, 0.75);
    part({0.0, "a"});
    part({0.5, "b"});
    part({1.0, "c"});
    EXPECT_EQ(recorder.fractions, (std::vector<double>{0.25, 0.5, 0.75}));
    EXPECT_EQ(recorder.stages, (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_FALSE(progress_part({}, 0.0, 1.0)) << "an empty whole gives an empty part";
}

}  // namespace
}  // namespace sandtin
