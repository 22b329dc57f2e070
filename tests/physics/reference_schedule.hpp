#pragma once
// What the two schedules' references (jacobi_schedule_test, sequential_schedule_test) define
// alike, from the definitions and not from TalusSolver: a vertex's levelling share, its outflow
// into one array over all the graph's slots (the plain edge kernel, or the face rule's own kernel,
// which has no second implementation), the active set's update after an iteration, and the
// scene they relax.

#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "physics/adjacency_graph.hpp"
#include "physics/face_kernel.hpp"
#include "physics/talus_solver.hpp"
#include "reference_talus_kernel.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

/// The share of its levelling volumes vertex i sends in `iteration`: the schedule's (each
/// edge levelled whole in the sequential schedule, damping of it in the Jacobi schedule,
/// physics/talus_kernel.hpp) times the jitter (1 without randomness).
inline double reference_share(const TalusSettings& s, std::uint32_t i, std::uint64_t iteration) {
    const double sigma = s.schedule == Schedule::Sequential ? 1.0 : s.parameters.damping;
    return s.randomness > 0.0
               ? sigma * (1.0 + s.randomness * signed_unit_hash(s.seed, i, iteration))
               : sigma;
}

/// Vertex i's outflow under the settings' rule: q[k] (m³) for every slot k of its row, in an
/// array over all the graph's slots, and their total; split requests go to `splits`.
inline double reference_outflow(const TalusSettings& s, const AdjacencyGraph& g,
                                const TalusArrays& a, std::uint32_t i, double share, double* q,
                                std::vector<std::uint32_t>& splits) {
    auto split = [&](std::uint32_t v) { splits.push_back(v); };
    if (s.parameters.rule == SlopeRule::Face)
        return face_outflow(i, g.offset(i), g.degree(i), g.targets().data(), g.lengths().data(),
                            g.face_rows(), g.longest_edges().data(), a.height, a.area, a.bedrock,
                            a.tan_alpha[i], s.parameters, share, q, split);
    return reference_talus_outflow(i, g.offset(i), g.degree(i), g.targets().data(),
                                   g.lengths().data(), g.longest_edges().data(), a.height, a.area,
                                   a.bedrock, a.tan_alpha[i], s.parameters, share, q, split);
}

/// After an iteration: vertices that did not change count a quiet iteration (ActiveSet::age),
/// and the changed ones and their neighbours are active again.
inline void age_and_wake(const AdjacencyGraph& g, ActiveSet& active,
                         std::span<const std::uint8_t> changed_flag,
                         std::span<const std::uint32_t> changed, int quiet_iterations) {
    active.age(changed_flag, quiet_iterations);
    for (std::uint32_t v : changed) {
        active.activate(v);
        for (std::uint32_t k = g.offset(v); k < g.offset(v) + g.degree(v); ++k)
            active.activate(g.targets()[k]);
    }
}

/// What the schedule tests relax, per vertex id: heights `base(position)` plus up to `noise`
/// metres of random sand, far steeper than repose; with `with_bedrock`, bedrock at the surface
/// under 30 % of the vertices and up to 1 cm below it elsewhere (else 1e9 m below); tan(alpha)
/// in [0.5, 0.8).
struct ScheduleScene {
    std::vector<double> height, bedrock, tan_alpha;
};

template <class Base>
ScheduleScene schedule_scene(const VertexArrays& va, Base base, double noise, bool with_bedrock,
                             std::mt19937_64& rng) {
    const std::size_t n = va.size();
    std::uniform_real_distribution<double> u(0.0, 1.0);
    ScheduleScene scene{std::vector<double>(n), std::vector<double>(n, -1e9),
                        std::vector<double>(n)};
    for (std::size_t v = 0; v < n; ++v) {
        scene.height[v] = base(va.position[v]) + noise * u(rng);
        if (with_bedrock) scene.bedrock[v] = scene.height[v] - (u(rng) < 0.3 ? 0.0 : 0.01 * u(rng));
        scene.tan_alpha[v] = 0.5 + 0.3 * u(rng);
    }
    return scene;
}

}  // namespace sandtin::test
