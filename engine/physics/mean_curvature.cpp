#include "physics/mean_curvature.hpp"

#include <cmath>
#include <cstddef>

namespace sandtin {

namespace {

/// cot of the angle between u and v.
double cot_between(const Vec3& u, const Vec3& v) {
    const double sine = length(cross(u, v));
    return sine > 0.0 ? dot(u, v) / sine : 0.0;
}

/// The centre's share of the triangle (centre, centre + u, centre + v) in its dual
/// (circumcentric) cell: |u|² cot(at v) / 8 + |v|² cot(at u) / 8. Negative past an obtuse
/// angle; over a Delaunay star the parts add up to the vertex's Voronoi cell.
double dual_cell_part(const Vec3& u, const Vec3& v, double cot_at_u, double cot_at_v) {
    return (dot(u, u) * cot_at_v + dot(v, v) * cot_at_u) / 8.0;
}

}  // namespace

double mean_curvature_of_star(const Vec3& centre, std::span<const Vec3> ring) {
    const std::size_t m = ring.size();
    if (m < 3) return 0.0;
    Vec3 laplacian;  // sum over the star's triangles, before dividing by 2A
    Vec3 normal;     // twice the area-weighted normal
    double dual_area = 0.0;
    double third_area = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
        const Vec3& p = ring[k];
        const Vec3& q = ring[(k + 1) % m];
        const Vec3 face_normal = cross(p - centre, q - centre);
        normal += face_normal;
        // The triangle (centre, p, q): its angle at q faces the edge to p, its angle at p
        // faces the edge to q.
        const double cot_q = cot_between(centre - q, p - q);
        const double cot_p = cot_between(centre - p, q - p);
        laplacian += cot_q * (p - centre);
        laplacian += cot_p * (q - centre);
        dual_area += dual_cell_part(p - centre, q - centre, cot_p, cot_q);
        third_area += length(face_normal) / 6.0;
    }
    // A star far from Delaunay (beside constraints) can have a dual cell of little or no area:
    // it takes the barycentric third there rather than blow the curvature up.
    const double area = dual_area >= 0.5 * third_area ? dual_area : third_area;
    if (!(area > 0.0)) return 0.0;
    const Vec3 n = normalised(normal);
    // K = laplacian / (2A) = -2 H n for a surface whose normal points out of the convex side.
    return -dot(laplacian, n) / (4.0 * area);
}

}  // namespace sandtin
