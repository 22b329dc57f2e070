#pragma once
// Orbit camera around a target point, z up. Units: metres and radians. Produces Vulkan clip
// matrices (y down in clip space, depth 0..1) and the pick ray through a pixel.

#include <array>
#include <optional>

#include "geom/vec3.hpp"

namespace sandtin::editor {

using Mat4 = std::array<float, 16>;  ///< column-major

struct Ray {
    Vec3 origin;
    Vec3 direction;  ///< unit length
};

/// A rectangle of a viewport, in pixels (y down).
struct PixelRect {
    double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
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
    /// Fits a box (metres), seen from the current direction, into the part `free` of a
    /// width x height viewport (what the panels leave uncovered): its eight corners project
    /// into `free` shrunk by `margin` (a fraction of its size on each side), and the box fills
    /// it as far as that allows. False when no fit was found (`free` empty, say): the camera
    /// then frames the box in the whole view.
    bool frame_in(Vec3 box_min, Vec3 box_max, double width, double height, PixelRect free,
                  double margin = 0.03);
    /// The pixel rectangle the box's eight corners project to; none when one of them is
    /// behind the camera.
    std::optional<PixelRect> projected_box(Vec3 box_min, Vec3 box_max, double width,
                                           double height) const;

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
