// Cancelling long engine work (io/cancellation.hpp): an import or an export whose token is
// cancelled stops at its next progress report with Cancelled, and leaves nothing behind: no
// TIN, no new file, every old file as it was, no temporary. Uncancelled, the work, its
// progress and its result are those of a plain run.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "io/cancellation.hpp"
#include "io/export_terrain.hpp"
#include "io/heightmap_import.hpp"
#include "io/session_file.hpp"

namespace sandtin {
namespace cancellation_test {
namespace {

namespace fs = std::filesystem;

/// Every report heard; cancels `token` at the first report whose stage contains `at` (never
/// when `at` is empty).
struct CancellingListener {
    explicit CancellingListener(CancellationToken* t, std::string stage = {})
        : token(t), at(std::move(stage)) {}

    CancellationToken* token;
    std::string at;
    std::vector<double> fractions;

    ProgressCallback callback() {
        return [this](const Progress& p) {
            fractions.push_back(p.fraction);
            if (!at.empty() && std::string(p.stage).find(at) != std::string::npos) token->cancel();
        };
    }

    void expect_monotone_short_of_one() const {
        ASSERT_FALSE(fractions.empty());
        for (std::size_t k = 1; k < fractions.size(); ++k)
            EXPECT_GE(fractions[k], fractions[k - 1]) << "report " << k;
        EXPECT_LT(fractions.back(), 1.0) << "a cancelled job never reports its end";
    }
};

std::vector<char> file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::uint8_t> bytes_of(const Tin& tin) {
    Session session;
    session.terrain = tin.snapshot();
    return encode_session(session);
}

const std::string kTile = std::string(SANDTIN_TEST_DATA_DIR) + "/bay-hills-terrain-rgb.png";

TEST(Cancellation, TheTokenIsCheckedBeforeEveryReportShortOfTheEnd) {
    CancellationToken token;
    std::vector<double> heard;
    const ProgressCallback p =
        cancellable([&](const Progress& r) { heard.push_back(r.fraction); }, token);
    p({0.5, "half"});
    token.cancel();
    token.cancel();  // idempotent
    EXPECT_THROW(p({0.6, "more"}), Cancelled);
    // The work is complete when it reports 1: what is done stays done.
    EXPECT_NO_THROW(p({1.0, "done"}));
    EXPECT_EQ(heard, (std::vector<double>{0.5, 1.0}));
    // An empty listener still carries the check.
    const ProgressCallback silent = cancellable({}, token);
    ASSERT_TRUE(silent);
    EXPECT_THROW(silent({0.0, "start"}), Cancelled);
}

TEST(Cancellation, AnImportCancelledWhileRefiningThrowsCancelled) {
    CancellationToken token;
    CancellingListener listener(&token, "refining");
    EXPECT_THROW(import_heightmap(kTile, ImportOptions{{}, {1.0, 0}},
                                  cancellable(listener.callback(), token)),
                 Cancelled);
    listener.expect_monotone_short_of_one();
    EXPECT_GT(listener.fractions.back(), 0.0) << "cancelled during the insertion, not before";
}

TEST(Cancellation, AnImportCancelledBeforeItStartsReadsNothing) {
    CancellationToken token;
    token.cancel();
    std::vector<double> heard;
    EXPECT_THROW(import_heightmap(
                     kTile, ImportOptions{},
                     cancellable([&](const Progress& p) { heard.push_back(p.fraction); }, token)),
                 Cancelled);
    EXPECT_TRUE(heard.empty());
}

TEST(Cancellation, AnUncancelledImportRisesToOneAndImportsTheSameTerrain) {
    CancellationToken token;
    std::vector<double> heard;
    const ImportOptions options{{}, {1.0, 0}};
    const ImportResult r = import_heightmap(
        kTile, options,
        cancellable([&](const Progress& p) { heard.push_back(p.fraction); }, token));
    ASSERT_GT(heard.size(), 2u);
    for (std::size_t k = 1; k < heard.size(); ++k)
        EXPECT_GE(heard[k], heard[k - 1]);
    EXPECT_EQ(heard.back(), 1.0);
    EXPECT_EQ(bytes_of(r.tin), bytes_of(import_heightmap(kTile, options).tin));
}

class CancelledExport : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("sandtin_cancel_test_" +
                std::to_string(::testing::UnitTest::GetInstance()->current_test_info()->line()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        options_.max_error = 0.002;
        options_.map_size = 128;
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::size_t files_in_dir() const {
        return static_cast<std::size_t>(
            std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
    }

    const Tin tin_ = Tin::random_points(Rect::from_size(1.0, 1.0), 2000, 3, [](Vec2 p) {
        return 0.1 * std::sin(6.0 * p.x) * std::cos(4.0 * p.y);
    });
    ExportOptions options_;
    fs::path dir_;
};

TEST_F(CancelledExport, AMeshCancelledAtEveryStageLeavesNoFile) {
    for (const char* stage : {"refining", "building the mesh", "baking the albedo texture",
                              "baking the normal texture"}) {
        for (const ExportFormat format : {ExportFormat::Glb, ExportFormat::Obj}) {
            const fs::path out = dir_ / (format == ExportFormat::Glb ? "t.glb" : "t.obj");
            CancellationToken token;
            CancellingListener listener(&token, stage);
            EXPECT_THROW(export_terrain(tin_, out, format, options_,
                                        cancellable(listener.callback(), token)),
                         Cancelled)
                << stage;
            listener.expect_monotone_short_of_one();
            EXPECT_EQ(files_in_dir(), 0u) << stage << ": no file, no companion, no temporary";
        }
    }
}

TEST_F(CancelledExport, ACancelAfterTheLastCheckIsTooLateAndTheExportCompletes) {
    // Cancelled while the export reports that it encodes and writes: no check follows before
    // the files are written, so the export is done, in full, and says so by reporting 1.
    const fs::path out = dir_ / "t.glb";
    CancellationToken token;
    CancellingListener listener(&token, "encoding and writing");
    EXPECT_NO_THROW(export_terrain(tin_, out, ExportFormat::Glb, options_,
                                   cancellable(listener.callback(), token)));
    EXPECT_TRUE(token.cancelled());
    EXPECT_EQ(listener.fractions.back(), 1.0);
    EXPECT_GT(fs::file_size(out), 0u);
}

TEST_F(CancelledExport, AMapCancelledWhileBakingLeavesTheOldFileAsItWas) {
    const fs::path out = dir_ / "h.png";
    {
        std::ofstream old(out, std::ios::binary);
        old << "the previous export";
    }
    const std::vector<char> before = file_bytes(out);
    CancellationToken token;
    CancellingListener listener(&token, "baking the map");
    EXPECT_THROW(export_terrain(tin_, out, ExportFormat::HeightPng, {},
                                cancellable(listener.callback(), token)),
                 Cancelled);
    EXPECT_EQ(file_bytes(out), before);
    EXPECT_EQ(files_in_dir(), 1u) << "no temporary left beside it";
}

TEST_F(CancelledExport, AnUncancelledExportWritesTheSameBytesAndEndsAtOne) {
    const fs::path quiet = dir_ / "quiet.glb";
    const fs::path heard = dir_ / "heard.glb";
    export_terrain(tin_, quiet, ExportFormat::Glb, options_);
    CancellationToken token;
    CancellingListener listener(&token);  // never cancels
    export_terrain(tin_, heard, ExportFormat::Glb, options_,
                   cancellable(listener.callback(), token));
    ASSERT_FALSE(listener.fractions.empty());
    for (std::size_t k = 1; k < listener.fractions.size(); ++k)
        EXPECT_GE(listener.fractions[k], listener.fractions[k - 1]);
    EXPECT_EQ(listener.fractions.back(), 1.0);
    EXPECT_EQ(file_bytes(heard), file_bytes(quiet));
}

}  // namespace
}  // namespace cancellation_test
}  // namespace sandtin
