#include "terrain_scale.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace sandtin::editor {

double terrain_size(const Rect& domain) {
    return std::max(domain.width(), domain.height());
}

double fit_settings_to_terrain(EditorSettings& s, double size) {
    if (!(s.scene_size > 0.0) || !std::isfinite(s.scene_size)) s.scene_size = 1.0;
    if (size == s.scene_size) return 1.0;
    const double k = size / s.scene_size;
    // (The stroke spacing is a fraction of the tool's radius, so it follows the tool.)
    for (double* length : {&s.tool_radius, &s.tool_depth, &s.brush_strength, &s.relocation_radius,
                           &s.simplify_tolerance})
        *length *= k;
    s.pour_volume *= k * k * k;
    s.scene_size = size;
    return k;
}

namespace {

DisplayUnit pick(std::span<const DisplayUnit> largest_first, double largest) {
    for (const DisplayUnit& u : largest_first) {
        if (std::abs(largest) / u.metres >= 10.0) return u;
    }
    return largest_first.back();
}

}  // namespace

DisplayUnit length_unit(double largest) {
    static constexpr DisplayUnit kUnits[] = {{"km", 1e3}, {"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}};
    return pick(kUnits, largest);
}

DisplayUnit volume_unit(double largest) {
    static constexpr DisplayUnit kUnits[] = {{"m3", 1.0}, {"L", 1e-3}, {"cm3", 1e-6}};
    return pick(kUnits, largest);
}

}  // namespace sandtin::editor
