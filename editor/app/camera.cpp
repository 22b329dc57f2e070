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

std::optional<PixelRect> OrbitCamera::projected_box(Vec3 lo, Vec3 hi, double width,
                                                    double height) const {
    PixelRect r{1e300, 1e300, -1e300, -1e300};
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{(corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                     (corner & 4) ? hi.z : lo.z};
        double px = 0.0, py = 0.0;
        if (!project(p, width, height, px, py)) return std::nullopt;
        r = {std::min(r.x0, px), std::min(r.y0, py), std::max(r.x1, px), std::max(r.y1, py)};
    }
    return r;
}

bool OrbitCamera::frame_in(Vec3 lo, Vec3 hi, double width, double height, PixelRect free,
                           double margin) {
    frame(lo, hi);
    const PixelRect want{free.x0 + margin * free.width(), free.y0 + margin * free.height(),
                         free.x1 - margin * free.width(), free.y1 - margin * free.height()};
    if (!(want.width() > 0.0 && want.height() > 0.0)) return false;
    const OrbitCamera whole_view = *this;
    // The projection is centred on the viewport and the free part need not be: alternately
    // pan the box's image onto the free part's centre and scale the distance so the image
    // fills it. Perspective makes each step approximate; a few dozen converge to a pixel.
    auto fits = [&] {
        const std::optional<PixelRect> r = projected_box(lo, hi, width, height);
        return r && r->x0 >= want.x0 && r->x1 <= want.x1 && r->y0 >= want.y0 && r->y1 <= want.y1;
    };
    for (int step = 0; step < 64; ++step) {
        const std::optional<PixelRect> r = projected_box(lo, hi, width, height);
        if (!r) {
            distance = std::min(distance * 1.5, kMaxDistance);  // a corner behind the eye
            continue;
        }
        pan(0.5 * (want.x0 + want.x1 - r->x0 - r->x1), 0.5 * (want.y0 + want.y1 - r->y0 - r->y1),
            height);
        const double scale = std::max(r->width() / want.width(), r->height() / want.height());
        distance = std::clamp(distance * scale, kMinDistance, kMaxDistance);
    }
    // Converged from inside or outside: step back until every corner is in.
    for (int step = 0; step < 100 && !fits(); ++step)
        distance = std::min(distance * 1.01, kMaxDistance);
    if (fits()) return true;
    *this = whole_view;
    return false;
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
