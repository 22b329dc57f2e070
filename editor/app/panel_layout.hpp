#pragma once
// Where the editor's main panel sits: a fixed-width column at the window's left edge, with the
// status line's window below it.

namespace sandtin::editor {

/// Pixels between the panel and the window's edges.
inline constexpr float kPanelMargin = 8.0f;
/// The panel's width in pixels.
inline constexpr float kPanelWidth = 320.0f;

}  // namespace sandtin::editor
