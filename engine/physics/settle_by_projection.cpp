#include "physics/settle_by_projection.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "tin/vertex_arrays.hpp"

namespace sandtin {

ProjectionSettleReport settle_by_projection(Tin& tin, const MaterialTable& materials,
                                            std::span<const VertexId> region,
                                            const ReposeProjectionOptions& options) {
    const VertexArrays& va = tin.vertices();
    const std::size_t n = va.size();
    // Dead ids have no faces and no area: the projection leaves them alone.
    std::vector<double> bedrock(n);
    for (std::size_t v = 0; v < n; ++v) {
        bedrock[v] = va.bedrock[v] > 0.5 * kNoBedrock ? va.bedrock[v]
                                                      : -std::numeric_limits<double>::infinity();
    }
    std::vector<std::uint8_t> held;
    if (!region.empty()) {
        held.assign(n, 1);
        for (VertexId v : region) {
            if (!tin.is_alive(v))
                throw std::invalid_argument("settle by projection: vertex " +
                                            std::to_string(v.value) + " is not alive");
            held[v.value] = 0;
        }
    }
    std::vector<std::array<std::uint32_t, 3>> faces;
    std::vector<double> face_tan;
    faces.reserve(tin.triangle_count());
    face_tan.reserve(tin.triangle_count());
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        double tan_sum = 0.0;
        for (VertexId v : t)
            tan_sum += materials.at(va.material[v.value])
                           .talus_slope(static_cast<double>(va.moisture[v.value]));
        faces.push_back({t[0].value, t[1].value, t[2].value});
        face_tan.push_back(tan_sum / 3.0);
    }
    const ReposeProblem problem{va.position, faces,   face_tan, va.lumped_area,
                                va.height,   bedrock, held};
    const ReposeProjection p = project_onto_repose(problem, options);
    ProjectionSettleReport report;
    report.iterations = p.iterations;
    report.converged = p.converged;
    report.free_vertices = p.free_vertices;
    report.degenerate_faces = p.degenerate_faces;
    report.steepest_ratio = p.steepest_ratio;
    report.volume_change = p.volume_change;
    std::vector<VertexId> moved;
    std::vector<double> heights;
    for (std::size_t v = 0; v < n; ++v) {
        if (va.alive[v] && p.height[v] != va.height[v]) {
            moved.push_back(VertexId{static_cast<std::uint32_t>(v)});
            heights.push_back(p.height[v]);
        }
    }
    tin.set_heights(moved, heights);
    report.moved_vertices = moved.size();
    return report;
}

}  // namespace sandtin
