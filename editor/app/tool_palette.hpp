#pragma once
// The editor's tool palette: the stamp tools from assets/tools, the sand pour and the brushes,
// in the order of the number keys 1..9, 0.

#include "tools/brushes.hpp"

namespace sandtin::editor {

enum class ToolKind { Stamp, Brush, Pour, Remove };

struct ToolEntry {
    const char* label;
    ToolKind kind;
    const char* asset;  ///< Stamp: assets/tools/<asset>.json
    BrushKind brush;
    const char* help;
};

inline constexpr ToolEntry kTools[] = {
    {"Circle", ToolKind::Stamp, "circle", BrushKind::Raise,
     "Flat round tool pressed along the stroke (key 1)"},
    {"Ball", ToolKind::Stamp, "ball", BrushKind::Raise, "Half-sphere: a rounded groove (key 2)"},
    {"Box", ToolKind::Stamp, "box", BrushKind::Raise, "Rectangular trowel (key 3)"},
    {"Rake", ToolKind::Stamp, "rake", BrushKind::Raise,
     "Rake with tines from a heightfield (key 4)"},
    {"Lambda", ToolKind::Stamp, "lambda", BrushKind::Raise,
     "Non-convex letter-shaped stamp (key 5)"},
    {"Pour", ToolKind::Pour, nullptr, BrushKind::Raise, "Pour sand: hold to keep pouring (key 6)"},
    {"Remove", ToolKind::Remove, nullptr, BrushKind::Raise,
     "Scoop sand away, never below bedrock (key 7)"},
    {"Raise", ToolKind::Brush, nullptr, BrushKind::Raise, "Brush: raise the surface (key 8)"},
    {"Smooth", ToolKind::Brush, nullptr, BrushKind::Smooth, "Brush: smooth bumps (key 9)"},
    {"Paint", ToolKind::Brush, nullptr, BrushKind::PaintMaterial,
     "Brush: paint the selected material (key 0)"},
};
inline constexpr int kToolCount = static_cast<int>(std::size(kTools));

}  // namespace sandtin::editor
