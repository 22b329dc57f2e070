#pragma once
// The editor's lengths follow the terrain. Its defaults are chosen for the 1 m sandbox; a
// terrain imported from a 200 m elevation model would otherwise get a 4 cm tool, a pour too
// small to see, and a 1 cm relocation radius that refines everything the sand touches into
// centimetre triangles (measured on a flat 100 m terrain: a Ball stroke, a pour and 90 frames of
// erosion turned 20 000 vertices into 204 000, and the editor grew to 3.25 GB). So the settings
// remember the terrain size they were chosen for, and a terrain of another size scales them: a
// tool, a pour or r_S stays the same fraction of any terrain, and the panels' sliders cover the
// same fractions.

#include "editor_settings.hpp"
#include "geom/rect.hpp"

namespace sandtin::editor {

/// The size a terrain's lengths are measured against: the larger side of its domain (metres).
double terrain_size(const Rect& domain);

/// Rescales every length setting (tool radius and depth, stroke spacing, brush height, r_S,
/// simplification tolerance) by k = size / settings.scene_size and the pour volume by k³, then
/// sets scene_size = size. Returns k (exactly 1 when the size is unchanged; nothing else
/// changes then). A scene_size that is not a positive finite number (a hand-edited file) is
/// taken as 1 m, the size the defaults are for. `size` must be positive and finite.
double fit_settings_to_terrain(EditorSettings& settings, double size);

/// A unit to show lengths or volumes in: `metres` (or m³) per unit.
struct DisplayUnit {
    const char* suffix;
    double metres;
};

/// The unit for a length slider whose largest value is `largest` metres: the largest of km, m,
/// cm and mm in which it reads at least 10, else mm. For the 1 m sandbox's sliders this keeps
/// the units they have always had (a 15 cm tool, a 40 mm depth).
DisplayUnit length_unit(double largest);

/// The same for a volume slider (m³, litres, cm³), largest value in m³.
DisplayUnit volume_unit(double largest);

}  // namespace sandtin::editor
