// The one list of keys and gestures (editor/app/shortcuts.hpp): the README's table is that
// list, row for row, and every key in it is one the key handler acts on, once.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shortcuts.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {
namespace {

constexpr const char* kTableHeader = "| Key or gesture | Action |";

/// The table's rows as the README must write them, one line each.
std::vector<std::string> expected_lines() {
    std::vector<std::string> lines;
    for (const HelpRow& row : help_rows())
        lines.push_back("| " + row.keys + " | " + row.action + " |");
    return lines;
}

/// The rows of the README's table under kTableHeader (after its |---| line).
std::vector<std::string> readme_lines() {
    std::ifstream in(std::filesystem::path(SANDTIN_SOURCE_DIR) / "README.md");
    std::vector<std::string> rows;
    std::string line;
    bool in_table = false;
    while (std::getline(in, line)) {
        if (line == kTableHeader) {
            in_table = true;
            std::getline(in, line);  // |---|---|
            continue;
        }
        if (!in_table) continue;
        if (!line.starts_with("|")) break;
        rows.push_back(line);
    }
    return rows;
}

TEST(Shortcuts, TheReadmeTableIsTheEditorsList) {
    const std::vector<std::string> expected = expected_lines();
    std::string table = std::string(kTableHeader) + "\n|---|---|\n";
    for (const std::string& line : expected)
        table += line + "\n";
    EXPECT_EQ(readme_lines(), expected)
        << "README.md's table of keys differs from editor/app/shortcuts.hpp; it should read:\n"
        << table;
}

TEST(Shortcuts, EveryToolAndEveryShortcutIsListedAndEveryKeyDoesOneThing) {
    const std::vector<HelpRow> rows = help_rows();
    const auto listed = [&](const std::string& keys, const std::string& action) {
        for (const HelpRow& r : rows) {
            if (r.keys == keys && r.action == action) return true;
        }
        return false;
    };
    for (const Shortcut& s : kShortcuts) {
        EXPECT_TRUE(listed(s.keys, s.action)) << s.keys;
        // The handler finds each by its key (it dispatches from this table).
        EXPECT_EQ(shortcut_for_key(s.key, s.ctrl), &s) << s.keys;
    }
    // Every tool's key appears in a row that names the tool.
    for (const ToolEntry& t : kTools) {
        bool found = false;
        for (const HelpRow& r : rows) {
            found |= r.keys.find(t.key) != std::string::npos &&
                     r.action.find(t.label) != std::string::npos;
        }
        EXPECT_TRUE(found) << t.label;
    }
    // No key (with or without Ctrl) is two things: a plain key is a tool's or a shortcut's.
    std::set<std::pair<int, bool>> keys;
    for (const Shortcut& s : kShortcuts)
        EXPECT_TRUE(keys.insert({s.key, s.ctrl}).second) << s.keys;
    for (const ToolEntry& t : kTools)
        EXPECT_TRUE(keys.insert({t.key, false}).second) << t.label;
    EXPECT_EQ(shortcut_for_key('R', true), nullptr) << "Ctrl+R is nothing";
    EXPECT_NE(shortcut_for_key(kKeyF1, false), nullptr) << "F1 shows the help";
}

}  // namespace
}  // namespace sandtin::editor
