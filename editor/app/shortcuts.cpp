#include "shortcuts.hpp"

#include "tool_palette.hpp"

namespace sandtin::editor {

namespace {

/// The palette's keys for tools of one group, "1 2 3", and their labels, "Circle, Ball, Box".
HelpRow tool_keys_row(const char* what, bool (*in_group)(ToolKind)) {
    HelpRow row;
    std::string labels;
    for (const ToolEntry& t : kTools) {
        if (!in_group(t.kind)) continue;
        row.keys += (row.keys.empty() ? "" : " ") + std::string(1, t.key);
        labels += (labels.empty() ? "" : ", ") + std::string(t.label);
    }
    row.action = std::string("pick ") + what + ": " + labels;
    return row;
}

}  // namespace

std::vector<HelpRow> help_rows() {
    std::vector<HelpRow> rows;
    for (const Gesture& g : kGestures)
        rows.push_back({g.input, g.action});
    rows.push_back(tool_keys_row("a stamp", [](ToolKind k) { return k == ToolKind::Stamp; }));
    rows.push_back(tool_keys_row("a sand or water tool", [](ToolKind k) {
        return k == ToolKind::Pour || k == ToolKind::Remove || k == ToolKind::Water ||
               k == ToolKind::Rain;
    }));
    rows.push_back(tool_keys_row("a brush", [](ToolKind k) { return k == ToolKind::Brush; }));
    for (const Shortcut& s : kShortcuts)
        rows.push_back({s.keys, s.action});
    return rows;
}

}  // namespace sandtin::editor
