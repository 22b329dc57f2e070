#pragma once
// Every keyboard shortcut and mouse gesture of the editor, in one list. The key handler
// dispatches from it (app_input.cpp), the Help window (F1) shows it, and a test checks that
// the README's table is this list row for row (tests/editor/shortcuts_test.cpp): the three
// cannot drift apart.

#include <string>
#include <vector>

namespace sandtin::editor {

/// What a shortcut does. App::run_command switches over every one without a default, so a
/// command added here and not handled there does not compile.
enum class Command { Undo, Redo, Save, New, Open, Quit, Frame, Help };

/// GLFW_KEY_F1, spelt out so that this header and its tests need no GLFW; app_input.cpp
/// checks the value against GLFW's.
inline constexpr int kKeyF1 = 290;

struct Shortcut {
    const char* keys;    ///< as the Help window and the README show them
    const char* action;  ///< what the key does, as they show it
    int key;             ///< GLFW key code: a letter is its upper-case ASCII code
    bool ctrl;           ///< with Ctrl held (and only then)
    bool repeats;        ///< a held key repeats it (not Ctrl+N: it would replace the scene again)
    Command command;
};

inline constexpr Shortcut kShortcuts[] = {
    {"Ctrl+Z", "undo the last stroke, brush stroke, pour, erosion run or material edit", 'Z', true,
     true, Command::Undo},
    {"Ctrl+Y", "redo", 'Y', true, true, Command::Redo},
    {"Ctrl+S", "save the scene (an untitled one to the path in the Scene field)", 'S', true, false,
     Command::Save},
    {"Ctrl+N", "start a new sandbox", 'N', true, false, Command::New},
    {"Ctrl+O", "open the scene named in the Scene field", 'O', true, false, Command::Open},
    {"Ctrl+Q", "quit (an untitled scene's unsaved edits are asked about first)", 'Q', true, false,
     Command::Quit},
    {"F", "frame the terrain (right of the panel)", 'F', false, false, Command::Frame},
    {"F1", "show or hide this list of keys and gestures", kKeyF1, false, false, Command::Help},
};

/// A mouse gesture: the pointer handlers (app_input.cpp) act on these by button, not by
/// looking them up, so they are listed here for people only.
struct Gesture {
    const char* input;
    const char* action;
};

inline constexpr Gesture kGestures[] = {
    {"Left drag",
     "apply the current tool along the stroke (Pour, Remove, Water and Rain also while held "
     "still)"},
    {"Right drag", "orbit the camera"},
    {"Middle drag", "pan the camera"},
    {"Wheel", "zoom"},
    {"Ctrl+click a slider", "type a value (kept inside the slider's range)"},
    {"Drop a file on the window", "open a scene (.sandtin) or import a heightmap"},
};

/// The shortcut `key` (a GLFW key code) with or without Ctrl runs, if any.
constexpr const Shortcut* shortcut_for_key(int key, bool ctrl) {
    for (const Shortcut& s : kShortcuts) {
        if (s.key == key && s.ctrl == ctrl) return &s;
    }
    return nullptr;
}

/// One row of the list of keys and gestures.
struct HelpRow {
    std::string keys;
    std::string action;
    friend bool operator==(const HelpRow&, const HelpRow&) = default;
};

/// The whole list as the Help window and the README show it: the gestures, the keys that
/// pick tools (from the tool palette, one row per kind of tool), then the shortcuts.
std::vector<HelpRow> help_rows();

}  // namespace sandtin::editor
