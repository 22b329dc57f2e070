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
/// subsampled evenly to kMaxControlPoints when denser. `terrain` is the TIN's domain; the centre
/// and the control points keep their positions when they lie outside it (the force model gives
/// them no force), with the height at the nearest point of the domain. Material: the vertex of
/// the triangle under the centre (or the nearest point of the domain) with the largest
/// barycentric weight. `hint` speeds up the point locations (the caller's own; the sculpting
/// context's hint is left alone so snapshots never influence edits). Sequence and time are
/// left at 0: ForceLoop::publish sets them.
HapticSnapshot build_snapshot(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                              const MaterialTable& materials, LocateHint* hint = nullptr);

}  // namespace sandtin::haptics
