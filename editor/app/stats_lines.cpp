#include "stats_lines.hpp"

#include <cmath>
#include <cstdio>

namespace sandtin::editor {

namespace {

/// The lines with their numbers already written: fps, then the stages in StageMedians' order.
std::array<std::string, 3> lines_of(const std::array<std::string, 8>& n) {
    return {n[0] + " fps (" + n[1] + " ms)",
            "tool " + n[2] + "  physics " + n[3] + "  mesh " + n[4],
            "upload " + n[5] + "  bake " + n[6] + "  render " + n[7] + " ms"};
}

}  // namespace

std::string capped_number(double value) {
    if (!std::isfinite(value) || value < 0.0) return "-";
    // The bounds are where a format's rounding would add a character: 99.996 written "%.2f"
    // is "100.00", so from there on it is written "%.1f".
    char text[32];
    if (value < 99.995)
        std::snprintf(text, sizeof(text), "%.2f", value);
    else if (value < 999.95)
        std::snprintf(text, sizeof(text), "%.1f", value);
    else if (value < 99999.5)
        std::snprintf(text, sizeof(text), "%.0f", value);
    else
        return ">99999";
    return text;
}

std::array<std::string, 3> stats_timing_lines(const StageMedians& m) {
    const double fps = m.frame > 0.0 ? 1000.0 / m.frame : 0.0;
    return lines_of({capped_number(fps), capped_number(m.frame), capped_number(m.tool),
                     capped_number(m.physics), capped_number(m.mesh), capped_number(m.upload),
                     capped_number(m.bake), capped_number(m.render)});
}

std::array<std::string, 3> widest_stats_timing_lines() {
    // Digits are the widest characters the numbers use ('>' and '.' are narrower in any font
    // the editor draws with), so a number of kCappedNumberChars digits bounds them all.
    const std::string widest(kCappedNumberChars, '0');
    std::array<std::string, 8> n;
    n.fill(widest);
    return lines_of(n);
}

}  // namespace sandtin::editor
