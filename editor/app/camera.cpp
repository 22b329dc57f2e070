#include "camera.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin::editor {

namespace {

Vec3 diff(Vec3 a, Vec3 b) {
    return a - b;
}

struct Basis {
    Vec3 forward, right, up;
};

Basis basis(const OrbitCamera& c) {
    const Vec3 f = normalised(diff(c.target, c.eye()));
    const Vec3 r = normalised(cross(f, Vec3{0.0, 0.0, 1.0}));
    return {f, r, cross(r, f)};
}

}  // namespace

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 m{};
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            float s = 0.0f;
            for (int k = 0; k < 4; ++k)
                s +=
                    a[static_cast<std::size_t>(k * 4 + r)] * b[static_cast<std::size_t>(c * 4 + k)];
            m[static_cast<std::size_t>(c * 4 + r)] = s;
        }
    }
    return m;
}

Vec3 OrbitCamera::eye() const {
    const double cp = std::cos(pitch);
    return {target.x + distance * cp * std::cos(yaw), target.y + distance * cp * std::sin(yaw),
            target.z + distance * std::sin(pitch)};
}

void OrbitCamera::orbit(double dx, double dy) {
    yaw -= dx * 0.005;
    pitch = std::clamp(pitch + dy * 0.005, kMinPitch, kMaxPitch);
}

void OrbitCamera::pan(double dx, double dy, double viewport_height) {
    const Basis b = basis(*this);
    // Metres per pixel at the target's depth.
    const double scale = 2.0 * distance * std::tan(0.5 * fov_y) / std::max(viewport_height, 1.0);
    target.x += (-dx * b.right.x + dy * b.up.x) * scale;
    target.y += (-dx * b.right.y + dy * b.up.y) * scale;
    target.z += (-dx * b.right.z + dy * b.up.z) * scale;
}

void OrbitCamera::zoom(double steps) {
    distance = std::clamp(distance * std::pow(0.88, steps), kMinDistance, kMaxDistance);
}

void OrbitCamera::frame(Vec3 lo, Vec3 hi) {
    target = {0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)};
    const Vec3 half{0.5 * (hi.x - lo.x), 0.5 * (hi.y - lo.y), 0.5 * (hi.z - lo.z)};
    const double radius = std::sqrt(dot(half, half));
    distance = std::clamp(1.05 * radius / std::sin(0.5 * fov_y), kMinDistance, kMaxDistance);
}

Mat4 OrbitCamera::view() const {
    const Basis b = basis(*this);
    const Vec3 e = eye();
    auto f = [](double v) { return static_cast<float>(v); };
    // Rows: right, up, -forward (right-handed view space looking down -z).
    return Mat4{f(b.right.x),        f(b.up.x),        f(-b.forward.x),      0.0f,
                f(b.right.y),        f(b.up.y),        f(-b.forward.y),      0.0f,
                f(b.right.z),        f(b.up.z),        f(-b.forward.z),      0.0f,
                f(-dot(b.right, e)), f(-dot(b.up, e)), f(dot(b.forward, e)), 1.0f};
}

Mat4 OrbitCamera::projection(double aspect) const {
    const double t = 1.0 / std::tan(0.5 * fov_y);
    const double n = near_plane(), fa = far_plane();
    Mat4 m{};
    m[0] = static_cast<float>(t / aspect);
    m[5] = static_cast<float>(-t);  // Vulkan clip space: y points down
    m[10] = static_cast<float>(fa / (n - fa));
    m[11] = -1.0f;
    m[14] = static_cast<float>(n * fa / (n - fa));
    return m;
}

Mat4 OrbitCamera::view_projection(double aspect) const {
    return multiply(projection(aspect), view());
}

Ray OrbitCamera::pixel_ray(double px, double py, double width, double height) const {
    const Basis b = basis(*this);
    const double t = std::tan(0.5 * fov_y);
    const double x = (2.0 * px / width - 1.0) * t * width / height;
    const double y = (1.0 - 2.0 * py / height) * t;
    const Vec3 d{b.forward.x + x * b.right.x + y * b.up.x, b.forward.y + x * b.right.y + y * b.up.y,
                 b.forward.z + x * b.right.z + y * b.up.z};
    return {eye(), normalised(d)};
}

bool OrbitCamera::project(Vec3 w, double width, double height, double& px, double& py) const {
    const Basis b = basis(*this);
    const Vec3 d = diff(w, eye());
    const double z = dot(d, b.forward);
    if (z <= 0.0) return false;
    const double t = std::tan(0.5 * fov_y);
    const double x = dot(d, b.right) / (z * t * width / height);
    const double y = dot(d, b.up) / (z * t);
    px = 0.5 * (x + 1.0) * width;
    py = 0.5 * (1.0 - y) * height;
    return true;
}

}  // namespace sandtin::editor
