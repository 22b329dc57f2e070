#pragma once
// The footprint of a tool in tool-local coordinates (metres; origin at the tool centre, +x is
// the tool's forward direction). The inner contour I is the part that presses the sand; the
// outer contour O surrounds it a small gap away, so no edge of the terrain is ever vertical
// (seed 003 §3.3, seed 004 §3.4).

#include <span>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

struct ToolShape {
    std::vector<Vec2> inner;       ///< I: simple polygon, counter-clockwise
    std::vector<Vec2> outer;       ///< O: simple polygon, counter-clockwise, enclosing I
    double gap = 0.0;              ///< distance from I to O (metres)
    double bounding_radius = 0.0;  ///< largest distance of an O point from the origin
};

/// Regular polygon with `points` vertices on a circle (first vertex on +x).
std::vector<Vec2> circle_contour(double radius, int points);
/// Axis-aligned rectangle centred on the origin, counter-clockwise.
std::vector<Vec2> rectangle_contour(double width, double length);

/// Validates a user contour and puts it in canonical form: repeated and collinear points
/// removed, counter-clockwise. Throws std::invalid_argument when it is not a simple polygon
/// with positive area (self-intersecting, fewer than three distinct points, non-finite).
std::vector<Vec2> normalise_contour(std::span<const Vec2> contour);

/// Outward offset of a counter-clockwise polygon by `distance` metres (mitred corners,
/// bevelled where the mitre would exceed four times the distance).
std::vector<Vec2> offset_contour(std::span<const Vec2> ccw, double distance);

/// I and O from an inner contour: O is I offset by `gap`; when the offset is not a simple
/// polygon enclosing I (tight concave corners), the gap is halved until it is.
ToolShape make_tool_shape(std::span<const Vec2> inner, double gap);

/// Inserts points on each edge of a closed polygon so no edge is longer than max_spacing.
std::vector<Vec2> subdivide_contour(std::span<const Vec2> polygon, double max_spacing);

/// Points strictly inside a simple polygon (one near each vertex, moved inwards): seeds for a
/// walk over the region a contour encloses.
std::vector<Vec2> interior_seeds(std::span<const Vec2> ccw);

/// A triangular lattice of points with the given spacing inside the polygon, each at least
/// spacing / 2 from its border: interior samples for curved tool profiles.
std::vector<Vec2> interior_lattice(std::span<const Vec2> polygon, double spacing);

/// Clips a polygon to an axis-aligned rectangle (Sutherland-Hodgman); may return < 3 points.
/// Points on the rectangle's sides lie exactly on them (their x or y equals the side's).
std::vector<Vec2> clip_to_rect(std::span<const Vec2> polygon, Vec2 min, Vec2 max);

/// Points along the edges of a closed polygon that lie on a side of `rect` (both ends exactly
/// on that side, as clip_to_rect leaves them), each such edge cut into equal pieces no longer
/// than `spacing` (m): the pieces' inner ends, exactly on the side. The polygon's own vertices
/// are not repeated. Empty when `spacing` is not positive.
std::vector<Vec2> samples_along_sides(std::span<const Vec2> polygon, const Rect& rect,
                                      double spacing);

}  // namespace sandtin
