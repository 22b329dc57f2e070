#include "physics/face_slopes.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "geom/plane_gradient.hpp"

namespace sandtin {

double face_gradient(const Vec3& a, const Vec3& b, const Vec3& c) {
    const std::optional<Vec2> g = plane_gradient(a, b, c);
    return g ? length(*g) : std::numeric_limits<double>::infinity();
}

namespace {

struct JudgedFace {
    double area = 0.0;       // m², in the plane
    double gradient = 0.0;   // |∇h|
    double tan_alpha = 0.0;  // mean of the corners'
    Vec2 centroid;
};

/// Adds the face's plane area, gradient and centroid, unless it lies outside the region or is
/// rock (counted).
void judge_into(std::vector<JudgedFace>& faces, const SlopeFace& f, const FaceSlopeOptions& options,
                std::size_t& rock) {
    const Vec2 centroid{(f.a.x + f.b.x + f.c.x) / 3.0, (f.a.y + f.b.y + f.c.y) / 3.0};
    if (options.region && !options.region->contains(centroid)) return;
    if (!f.sand) {
        ++rock;
        return;
    }
    const double area =
        0.5 * std::abs((f.b.x - f.a.x) * (f.c.y - f.a.y) - (f.b.y - f.a.y) * (f.c.x - f.a.x));
    faces.push_back({area, face_gradient(f.a, f.b, f.c), f.tan_alpha, centroid});
}

/// The sand faces of the TIN in the region, and how many were rock.
std::vector<JudgedFace> collect_faces(const Tin& tin, const MaterialTable& materials,
                                      const FaceSlopeOptions& options, std::size_t& rock) {
    const VertexArrays& va = tin.vertices();
    std::vector<JudgedFace> faces;
    faces.reserve(tin.triangle_count());
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s) {
        const std::array<VertexId, 3> t = tin.slot_triangle(s);
        if (!t[0].valid()) continue;
        Vec3 p[3];
        double tan_sum = 0.0;
        bool sand = false;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = t[k].value;
            p[k] = {va.position[v].x, va.position[v].y, va.height[v]};
            tan_sum += materials.at(va.material[v]).talus_slope(va.moisture[v]);
            sand = sand || va.height[v] > va.bedrock[v];
        }
        judge_into(faces, {p[0], p[1], p[2], tan_sum / 3.0, sand}, options, rock);
    }
    return faces;
}

void check_options(const FaceSlopeOptions& options) {
    // Written so that NaN fails too.
    if (!(options.tolerance >= 0.0))
        throw std::invalid_argument("face slopes: tolerance must be >= 0");
    if (!(options.sloped_fraction >= 0.0))
        throw std::invalid_argument("face slopes: sloped_fraction must be >= 0");
    if (!(options.min_area_fraction >= 0.0 && options.min_area_fraction < 1.0))
        throw std::invalid_argument("face slopes: min_area_fraction must be in [0, 1)");
}

FaceSlopeReport judge(const std::vector<JudgedFace>& faces, const FaceSlopeOptions& options,
                      std::size_t rock) {
    FaceSlopeReport report;
    report.rock_faces = rock;
    double total = 0.0;
    for (const JudgedFace& f : faces)
        total += f.area;
    const double smallest = options.min_area_fraction * total;
    for (const JudgedFace& f : faces) {
        if (f.area < smallest || f.area == 0.0) {
            ++report.skipped_faces;
            continue;
        }
        ++report.faces;
        report.area += f.area;
        const double ratio =
            f.tan_alpha > 0.0 ? f.gradient / f.tan_alpha : std::numeric_limits<double>::infinity();
        if (ratio > options.sloped_fraction) report.sloped_area += f.area;
        if (ratio > 1.0 + options.tolerance) {
            ++report.steep_faces;
            report.steep_area += f.area;
        }
        if (ratio > report.max_ratio) {
            report.max_ratio = ratio;
            report.steepest_at = f.centroid;
        }
    }
    return report;
}

}  // namespace

FaceSlopeReport measure_face_slopes(std::span<const SlopeFace> faces,
                                    const FaceSlopeOptions& options) {
    check_options(options);
    std::size_t rock = 0;
    std::vector<JudgedFace> judged;
    judged.reserve(faces.size());
    for (const SlopeFace& f : faces)
        judge_into(judged, f, options, rock);
    return judge(judged, options, rock);
}

FaceSlopeReport measure_face_slopes(const Tin& tin, const MaterialTable& materials,
                                    const FaceSlopeOptions& options) {
    check_options(options);
    std::size_t rock = 0;
    const std::vector<JudgedFace> faces = collect_faces(tin, materials, options, rock);
    return judge(faces, options, rock);
}

}  // namespace sandtin
