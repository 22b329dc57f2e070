// Long work in the editor (issue 42, item 4): importing, opening and exporting run on a worker
// while frames go on drawing, under a progress bar with Cancel; a cancelled job leaves the
// scene (and the files) as they were; a completed one gives what the synchronous call gives.
// The erosion's settle to rest shows its bar too, and Stop keeps what settled as one undo
// level. Jobs are held at a fraction by the script's "jobs" op (pause_at), so the bar is seen
// mid-way and Cancel pressed whatever the machine's speed; no timing is asserted.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "editor_harness.hpp"
#include "io/heightmap_import.hpp"

namespace sandtin::editor_test::progress {
namespace {

/// Rolling hills with ripples, 1 m cells, as an ESRI ASCII grid: many insertions before the
/// editor's 1 m import bound.
fs::path hills_grid(const std::string& name, int n) {
    const fs::path p = kWork / (name + ".asc");
    fs::create_directories(kWork);
    std::ofstream out(p);
    out << "ncols " << n << "\nnrows " << n
        << "\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
    for (int row = 0; row < n; ++row) {
        for (int col = 0; col < n; ++col) {
            const double h = 40.0 * std::sin(0.05 * col) * std::cos(0.07 * row) +
                             4.0 * std::sin(0.9 * col + 0.4 * row);
            out << h << (col + 1 < n ? " " : "\n");
        }
    }
    return p;
}

std::string read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool said(const EditorRun& r, const std::string& words) {
    for (const auto& m : r.stats.at("messages")) {
        if (m.get<std::string>().find(words) != std::string::npos) return true;
    }
    return false;
}

/// The scenes saved at `a` and `b` hold the same terrain: as many vertices, the same surface.
void expect_same_terrain(const fs::path& a, const fs::path& b) {
    const Tin ta = Tin::from_snapshot(load_session(a).terrain);
    const Tin tb = Tin::from_snapshot(load_session(b).terrain);
    EXPECT_EQ(ta.vertex_count(), tb.vertex_count());
    EXPECT_LT(surface_difference(ta, tb), 1e-12);
}

/// The one job record of a run.
const nlohmann::json& only_job(const EditorRun& r) {
    return r.stats.at("jobs").at(0);
}

/// The bar was drawn mid-way, over several frames, while the job ran.
void expect_bar_shown_mid_way(const nlohmann::json& job) {
    EXPECT_GT(job.at("frames").get<int>(), 1) << "frames kept drawing while the job ran";
    EXPECT_GT(job.at("bar_frames").get<int>(), 1) << job;
    ASSERT_GT(job.at("fractions_shown").get<int>(), 0) << job;
    EXPECT_GT(job.at("fraction_min_shown").get<double>(), 0.0) << job;
    EXPECT_LT(job.at("fraction_max_shown").get<double>(), 1.0) << job;
    EXPECT_LE(job.at("fraction_min_shown").get<double>(),
              job.at("fraction_max_shown").get<double>());
}

/// Start a job through its button, see it held mid-way for a few frames, press Cancel.
std::string start_then_cancel(const std::string& field, const fs::path& path,
                              const std::string& button) {
    return R"({"op": "jobs", "wait": false, "pause_at": 0.3},
              {"op": "set", ")" +
           field + R"(": ")" + path.string() + R"("},
              {"op": "click", "widget": ")" +
           button + R"("},
              {"op": "job", "until": "paused"}, {"op": "wait", "frames": 3},
              {"op": "cancel_job"}, {"op": "job", "until": "done"},
              {"op": "jobs", "wait": true}, {"op": "wait", "frames": 2})";
}

TEST_F(EditorXvfb, ACancelledImportShowedItsBarAndLeftTheSceneAsItWas) {
    const fs::path grid = hills_grid("progress-hills", 400);
    const fs::path before = kWork / "progress-before.sandtin";
    const fs::path after = kWork / "progress-after.sandtin";
    ASSERT_EQ(run_editor("progress-before", kFlat,
                         "--save-after " + before.string() + fresh_settings("progress-before"))
                  .exit_code,
              0);
    const EditorRun r = run_editor(
        "progress-import-cancel", then(kFlat, start_then_cancel("import_path", grid, "Import")),
        "--save-after " + after.string() + fresh_settings("progress-import-cancel"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    ASSERT_EQ(r.stats.at("jobs").size(), 1u) << r.stats.at("jobs");
    const nlohmann::json& job = only_job(r);
    EXPECT_EQ(job.at("kind"), "import");
    EXPECT_EQ(job.at("outcome"), "cancelled");
    expect_bar_shown_mid_way(job);
    EXPECT_FALSE(r.stats.at("job_running").get<bool>());
    // The sandbox is still open, as it was (--save-after then saved it): unedited, the same
    // terrain, and the heightmap is not a recent file.
    EXPECT_EQ(r.stats.at("undo_levels").get<int>(), 0);
    for (const auto& f : r.stats.at("recent_files"))
        EXPECT_NE(f.get<std::string>(), grid.string()) << "a cancelled import is not recent";
    EXPECT_TRUE(said(r, "cancelled")) << r.stats.at("messages");
    expect_same_terrain(after, before);
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
}

// The scene named on the command line is read on a worker after the window opened, under the
// bar, as Open reads one: frames go on meanwhile, and it lands in the Scene field and the
// recent list. Only the document's install is left to the UI thread.
TEST_F(EditorXvfb, ASceneOnTheCommandLineOpensUnderTheBarAfterTheWindowOpened) {
    const fs::path scene = kWork / "startup-scene.sandtin";
    const fs::path saved = kWork / "startup-saved.sandtin";
    ASSERT_EQ(run_editor("startup-base", then(kFlat, R"({"op": "drag", "button": "left",
                  "path": [[0.4, 0.5], [0.6, 0.5]], "steps": 4})"),
                         "--save-after " + scene.string() + fresh_settings("startup-base"))
                  .exit_code,
              0);
    const EditorRun r = run_editor(
        "startup-open",
        then(R"([{"op": "jobs", "wait": false, "pause_at": 0.5}])",
             R"({"op": "job", "until": "paused"}, {"op": "wait", "frames": 3},
                                {"op": "resume_job"}, {"op": "job", "until": "done"},
                                {"op": "jobs", "wait": true}, {"op": "wait", "frames": 2})"),
        scene.string() + " --save-after " + saved.string() + fresh_settings("startup-open"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_TRUE(r.stats.at("jobs").empty()) << "the start's job is recorded on its own";
    const nlohmann::json& job = r.stats.at("startup_job");
    EXPECT_EQ(job.at("kind"), "open");
    EXPECT_EQ(job.at("outcome"), "done");
    expect_bar_shown_mid_way(job);
    // --save-after made the saved copy the newest recent file; the scene came before it.
    const auto& recent = r.stats.at("recent_files");
    EXPECT_NE(std::find(recent.begin(), recent.end(), scene.string()), recent.end()) << recent;
    EXPECT_EQ(r.stats.at("install_ms").size(), 2u) << "the placeholder, then the scene";
    EXPECT_TRUE(said(r, "opened " + scene.string())) << r.stats.at("messages");
    expect_same_terrain(saved, scene);
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
}

// A scene that does not load fails a scripted run with a message naming it, after the window
// opened and the worker tried; an interactive run would get the sandbox and the same words.
TEST_F(EditorXvfb, ADamagedSceneOnTheCommandLineFailsAScriptNamingIt) {
    const fs::path scene = kWork / "startup-damaged.sandtin";
    fs::create_directories(kWork);
    std::ofstream(scene, std::ios::binary) << "not a sandtin session at all";
    const EditorRun r = run_editor("startup-damaged", kFlat, scene.string());
    EXPECT_EQ(r.exit_code, 1) << r.log;
    EXPECT_NE(r.log.find("cannot open " + scene.string()), std::string::npos) << r.log;
}

// Save copies the scene on the UI thread and writes it on a worker under the bar (a
// 10^6-vertex save took 1.8 s of one frame). Cancelled before it writes, it writes nothing and
// the scene stays unsaved; completed, the file is the scene, byte for byte what --save-after
// (the synchronous save) writes of the same scene.
TEST_F(EditorXvfb, ASaveRunsUnderTheBarAndACancelledOneWritesNothing) {
    const fs::path target = kWork / "save-job.sandtin";
    const fs::path direct = kWork / "save-job-direct.sandtin";
    fs::remove(target);
    const std::string save = R"({"op": "save", "path": ")" + target.string() + R"("})";
    const EditorRun r =
        run_editor("save-job",
                   then(kStroke, R"({"op": "jobs", "wait": false, "pause_at": 0.0}, )" + save +
                                     R"(, {"op": "job", "until": "paused"},
                {"op": "wait", "frames": 2}, {"op": "cancel_job"}, {"op": "job", "until": "done"},
                {"op": "jobs", "wait": true}, {"op": "wait", "frames": 1}, )" +
                                     save),
                   "--save-after " + direct.string() + fresh_settings("save-job"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const nlohmann::json& jobs = r.stats.at("jobs");
    ASSERT_EQ(jobs.size(), 2u) << jobs;
    EXPECT_EQ(jobs.at(0).at("kind"), "save");
    EXPECT_EQ(jobs.at(0).at("outcome"), "cancelled");
    EXPECT_GE(jobs.at(0).at("bar_frames").get<int>(), 2) << jobs.at(0);
    EXPECT_TRUE(said(r, "no file was written")) << r.stats.at("messages");
    EXPECT_EQ(jobs.at(1).at("kind"), "save");
    EXPECT_EQ(jobs.at(1).at("outcome"), "done");
    EXPECT_TRUE(said(r, "saved " + target.string())) << r.stats.at("messages");
    ASSERT_TRUE(fs::exists(target));
    const Session written = load_session(target);
    const Session synchronous = load_session(direct);
    EXPECT_GT(written.terrain.vertices.size(), 0u);
    EXPECT_EQ(written.terrain.vertices.height, synchronous.terrain.vertices.height);
    EXPECT_EQ(written.terrain.slots, synchronous.terrain.slots);
}

// Keys typed while a job runs wait for it and then act, in order: Ctrl+S pressed during an
// import saves the imported scene once it is in (under the name the import gave it), as a hand
// typing ahead expects; nothing is dropped.
TEST_F(EditorXvfb, AKeyTypedDuringAnImportActsOnceTheImportIsIn) {
    const fs::path grid = hills_grid("typed-ahead-hills", 120);
    const fs::path named = kWork / "typed-ahead-hills.sandtin";
    fs::remove(named);
    const EditorRun r = run_editor("typed-ahead",
                                   then(kFlat, R"({"op": "jobs", "wait": false, "pause_at": 0.3},
            {"op": "set", "import_path": ")" + grid.string() +
                                                   R"("},
            {"op": "click", "widget": "Import"}, {"op": "job", "until": "paused"},
            {"op": "key", "key": "s", "ctrl": true}, {"op": "wait", "frames": 2},
            {"op": "resume_job"}, {"op": "job", "until": "done"},
            {"op": "jobs", "wait": true}, {"op": "wait", "frames": 2})"),
                                   fresh_settings("typed-ahead"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    ASSERT_GE(r.stats.at("jobs").size(), 1u);
    EXPECT_EQ(r.stats.at("jobs").at(0).at("kind"), "import");
    EXPECT_EQ(r.stats.at("jobs").at(0).at("outcome"), "done");
    ASSERT_TRUE(fs::exists(named)) << r.stats.at("messages");
    EXPECT_TRUE(said(r, "saved " + named.string())) << r.stats.at("messages");
    EXPECT_FALSE(r.stats.at("dirty").get<bool>());
    EXPECT_GT(Tin::from_snapshot(load_session(named).terrain).domain().width(), 100.0);
}

TEST_F(EditorXvfb, ACompletedBackgroundImportIsTheSynchronousImport) {
    const fs::path grid = hills_grid("progress-small-hills", 160);
    const fs::path saved = kWork / "progress-imported.sandtin";
    const EditorRun r = run_editor(
        "progress-import", then(kFlat, R"({"op": "set", "import_path": ")" + grid.string() + R"("},
                       {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 2})"),
        "--save-after " + saved.string() + fresh_settings("progress-import"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    ASSERT_EQ(r.stats.at("jobs").size(), 1u);
    EXPECT_EQ(only_job(r).at("outcome"), "done");
    EXPECT_TRUE(said(r, "imported " + grid.string())) << r.stats.at("messages");
    const Tin in_editor = Tin::from_snapshot(load_session(saved).terrain);
    const ImportResult direct = import_heightmap(grid, ImportOptions{});
    EXPECT_EQ(in_editor.vertex_count(), direct.tin.vertex_count());
    EXPECT_LT(surface_difference(in_editor, direct.tin), 1e-9);
    EXPECT_LT(surface_difference(direct.tin, in_editor), 1e-9);
}

TEST_F(EditorXvfb, ACancelledOpenKeepsTheSceneOpenBefore) {
    // A scene to open, and the sandbox it must not replace when cancelled.
    const fs::path grid = hills_grid("progress-open-hills", 160);
    const fs::path scene = kWork / "progress-open.sandtin";
    {
        Session s;
        s.terrain = import_heightmap(grid, ImportOptions{}).tin.snapshot();
        save_session(scene, s);
    }
    const EditorRun r = run_editor("progress-open-cancel",
                                   then(kFlat, start_then_cancel("scene_path", scene, "Open")),
                                   fresh_settings("progress-open-cancel"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const nlohmann::json& job = only_job(r);
    EXPECT_EQ(job.at("kind"), "open");
    EXPECT_EQ(job.at("outcome"), "cancelled");
    expect_bar_shown_mid_way(job);
    EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), "") << "the sandbox stays open";
    EXPECT_EQ(r.stats.at("recent_files").size(), 0u);
}

TEST_F(EditorXvfb, ACancelledExportLeavesTheOldFileAndACompletedOneWritesIt) {
    const fs::path old_file = kWork / "progress-old.glb";
    const fs::path fresh = kWork / "progress-fresh.glb";
    std::ofstream(old_file, std::ios::binary) << "the previous export";
    fs::remove(fresh);
    const EditorRun r =
        run_editor("progress-export",
                   then(kFlat, start_then_cancel("export_path", old_file, "Export") +
                                   R"(, {"op": "set", "export_path": ")" + fresh.string() + R"("},
                       {"op": "click", "widget": "Export"}, {"op": "wait", "frames": 2})"),
                   fresh_settings("progress-export"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    ASSERT_EQ(r.stats.at("jobs").size(), 2u) << r.stats.at("jobs");
    const nlohmann::json& cancelled = r.stats.at("jobs").at(0);
    EXPECT_EQ(cancelled.at("kind"), "export");
    EXPECT_EQ(cancelled.at("outcome"), "cancelled");
    expect_bar_shown_mid_way(cancelled);
    EXPECT_EQ(read_bytes(old_file), "the previous export");
    EXPECT_EQ(r.stats.at("jobs").at(1).at("outcome"), "done");
    EXPECT_GT(fs::file_size(fresh), 1000u);
    EXPECT_TRUE(said(r, "no file was written")) << r.stats.at("messages");
    // Nothing else was left beside them: no temporary, no companion.
    std::size_t exports = 0;
    for (const auto& e : fs::directory_iterator(kWork)) {
        const std::string name = e.path().filename().string();
        // Temporaries are hidden files named after their target (util/atomic_file.cpp).
        exports += name.find("progress-old") != std::string::npos ||
                   name.find("progress-fresh") != std::string::npos;
    }
    EXPECT_EQ(exports, 2u) << "the old export and the fresh one, nothing else";
}

TEST_F(EditorXvfb, ErosionToRestShowsItsBarAndStopKeepsWhatSettledAsOneLevel) {
    // A cone far steeper than repose: its sand slides for many frames at one step a frame.
    const fs::path cone = kWork / "progress-cone.sandtin";
    const fs::path after = kWork / "progress-cone-after.sandtin";
    {
        Session s;
        s.terrain = Tin::random_points(Rect::from_size(1.0, 1.0), 3000, 7, [](Vec2 p) {
                        return std::max(0.0, 0.4 - std::hypot(p.x - 0.5, p.y - 0.5));
                    }).snapshot();
        save_session(cone, s);
    }
    const Tin original = Tin::from_snapshot(load_session(cone).terrain);
    const EditorRun r = run_editor(
        "progress-erosion",
        R"([{"op": "set", "erosion": false, "steps": 1}, {"op": "wait", "frames": 2},
            {"op": "erode", "frames": 45}, {"op": "cancel_job"}, {"op": "wait", "frames": 3}])",
        cone.string() + " --save-after " + after.string() + fresh_settings("progress-erosion"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const nlohmann::json& settle = r.stats.at("settle");
    ASSERT_TRUE(settle.value("shown", false)) << settle << r.stats.at("erosion_status");
    EXPECT_GT(settle.at("bar_frames").get<int>(), 1);
    EXPECT_GE(settle.at("fraction_max_shown").get<double>(), 0.0);
    EXPECT_LT(settle.at("fraction_max_shown").get<double>(), 1.0);
    EXPECT_TRUE(settle.value("stopped", false));
    EXPECT_FALSE(r.stats.at("erosion_running").get<bool>());
    EXPECT_EQ(r.stats.at("undo_levels").get<int>(), 1) << "what settled is one undo level";
    EXPECT_GT(surface_difference(Tin::from_snapshot(load_session(after).terrain), original), 1e-4)
        << "the sand that slid stays where it went";
}

}  // namespace
}  // namespace sandtin::editor_test::progress
