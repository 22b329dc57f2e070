// The file dialogs (issue 42), through the real editor under Xvfb: the editor's own browser
// driven by the script's pick_file op with real input (open, cancel, import, export with the
// overwrite question, the last folder across a restart), and the desktop's dialog as a fake
// zenity put first on PATH (its answer applied, its failure falling back to the browser).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "editor_harness.hpp"
#include "editor_settings.hpp"
#include "io/session_file.hpp"

// A namespace of its own: the tests are built as one unity source, and the other files have
// helpers of these names in theirs.
namespace sandtin::file_dialog_xvfb {
namespace {

using namespace editor_test;

const fs::path kHillsHeightmap =
    fs::path(SANDTIN_SOURCE_DIR) / "tests/data/bay-hills-terrain-rgb.png";

/// Sets an environment variable for one test (the editor runs inherit it), then restores it.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    const char* name_;
    std::optional<std::string> old_;
};

fs::path fresh_settings_file(const std::string& name) {
    const fs::path p = kWork / (name + ".settings.json");
    fs::remove(p);
    return p;
}

std::size_t alive_vertices(const Session& s) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < s.terrain.vertices.alive.size(); ++i)
        n += s.terrain.vertices.alive[i] ? 1 : 0;
    return n;
}

bool said(const EditorRun& r, const std::string& words) {
    for (const auto& m : r.stats.at("messages")) {
        if (m.get<std::string>().find(words) != std::string::npos) return true;
    }
    return false;
}

std::string pick(const std::string& dialog, const fs::path& path, const std::string& more = "") {
    return R"({"op": "pick_file", "dialog": ")" + dialog + R"(", "path": ")" + path.string() +
           "\"" + more + "}";
}

/// A folder with a space in its name holding two scenes, a heightmap and a sub-folder.
struct PickFolder {
    fs::path folder, scene, other;
    Session saved;
};
PickFolder make_pick_folder(const std::string& name) {
    PickFolder f;
    f.folder = kWork / (name + " folder");
    fs::remove_all(f.folder);
    f.scene = f.folder / "picked dunes.sandtin";
    f.other = f.folder / "other.sandtin";
    f.saved = save_flat_scene(f.scene, 1.0, unit_square_points(321, 7), 0.01);
    save_flat_scene(f.other, 1.0, unit_square_points(100, 8));
    fs::create_directories(f.folder / "sub");
    return f;
}

class EditorFileDialog : public EditorXvfb {
  protected:
    // The editor's own browser, whatever this machine has on PATH.
    ScopedEnv imgui_{"SANDTIN_FILE_DIALOG", "imgui"};
};

TEST_F(EditorFileDialog, OpensASceneThroughTheBrowserBehindTheUnsavedEditsPrompt) {
    const PickFolder f = make_pick_folder("pick-open");
    const fs::path settings = fresh_settings_file("pick-open");
    // A sculpted untitled sandbox: Open through the browser asks first, as the Open button does.
    const EditorRun r = run_editor("pick-open", then(kStroke, pick("open", f.scene) + R"(,
            {"op": "discard", "choice": "discard"}, {"op": "wait", "frames": 2},
            {"op": "save_settings"})"),
                                   "--settings " + settings.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), f.scene.string());
    EXPECT_EQ(r.stats.at("vertices").get<std::size_t>(), alive_vertices(f.saved));
    EXPECT_FALSE(r.stats.at("dirty").get<bool>());
    EXPECT_FALSE(r.stats.at("file_browser").at("open").get<bool>());
    // The path lands in the Scene field and the recent list, its folder in the settings.
    EXPECT_EQ(r.stats.at("scene_field").get<std::string>(), f.scene.string());
    EXPECT_EQ(r.stats.at("recent_files").at(0).get<std::string>(), f.scene.string());
    EXPECT_EQ(r.stats.at("last_folder").get<std::string>(), f.folder.string());
    EXPECT_EQ(editor::load_settings(settings).last_folder, f.folder.string());

    // The next session's browser starts in that folder.
    const EditorRun again =
        run_editor("pick-open-again", then(kFlat, R"({"op": "click", "widget": "Open..."},
            {"op": "wait", "frames": 3})"),
                   "--settings " + settings.string());
    ASSERT_EQ(again.exit_code, 0) << again.log;
    EXPECT_TRUE(again.stats.at("file_browser").at("open").get<bool>());
    EXPECT_EQ(again.stats.at("file_browser").at("folder").get<std::string>(), f.folder.string());
    EXPECT_EQ(again.stats.at("file_browser").at("error").get<std::string>(), "");
    // Its list: the sub-folder, then the scenes (not the settings, not the heightmap).
    const auto& widgets = again.stats.at("widgets");
    EXPECT_TRUE(widgets.contains("browser/entry/sub"));
    EXPECT_TRUE(widgets.contains("browser/entry/picked dunes.sandtin"));
    EXPECT_TRUE(widgets.contains("browser/entry/other.sandtin"));
    ASSERT_TRUE(again.stats.at("layout_overflow_px").contains("File browser"));
    EXPECT_EQ(again.stats.at("layout_overflow_px").at("File browser").get<double>(), 0.0);
    EXPECT_EQ(again.stats.at("layout_hidden_px").at("browser/OK").get<double>(), 0.0);
}

TEST_F(EditorFileDialog, CancellingTheBrowserChangesNothing) {
    const PickFolder f = make_pick_folder("pick-cancel");
    const fs::path settings = fresh_settings_file("pick-cancel");
    // Quoted: the harness runs the editor through a shell, and the folder has a space.
    const std::string args = "'" + f.other.string() + "' --settings " + settings.string();
    const EditorRun before = run_editor("pick-cancel-before", kFlat, args);
    ASSERT_EQ(before.exit_code, 0) << before.log;
    const EditorRun r =
        run_editor("pick-cancel", then(kFlat, pick("open", f.scene, R"(, "cancel": true)") + R"(,
            {"op": "wait", "frames": 2}, {"op": "save_settings"})"),
                   args);
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_FALSE(r.stats.at("file_browser").at("open").get<bool>());
    EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), f.other.string());
    EXPECT_EQ(r.stats.at("scene_field"), before.stats.at("scene_field"));
    EXPECT_EQ(r.stats.at("vertices"), before.stats.at("vertices"));
    EXPECT_FALSE(r.stats.at("dirty").get<bool>());
    EXPECT_EQ(r.stats.at("recent_files"), before.stats.at("recent_files"));
    EXPECT_EQ(r.stats.at("last_folder").get<std::string>(), "") << "nothing was picked";
    EXPECT_EQ(editor::load_settings(settings).last_folder, "");
}

TEST_F(EditorFileDialog, ImportsAHeightmapAndExportsThroughTheBrowser) {
    const PickFolder f = make_pick_folder("pick-import");
    const fs::path hills = f.folder / "hills.png";
    fs::copy_file(kHillsHeightmap, hills, fs::copy_options::overwrite_existing);
    const fs::path out = f.folder / "sub" / "export.obj";
    fs::remove(out);
    // The imported scene saved under a name typed into the browser (no extension: it gets
    // .sandtin), then exported.
    const fs::path saved = f.folder / "sub" / "saved hills.sandtin";
    fs::remove(saved);
    const EditorRun r = run_editor(
        "pick-import", then(kFlat, pick("import", hills) + R"(, {"op": "wait", "frames": 2}, )" +
                                       pick("save_as", f.folder / "sub" / "saved hills") +
                                       R"(, {"op": "wait", "frames": 2}, )" + pick("export", out) +
                                       R"(, {"op": "wait", "frames": 2})"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_TRUE(said(r, "imported " + hills.string())) << r.stats.at("messages");
    EXPECT_EQ(r.stats.at("import_field").get<std::string>(), hills.string());
    EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), saved.string());
    EXPECT_EQ(r.stats.at("scene_field").get<std::string>(), saved.string());
    EXPECT_TRUE(fs::exists(saved));
    EXPECT_EQ(r.stats.at("export_field").get<std::string>(), out.string());
    EXPECT_TRUE(said(r, "exported")) << r.stats.at("messages");
    ASSERT_TRUE(fs::exists(out));
    EXPECT_GT(fs::file_size(out), 1000u);

    // Exporting over it: the browser asks, and Replace writes it again.
    fs::resize_file(out, 0);
    const EditorRun replaced =
        run_editor("pick-export-replace", then(kFlat, pick("export", out, R"(, "replace": true)") +
                                                          R"(, {"op": "wait", "frames": 2})"));
    ASSERT_EQ(replaced.exit_code, 0) << replaced.log;
    EXPECT_TRUE(said(replaced, "exported")) << replaced.stats.at("messages");
    EXPECT_GT(fs::file_size(out), 1000u);
}

/// A fake zenity first on PATH: writes its arguments to `args`, then runs `body`.
fs::path fake_zenity(const std::string& name, const std::string& body) {
    const fs::path bin = kWork / (name + "-bin");
    fs::remove_all(bin);
    fs::create_directories(bin);
    std::ofstream(bin / "zenity") << "#!/bin/sh\nprintf '%s\\n' \"$@\" > '"
                                  << (kWork / (name + ".args")).string() << "'\n"
                                  << body << "\n";
    fs::permissions(bin / "zenity", fs::perms::owner_all);
    return bin;
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST_F(EditorXvfb, TheDesktopsDialogPicksTheFileAndAFailedOneGivesWayToTheBrowser) {
    const PickFolder f = make_pick_folder("pick-native");
    const std::string path_env = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
    ScopedEnv native("SANDTIN_FILE_DIALOG", "native");
    {
        const fs::path bin = fake_zenity("pick-native", "echo '" + f.scene.string() + "'");
        ScopedEnv path("PATH", bin.string() + ":" + path_env);
        const EditorRun r =
            run_editor("pick-native", then(kFlat, R"({"op": "pick_file", "dialog": "open"},
                {"op": "wait", "frames": 2})"));
        ASSERT_EQ(r.exit_code, 0) << r.log;
        EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), f.scene.string());
        EXPECT_EQ(r.stats.at("vertices").get<std::size_t>(), alive_vertices(f.saved));
        EXPECT_FALSE(r.stats.at("native_dialog_busy").get<bool>());
        const std::string args = read_text(kWork / "pick-native.args");
        EXPECT_NE(args.find("--file-selection\n--title=Open a scene\n"), std::string::npos) << args;
    }
    {
        const fs::path bin = fake_zenity("pick-native-fails", "echo 'no display' >&2; exit 5");
        ScopedEnv path("PATH", bin.string() + ":" + path_env);
        const EditorRun r =
            run_editor("pick-native-fails", then(kFlat, R"({"op": "pick_file", "dialog": "open"},
                {"op": "wait", "frames": 3})"));
        ASSERT_EQ(r.exit_code, 0) << r.log;
        EXPECT_TRUE(r.stats.at("file_browser").at("open").get<bool>());
        const std::string status = r.stats.at("status").get<std::string>();
        EXPECT_NE(status.find("zenity exited with 5: no display"), std::string::npos) << status;
        EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), "");
    }
}

}  // namespace
}  // namespace sandtin::file_dialog_xvfb
