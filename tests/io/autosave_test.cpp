// Autosave and recovery: the autosave sits next to the scene, a crash during an autosave
// keeps the previous one, recovery is offered only for a loadable autosave newer than the
// scene, and an explicit save retires the autosave.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "io/autosave.hpp"
#include "io/autosave_writer.hpp"
#include "io/session_keeper.hpp"
#include "support/scratch_folder.hpp"
#include "support/tin_oracles.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

namespace fs = std::filesystem;

Session session_with(std::size_t points, double height) {
    Session s;
    s.terrain = Tin::random_points(Rect::from_size(3.0, 2.0), points, points, [height](Vec2) {
                    return height;
                }).snapshot();
    s.metadata_json = R"({"name":"beach"})";
    return s;
}

class Autosave : public test::ScratchFolderTest {
  protected:
    Autosave() : ScratchFolderTest("autosave") {}
    void SetUp() override {
        ScratchFolderTest::SetUp();
        scene_ = dir_ / "beach.sandtin";
    }

    /// File times have coarse resolution on some file systems: make "later" unambiguous.
    static void age(const fs::path& p, int seconds) {
        fs::last_write_time(p, fs::last_write_time(p) - std::chrono::seconds(seconds));
    }

    fs::path scene_;
};

TEST_F(Autosave, PathSitsNextToTheScene) {
    EXPECT_EQ(autosave_path("/a/b/beach.sandtin"), fs::path("/a/b/beach.sandtin.autosave"));
    EXPECT_EQ(autosave_path("untitled"), fs::path("untitled.autosave"));
}

TEST_F(Autosave, NoAutosaveNothingToRecover) {
    save_session(scene_, session_with(20, 1.0));
    EXPECT_FALSE(find_autosave(scene_).has_value());
    EXPECT_FALSE(discard_autosave(scene_));
}

TEST_F(Autosave, NewerAutosaveIsOfferedAndRecovers) {
    const Session saved = session_with(20, 1.0);
    const Session edited = session_with(50, 2.0);
    save_session(scene_, saved);
    age(scene_, 60);
    write_autosave(scene_, edited);
    EXPECT_EQ(read_file(scene_), encode_session(saved)) << "autosave must not touch the scene";
    const auto info = find_autosave(scene_);
    ASSERT_TRUE(info.has_value());
    EXPECT_TRUE(info->scene_exists);
    EXPECT_TRUE(info->newer_than_scene);
    EXPECT_EQ(info->problem, "");
    EXPECT_TRUE(info->offer_recovery());
    const Session recovered = recover_autosave(scene_);
    test::expect_snapshots_equal(recovered.terrain, edited.terrain, 1.0);
    EXPECT_EQ(recovered.metadata_json, edited.metadata_json);
}

TEST_F(Autosave, UnsavedNewSceneIsOffered) {
    write_autosave(scene_, session_with(10, 0.5));
    const auto info = find_autosave(scene_);
    ASSERT_TRUE(info.has_value());
    EXPECT_FALSE(info->scene_exists);
    EXPECT_TRUE(info->offer_recovery());
}

TEST_F(Autosave, OlderAutosaveIsNotOffered) {
    write_autosave(scene_, session_with(10, 0.5));
    age(autosave_path(scene_), 60);
    save_session(scene_, session_with(20, 1.0));
    const auto info = find_autosave(scene_);
    ASSERT_TRUE(info.has_value());
    EXPECT_FALSE(info->newer_than_scene);
    EXPECT_FALSE(info->offer_recovery());
}

TEST_F(Autosave, DamagedAutosaveIsReportedNotOffered) {
    save_session(scene_, session_with(20, 1.0));
    age(scene_, 60);
    write_autosave(scene_, session_with(30, 1.5));
    std::vector<std::uint8_t> bytes = read_file(autosave_path(scene_));
    bytes.resize(bytes.size() / 2);
    {
        std::ofstream out(autosave_path(scene_), std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    }
    const auto info = find_autosave(scene_);
    ASSERT_TRUE(info.has_value());
    EXPECT_NE(info->problem.find("truncated"), std::string::npos) << info->problem;
    EXPECT_FALSE(info->offer_recovery());
    EXPECT_THROW(recover_autosave(scene_), std::runtime_error);
    EXPECT_TRUE(discard_autosave(scene_));
    EXPECT_FALSE(find_autosave(scene_).has_value());
}

TEST_F(Autosave, InterruptedAutosaveKeepsThePreviousAutosave) {
    const Session first = session_with(40000, 1.0);  // > 1 MiB: the hook sees a partial write
    write_autosave(scene_, first);
    const std::vector<std::uint8_t> before = read_file(autosave_path(scene_));
    EXPECT_THROW(
        write_autosave(scene_, session_with(40000, 2.0), [](std::size_t) { return false; }),
        std::runtime_error);
    EXPECT_EQ(read_file(autosave_path(scene_)), before);
    EXPECT_EQ(find_autosave(scene_)->problem, "");
}

TEST_F(Autosave, ExplicitSaveRetiresTheAutosave) {
    write_autosave(scene_, session_with(10, 0.5));
    const Session s = session_with(20, 1.0);
    save_session_clearing_autosave(scene_, s);
    EXPECT_FALSE(fs::exists(autosave_path(scene_)));
    test::expect_snapshots_equal(load_session(scene_).terrain, s.terrain, 1.0);
    // An interrupted explicit save keeps both the old scene and the autosave.
    write_autosave(scene_, session_with(30, 1.5));
    EXPECT_THROW(save_session_clearing_autosave(scene_, session_with(40000, 2.0),
                                                [](std::size_t) { return false; }),
                 std::runtime_error);
    EXPECT_TRUE(fs::exists(autosave_path(scene_)));
    test::expect_snapshots_equal(load_session(scene_).terrain, s.terrain, 1.0);
}

/// A write hook that holds the first write it sees until released, so a test knows what the
/// worker is doing while it submits more.
class HeldWrite {
  public:
    WriteInterruption hook() {
        return [this](std::size_t) {
            started_ = true;
            while (!released_)
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            return true;
        };
    }
    void wait_until_started() const {
        while (!started_)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    void release() { released_ = true; }

  private:
    std::atomic<bool> started_{false};
    std::atomic<bool> released_{false};
};

TEST_F(Autosave, WriterWritesOnItsOwnThread) {
    const Session s = session_with(30, 1.25);
    AutosaveWriter writer;
    writer.submit(scene_, s);
    writer.flush();
    EXPECT_EQ(writer.written(), 1u);
    EXPECT_FALSE(writer.take_error().has_value());
    EXPECT_FALSE(fs::exists(scene_)) << "an autosave never writes the scene itself";
    EXPECT_EQ(read_file(autosave_path(scene_)), encode_session(s));
}

// The editor's autosave: the frame hands the writer a source (SessionKeeper) and goes on
// editing while the writer copies the kept terrain on its own thread. Under ThreadSanitizer
// (test.sh) this is the check that the frame never writes the copy the writer is reading.
TEST_F(Autosave, WriterMakesAKeptSessionOnItsThreadWhileTheFrameEdits) {
    Tin tin = Tin::random_points(Rect::from_size(3.0, 2.0), 8000, 6,
                                 [](Vec2 p) { return 0.1 + 0.01 * p.x; });
    tin.set_track_changes(false);
    SessionKeeper keeper(tin);
    AutosaveWriter writer;
    std::mt19937_64 rng = test::test_rng(3);
    std::uniform_real_distribution<double> x(0.05, 2.95), y(0.05, 1.95);
    std::vector<std::uint8_t> last_submitted;
    for (int frame = 0; frame < 48; ++frame) {
        for (int k = 0; k < 10; ++k) {
            const VertexId v = tin.insert_point({x(rng), y(rng)}, 0.12);
            tin.set_height(v, tin.height(v) + 1e-3);
        }
        keeper.follow();
        if (frame % 8 != 0) continue;
        Session now;
        now.terrain = tin.snapshot();
        now.next_generation = static_cast<Generation>(frame + 1);
        now.metadata_json = R"({"name":"beach"})";
        last_submitted = encode_session(now);
        writer.submit(scene_, keeper.hand_out(now.next_generation, now.metadata_json));
    }
    writer.flush();
    EXPECT_FALSE(writer.take_error().has_value());
    EXPECT_GE(writer.written(), 1u);
    EXPECT_EQ(read_file(autosave_path(scene_)), last_submitted);
}

TEST_F(Autosave, WriterKeepsOnlyTheNewestQueuedAutosave) {
    const Session first = session_with(30, 1.0), second = session_with(40, 2.0),
                  third = session_with(50, 3.0);
    HeldWrite held;  // outlives the writer, whose worker calls its hook
    AutosaveWriter writer;
    writer.submit(scene_, first, held.hook());
    held.wait_until_started();
    writer.submit(scene_, second);  // queued while the first is being written ...
    writer.submit(scene_, third);   // ... and replaced before it starts
    held.release();
    writer.flush();
    EXPECT_EQ(writer.written(), 2u);
    EXPECT_EQ(read_file(autosave_path(scene_)), encode_session(third));
}

TEST_F(Autosave, WriterCancelWaitsForTheWriteInProgressAndDropsTheQueue) {
    const Session first = session_with(30, 1.0), second = session_with(40, 2.0);
    HeldWrite held;  // outlives the writer, whose worker calls its hook
    AutosaveWriter writer;
    writer.submit(scene_, first, held.hook());
    held.wait_until_started();
    writer.submit(scene_, second);
    std::thread releaser([&held] {
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
        held.release();
    });
    writer.cancel();  // returns only once the first write is done
    releaser.join();
    EXPECT_EQ(writer.written(), 1u);
    EXPECT_EQ(read_file(autosave_path(scene_)), encode_session(first));
    // What the caller does next (an explicit save retiring the autosave) is not undone.
    save_session_clearing_autosave(scene_, second);
    writer.flush();
    EXPECT_FALSE(fs::exists(autosave_path(scene_)));
    EXPECT_EQ(writer.written(), 1u);
}

TEST_F(Autosave, WriterKeepsFailuresForTheCallerAndCarriesOn) {
    const fs::path unwritable = dir_ / "no-such-folder" / "beach.sandtin";
    AutosaveWriter writer;
    writer.submit(unwritable, session_with(20, 1.0));
    writer.flush();
    const std::optional<std::string> error = writer.take_error();
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("no-such-folder"), std::string::npos) << *error;
    EXPECT_FALSE(writer.take_error().has_value()) << "each failure is reported once";
    EXPECT_EQ(writer.written(), 0u);
    writer.submit(scene_, session_with(20, 1.0));
    writer.flush();
    EXPECT_EQ(writer.written(), 1u);
    EXPECT_TRUE(fs::exists(autosave_path(scene_)));
}

// The editor hands a replaced scene's edits over without waiting, and learns of a failure
// later, when another scene may be open: the failure names the scene it was for.
TEST_F(Autosave, WriterNamesTheSceneOfAFailure) {
    const fs::path unwritable = dir_ / "no-such-folder" / "beach.sandtin";
    AutosaveWriter writer;
    writer.submit(unwritable, session_with(20, 1.0));
    writer.submit(scene_, session_with(20, 2.0));  // replaces it before it starts, or after
    writer.flush();
    writer.submit(unwritable, session_with(20, 3.0));
    writer.flush();
    const std::optional<AutosaveWriter::Failure> failure = writer.take_failure();
    ASSERT_TRUE(failure.has_value());
    EXPECT_EQ(failure->scene, unwritable);
    EXPECT_NE(failure->message.find("no-such-folder"), std::string::npos) << failure->message;
    EXPECT_FALSE(writer.take_failure().has_value()) << "each failure is reported once";
    EXPECT_TRUE(fs::exists(autosave_path(scene_)));
}

TEST_F(Autosave, WriterFinishesTheQueueWhenDestroyed) {
    const Session first = session_with(30, 1.0), second = session_with(40, 2.0);
    {
        HeldWrite held;
        AutosaveWriter writer;
        writer.submit(scene_, first, held.hook());
        held.wait_until_started();
        writer.submit(scene_, second);
        held.release();
    }  // quitting: the queued autosave is written before the writer goes
    EXPECT_EQ(read_file(autosave_path(scene_)), encode_session(second));
}

TEST(AutosaveSchedule, DueOnlyAfterAnEditAndTheInterval) {
    using namespace std::chrono_literals;
    AutosaveSchedule schedule(60s);
    const auto t0 = AutosaveSchedule::Clock::time_point{} + 1000s;
    EXPECT_FALSE(schedule.due(t0 + 3600s)) << "nothing changed: no autosave";
    schedule.edited(t0);
    EXPECT_FALSE(schedule.due(t0 + 59s));
    schedule.edited(t0 + 30s);  // later edits do not postpone it
    EXPECT_TRUE(schedule.due(t0 + 60s));
    schedule.saved(t0 + 61s);
    EXPECT_FALSE(schedule.dirty());
    EXPECT_FALSE(schedule.due(t0 + 500s));
    schedule.edited(t0 + 500s);
    EXPECT_FALSE(schedule.due(t0 + 559s));
    EXPECT_TRUE(schedule.due(t0 + 560s));
}

}  // namespace
}  // namespace sandtin
