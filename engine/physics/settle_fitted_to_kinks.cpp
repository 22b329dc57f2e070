#include "physics/settle_fitted_to_kinks.hpp"

#include <stdexcept>
#include <vector>

#include "physics/repose_kinks.hpp"

namespace sandtin {

std::size_t fit_projection_bends(Tin& tin, const ProjectionInput& input,
                                 const ReposeProjection& projected) {
    const std::vector<Vec2> bends =
        find_repose_kinks(input.position, input.faces, input.face_tan_alpha, projected.height);
    if (bends.empty()) return 0;
    const std::size_t before = tin.vertex_count();
    tin.insert_points_on_surface(bends);
    return tin.vertex_count() - before;
}

ProjectionSettleReport settle_fitted_to_kinks(Tin& tin, const MaterialTable& materials, int rounds,
                                              const ReposeProjectionOptions& options,
                                              const OutOfReposeOptions& region_options) {
    if (rounds < 0) throw std::invalid_argument("settle fitted to kinks: rounds must be >= 0");
    int iterations = 0;
    int projections = 0;
    std::size_t fitted = 0;
    for (int round = 0;; ++round) {
        const ProjectionInput input = gather_projection_input(tin, materials);
        OutOfReposeReport local;
        const ReposeProjection projected =
            project_out_of_repose(input, options, region_options, &local);
        iterations += projected.iterations;
        projections += local.rounds;
        const std::size_t added =
            round < rounds && local.rounds > 0 ? fit_projection_bends(tin, input, projected) : 0;
        if (added == 0) {
            ProjectionSettleReport report = apply_projection(tin, input, projected);
            report.steep_faces = local.steep_faces;
            report.iterations = iterations;
            report.rounds = projections;
            report.fitted_vertices = fitted;
            return report;
        }
        fitted += added;  // the next round projects the same sand over them
    }
}

}  // namespace sandtin
