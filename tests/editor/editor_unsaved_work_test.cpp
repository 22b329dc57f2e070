// The editor's care for unsaved work under Xvfb (crashes and lost work): the autosave
// beside the scene is offered when it is newer and can be recovered or discarded, unsaved edits
// go to it and never over the scene, a failing session keeps them there, New and closing ask
// before dropping an untitled scene's edits (and can save first), an autosave that cannot be
// rebuilt leaves the scene open, and an unwritable settings file is reported without ending
// the session. Oracles: the files on disk, read back through engine/io.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "editor_harness.hpp"
#include "io/autosave.hpp"
#include "io/session_file.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

TEST_F(EditorXvfb, AutosaveNewerThanTheSceneIsOfferedAndCanBeRecoveredOrDiscarded) {
    const fs::path scene = kWork / "recover.sandtin";
    ASSERT_EQ(run_editor("recover-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    // An autosave with one vertex raised by 3 cm, written after the scene.
    const Session edited = write_autosave_raising_a_vertex(scene, 0.03).session;
    ASSERT_TRUE(find_autosave(scene).has_value());
    ASSERT_TRUE(find_autosave(scene)->offer_recovery());

    // Erosion paused: a raised vertex is far steeper than repose, and an opened document's
    // sand slides when the erosion runs (AnOpenedSceneSteeperThanReposeSlides).
    const fs::path recovered = kWork / "recovered.sandtin";
    const EditorRun r = run_editor("recover", R"([{"op": "set", "erosion": false},
                                                 {"op": "recovery", "choice": "recover"}])",
                                   scene.string() + " --save-after " + recovered.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const Session got = load_session(recovered);
    EXPECT_EQ(got.terrain.vertices.height, edited.terrain.vertices.height);
    // Saving (here to another file) leaves the scene's own autosave alone.
    ASSERT_TRUE(find_autosave(scene).has_value());

    const fs::path kept = kWork / "kept.sandtin";
    const EditorRun d = run_editor("discard", R"([{"op": "recovery", "choice": "discard"}])",
                                   scene.string() + " --save-after " + kept.string());
    ASSERT_EQ(d.exit_code, 0) << d.log;
    EXPECT_FALSE(find_autosave(scene).has_value());
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(scene).terrain.vertices.height);

    // Without an autosave, answering the prompt is a clear error.
    const EditorRun e =
        run_editor("no-autosave", R"([{"op": "recovery", "choice": "recover"}])", scene.string());
    EXPECT_EQ(e.exit_code, 1) << e.log;
    EXPECT_NE(e.log.find("no autosave"), std::string::npos) << e.log;
}

TEST_F(EditorXvfb, UnsavedEditsGoToTheAutosaveAndLeaveTheSceneAlone) {
    const fs::path scene = kWork / "unsaved.sandtin";
    ASSERT_EQ(run_editor("unsaved-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    const std::vector<std::uint8_t> scene_bytes = read_file(scene);
    ASSERT_FALSE(find_autosave(scene).has_value());
    // Untouched: nothing unsaved, nothing to autosave.
    ASSERT_EQ(run_editor("unsaved-idle", R"([{"op": "autosave"}])", scene.string()).exit_code, 0);
    EXPECT_FALSE(find_autosave(scene).has_value());

    const EditorRun r =
        run_editor("unsaved", then(kStroke, R"({"op": "autosave"})"), scene.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(read_file(scene), scene_bytes) << "an autosave never touches the scene";
    const std::optional<AutosaveInfo> info = find_autosave(scene);
    ASSERT_TRUE(info.has_value());
    EXPECT_TRUE(info->offer_recovery()) << info->problem;
    // The stroke and the pour are in it: the terrain differs from the scene's.
    EXPECT_NE(recover_autosave(scene).terrain.vertices.height,
              load_session(scene).terrain.vertices.height);
}

TEST_F(EditorXvfb, AFailingSessionKeepsItsEditsInTheAutosave) {
    const fs::path scene = kWork / "failing.sandtin";
    ASSERT_EQ(run_editor("failing-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    const std::string first = R"([{"op": "set", "erosion": false},
        {"op": "tool", "name": "Ball"}, {"op": "set", "radius": 0.05, "depth": 0.015},
        {"op": "drag", "path": [[0.45, 0.5], [0.75, 0.5]], "steps": 20}])";
    const std::string second = R"({"op": "drag", "path": [[0.5, 0.35], [0.5, 0.65]], "steps": 20})";
    // The oracle: the same two strokes in a session that ends normally, and the first alone
    // (so the comparison below can tell whether the second stroke reached the autosave).
    const fs::path both = kWork / "failing-both.sandtin";
    const fs::path one = kWork / "failing-one.sandtin";
    ASSERT_EQ(run_editor("failing-both", then(first, second),
                         scene.string() + " --save-after " + both.string())
                  .exit_code,
              0);
    ASSERT_EQ(run_editor("failing-one", first, scene.string() + " --save-after " + one.string())
                  .exit_code,
              0);
    const Session expected = load_session(both);
    ASSERT_NE(expected.terrain.vertices.height, load_session(one).terrain.vertices.height);

    // The session asks for autosaving after the first stroke, makes the second, then fails on
    // an op it cannot run: the error is reported, and the autosave written on the way out holds
    // both strokes, while the scene file stays as it was.
    const std::vector<std::uint8_t> scene_bytes = read_file(scene);
    const EditorRun r = run_editor("failing",
                                   then(then(first, R"({"op": "autosave"}, )" + second),
                                        R"({"op": "tool", "name": "NoSuchTool"})"),
                                   scene.string());
    EXPECT_EQ(r.exit_code, 1) << r.log;
    EXPECT_NE(r.log.find("unknown tool 'NoSuchTool'"), std::string::npos) << r.log;
    EXPECT_EQ(read_file(scene), scene_bytes);
    ASSERT_TRUE(find_autosave(scene).has_value()) << r.log;
    const Session kept = recover_autosave(scene);
    EXPECT_EQ(kept.terrain.vertices.alive, expected.terrain.vertices.alive);
    EXPECT_EQ(kept.terrain.vertices.position, expected.terrain.vertices.position);
    EXPECT_EQ(kept.terrain.vertices.height, expected.terrain.vertices.height);
    discard_autosave(scene);
}

TEST_F(EditorXvfb, NewAsksBeforeDroppingAnUntitledScenesEdits) {
    const fs::path fresh = kWork / "untitled-fresh.sandtin";
    ASSERT_EQ(run_editor("untitled-fresh", kFlat, "--save-after " + fresh.string()).exit_code, 0);
    const std::string press_new = R"({"op": "key", "key": "n", "ctrl": true}, )";

    // Cancel: the stroke and the pour stay, untouched by the Ctrl+Z pressed while the prompt
    // waited (shortcuts wait for the answer too).
    const fs::path stroked = kWork / "untitled-stroked.sandtin";
    ASSERT_EQ(run_editor("untitled-stroked", kStroke, "--save-after " + stroked.string()).exit_code,
              0);
    const fs::path kept = kWork / "untitled-kept.sandtin";
    const EditorRun c = run_editor(
        "untitled-cancel", then(kStroke, press_new + R"({"op": "key", "key": "z", "ctrl": true},
                                       {"op": "discard", "choice": "cancel"})"),
        "--save-after " + kept.string());
    ASSERT_EQ(c.exit_code, 0) << c.log;
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(stroked).terrain.vertices.height);
    EXPECT_NE(load_session(kept).terrain.vertices.height,
              load_session(fresh).terrain.vertices.height);

    // Discard: a new sandbox, as the editor starts with.
    const fs::path replaced = kWork / "untitled-new.sandtin";
    const EditorRun d = run_editor(
        "untitled-discard", then(kStroke, press_new + R"({"op": "discard", "choice": "discard"})"),
        "--save-after " + replaced.string());
    ASSERT_EQ(d.exit_code, 0) << d.log;
    EXPECT_EQ(load_session(replaced).terrain.vertices.height,
              load_session(fresh).terrain.vertices.height);

    // Nothing unsaved: Ctrl+N asks nothing, so there is nothing to answer.
    const EditorRun n = run_editor("untitled-nothing", R"([{"op": "key", "key": "n", "ctrl": true},
            {"op": "discard", "choice": "discard"}])");
    EXPECT_EQ(n.exit_code, 1) << n.log;
    EXPECT_NE(n.log.find("no unsaved edits"), std::string::npos) << n.log;
}

TEST_F(EditorXvfb, ClosingAsksBeforeDroppingAnUntitledScenesEdits) {
    // Whether the editor is still open after `ops`: their script ends with a save.
    auto stays_open = [](const std::string& name, const std::string& ops) {
        const fs::path probe = kWork / (name + ".sandtin");
        fs::remove(probe);
        const EditorRun r =
            run_editor(name, then(ops, R"({"op": "save", "path": ")" + probe.string() + R"("})"));
        EXPECT_EQ(r.exit_code, 0) << r.log;
        return fs::exists(probe);
    };
    const std::string close = R"({"op": "close"}, )";
    // Cancel: the editor stays open, and the script's next op still runs.
    EXPECT_TRUE(stays_open("close-cancel",
                           then(kStroke, close + R"({"op": "discard", "choice": "cancel"})")));
    // Discard: the editor closes before the next op.
    EXPECT_FALSE(stays_open("close-discard",
                            then(kStroke, close + R"({"op": "discard", "choice": "discard"})")));
    // Nothing unsaved: closing closes at once.
    EXPECT_FALSE(stays_open("close-clean", R"([{"op": "close"}])"));
}

// The unsaved-edits prompt offers Save too (it had only Discard and Cancel): it saves the
// untitled scene where Save and Ctrl+S would (the Scene field), then goes on; a save that
// fails keeps the scene and says why.
TEST_F(EditorXvfb, TheUnsavedEditsPromptCanSaveFirst) {
    const fs::path fresh = kWork / "prompt-fresh.sandtin";
    ASSERT_EQ(run_editor("prompt-fresh", kFlat, "--save-after " + fresh.string()).exit_code, 0);
    const fs::path stroked = kWork / "prompt-stroked.sandtin";
    ASSERT_EQ(run_editor("prompt-stroked", kStroke, "--save-after " + stroked.string()).exit_code,
              0);
    const auto save_to = [](const fs::path& p) {
        return R"({"op": "set", "scene_path": ")" + p.string() + R"("}, )";
    };
    const std::string press_new = R"({"op": "key", "key": "n", "ctrl": true}, )";

    // Save and New: the edits are in the file, and the editor holds a new sandbox.
    const fs::path saved = kWork / "prompt-saved.sandtin";
    const fs::path after_new = kWork / "prompt-after-new.sandtin";
    fs::remove(saved);
    const EditorRun s = run_editor(
        "prompt-save-new",
        then(kStroke, save_to(saved) + press_new + R"({"op": "discard", "choice": "save"})"),
        "--save-after " + after_new.string());
    ASSERT_EQ(s.exit_code, 0) << s.log;
    ASSERT_TRUE(fs::exists(saved)) << s.log;
    EXPECT_EQ(load_session(saved).terrain.vertices.height,
              load_session(stroked).terrain.vertices.height);
    EXPECT_EQ(load_session(after_new).terrain.vertices.height,
              load_session(fresh).terrain.vertices.height);

    // Save and Quit: saved, and the editor closed before the script's next op.
    const fs::path quit_saved = kWork / "prompt-quit-saved.sandtin";
    const fs::path probe = kWork / "prompt-quit-probe.sandtin";
    fs::remove(quit_saved);
    fs::remove(probe);
    const EditorRun q = run_editor(
        "prompt-save-quit",
        then(kStroke, save_to(quit_saved) + R"({"op": "close"}, {"op": "discard", "choice": "save"},
            {"op": "save", "path": ")" +
                          probe.string() + R"("})"));
    ASSERT_EQ(q.exit_code, 0) << q.log;
    EXPECT_TRUE(fs::exists(quit_saved)) << q.log;
    EXPECT_FALSE(fs::exists(probe)) << "the editor stayed open after Save and Quit";

    // A save that fails (a name that claims another format): the scene and its edits stay.
    const fs::path kept = kWork / "prompt-kept.sandtin";
    ::setenv("SANDTIN_EDITOR_TRACE", "1", 1);  // the status line's reports go to the log
    const EditorRun f = run_editor("prompt-save-fails",
                                   then(kStroke, save_to(kWork / "x.png") + press_new +
                                                     R"({"op": "discard", "choice": "save"})"),
                                   "--save-after " + kept.string());
    ::unsetenv("SANDTIN_EDITOR_TRACE");
    ASSERT_EQ(f.exit_code, 0) << f.log;
    EXPECT_NE(f.log.find("save failed"), std::string::npos) << f.log;
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(stroked).terrain.vertices.height);
}

TEST_F(EditorXvfb, AnAutosaveThatCannotBeRebuiltLeavesTheSceneOpen) {
    const fs::path scene = kWork / "bad-autosave.sandtin";
    ASSERT_EQ(run_editor("bad-autosave-base", kFlat, "--save-after " + scene.string()).exit_code,
              0);
    // The file loads (so recovery is offered) but its triangles do not tile the domain: one
    // finite triangle turned clockwise.
    Session damaged = load_session(scene);
    for (auto& corners : damaged.terrain.slots) {
        if (corners[0] < kOutsideCorner && corners[1] < kOutsideCorner &&
            corners[2] < kOutsideCorner) {
            std::swap(corners[0], corners[1]);
            break;
        }
    }
    write_autosave(scene, damaged);
    ASSERT_TRUE(find_autosave(scene)->offer_recovery());
    const fs::path kept = kWork / "bad-autosave-kept.sandtin";
    const EditorRun r = run_editor("bad-autosave", R"([{"op": "recovery", "choice": "recover"}])",
                                   scene.string() + " --save-after " + kept.string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(scene).terrain.vertices.height);
}

TEST_F(EditorXvfb, AnUnwritableSettingsFileIsReportedAndTheSessionGoesOn) {
    // The settings file's folder is a regular file: writing the settings must fail.
    const fs::path blocker = kWork / "not-a-folder";
    std::ofstream(blocker) << "x";
    const fs::path saved = kWork / "after-settings.sandtin";
    fs::remove(saved);
    const std::string ops = R"([{"op": "set", "erosion": false}, {"op": "save_settings"},
        {"op": "save", "path": ")" +
                            saved.string() + R"("}])";
    const EditorRun r =
        run_editor("unwritable-settings", ops, "--settings " + (blocker / "s.json").string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_TRUE(fs::exists(saved)) << "the script went on after the failed settings write";
}

}  // namespace
}  // namespace sandtin
