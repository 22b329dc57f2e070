#pragma once
// What the simulation hands to the force loop after each consistent state (seed 004 §5.3.1,
// the "buffer"; seed 000 §7.4, the "stable state"): the tool's control-point ring with the
// terrain heights under it, the terrain height under the tool centre, and the material there.
//
// Units: metres for positions and heights (terrain frame: x east, y north, z up), N/m for
// stiffness, nanoseconds of the monotonic clock for times.
//
// Trivially copyable with a fixed capacity, so publishing it through the lock-free triple
// buffer is a plain copy and the force loop never allocates.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin::haptics {

/// Upper bound on the control points the force loop averages over. Seed 004 §5.4.2 tests a
/// 12-point circle; denser outer contours are subsampled evenly to this many.
inline constexpr std::size_t kMaxControlPoints = 64;

struct HapticSnapshot {
    /// Increases by one per publication; 0 means "no snapshot yet".
    std::uint64_t sequence = 0;
    /// Monotonic-clock time of publication (ns); the loop measures staleness against it.
    std::int64_t published_ns = 0;
    /// Where there is terrain (m): the domain of the TIN. Outside it there is nothing to touch:
    /// a centre or a control point outside gives no force (force_model.hpp). The default, the
    /// whole plane, is for snapshots made by hand.
    Rect terrain{
        {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()},
        {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}};
    /// Tool centre when the snapshot was taken (m), where the device is, on the terrain or not.
    /// Directions of the control-point ring are measured from here (see force_model.hpp).
    Vec2 centre;
    /// Terrain height under the tool centre (m). For a centre off the terrain, the height at
    /// the nearest point of the terrain (so the value stays meaningful); the model ignores it.
    double centre_height = 0.0;
    /// Control points of the tool's outer contour, in order around the ring (m), and the
    /// interpolated terrain heights under them (m). A point off the terrain keeps its position
    /// and carries the height at the nearest point of the terrain: the model gives it no force,
    /// and uses that height only to interpolate ring crossings that lie on the terrain.
    std::uint32_t control_count = 0;
    std::array<Vec2, kMaxControlPoints> control{};
    std::array<double, kMaxControlPoints> control_height{};
    /// Material under the tool centre (physics/material.hpp): penetration stiffness (N/m) and
    /// the dimensionless friction that scales the directional resistance.
    double stiffness = 800.0;
    double friction = 0.55;
};

}  // namespace sandtin::haptics
