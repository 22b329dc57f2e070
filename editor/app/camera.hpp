#pragma once
// Orbit camera around a target point, z up. Units: metres and radians. Produces Vulkan clip
// matrices (y down in clip space, depth 0..1) and the pick ray through a pixel.

#include <array>

#include "geom/vec3.hpp"

namespace sandtin::editor {

using Mat4 = std::array<float, 16>;  ///< column-major

struct Ray {
    Vec3 origin;
    Vec3 direction;  ///< unit length
};

class OrbitCamera {
  public:
    Vec3 target{0.0, 0.0, 0.0};
    double yaw = -1.9;      ///< radians, around +z, 0 looks along -x from +x
    double pitch = 0.75;    ///< radians above the horizon, in [kMinPitch, kMaxPitch]
    double distance = 1.6;  ///< metres from the target
    double fov_y = 0.8;     ///< radians

    static constexpr double kMinPitch = 0.05;
    static constexpr double kMaxPitch = 1.55;
    static constexpr double kMinDistance = 0.01;
    static constexpr double kMaxDistance = 1.0e4;

    Vec3 eye() const;
    /// Drag by (dx, dy) pixels: 0.005 rad per pixel.
    void orbit(double dx, double dy);
    /// Moves the target with the drag so the point under the cursor follows it (approximately,
    /// at the target's depth). `viewport_height` in pixels.
    void pan(double dx, double dy, double viewport_height);
    /// Wheel steps: each step brings the camera 12 % closer (negative: farther).
    void zoom(double steps);
    /// Fits a box (metres) in view from the current direction.
    void frame(Vec3 box_min, Vec3 box_max);

    Mat4 view() const;
    Mat4 projection(double aspect) const;
    Mat4 view_projection(double aspect) const;
    /// The ray through pixel (px, py) of a width x height viewport (pixel centres at +0.5).
    Ray pixel_ray(double px, double py, double width, double height) const;
    /// Projects a world point to pixel coordinates; false when it is behind the camera.
    bool project(Vec3 world, double width, double height, double& px, double& py) const;

    double near_plane() const { return distance * 0.01; }
    double far_plane() const { return distance * 100.0; }
};

Mat4 multiply(const Mat4& a, const Mat4& b);

}  // namespace sandtin::editor
