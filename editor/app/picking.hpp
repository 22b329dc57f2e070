#pragma once
// Where a view ray first meets the terrain surface. The ray is marched in steps no longer than
// `step` metres (so it cannot jump over a ridge wider than that) and the crossing is refined
// by bisection to 1e-7 of the step.

#include <optional>

#include "camera.hpp"
#include "tin/tin.hpp"

namespace sandtin::editor {

struct Pick {
    Vec3 point;  ///< metres, in the TIN's coordinates
    double distance = 0.0;
};

/// `offset` is subtracted from TIN coordinates to get the ray's (render) coordinates.
std::optional<Pick> pick_terrain(const Tin& tin, const Ray& ray, Vec2 offset, double step,
                                 double max_distance);

}  // namespace sandtin::editor
