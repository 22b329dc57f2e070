// The editor's file browser without its UI (editor/app/file_browser.hpp, folder_listing.hpp)
// on temporary folders: folders first, the extension filter, type to filter, hidden files, a
// folder that cannot be read, and what picking does; and the dialogs' extension lists
// (file_dialog_request.hpp) against the importer's and the exporter's.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "file_browser.hpp"
#include "file_dialog_request.hpp"
#include "file_kinds.hpp"
#include "folder_listing.hpp"
#include "io/export_terrain.hpp"

namespace sandtin::editor {
namespace {

namespace fs = std::filesystem;

class FileBrowserTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ =
            fs::temp_directory_path() / ("sandtin-file-browser-test-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "b folder");
        fs::create_directories(dir_ / "Alpha");
        fs::create_directories(dir_ / ".hidden folder");
        for (const char* f : {"zeta.sandtin", "Beta.SANDTIN", "dunes.png", "notes.txt",
                              ".secret.sandtin", "alpha.sandtin"})
            std::ofstream(dir_ / f) << "x";
    }
    void TearDown() override {
        std::error_code ec;
        fs::permissions(dir_ / "locked", fs::perms::owner_all, ec);
        fs::remove_all(dir_, ec);
    }
    static std::vector<std::string> names(const std::vector<FolderEntry>& entries) {
        std::vector<std::string> out;
        for (const FolderEntry& e : entries)
            out.push_back(e.name + (e.folder ? "/" : ""));
        return out;
    }
    fs::path dir_;
};

TEST_F(FileBrowserTest, ListsFoldersFirstThenFilesByNameCaseAside) {
    const FolderListing l = read_folder(dir_);
    EXPECT_EQ(l.error, "");
    EXPECT_EQ(names(l.entries),
              (std::vector<std::string>{".hidden folder/", "Alpha/", "b folder/", ".secret.sandtin",
                                        "alpha.sandtin", "Beta.SANDTIN", "dunes.png", "notes.txt",
                                        "zeta.sandtin"}));
}

TEST_F(FileBrowserTest, FiltersByExtensionTypedTextAndHiddenNames) {
    const std::vector<FolderEntry> all = read_folder(dir_).entries;
    const FileDialogRequest open = file_dialog_request(FileDialogKind::Open, dir_);
    ASSERT_EQ(open.filters.size(), 2u);
    // Scenes, with the extension in any case; folders are always listed; dot names hidden.
    EXPECT_EQ(names(visible_entries(all, open.filters[0], "", false)),
              (std::vector<std::string>{"Alpha/", "b folder/", "alpha.sandtin", "Beta.SANDTIN",
                                        "zeta.sandtin"}));
    // All files, with the hidden ones.
    EXPECT_EQ(visible_entries(all, open.filters[1], "", true).size(), all.size());
    EXPECT_EQ(names(visible_entries(all, open.filters[1], "", false)).size(), 7u);
    // Typed text narrows folders and files alike, case aside.
    EXPECT_EQ(names(visible_entries(all, open.filters[0], "ALP", false)),
              (std::vector<std::string>{"Alpha/", "alpha.sandtin"}));
    EXPECT_EQ(names(visible_entries(all, open.filters[1], "not", false)),
              (std::vector<std::string>{"notes.txt"}));
    EXPECT_TRUE(visible_entries(all, open.filters[0], "nothing like it", false).empty());
    // Heightmaps: the importer's extensions.
    const FileDialogRequest import = file_dialog_request(FileDialogKind::Import, dir_);
    EXPECT_EQ(names(visible_entries(all, import.filters[0], "", false)),
              (std::vector<std::string>{"Alpha/", "b folder/", "dunes.png"}));
}

TEST_F(FileBrowserTest, AFolderThatCannotBeReadGivesAnErrorNotACrash) {
    const FolderListing missing = read_folder(dir_ / "no such folder");
    EXPECT_TRUE(missing.entries.empty());
    EXPECT_NE(missing.error.find("does not exist"), std::string::npos) << missing.error;
    const FolderListing file = read_folder(dir_ / "notes.txt");
    EXPECT_NE(file.error.find("is not a folder"), std::string::npos) << file.error;

    // The browser shows the error in the folder it was sent to, and Up leaves it.
    FileBrowser b;
    b.open(file_dialog_request(FileDialogKind::Open, dir_ / "no such folder"));
    EXPECT_TRUE(b.is_open());
    EXPECT_FALSE(b.error().empty());
    EXPECT_TRUE(b.visible().empty());
    b.up();
    EXPECT_EQ(b.folder(), dir_);
    EXPECT_EQ(b.error(), "");

    // A folder without read permission (root reads any folder: nothing to check then).
    fs::create_directories(dir_ / "locked");
    fs::permissions(dir_ / "locked", fs::perms::none);
    if (::geteuid() != 0) {
        const FolderListing locked = read_folder(dir_ / "locked");
        EXPECT_TRUE(locked.entries.empty());
        EXPECT_NE(locked.error.find("cannot read"), std::string::npos) << locked.error;
    }
}

TEST_F(FileBrowserTest, NavigatesIntoFoldersAndUp) {
    FileBrowser b;
    b.open(file_dialog_request(FileDialogKind::Open, dir_ / "."));
    EXPECT_EQ(b.folder(), dir_) << "the folder is shown without . or a trailing separator";
    std::ofstream(dir_ / "b folder" / "inner.sandtin") << "x";
    EXPECT_FALSE(b.activate({"b folder", true}));
    EXPECT_EQ(b.folder(), dir_ / "b folder");
    EXPECT_EQ(names(b.visible()), (std::vector<std::string>{"inner.sandtin"}));
    b.up();
    EXPECT_EQ(b.folder(), dir_);
    // A relative folder typed in the folder field is taken from the current one.
    b.navigate("Alpha");
    EXPECT_EQ(b.folder(), dir_ / "Alpha");
    b.navigate("..");
    EXPECT_EQ(b.folder(), dir_);
    // "~" is the home folder, as in a shell.
    if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
        b.navigate("~");
        EXPECT_EQ(b.folder(), fs::path(home).lexically_normal());
        b.navigate("~/");
        EXPECT_EQ(b.folder(), fs::path(home).lexically_normal());
    }
    // Up from the root stays there.
    b.navigate("/");
    b.up();
    EXPECT_EQ(b.folder(), fs::path("/"));
}

TEST_F(FileBrowserTest, OpenPicksAnExistingFileBySelectionNameOrFilter) {
    FileBrowser b;
    b.open(file_dialog_request(FileDialogKind::Open, dir_));
    // Nothing chosen: a message, still open.
    EXPECT_FALSE(b.accept());
    EXPECT_EQ(b.message(), "choose a file");
    // A click fills the name; the pick button picks it and closes the browser.
    b.select({"zeta.sandtin", false});
    EXPECT_EQ(b.name, "zeta.sandtin");
    EXPECT_EQ(b.accept(), dir_ / "zeta.sandtin");
    EXPECT_FALSE(b.is_open());

    // A name that is not there: a message naming it.
    b.open(file_dialog_request(FileDialogKind::Open, dir_));
    b.name = "gone.sandtin";
    EXPECT_FALSE(b.accept());
    EXPECT_NE(b.message().find("no file gone.sandtin"), std::string::npos) << b.message();
    EXPECT_TRUE(b.is_open());

    // Enter in the filter box: the one file listed is picked...
    b.text = "bet";
    EXPECT_EQ(b.accept_filter(), dir_ / "Beta.SANDTIN");
    // ...several: a message; exactly a name: that one; only a folder: it is entered.
    b.open(file_dialog_request(FileDialogKind::Open, dir_));
    b.text = "a.sandtin";
    EXPECT_FALSE(b.accept_filter());
    EXPECT_NE(b.message().find("3 files match"), std::string::npos) << b.message();
    b.text = "zeta.sandtin";
    EXPECT_EQ(b.accept_filter(), dir_ / "zeta.sandtin");
    b.open(file_dialog_request(FileDialogKind::Open, dir_));
    b.text = "b fol";
    EXPECT_FALSE(b.accept_filter());
    EXPECT_EQ(b.folder(), dir_ / "b folder");
    EXPECT_TRUE(b.is_open());
}

TEST_F(FileBrowserTest, SavingProposesANameAddsTheExtensionAndAsksBeforeReplacing) {
    FileBrowser b;
    b.open(file_dialog_request(FileDialogKind::Export, dir_, "terrain.glb"));
    EXPECT_EQ(b.name, "terrain.glb");
    EXPECT_EQ(b.accept(), dir_ / "terrain.glb") << "a new file is picked at once";

    // An existing file: the overwrite question first; Keep leaves the browser open.
    b.open(file_dialog_request(FileDialogKind::Export, dir_, "dunes.png"));
    EXPECT_FALSE(b.accept());
    ASSERT_TRUE(b.replacing());
    EXPECT_EQ(*b.replacing(), dir_ / "dunes.png");
    EXPECT_FALSE(b.answer_overwrite(false));
    EXPECT_TRUE(b.is_open());
    EXPECT_FALSE(b.replacing());
    EXPECT_FALSE(b.accept());
    EXPECT_EQ(b.answer_overwrite(true), dir_ / "dunes.png");
    EXPECT_FALSE(b.is_open());

    // Save As: a name without an extension gets .sandtin; the editor's own prompt asks
    // about an existing scene (it knows about autosaves), so the browser does not.
    b.open(file_dialog_request(FileDialogKind::SaveAs, dir_, "untitled"));
    b.name = "new scene";
    EXPECT_EQ(b.accept(), dir_ / "new scene.sandtin");
    b.open(file_dialog_request(FileDialogKind::SaveAs, dir_, "zeta.sandtin"));
    EXPECT_EQ(b.accept(), dir_ / "zeta.sandtin");
    EXPECT_FALSE(b.replacing());

    // A name in a folder that does not exist: a message; a folder's name: it is entered.
    b.open(file_dialog_request(FileDialogKind::SaveAs, dir_, "x"));
    b.name = "nowhere/x.sandtin";
    EXPECT_FALSE(b.accept());
    EXPECT_NE(b.message().find("there is no folder"), std::string::npos) << b.message();
    b.name = "Alpha";
    EXPECT_FALSE(b.accept());
    EXPECT_EQ(b.folder(), dir_ / "Alpha");
    EXPECT_EQ(b.name, "");
}

TEST(FileDialogRequest, ExtensionListsAreTheImportersAndTheExportersOwn) {
    // Every export extension offered is a format the exporter writes...
    for (const char* e : kExportExtensions)
        EXPECT_NO_THROW(export_format_for(std::string("out") + e)) << e;
    // ...and every format it names in its refusal is offered.
    std::string refusal;
    try {
        export_format_for("out.unknown");
    } catch (const std::invalid_argument& e) {
        refusal = e.what();
    }
    for (const char* e : kExportExtensions)
        EXPECT_NE(refusal.find(e), std::string::npos) << e << " in: " << refusal;
    // The import filter is the heightmap kinds the editor accepts (file_kinds.hpp).
    const FileDialogRequest import = file_dialog_request(FileDialogKind::Import, "/data");
    for (const std::string& e : import.filters[0].extensions)
        EXPECT_EQ(file_kind("a" + e), FileKind::Heightmap) << e;
    EXPECT_EQ(import.filters[0].extensions.size(), std::size(kHeightmapExtensions));
    EXPECT_EQ(import.filters.back().label, "All files");
    EXPECT_TRUE(import.filters.back().extensions.empty());
    // Each kind: its title, its button, whether it saves, and its name for scripts.
    for (FileDialogKind k : {FileDialogKind::Open, FileDialogKind::SaveAs, FileDialogKind::Import,
                             FileDialogKind::Export}) {
        const FileDialogRequest r = file_dialog_request(k, "/data", "proposed.x");
        EXPECT_EQ(file_dialog_kind_named(to_string(k)), k);
        EXPECT_EQ(r.saving, k == FileDialogKind::SaveAs || k == FileDialogKind::Export);
        EXPECT_EQ(r.name, r.saving ? "proposed.x" : "");
        EXPECT_FALSE(r.title.empty());
    }
    EXPECT_EQ(file_dialog_request(FileDialogKind::Open, "/d").filters[0].label,
              "Scenes (.sandtin)");
    EXPECT_FALSE(file_dialog_kind_named("save"));
}

}  // namespace
}  // namespace sandtin::editor
