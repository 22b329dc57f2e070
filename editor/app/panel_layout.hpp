#pragma once
// Where the editor's main panel sits: a fixed-width column at the window's left edge, with the
// status line's window below it. The panels draw it there, and the camera frames the terrain
// in what it leaves free.

#include "camera.hpp"

namespace sandtin::editor {

/// Pixels between the panel and the window's edges.
inline constexpr float kPanelMargin = 8.0f;
/// The panel's width in pixels.
inline constexpr float kPanelWidth = 320.0f;

/// The part of a width x height window the panel leaves free: right of it, the full height
/// (the panel is semi-transparent and as tall as its open sections, up to the whole window).
inline PixelRect free_viewport(double width, double height) {
    return {static_cast<double>(2.0f * kPanelMargin + kPanelWidth), 0.0, width, height};
}

}  // namespace sandtin::editor
