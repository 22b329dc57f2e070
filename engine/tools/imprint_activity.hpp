#pragma once
// Where a stamp would move sand: the parts of the inner contour I (and of its interior) where
// the terrain stands off the tool's imprint. A stamp whose imprint the terrain already holds
// changes nothing, so re-working a trail adds no vertices or constraints.
//
// The test is three-dimensional. A point of I whose terrain stands off vertically by more
// than the tolerance, but where a `lateral` distance further in the terrain is at least
// halfway down to the imprint, is a wall the contour grazes, not sand to move (fresh sand
// stands off as much a little further in). On a steep wall a vertical test alone would call
// every micrometre of lateral offset between stamps (polygon scallops, a path that does not
// repeat exactly) active.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

/// The height the tool leaves at p (m) over terrain at height `terrain` (m).
using ImprintHeight = std::function<double(Vec2 p, double terrain)>;

struct ImprintActivity {
    std::vector<std::uint8_t> inner_active;  ///< per segment i of I (from point i to i + 1)
    bool any_segment = false;
};

/// Tests each segment of the closed inner contour `inner` (counter-clockwise or clockwise) at
/// the terrain's section points. `tolerance` and `lateral` in metres.
ImprintActivity inner_contour_activity(const Tin& tin, std::span<const Vec2> inner,
                                       const ImprintHeight& imprint, double tolerance,
                                       double lateral, LocateHint* hint);

/// Whether a vertex inside `inner` (within the disc of `radius` m around `centre`) stands off
/// the imprint by more than `tolerance`, farther than `lateral` from the contour.
bool interior_stands_off(const Tin& tin, std::span<const Vec2> inner, const ImprintHeight& imprint,
                         double tolerance, double lateral, Vec2 centre, double radius,
                         LocateHint* hint);

}  // namespace sandtin
