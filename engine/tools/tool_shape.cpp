#include "tools/tool_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "geom/near_edge_index.hpp"
#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"

namespace sandtin {

std::vector<Vec2> circle_contour(double radius, int points) {
    if (!(radius > 0.0) || !std::isfinite(radius)) {
        throw std::invalid_argument("circle contour: radius must be a positive number of metres");
    }
    if (points < 3 || points > 4096) {
        throw std::invalid_argument("circle contour: control points must lie in 3..4096");
    }
    std::vector<Vec2> c;
    c.reserve(static_cast<std::size_t>(points));
    for (int i = 0; i < points; ++i) {
        const double a = 2.0 * std::numbers::pi * i / points;
        c.push_back({radius * std::cos(a), radius * std::sin(a)});
    }
    return c;
}

std::vector<Vec2> rectangle_contour(double width, double length) {
    if (!(width > 0.0) || !(length > 0.0) || !std::isfinite(width) || !std::isfinite(length)) {
        throw std::invalid_argument("rectangle contour: width and length must be positive");
    }
    const double hx = 0.5 * length;
    const double hy = 0.5 * width;
    return {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
}

std::vector<Vec2> normalise_contour(std::span<const Vec2> contour) {
    std::vector<Vec2> pts;
    for (Vec2 p : contour) {
        if (!is_finite(p)) throw std::invalid_argument("tool contour has a non-finite point");
        if (pts.empty() || !(pts.back() == p)) pts.push_back(p);
    }
    while (pts.size() > 1 && pts.front() == pts.back())
        pts.pop_back();
    // Drop exactly collinear points: they would only add constraint vertices.
    bool changed = true;
    while (changed && pts.size() > 3) {
        changed = false;
        for (std::size_t i = 0; i < pts.size() && pts.size() > 3; ++i) {
            const Vec2 a = pts[(i + pts.size() - 1) % pts.size()];
            const Vec2 b = pts[i];
            const Vec2 c = pts[(i + 1) % pts.size()];
            if (cross(b - a, c - b) == 0.0 && dot(b - a, c - b) > 0.0) {
                pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
                changed = true;
            }
        }
    }
    if (pts.size() < 3)
        throw std::invalid_argument("tool contour needs at least three distinct points");
    if (!is_simple_polygon(pts)) {
        throw std::invalid_argument(
            "tool contour is not a simple polygon (its edges cross or it has no area)");
    }
    if (signed_area(pts) < 0.0) std::reverse(pts.begin(), pts.end());
    return pts;
}

std::vector<Vec2> offset_contour(std::span<const Vec2> ccw, double distance) {
    const std::size_t n = ccw.size();
    std::vector<Vec2> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 prev = ccw[(i + n - 1) % n];
        const Vec2 p = ccw[i];
        const Vec2 next = ccw[(i + 1) % n];
        const Vec2 e1 = (p - prev) / length(p - prev);
        const Vec2 e2 = (next - p) / length(next - p);
        // Outward normals of a counter-clockwise polygon point to the right of the edges.
        const Vec2 n1{e1.y, -e1.x};
        const Vec2 n2{e2.y, -e2.x};
        const Vec2 bisector = n1 + n2;
        const double blen = length(bisector);
        if (blen < 1e-12) {  // a spike turning back on itself
            out.push_back(p + n1 * distance);
            out.push_back(p + n2 * distance);
            continue;
        }
        const Vec2 m = bisector / blen;
        const double cos_half = dot(m, n1);
        const double miter = distance / std::max(cos_half, 1e-12);
        const bool convex = cross(e1, e2) > 0.0;
        if (convex && miter > 4.0 * distance) {
            out.push_back(p + n1 * distance);
            out.push_back(p + n2 * distance);
        } else {
            out.push_back(p + m * miter);
        }
    }
    return out;
}

namespace {

bool encloses(std::span<const Vec2> outer, std::span<const Vec2> inner) {
    if (!is_simple_polygon(outer) || signed_area(outer) <= 0.0) return false;
    for (Vec2 p : inner) {
        if (!point_in_polygon(p, outer)) return false;
    }
    for (std::size_t i = 0; i < inner.size(); ++i) {
        const Vec2 a = inner[i];
        const Vec2 b = inner[(i + 1) % inner.size()];
        for (std::size_t j = 0; j < outer.size(); ++j) {
            if (segments_intersect(a, b, outer[j], outer[(j + 1) % outer.size()])) return false;
        }
    }
    return true;
}

}  // namespace

ToolShape make_tool_shape(std::span<const Vec2> inner, double gap) {
    if (!(gap > 0.0) || !std::isfinite(gap)) {
        throw std::invalid_argument(
            "tool shape: the gap between inner and outer contour must be positive");
    }
    ToolShape shape;
    shape.inner = normalise_contour(inner);
    for (int attempt = 0; attempt < 24; ++attempt, gap *= 0.5) {
        std::vector<Vec2> outer = offset_contour(shape.inner, gap);
        if (encloses(outer, shape.inner)) {
            shape.outer = std::move(outer);
            shape.gap = gap;
            for (Vec2 p : shape.outer)
                shape.bounding_radius = std::max(shape.bounding_radius, length(p));
            return shape;
        }
    }
    throw std::invalid_argument(
        "tool shape: no outer contour encloses the inner one (degenerate contour)");
}

std::vector<Vec2> subdivide_contour(std::span<const Vec2> polygon, double max_spacing) {
    std::vector<Vec2> out;
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = polygon[i];
        const Vec2 b = polygon[(i + 1) % n];
        out.push_back(a);
        if (!(max_spacing > 0.0)) continue;
        const int pieces = static_cast<int>(std::ceil(distance(a, b) / max_spacing));
        for (int k = 1; k < pieces; ++k)
            out.push_back(lerp(a, b, static_cast<double>(k) / pieces));
    }
    return out;
}

std::vector<Vec2> interior_seeds(std::span<const Vec2> ccw) {
    std::vector<Vec2> seeds;
    const std::size_t n = ccw.size();
    double min_edge = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
        min_edge = std::min(min_edge, distance(ccw[i], ccw[(i + 1) % n]));
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = ccw[i];
        const Vec2 b = ccw[(i + 1) % n];
        const Vec2 mid = (a + b) * 0.5;
        const Vec2 e = (b - a) / length(b - a);
        const Vec2 inward{-e.y, e.x};
        for (double f : {0.25, 0.05, 0.01}) {
            const Vec2 s = mid + inward * (f * min_edge);
            if (point_in_polygon(s, ccw)) {
                seeds.push_back(s);
                break;
            }
        }
    }
    return seeds;
}

std::vector<Vec2> interior_lattice(std::span<const Vec2> polygon, double spacing) {
    std::vector<Vec2> out;
    if (!(spacing > 0.0) || polygon.size() < 3) return out;
    const Rect box = bounding_box(polygon);
    // A mesh or heightfield profile puts thousands of lattice points inside a contour of
    // hundreds of edges: both tests are indexed.
    const PolygonInclusion inside(polygon, box.centre());
    const NearEdgeIndex border(polygon, 0.5 * spacing);
    const double row = spacing * std::sqrt(3.0) / 2.0;
    // Counted loops: x += spacing would stand still where spacing is below an ulp of x.
    const double rows = std::ceil((box.max.y - box.min.y) / row - 0.5);
    const double columns = std::ceil((box.max.x - box.min.x) / spacing - 0.5);
    for (double r = 0.0; r < rows; r += 1.0) {
        const double y = box.min.y + (0.5 + r) * row;
        if (!(y < box.max.y)) break;
        const double shift = std::fmod(r, 2.0) == 0.0 ? 0.0 : 0.5 * spacing;
        for (double c = 0.0; c < columns; c += 1.0) {
            const double x = box.min.x + 0.5 * spacing + shift + c * spacing;
            if (!(x < box.max.x)) break;
            const Vec2 p{x, y};
            if (inside.contains(p) && !(border.nearest_within_reach(p).distance < 0.5 * spacing))
                out.push_back(p);
        }
    }
    return out;
}

std::vector<Vec2> samples_along_sides(std::span<const Vec2> polygon, const Rect& rect,
                                      double spacing) {
    std::vector<Vec2> out;
    if (!(spacing > 0.0)) return out;
    const std::size_t n = polygon.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2 a = polygon[k];
        const Vec2 b = polygon[(k + 1) % n];
        if (!rect.has_on_one_side(a, b)) continue;
        const double pieces = std::ceil(distance(a, b) / spacing);
        for (double i = 1.0; i < pieces; i += 1.0) {
            Vec2 p = lerp(a, b, i / pieces);
            // On the side exactly: lerp rounds the other coordinate only.
            if (a.x == b.x) p.x = a.x;
            if (a.y == b.y) p.y = a.y;
            out.push_back(p);
        }
    }
    return out;
}

std::vector<Vec2> clip_to_rect(std::span<const Vec2> polygon, Vec2 min, Vec2 max) {
    std::vector<Vec2> current(polygon.begin(), polygon.end());
    // Each clip edge: keep points with value(p) >= 0.
    auto clip = [&](auto value, auto intersect) {
        std::vector<Vec2> out;
        const std::size_t n = current.size();
        for (std::size_t i = 0; i < n; ++i) {
            const Vec2 a = current[i];
            const Vec2 b = current[(i + 1) % n];
            const double va = value(a);
            const double vb = value(b);
            if (va >= 0.0) out.push_back(a);
            if ((va >= 0.0) != (vb >= 0.0)) out.push_back(intersect(a, b, va / (va - vb)));
        }
        current = std::move(out);
    };
    auto lerp_at = [](Vec2 a, Vec2 b, double t) { return lerp(a, b, t); };
    clip([&](Vec2 p) { return p.x - min.x; },
         [&](Vec2 a, Vec2 b, double t) {
             Vec2 q = lerp_at(a, b, t);
             q.x = min.x;
             return q;
         });
    if (current.empty()) return current;
    clip([&](Vec2 p) { return max.x - p.x; },
         [&](Vec2 a, Vec2 b, double t) {
             Vec2 q = lerp_at(a, b, t);
             q.x = max.x;
             return q;
         });
    if (current.empty()) return current;
    clip([&](Vec2 p) { return p.y - min.y; },
         [&](Vec2 a, Vec2 b, double t) {
             Vec2 q = lerp_at(a, b, t);
             q.y = min.y;
             return q;
         });
    if (current.empty()) return current;
    clip([&](Vec2 p) { return max.y - p.y; },
         [&](Vec2 a, Vec2 b, double t) {
             Vec2 q = lerp_at(a, b, t);
             q.y = max.y;
             return q;
         });
    // Remove repeated points the clipping may leave.
    std::vector<Vec2> out;
    for (Vec2 p : current) {
        if (out.empty() || !(out.back() == p)) out.push_back(p);
    }
    while (out.size() > 1 && out.front() == out.back())
        out.pop_back();
    return out;
}

}  // namespace sandtin
