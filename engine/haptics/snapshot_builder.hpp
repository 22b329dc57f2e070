#pragma once
// Fills a HapticSnapshot from the terrain in a consistent state (seed 004 §5.3.1: the main
// thread refreshes the buffer whenever its structures are consistent): the tool's outer
// contour O placed at the device (the seeds' control points), the interpolated terrain heights
// under them and under the centre, and the material there.

#include "haptics/haptic_snapshot.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"
#include "tools/tool.hpp"

namespace sandtin::haptics {

/// Control points: the outer contour of `tool` at `at` (centre and heading; bottom unused),
/// subsampled evenly to kMaxControlPoints when denser. Points outside the domain are clamped
/// into it. Material: the vertex of the triangle under the centre with the largest
/// barycentric weight. `hint` speeds up the point locations (the caller's own; the sculpting
/// context's hint is left alone so snapshots never influence edits). Sequence and time are
/// left at 0: ForceLoop::publish sets them.
HapticSnapshot build_snapshot(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                              const MaterialTable& materials, LocateHint* hint = nullptr);

}  // namespace sandtin::haptics
