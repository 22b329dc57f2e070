#pragma once
// The editor: one window, one terrain document, ImGui panels, mouse and keyboard, undo/redo,
// and a scripted mode that feeds synthetic input through the same handlers as the real mouse.

#include <filesystem>
#include <optional>
#include <string>

namespace sandtin::editor {

struct EditorOptions {
    std::filesystem::path scene;       ///< empty: a new flat sandbox
    std::filesystem::path script;      ///< JSON script of input events
    std::filesystem::path screenshot;  ///< PNG written after the script and frames
    std::filesystem::path stats;       ///< JSON with timings and counters, written at exit
    std::filesystem::path settings;    ///< settings file (default_settings_path())
    std::filesystem::path save_after;  ///< save the scene here after the script
    int frames = 0;                    ///< frames rendered after the script (scripted mode)
    int width = 1280;
    int height = 720;
    double idle_seconds = 0.0;  ///< scripted: then sit idle this long, counting submits
    /// Written after every frame whose controls moved: where each named control is (window
    /// pixels), so that a test driving the editor with real X events (xdotool) can aim.
    std::filesystem::path widget_map;
    bool validation = false;  ///< Vulkan validation layer; exit code 3 on messages
    bool scripted() const { return !script.empty() || !screenshot.empty() || frames > 0; }
};

/// Runs the editor until the window closes (or the script ends). Returns the exit code.
int run_editor(const EditorOptions& options);

}  // namespace sandtin::editor
