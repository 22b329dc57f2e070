// The desktop's file dialog run as a child process (editor/app/native_file_dialog.hpp), against
// fake `zenity` and `kdialog` scripts put first on PATH: each writes the arguments it received
// to a file, then answers as it is told (a path, a cancel, a failure). Independent of a real
// zenity being installed.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "native_file_dialog.hpp"

namespace sandtin::editor {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

class NativeFileDialogTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("sandtin-native-dialog-test-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "bin");
    }
    void TearDown() override { fs::remove_all(dir_); }

    /// A fake dialog program `name` in dir_/bin running `body` (sh) after writing its
    /// arguments, NUL-separated, to dir_/args.
    DialogProgram fake(const std::string& name, const std::string& body) {
        const fs::path p = dir_ / "bin" / name;
        std::ofstream(p) << "#!/bin/sh\nprintf '%s\\0' \"$@\" > '" << (dir_ / "args").string()
                         << "'\n"
                         << body << "\n";
        fs::permissions(p, fs::perms::owner_all);
        const auto found = find_dialog_program((dir_ / "bin").string() + ":/usr/bin:/bin", "");
        EXPECT_TRUE(found);
        return found.value_or(DialogProgram{});
    }
    std::vector<std::string> received() const {
        std::ifstream in(dir_ / "args", std::ios::binary);
        const std::string all((std::istreambuf_iterator<char>(in)), {});
        std::vector<std::string> args;
        std::size_t begin = 0;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (all[i] == '\0') {
                args.push_back(all.substr(begin, i - begin));
                begin = i + 1;
            }
        }
        return args;
    }
    /// Runs the dialog as the editor does (on its thread) and waits for the answer.
    NativeDialogResult run(const DialogProgram& program, const FileDialogRequest& request) {
        std::atomic<int> woken{0};
        NativeFileDialog dialog([&woken] { ++woken; });
        dialog.start(program, request);
        EXPECT_TRUE(dialog.busy());
        const auto until = std::chrono::steady_clock::now() + 20s;
        std::optional<NativeDialogResult> r;
        while (!(r = dialog.take_result()) && std::chrono::steady_clock::now() < until)
            std::this_thread::sleep_for(5ms);
        EXPECT_TRUE(r) << "the dialog never answered";
        EXPECT_EQ(woken.load(), 1) << "the UI is woken once, when the answer is there";
        EXPECT_FALSE(dialog.busy());
        return r.value_or(NativeDialogResult{});
    }
    fs::path dir_;
};

TEST_F(NativeFileDialogTest, FindsZenityOrKdialogOnThePath) {
    const std::string path = (dir_ / "bin").string();
    EXPECT_FALSE(find_dialog_program(path, ""));
    // Not executable: not a program.
    std::ofstream(dir_ / "bin" / "zenity") << "#!/bin/sh\n";
    fs::permissions(dir_ / "bin" / "zenity", fs::perms::owner_read | fs::perms::owner_write);
    EXPECT_FALSE(find_dialog_program(path, ""));
    std::ofstream(dir_ / "bin" / "kdialog") << "#!/bin/sh\n";
    fs::permissions(dir_ / "bin" / "kdialog", fs::perms::owner_all);
    ASSERT_TRUE(find_dialog_program("/nonexistent:" + path, ""));
    EXPECT_EQ(find_dialog_program(path, "")->kind, DialogProgram::Kind::KDialog);
    fs::permissions(dir_ / "bin" / "zenity", fs::perms::owner_all);
    EXPECT_EQ(find_dialog_program(path, "GNOME")->kind, DialogProgram::Kind::Zenity);
    EXPECT_EQ(find_dialog_program(path, "")->path, dir_ / "bin" / "zenity");
    EXPECT_EQ(find_dialog_program(path, "KDE")->kind, DialogProgram::Kind::KDialog)
        << "on KDE, its own dialog";
}

TEST_F(NativeFileDialogTest, ZenityGetsTheTitleFolderFiltersAsArgvAndItsPathWithSpacesComesBack) {
    // A folder and an answer with spaces and quotes: no shell sees them.
    const fs::path folder = dir_ / "my \"quoted\" folder's files";
    const fs::path chosen = folder / "a scene with spaces.sandtin";
    // The answer comes from a file: the script's own quoting would not hold that path.
    std::ofstream(dir_ / "answer") << chosen.string() << "\n";
    const DialogProgram zenity = fake("zenity", "cat '" + (dir_ / "answer").string() + "'");
    const FileDialogRequest request = file_dialog_request(FileDialogKind::Open, folder);
    const NativeDialogResult r = run(zenity, request);
    EXPECT_EQ(r.outcome, NativeDialogResult::Outcome::Chosen) << r.error;
    EXPECT_EQ(r.path, chosen);
    const std::vector<std::string> args = received();
    EXPECT_EQ(args, dialog_arguments(zenity, request));
    EXPECT_EQ(args,
              (std::vector<std::string>{"--file-selection", "--title=Open a scene",
                                        "--filename=" + folder.string() + "/",
                                        "--file-filter=Scenes (.sandtin) | *.sandtin *.SANDTIN",
                                        "--file-filter=All files | *"}));
}

TEST_F(NativeFileDialogTest, SavingAsksToSaveProposesTheNameAndExportConfirmsOverwrite) {
    const DialogProgram zenity = fake("zenity", "echo /out/terrain.obj");
    const FileDialogRequest request =
        file_dialog_request(FileDialogKind::Export, dir_, "terrain.glb");
    EXPECT_EQ(run(zenity, request).path, fs::path("/out/terrain.obj"));
    const std::vector<std::string> args = received();
    ASSERT_GE(args.size(), 5u);
    EXPECT_EQ(args[2], "--filename=" + (dir_ / "terrain.glb").string());
    EXPECT_EQ(args[3], "--save");
    EXPECT_EQ(args[4], "--confirm-overwrite");
    EXPECT_EQ(args[5],
              "--file-filter=Meshes and height maps (.obj .ply .stl .gltf .glb .png .exr) | "
              "*.obj *.OBJ *.ply *.PLY *.stl *.STL *.gltf *.GLTF *.glb *.GLB *.png *.PNG *.exr "
              "*.EXR");
    // Save As leaves the overwrite question to the editor's own prompt.
    const std::vector<std::string> save_as = dialog_arguments(
        zenity, file_dialog_request(FileDialogKind::SaveAs, dir_, "scene.sandtin"));
    EXPECT_EQ(std::count(save_as.begin(), save_as.end(), "--save"), 1);
    EXPECT_EQ(std::count(save_as.begin(), save_as.end(), "--confirm-overwrite"), 0);
}

TEST_F(NativeFileDialogTest, KdialogGetsItsOwnArguments) {
    fake("kdialog", "echo /data/hills.png");
    const DialogProgram kdialog = find_dialog_program((dir_ / "bin").string(), "KDE").value();
    const FileDialogRequest request = file_dialog_request(FileDialogKind::Import, dir_);
    const NativeDialogResult r = run(kdialog, request);
    EXPECT_EQ(r.path, fs::path("/data/hills.png"));
    EXPECT_EQ(received(),
              (std::vector<std::string>{
                  "--title", "Import a heightmap", "--getopenfilename", dir_.string() + "/",
                  "Heightmaps (.png .exr .tif .tiff .asc) (*.png *.PNG *.exr *.EXR "
                  "*.tif *.TIF *.tiff *.TIFF *.asc *.ASC)\nAll files (*)"}));
}

TEST_F(NativeFileDialogTest, ExitOneIsACancelAndAnyOtherFailureSaysWhy) {
    const FileDialogRequest request = file_dialog_request(FileDialogKind::Open, dir_);
    EXPECT_EQ(run(fake("zenity", "exit 1"), request).outcome,
              NativeDialogResult::Outcome::Cancelled);

    const NativeDialogResult five =
        run(fake("zenity", "echo 'Gtk-WARNING: cannot open display' >&2; exit 5"), request);
    EXPECT_EQ(five.outcome, NativeDialogResult::Outcome::Failed);
    EXPECT_NE(five.error.find("zenity exited with 5"), std::string::npos) << five.error;
    EXPECT_NE(five.error.find("cannot open display"), std::string::npos) << five.error;

    const NativeDialogResult silent = run(fake("zenity", "exit 0"), request);
    EXPECT_EQ(silent.outcome, NativeDialogResult::Outcome::Failed);
    EXPECT_NE(silent.error.find("printed no file name"), std::string::npos) << silent.error;

    const NativeDialogResult killed = run(fake("zenity", "kill -9 $$"), request);
    EXPECT_EQ(killed.outcome, NativeDialogResult::Outcome::Failed);
    EXPECT_NE(killed.error.find("signal 9"), std::string::npos) << killed.error;

    // A program that cannot run at all (its interpreter is missing).
    const fs::path broken = dir_ / "bin" / "broken";
    std::ofstream(broken) << "#!/nonexistent/interpreter\n";
    fs::permissions(broken, fs::perms::owner_all);
    const NativeDialogResult cannot =
        run(DialogProgram{DialogProgram::Kind::Zenity, broken}, request);
    EXPECT_EQ(cannot.outcome, NativeDialogResult::Outcome::Failed);
    EXPECT_FALSE(cannot.error.empty());
}

TEST_F(NativeFileDialogTest, TheCallerIsNeverBlockedAndClosingTheEditorEndsTheDialog) {
    const DialogProgram slow = fake("zenity", "sleep 30; echo /late.sandtin");
    const auto begun = std::chrono::steady_clock::now();
    {
        NativeFileDialog dialog;
        dialog.start(slow, file_dialog_request(FileDialogKind::Open, dir_));
        EXPECT_LT(std::chrono::steady_clock::now() - begun, 1s) << "start waited for the dialog";
        std::this_thread::sleep_for(200ms);
        EXPECT_TRUE(dialog.busy());
        EXPECT_FALSE(dialog.take_result()) << "no answer while the dialog is open";
        EXPECT_THROW(dialog.start(slow, file_dialog_request(FileDialogKind::Open, dir_)),
                     std::logic_error)
            << "one dialog at a time";
    }  // the editor closes with the dialog open
    EXPECT_LT(std::chrono::steady_clock::now() - begun, 5s) << "closing waited for the dialog";
}

}  // namespace
}  // namespace sandtin::editor
