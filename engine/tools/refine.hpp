#pragma once
// Long-edge refinement: splits edges longer than a maximum length near a point at their
// midpoints, on the surface and volume-conserving, so long TIN edges never spoil a stamp or a
// brush (seed 000 §7.2, "prevention of long edges").

#include <cstddef>

#include "tin/tin.hpp"

namespace sandtin {

/// Splits, round after round, every edge longer than `max_length` among the faces meeting the
/// disc (centre, radius), until none is left or `max_insertions` points were inserted.
/// Returns the number of vertices inserted.
std::size_t refine_long_edges(Tin& tin, Vec2 centre, double radius, double max_length,
                              LocateHint* hint = nullptr, std::size_t max_insertions = 200000,
                              EditReport* report = nullptr);

}  // namespace sandtin
