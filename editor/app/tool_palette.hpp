#pragma once
// The editor's tool palette: the stamp tools from assets/tools, the sand pour and removal, and
// the brushes, each with the key that picks it.

#include <optional>
#include <string_view>

#include "tools/brushes.hpp"
#include "tools/tool.hpp"

namespace sandtin::editor {

enum class ToolKind { Stamp, Brush, Pour, Remove, Water, Rain };

struct ToolEntry {
    const char* label;
    ToolKind kind;
    const char* asset;  ///< Stamp: assets/tools/<asset>.json
    BrushKind brush;    ///< Brush: which one
    /// The key that picks the tool: a digit or an upper-case letter, which is also its GLFW
    /// key code. Stamps and sand have digits; brushes the letter of their name (T: flatTen,
    /// since F frames the terrain).
    char key;
    const char* help;
};

inline constexpr ToolEntry kTools[] = {
    {"Circle", ToolKind::Stamp, "circle", BrushKind::Raise, '1',
     "Flat round tool pressed along the stroke (key 1)"},
    {"Ball", ToolKind::Stamp, "ball", BrushKind::Raise, '2',
     "Half-sphere: a rounded groove (key 2)"},
    {"Box", ToolKind::Stamp, "box", BrushKind::Raise, '3', "Rectangular trowel (key 3)"},
    {"Rake", ToolKind::Stamp, "rake", BrushKind::Raise, '4',
     "Rake with tines from a heightfield (key 4)"},
    {"Lambda", ToolKind::Stamp, "lambda", BrushKind::Raise, '5',
     "Non-convex letter-shaped stamp (key 5)"},
    {"Foot", ToolKind::Stamp, "foot", BrushKind::Raise, '6',
     "Footprint: the imprint of a shoe sole mesh seen from below (key 6)"},
    {"Pour", ToolKind::Pour, nullptr, BrushKind::Raise, '7',
     "Pour sand: hold to keep pouring (key 7)"},
    {"Remove", ToolKind::Remove, nullptr, BrushKind::Raise, '8',
     "Scoop sand away, never below bedrock (key 8)"},
    {"Water", ToolKind::Water, nullptr, BrushKind::Raise, '9',
     "Water from a nozzle under the cursor while held, at the Tools panel's Flow (key 9)"},
    {"Rain", ToolKind::Rain, nullptr, BrushKind::Raise, '0',
     "Rain on a disc of the Size under the cursor while held, at the Tools panel's rate (key 0)"},
    {"Raise", ToolKind::Brush, nullptr, BrushKind::Raise, 'R', "Brush: raise the surface (key R)"},
    {"Lower", ToolKind::Brush, nullptr, BrushKind::Lower, 'L', "Brush: lower the surface (key L)"},
    {"Smooth", ToolKind::Brush, nullptr, BrushKind::Smooth, 'S', "Brush: smooth bumps (key S)"},
    {"Flatten", ToolKind::Brush, nullptr, BrushKind::Flatten, 'T',
     "Brush: level the surface to its height where the stroke began (key T)"},
    {"Weather", ToolKind::Brush, nullptr, BrushKind::Weather, 'W',
     "Brush: weather the sand, rounding crests and filling hollows with their sand (key W)"},
    {"Paint", ToolKind::Brush, nullptr, BrushKind::PaintMaterial, 'P',
     "Brush: paint the selected material (key P)"},
};
inline constexpr int kToolCount = static_cast<int>(std::size(kTools));

/// Whether the Size slider sets a stamp's radius: only for round contours (the circle and the
/// ball); the others (box, rake, letter, foot) keep their asset's shape and size.
inline bool sized_by_slider(const ToolSpec& stamp) {
    return stamp.contour == ContourKind::Circle;
}

/// Which of the Tools panel's shared sliders act on a tool, so the panel shows only those.
struct ToolSliders {
    bool size = false;   ///< the radius of brushes, the pour and round stamps (not the nozzle)
    bool depth = false;  ///< how deep a stamp presses; the haptic pen's tip depth for any tool
};

/// `round_stamp`: a stamp whose asset sized_by_slider(); `haptics`: the pen is connected.
constexpr ToolSliders sliders_for(const ToolEntry& t, bool round_stamp, bool haptics) {
    const bool stamp = t.kind == ToolKind::Stamp;
    return {(!stamp && t.kind != ToolKind::Water) || round_stamp, stamp || haptics};
}

/// The tool a key picks (digits and upper-case letters, as GLFW's key codes), if any.
constexpr std::optional<int> tool_for_key(int key) {
    for (int i = 0; i < kToolCount; ++i) {
        if (kTools[i].key == key) return i;
    }
    return std::nullopt;
}

/// The tool with this label, if any.
constexpr std::optional<int> tool_named(std::string_view label) {
    for (int i = 0; i < kToolCount; ++i) {
        if (label == kTools[i].label) return i;
    }
    return std::nullopt;
}

}  // namespace sandtin::editor
