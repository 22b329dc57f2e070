#include "maps/vertex_normals.hpp"

namespace sandtin {

std::vector<Vec3> vertex_normals(const Tin& tin, double z_scale) {
    const VertexArrays& va = tin.vertices();
    std::vector<Vec3> sum(va.size());
    auto point = [&](VertexId v) {
        const Vec2 p = va.position[v.index()];
        return Vec3{p.x, p.y, va.height[v.index()] * z_scale};
    };
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        const Vec3 a = point(t[0]);
        // Twice the area times the unit normal: larger triangles weigh more.
        const Vec3 n = cross(point(t[1]) - a, point(t[2]) - a);
        for (VertexId v : t)
            sum[v.index()] += n;
    }
    for (Vec3& n : sum)
        n = normalised(n);
    return sum;
}

Vec3 face_normal(Vec3 a, Vec3 b, Vec3 c) {
    return normalised(cross(b - a, c - a));
}

Vec3 surface_tangent(Vec3 n, Vec3 up) {
    const Vec3 east{1.0, 0.0, 0.0};
    return normalised(east - n * dot(n, east), normalised(cross(n, up), east));
}

}  // namespace sandtin
