#include "physics/settle_by_projection.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/project_out_of_repose.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {

ProjectionInput gather_projection_input(const Tin& tin, const MaterialTable& materials,
                                        std::span<const VertexId> region) {
    const VertexArrays& va = tin.vertices();
    const std::size_t n = va.size();
    ProjectionInput in;
    in.position = va.position;
    in.area = va.lumped_area;
    in.height = va.height;
    in.alive = va.alive;
    in.bedrock.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        in.bedrock[v] = va.bedrock[v] > 0.5 * kNoBedrock ? va.bedrock[v]
                                                         : -std::numeric_limits<double>::infinity();
    }
    if (!region.empty()) {
        in.held.assign(n, 1);
        for (VertexId v : region) {
            if (!tin.is_alive(v))
                throw std::invalid_argument("settle by projection: vertex " +
                                            std::to_string(v.value) + " is not alive");
            in.held[v.value] = 0;
        }
    }
    // Each vertex's tan(alpha) once (a material lookup and a blend), not once per corner.
    std::vector<double> vertex_tan(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        if (va.alive[v])
            vertex_tan[v] =
                materials.at(va.material[v]).talus_slope(static_cast<double>(va.moisture[v]));
    }
    in.faces.reserve(tin.triangle_count());
    in.face_tan_alpha.reserve(tin.triangle_count());
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        in.faces.push_back({t[0].value, t[1].value, t[2].value});
        in.face_tan_alpha.push_back(
            (vertex_tan[t[0].value] + vertex_tan[t[1].value] + vertex_tan[t[2].value]) / 3.0);
    }
    return in;
}

ProjectionSettleReport apply_projection(Tin& tin, const ProjectionInput& input,
                                        const ReposeProjection& projected) {
    const VertexArrays& va = tin.vertices();
    const std::size_t n = va.size();
    // The whole terrain is compared (O(n), a small part of a projection's cost): heights
    // projected from another surface would put sand where there is none, or take it away.
    bool same = n == input.height.size() && projected.height.size() == n &&
                tin.triangle_count() == input.faces.size();
    for (std::size_t v = 0; same && v < n; ++v) {
        same = va.alive[v] == input.alive[v] &&
               (!va.alive[v] ||
                (va.height[v] == input.height[v] && va.position[v] == input.position[v]));
    }
    if (!same)
        throw std::runtime_error(
            "settle by projection: the terrain changed while it was projected; nothing was "
            "applied");
    ProjectionSettleReport report;
    report.iterations = projected.iterations;
    report.converged = projected.converged;
    report.free_vertices = projected.free_vertices;
    report.degenerate_faces = projected.degenerate_faces;
    report.steepest_ratio = projected.steepest_ratio;
    report.volume_change = projected.volume_change;
    std::vector<VertexId> moved;
    std::vector<double> heights;
    for (std::size_t v = 0; v < n; ++v) {
        if (va.alive[v] && projected.height[v] != va.height[v]) {
            moved.push_back(VertexId{static_cast<std::uint32_t>(v)});
            heights.push_back(projected.height[v]);
        }
    }
    tin.set_heights(moved, heights);
    report.moved_vertices = moved.size();
    return report;
}

ProjectionSettleReport settle_by_projection(Tin& tin, const MaterialTable& materials,
                                            std::span<const VertexId> region,
                                            const ReposeProjectionOptions& options) {
    const ProjectionInput input = gather_projection_input(tin, materials, region);
    // The whole terrain: only where it is out of repose, which gives the same surface.
    OutOfReposeReport local;
    ProjectionSettleReport report =
        apply_projection(tin, input,
                         region.empty() ? project_out_of_repose(input, options, {}, &local)
                                        : project_onto_repose(input.problem(), options));
    report.steep_faces = local.steep_faces;
    report.rounds = region.empty() ? local.rounds : 1;
    return report;
}

}  // namespace sandtin
