#pragma once
// Curvature-driven weathering (seed 001, §9.1–9.3; issue 40 item 5): convex features wear
// down and their sand settles into the concave ones, so crests round off and hollows fill, as
// wind and rain round a dune or a sandcastle's edges over time.
//
// One iteration over a set of vertices, from the heights before it (Jacobi):
//  1. Curvature: the mean curvature H of each vertex's star (physics/mean_curvature.hpp).
//     Border vertices have no full star and are not weathered.
//  2. Normalisation (seed eq. 9.1): c = H / H_n with H_n the largest |H| in the set, so the
//     sharpest feature weathers fastest; but H_n is at least kNearlyFlat / e_avg, where e_avg
//     is the set's mean edge length. The seed does not rescale "scenes with almost no
//     curvature"; measuring the bend per edge (H e_avg) makes that rule independent of scale.
//  3. Wear (seed eqs. 9.3, 9.5): a vertex with c > 0 loses d = w strength c^power e_avg / 10,
//     the seed's largest step of a tenth of the mean edge, times the vertex's weight w in
//     [0, 1] (a brush's falloff).
//  4. Where the sand goes. The seed moves vertices along the umbrella Laplacian, which neither
//     keeps the volume nor respects a bedrock. Here the worn volume A_i d leaves vertex i for
//     its lower neighbours, in proportion to the drop to each times (1 + its concavity), so
//     it runs downhill and gathers in the hollows; each share raises its receiver by
//     share / A_j. Every share leaves one vertex and enters another, so sum(A h) is kept to
//     rounding (A: the lumped areas of tin/vertex_arrays.hpp).
// Limits, so one iteration never inverts a slope: d never takes a vertex below its bedrock,
// and d plus any receiver's rise stays within half the drop between them. A vertex with no
// lower neighbour keeps its sand. A plane (|H| e_avg below rounding) is left bit for bit.
// The material and moisture of each vertex stay as they are. Units: metres.

#include <cstddef>
#include <span>

#include "tin/tin.hpp"

namespace sandtin {

struct WeatheringSettings {
    /// Fraction in [0, 1] of the seed's largest step (a tenth of the mean edge length), taken
    /// at the most curved vertex per iteration.
    double strength = 1.0;
    /// The seed's power modifier n >= 1 (eq. 9.5): larger values spare gentle curves and
    /// wear only the sharpest features.
    double power = 1.0;
};

/// H e_avg below which a set counts as nearly flat (step 2): its curvature is not stretched
/// to full strength.
inline constexpr double kNearlyFlat = 0.01;

struct WeatheringReport {
    std::size_t vertices_worn = 0;    ///< lost sand this iteration
    std::size_t vertices_raised = 0;  ///< received sand
    double volume_moved = 0.0;        ///< m³ worn off and laid down elsewhere
    double deepest_wear = 0.0;        ///< m, the largest d
    double mean_edge = 0.0;           ///< e_avg (m)
    double largest_curvature = 0.0;   ///< max |H| in the set (1/m)

    WeatheringReport& operator+=(const WeatheringReport& r);
};

/// One iteration of weathering over `vertices`, vertex k weighted by weight[k] in [0, 1]
/// (empty: all 1). Dead ids are skipped; neighbours outside the set receive sand but do not
/// wear. Writes the heights through Tin::set_heights, so the journal, undo and the GPU mirror
/// see them. Throws std::invalid_argument for settings out of range, a weight outside [0, 1]
/// or spans of different sizes.
WeatheringReport weather_vertices(Tin& tin, std::span<const VertexId> vertices,
                                  std::span<const double> weight,
                                  const WeatheringSettings& settings);

/// `iterations` iterations over every live vertex of `tin`.
WeatheringReport weather_terrain(Tin& tin, int iterations, const WeatheringSettings& settings);

}  // namespace sandtin
