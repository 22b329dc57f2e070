// The recent list (editor/app/recent_files.hpp), what the editor does with a file by its kind
// (file_kinds.hpp), and the list in the settings file with its field-by-field fallback.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "editor_settings.hpp"
#include "file_kinds.hpp"
#include "recent_files.hpp"

namespace sandtin::editor {
namespace {

TEST(RecentFiles, NewestFirstAbsoluteNoRepeatsAtMostTen) {
    std::vector<std::string> recent;
    note_recent_file(recent, "/data/a.sandtin");
    note_recent_file(recent, "/data/b.png");
    EXPECT_EQ(recent, (std::vector<std::string>{"/data/b.png", "/data/a.sandtin"}));
    // Opened again: it moves to the front, and is not listed twice (however it was spelt).
    note_recent_file(recent, "/data/sub/../a.sandtin");
    EXPECT_EQ(recent, (std::vector<std::string>{"/data/a.sandtin", "/data/b.png"}));
    // A relative path is kept absolute: the list means the same from any working directory.
    note_recent_file(recent, "rel.sandtin");
    EXPECT_EQ(recent.front(), (std::filesystem::current_path() / "rel.sandtin").string());
    for (int i = 0; i < 20; ++i)
        note_recent_file(recent, "/data/f" + std::to_string(i) + ".sandtin");
    ASSERT_EQ(recent.size(), kRecentFilesKept);
    EXPECT_EQ(recent.front(), "/data/f19.sandtin");
    EXPECT_EQ(recent.back(), "/data/f10.sandtin");

    EXPECT_EQ(tidy_recent_files({"", "/a", "/b", "/a", ""}),
              (std::vector<std::string>{"/a", "/b"}));
    std::vector<std::string> many(15);
    for (std::size_t i = 0; i < many.size(); ++i)
        many[i] = "/m" + std::to_string(i);
    EXPECT_EQ(tidy_recent_files(many).size(), kRecentFilesKept);
}

TEST(RecentFiles, AFileIsOpenedImportedOrRefusedByItsExtension) {
    EXPECT_EQ(file_kind("/x/dunes.sandtin"), FileKind::Scene);
    EXPECT_EQ(file_kind("/x/DUNES.SANDTIN"), FileKind::Scene);
    for (const char* name : {"a.png", "a.exr", "a.tif", "a.TIFF", "a.asc"})
        EXPECT_EQ(file_kind(name), FileKind::Heightmap) << name;
    for (const char* name : {"notes.txt", "mesh.obj", "noextension", "a.sandtin.bak"})
        EXPECT_EQ(file_kind(name), FileKind::Other) << name;
    EXPECT_EQ(accepted_files_text(),
              "a scene (.sandtin) or a heightmap (.png .exr .tif .tiff .asc)");
}

TEST(RecentFiles, SurviveTheSettingsFileAndABadListFallsBackAlone) {
    const auto dir = std::filesystem::temp_directory_path() / "sandtin-recent-files-test";
    std::filesystem::remove_all(dir);
    const auto path = dir / "editor.json";
    EditorSettings s;
    s.recent_files = {"/data/b.png", "/data/a.sandtin"};
    save_settings(path, s);
    std::string problem;
    EXPECT_EQ(load_settings(path, &problem).recent_files, s.recent_files);
    EXPECT_TRUE(problem.empty()) << problem;

    // Not a list of strings: the list alone goes back to empty, and the rest still counts.
    std::ofstream(path) << R"({"tool_radius": 0.07, "recent_files": [1, 2]})";
    const EditorSettings bad = load_settings(path, &problem);
    EXPECT_TRUE(bad.recent_files.empty());
    EXPECT_DOUBLE_EQ(bad.tool_radius, 0.07);
    EXPECT_NE(problem.find("recent_files"), std::string::npos) << problem;
    problem.clear();
    std::ofstream(path) << R"({"recent_files": "/data/a.sandtin"})";
    EXPECT_TRUE(load_settings(path, &problem).recent_files.empty());
    EXPECT_NE(problem.find("recent_files"), std::string::npos) << problem;
    // Repeats and more than ten, as a hand edit may leave them: tidied, not refused.
    std::ofstream(path)
        << R"({"recent_files": ["/a", "/a", "", "/b", "/c", "/d", "/e", "/f", "/g", "/h", "/i", "/j", "/k"]})";
    problem.clear();
    const EditorSettings tidied = load_settings(path, &problem);
    EXPECT_TRUE(problem.empty()) << problem;
    EXPECT_EQ(tidied.recent_files, (std::vector<std::string>{"/a", "/b", "/c", "/d", "/e", "/f",
                                                             "/g", "/h", "/i", "/j"}));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sandtin::editor
