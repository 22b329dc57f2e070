#pragma once
// Moisture in the sand spreads into dry sand and dries (issue 40, item 4). Each vertex of the
// TIN holds a saturation m in [0, 1] (VertexArrays::moisture, a float); the material turns it
// into an angle of repose (physics/material.hpp). Over `seconds` of time with no water:
//
//   dm_i/dt = (1 / A_i) sum_j D w_ij (m_j - m_i)  -  (ln 2 / T) m_i
//
// with A_i the vertex's lumped area (a third of its triangles' areas), D the diffusivity (m²/s),
// T the drying half-life (s), and w_ij the edge's cotangent weight: its dual (Voronoi) edge
// length over its length, 1/2 (cot alpha + cot beta) with alpha, beta the angles opposite the
// edge in its two triangles (one at the domain's border), in the plane (x, y) as the lumped
// areas are. A weight below zero (an edge whose opposite angles sum beyond 180 degrees: a
// non-Delaunay edge, which constraints make) is taken as 0, as the water's pipes do
// (virtual_pipes.hpp): it would otherwise carry moisture from the drier end to the wetter.
// The domain's border is closed (no moisture leaves through it).
//
// Scheme, per sub-step of dt seconds:
//  1. spreading (explicit Euler): each edge moves D w_ij (m_j - m_i) dt of A m from one end to
//     the other, computed once per edge and added to one end and taken from the other, so
//     sum_i A_i m_i is conserved to rounding (1e-12 relative over thousands of sub-steps);
//  2. drying: m <- m 2^(-dt / T), the exact exponential decay over dt (the same factor for every
//     vertex, so it commutes with step 1: with a uniform half-life, splitting them costs
//     nothing). With drying, moisture below kNegligibleMoisture at the end of the call is
//     written as dry (0), and the call stops as soon as all of it is below: the terrain dries
//     out completely in a finite time, and then costs nothing. (Only at the end: cleared
//     every sub-step, the thin front of spreading moisture would be a sink.)
// Sub-steps: a vertex's stability bound is 0.5 A_i / (D sum_j w_ij); under it the scheme is
// stable and each new m_i a convex combination of the old ones (the weight of m_i itself at
// least 1/2), so moisture never leaves [min, max] of what it was (never below 0 nor above 1)
// and does not oscillate. On a regular mesh of edge length h it is about h² / (8 D): 2 minutes
// at h = 1 cm, 1.25 s at 1 mm with the default D. A TIN's smallest cells ask for far less: on
// random points (the scripts' terrains, the default scene) the smallest bound is 1/5000 of
// the median one, the 1st percentile 1/35 (measured on 4 000 and 40 000 points). So the
// sub-step is the bound of the vertex at 1 % from the stiffest among those computed (on fewer
// than 100 vertices, the stiffest's), but never below 1/64 of the median vertex's (so that a
// few slivers among a few wet vertices cannot stall a call), and the `seconds` are split into
// ceil(seconds / that) equal sub-steps; it is worked out again when the set of vertices
// computed grows. The vertices whose own bound is shorter (the stiffest 1 %, or more where
// slivers crowd) have their exchanges slowed by bound / dt (an edge by the smaller slowing of
// its ends): they then take at most half the way to their neighbours' moisture in a sub-step
// instead of all of it in less than one. Conservation and the bound on the range are
// untouched (each exchange still leaves one end and enters the other; each m_i still keeps at
// least half its weight); what they change is how fast moisture crosses cells whose own time
// is shorter than a sub-step. The report counts them.
//
// What it touches: one read-only pass over the moisture array finds the wet vertices (a
// terrain without moisture returns after it, writing nothing). Only wet vertices and the
// vertices next to them are computed: a vertex at least kNegligibleMoisture wet takes in its
// neighbours, so the set grows by at most one ring of vertices per sub-step, and only as far as
// the moisture really reaches; an edge between two vertices wetter than 0 but both below the
// threshold exchanges nothing. The state is kept in double for the whole call and written
// back once, as floats, and only where the float changed (Tin::set_moisture, journaled, so
// undo, the GPU mirror and the relaxation see it): a step that changes nothing writes nothing.
//
// Units: metres, seconds; moisture is a saturation (dimensionless), so sum A m is in m².

#include <cstddef>
#include <limits>
#include <vector>

#include "tin/ids.hpp"

namespace sandtin {

class Tin;

/// Moisture below this saturation does not spread into dry neighbours, and when drying it is
/// dry (0) at the end of the call. At it, sand stands 3e-4 degrees steeper than dry sand with the
/// presets' moisture response (12 degrees x m / 0.04, physics/material.hpp): dry for every purpose.
inline constexpr double kNegligibleMoisture = 1e-6;

struct MoistureSettings {
    /// D, m²/s: how fast moisture spreads into drier sand, >= 0 (0: it does not spread). The
    /// rms distance moisture spreads in time t is sqrt(4 D t): with 1e-7, 1.5 cm in ten
    /// minutes, 4 cm in an hour, 9 cm in six hours: "centimetres over minutes to hours", as
    /// water wicks sideways into dry sand beside a wet patch. Soil-water diffusivities of sands
    /// span roughly 1e-8 to 1e-4 m²/s, rising steeply with the saturation; 1e-7 is near the low
    /// end, where the pendular moisture that holds sand together lies. A constant stands for
    /// that curve.
    double diffusivity = 1e-7;
    /// T, s: the time in which moisture halves by drying, > 0 (+infinity: no drying). Four
    /// hours: a surface layer d deep of porosity phi holds phi d of water at saturation, and
    /// evaporation at E takes it at first at the rate ln 2 phi d / T of the exponential, so
    /// T = ln 2 phi d / E. With phi = 0.4, d = 5 mm to 1 cm (the skin of sand whose moisture
    /// holds a wall's face) and E = 0.25 to 0.5 mm an hour (a sunny day's 3 to 6 mm of
    /// evaporation over its daylight), T is 3 to 11 hours; four is near the short end.
    double drying_half_life = 4.0 * 3600.0;
};

struct MoistureReport {
    double seconds = 0.0;
    std::size_t sub_steps = 0;
    std::size_t vertices_computed = 0;  ///< wet vertices and the neighbours they reached
    std::size_t vertices_changed = 0;   ///< moisture written (each one journal entry)
    /// Most vertices whose exchanges a sub-step slowed (their own bound below the sub-step).
    std::size_t vertices_slowed = 0;
    /// sum A_i m_i (m²) of the terrain's moisture before and after, and of the double-precision
    /// result before it was written as floats (without drying, equal to `before` to rounding;
    /// `after` differs from it by the float rounding, at most 2^-24 of it, and with drying by
    /// the moisture below kNegligibleMoisture cleared, at most 1e-6 x its vertices' area).
    double total_before = 0.0;
    double total_after = 0.0;
    double total_computed = 0.0;
    /// The wettest vertex afterwards (the lowest id among equals); invalid when all is dry.
    VertexId wettest;
    float wettest_moisture = 0.0f;
};

/// The sub-step's rule (above), from the ratios A_i / sum_j w_ij of the vertices with edges:
/// the ratio at 1 % from the stiffest, but at least 1/64 of the median's (the sub-step is
/// 0.5 ratio / D); +inf when there are none. Reorders `ratios`. Shared with the GPU's
/// moisture (gpu/gpu_moisture.hpp).
double moisture_step_ratio(std::vector<double>& ratios);

/// Lets `seconds` of time pass over the terrain's moisture with no water on it: moisture
/// spreads into drier sand and dries, as above. Throws std::invalid_argument naming the value
/// ("seconds", "diffusivity", "drying_half_life") when seconds or the diffusivity is negative
/// or not finite, or the half-life is not > 0 (NaN included); the TIN is then untouched.
MoistureReport spread_and_dry_moisture(Tin& tin, double seconds,
                                       const MoistureSettings& settings = {});

}  // namespace sandtin
