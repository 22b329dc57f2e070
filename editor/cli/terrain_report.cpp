#include "terrain_report.hpp"

#include <algorithm>
#include <limits>

#include "physics/face_slopes.hpp"

namespace sandtin::cli {

nlohmann::json describe_terrain(const Tin& tin, bool validate) {
    const VertexArrays& va = tin.vertices();
    double zmin = std::numeric_limits<double>::infinity();
    double zmax = -std::numeric_limits<double>::infinity();
    // Sand over bedrock, at the vertices that have one (kNoBedrock: none).
    double thinnest = std::numeric_limits<double>::infinity();
    double thickest = 0.0;
    std::size_t on_bedrock = 0;
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        zmin = std::min(zmin, va.height[i]);
        zmax = std::max(zmax, va.height[i]);
        if (va.bedrock[i] > kNoBedrock) {
            ++on_bedrock;
            thinnest = std::min(thinnest, va.height[i] - va.bedrock[i]);
            thickest = std::max(thickest, va.height[i] - va.bedrock[i]);
        }
    }
    const Rect d = tin.domain();
    nlohmann::json j;
    j["vertices"] = tin.vertex_count();
    j["triangles"] = tin.triangle_count();
    j["constrained_edges"] = tin.constrained_edge_count();
    j["constraints"] = tin.constraint_count();
    j["volume"] = tin.volume();
    j["bbox"] = {{"min", {d.min.x, d.min.y, zmin}}, {"max", {d.max.x, d.max.y, zmax}}};
    if (on_bedrock > 0) {
        j["sand"] = {{"vertices_over_bedrock", on_bedrock},
                     {"min_thickness", thinnest},
                     {"max_thickness", thickest}};
    }
    if (validate) {
        const ValidationReport report = tin.check_valid();
        j["valid"] = report.ok();
        if (!report.ok()) j["problems"] = report.problems;
    }
    return j;
}

nlohmann::json describe_slopes(const Tin& tin, const MaterialTable& materials) {
    const FaceSlopeOptions options;
    const FaceSlopeReport r = measure_face_slopes(tin, materials, options);
    return {{"tolerance", options.tolerance}, {"faces", r.faces},
            {"rock_faces", r.rock_faces},     {"skipped_faces", r.skipped_faces},
            {"steep_faces", r.steep_faces},   {"sloped_area", r.sloped_area},
            {"steep_area", r.steep_area},     {"steep_share_of_slopes", r.steep_share_of_slopes()},
            {"max_ratio", r.max_ratio},       {"steepest_at", {r.steepest_at.x, r.steepest_at.y}}};
}

}  // namespace sandtin::cli
