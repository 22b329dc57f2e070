#pragma once
// The sand force model of seed 000 §7.4.1 and seed 004 §5.3.2-5.3.5, in metres and newtons.
//
// With z the height of the tool's lowest point (the device point), δ the contact offset,
// k and μ the stiffness and friction of the material under the tool:
//
//  1. Penetration (seed 004 §5.3.2-5.3.3, "early force"): vertical,
//        F_p = k (h_centre - z + δ)         while h_centre - z > -δ, else 0,
//     so the resistance grows with immersion depth and starts δ before contact.
//  2. Directional resistance (seed 004 §5.3.4-5.3.5, seed 000 Eqs. 7.10-7.11): consecutive
//     control points are joined by "fictitious edges"; for each control point c_i, a 2D ray is
//     cast from the tool centre in the direction u_i towards c_i, the first fictitious edge it
//     crosses gives the terrain height H_i there (linear interpolation between the edge's two
//     end heights), and the material in that direction, m_i = max(0, H_i - z + δ), pushes back
//     along -u_i:
//        F_r = -(μ k / N) Σ_i u_i m_i      (mean over all N control points; seed 000 Eq. 7.8).
//     For a convex ring the ray's first crossing is c_i itself (H_i = h_i); for a concave one
//     a nearer edge can hide c_i.
//     Averaging over the whole ring instead of querying the motion direction is the seeds'
//     anti-jitter fix: at rest the terms balance, so the pen does not vibrate.
//     u_i is measured from the snapshot's centre (where the ring was cast), not from the
//     moving device point: measured from the device point, unit vectors to a ring on flat sand
//     would push the pen away from the ring centre (positive feedback); from the ring centre
//     they balance exactly on flat sand, whatever the pen does between snapshots.
//  3. Gel drag (seed 000 Eq. 7.14): F_G = -c v_xy with c = F_M x 1 frame / 1 application unit
//     = 10 N x 1 ms / 1 m = 0.01 N s/m (the seed's unit domain is our 1 m sandbox).
//  4. Gel minimum (seed 004 §5.3.3): in contact, a total force below 0.2 N is raised to 0.2 N
//     (along the force, or straight up when it is zero).
//  5. Zero out of contact: no control point and not the centre within δ of the surface.
//     Where there is no terrain (outside the snapshot's `terrain`, the TIN's domain) there is
//     no surface: a centre off the terrain gives no penetration force, and a direction whose
//     control point or ray crossing is off the terrain gives no resistance (its m_i is 0, yet
//     it still counts in N). A tool entirely off the terrain gets no force and no contact; one
//     straddling the border feels only the part over the terrain.
//  6. Clamp (seed 000 §7.4: Phantom Omni F_M = 10 N): |F| <= max_force, direction kept.
//
// Interpolation between geometry updates (seed 000 Eq. 7.15) and the stale-snapshot ramp are
// in force_renderer.hpp; this file is the memoryless model.

#include <array>
#include <optional>

#include "geom/vec2.hpp"
#include "geom/vec3.hpp"
#include "haptics/haptic_snapshot.hpp"

namespace sandtin::haptics {

struct ForceModelParams {
    /// δ (m). Seed 004 §5.3.3 starts the force 0.05 application units before contact with a
    /// gain of 10 N per unit, i.e. 0.5 N at the moment of contact. We keep that onset force:
    /// δ = 0.5 N / k_dry = 0.5 / 800 m = 0.625 mm with the dry-sand stiffness of
    /// physics/material.hpp (the seed's own offset, 5 cm on a 1 m sandbox, is wider than the
    /// tool). Seed 000 Eq. 7.9 has the same tolerance T but gives no value.
    double contact_offset = 0.000625;
    /// Seed 004 §5.3.3: minimum force on contact, set experimentally (N).
    double gel_force = 0.2;
    /// Seed 000 Eq. 7.14 with the seeds' unit time step (one 1 kHz frame): N s/m.
    double gel_damping = 0.01;
    /// Seed 000 §7.4 and seed 004 §5.3: the PHANToM's maximum force (N).
    double max_force = 10.0;
};

struct ForceSample {
    Vec3 force;            ///< N, terrain frame
    bool contact = false;  ///< some part of the tool is within δ of the surface
    /// h_centre - z (m): positive when the tool is below the surface; -∞ when the centre is off
    /// the terrain (no surface above or below it).
    double immersion = 0.0;
};

/// What the force loop derives from a snapshot once, when it arrives: the unit direction from
/// the centre to each control point and the ray-cast height H_i in that direction. Evaluating
/// the model is then O(N) per tick.
struct PreparedSnapshot {
    HapticSnapshot snapshot;
    std::array<Vec2, kMaxControlPoints> direction{};  ///< unit u_i; zero for a point at the centre
    std::array<double, kMaxControlPoints> height_along{};  ///< H_i (m)
    /// Whether direction i has terrain: its control point and its ray crossing both on it.
    std::array<bool, kMaxControlPoints> on_terrain{};
    bool centre_on_terrain = false;
};
PreparedSnapshot prepare_snapshot(const HapticSnapshot& snapshot);

/// The seed's "material in a direction" query (seed 004 §5.3.4): the height where a ray from
/// the snapshot centre along `direction` first crosses the control-point ring, interpolated
/// along the crossed edge; nullopt when it crosses none (fewer than two points, zero direction).
std::optional<double> ring_height_along(const HapticSnapshot& snapshot, Vec2 direction);

/// The model of the header comment for a device point at `position` (m) moving at `velocity`
/// (m/s). A snapshot with sequence 0 (none yet) gives zero force. Non-finite inputs give zero.
ForceSample evaluate_force(const PreparedSnapshot& prepared, const Vec3& position,
                           const Vec3& velocity, const ForceModelParams& params);
/// The same, preparing the snapshot on the fly (tests and one-off queries).
ForceSample evaluate_force(const HapticSnapshot& snapshot, const Vec3& position,
                           const Vec3& velocity, const ForceModelParams& params);

/// |v| <= limit, direction kept (limit >= 0). |v| is measured without overflowing, so a huge
/// vector (components beyond 1e154, where |v|² overflows) comes out at exactly `limit`; an
/// infinite component gives `limit` along the infinite components.
Vec3 clamp_magnitude(const Vec3& v, double limit);

}  // namespace sandtin::haptics
