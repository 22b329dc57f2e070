#pragma once
// The Erosion panel's state line, from facts the panel has: whether the erosion runs, whether
// the sand is at rest, and how many distinct vertices its last step left active.

#include <cstddef>
#include <string>

namespace sandtin::editor {

/// "paused" while the erosion does not run (whether the sand would slide is not known until it
/// steps, and the active set then still holds whatever the last edit or load put in it),
/// "at rest", or "sliding, N active".
inline std::string erosion_status_text(bool running, bool at_rest, std::size_t active) {
    if (!running) return "paused";
    if (at_rest) return "at rest";
    return "sliding, " + std::to_string(active) + " active";
}

}  // namespace sandtin::editor
