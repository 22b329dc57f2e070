#include "stress/terrain_invariants.hpp"

#include <cmath>

namespace sandtin {

std::optional<InvariantViolation> check_terrain_invariants(const Tin& tin,
                                                           Generation next_generation,
                                                           const InvariantLimits& limits,
                                                           TriangulationCheck triangulation) {
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t i = 0; i < tin.vertex_capacity(); ++i) {
        if (!tin.is_alive(VertexId{i})) continue;
        const bool finite = std::isfinite(va.position[i].x) && std::isfinite(va.position[i].y) &&
                            std::isfinite(va.height[i]) && std::isfinite(va.bedrock[i]) &&
                            std::isfinite(va.moisture[i]) && std::isfinite(va.slide[i].x) &&
                            std::isfinite(va.slide[i].y) && std::isfinite(va.lumped_area[i]);
        if (!finite) {
            return InvariantViolation{
                "finite", "vertex " + std::to_string(i) + " has a NaN or Inf attribute"};
        }
        if (va.bedrock[i] > va.height[i]) {
            return InvariantViolation{"bedrock", "vertex " + std::to_string(i) + " has its sand " +
                                                     std::to_string(va.height[i] - va.bedrock[i]) +
                                                     " m thick: bedrock is exposed"};
        }
        if (!(va.moisture[i] >= 0.0f && va.moisture[i] <= 1.0f) ||
            !(va.slide[i].x >= 0.0f && va.slide[i].x < 1.0f && va.slide[i].y >= 0.0f &&
              va.slide[i].y < 1.0f)) {
            return InvariantViolation{"range", "vertex " + std::to_string(i) +
                                                   " has moisture or texture slide out of range"};
        }
    }
    if (triangulation == TriangulationCheck::full) {
        if (const ValidationReport v = tin.check_valid(); !v.ok())
            return InvariantViolation{"valid", v.summary()};
    }
    // Generation 0 is the terrain before the first stamp: the first stamp's fences
    // (Tin::fence_bent_edges) guard it, one generation older than the stamp. The newest
    // generation alone decides; the constraint is looked up only to name it.
    if (const auto newest = tin.newest_constraint_generation();
        newest && *newest >= next_generation) {
        for (const ConstraintInfo& c : tin.constraints()) {
            if (c.generation < next_generation) continue;
            return InvariantViolation{
                "generations", "constraint " + std::to_string(c.id.value) + " has generation " +
                                   std::to_string(c.generation) + ", but only 0.." +
                                   std::to_string(next_generation - 1) + " were handed out"};
        }
    }
    if (limits.max_vertices != 0 && tin.vertex_count() > limits.max_vertices) {
        return InvariantViolation{"bounded", std::to_string(tin.vertex_count()) +
                                                 " vertices exceed the bound of " +
                                                 std::to_string(limits.max_vertices)};
    }
    // Ids are recycled, so the arrays indexed by id stay within a small multiple of the live
    // count (the ids freed by the last edit wait for the journal to report them).
    if (limits.max_vertices != 0 && tin.vertex_capacity() > 2 * limits.max_vertices) {
        return InvariantViolation{"bounded", "vertex arrays grew to " +
                                                 std::to_string(tin.vertex_capacity()) +
                                                 " ids: freed ids are not being recycled"};
    }
    if (limits.max_constraints != 0 && tin.constraint_count() > limits.max_constraints) {
        return InvariantViolation{"bounded", std::to_string(tin.constraint_count()) +
                                                 " constraints exceed the bound of " +
                                                 std::to_string(limits.max_constraints)};
    }
    return std::nullopt;
}

}  // namespace sandtin
