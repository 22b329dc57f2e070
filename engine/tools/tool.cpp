#include "tools/tool.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "geom/polygon.hpp"

namespace sandtin {

namespace {

void require_positive(double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v)) {
        throw std::invalid_argument(std::string("tool: ") + what + " must be a positive number");
    }
}

void require_non_negative(double v, const char* what) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
        throw std::invalid_argument(std::string("tool: ") + what +
                                    " must be a non-negative number");
    }
}

double perimeter(std::span<const Vec2> polygon) {
    double p = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
        p += distance(polygon[i], polygon[(i + 1) % polygon.size()]);
    return p;
}

}  // namespace

std::vector<Vec2> mesh_outline(const TriangleMesh& mesh, double scale) {
    // Border edges appear in exactly one triangle; chain them into loops.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            std::uint32_t a = t[static_cast<std::size_t>(k)];
            std::uint32_t b = t[static_cast<std::size_t>((k + 1) % 3)];
            if (a > b) std::swap(a, b);
            ++count[{a, b}];
        }
    }
    std::multimap<std::uint32_t, std::uint32_t> next;
    for (const auto& [e, c] : count) {
        if (c == 1) {
            next.emplace(e.first, e.second);
            next.emplace(e.second, e.first);
        }
    }
    if (next.empty())
        throw std::invalid_argument("tool mesh has no open border to use as its contour");
    Rect box;
    for (const auto& v : mesh.vertices)
        box.expand(Vec2{v[0], v[1]});
    const Vec2 centre = box.centre();
    std::vector<Vec2> best;
    double best_area = 0.0;
    while (!next.empty()) {
        const std::uint32_t start = next.begin()->first;
        std::vector<std::uint32_t> loop = {start};
        std::uint32_t prev = start;
        std::uint32_t cur = next.begin()->second;
        next.erase(next.begin());
        // Remove the reverse half of the first edge.
        for (auto it = next.lower_bound(cur); it != next.end() && it->first == cur; ++it) {
            if (it->second == prev) {
                next.erase(it);
                break;
            }
        }
        while (cur != start && loop.size() <= mesh.vertices.size()) {
            loop.push_back(cur);
            auto it = next.lower_bound(cur);
            if (it == next.end() || it->first != cur) break;
            const std::uint32_t to = it->second;
            next.erase(it);
            for (auto jt = next.lower_bound(to); jt != next.end() && jt->first == to; ++jt) {
                if (jt->second == cur) {
                    next.erase(jt);
                    break;
                }
            }
            prev = cur;
            cur = to;
        }
        std::vector<Vec2> pts;
        for (std::uint32_t v : loop) {
            const auto& p = mesh.vertices[v];
            pts.push_back((Vec2{p[0], p[1]} - centre) * scale);
        }
        const double area = std::abs(signed_area(pts));
        if (area > best_area) {
            best_area = area;
            best = std::move(pts);
        }
    }
    if (best.size() < 3) throw std::invalid_argument("tool mesh border is degenerate");
    return best;
}

ToolSpec scaled_tool_spec(ToolSpec spec, double factor) {
    if (!(factor > 0.0) || !std::isfinite(factor))
        throw std::invalid_argument("tool scale factor must be positive and finite");
    for (double* length :
         {&spec.radius, &spec.width, &spec.length, &spec.scale, &spec.sphere_radius, &spec.relief,
          &spec.gap, &spec.rim_spacing, &spec.rim_tolerance, &spec.extrusion_width})
        *length *= factor;
    return spec;
}

Tool Tool::build(const ToolSpec& spec) {
    Tool tool;
    tool.spec_ = spec;
    require_positive(spec.scale, "scale");
    TriangleMesh mesh;
    if (spec.profile == ProfileKind::Mesh) {
        if (spec.profile_file.empty())
            throw std::invalid_argument("tool: a mesh profile needs a profile file (OBJ)");
        mesh = read_obj(spec.profile_file);
    }

    std::vector<Vec2> inner;
    switch (spec.contour) {
        case ContourKind::Circle:
            require_positive(spec.radius, "radius");
            inner = circle_contour(spec.radius, spec.control_points);
            break;
        case ContourKind::Rectangle:
            require_positive(spec.width, "width");
            require_positive(spec.length, "length");
            inner = rectangle_contour(spec.width, spec.length);
            break;
        case ContourKind::Polygon:
            if (spec.contour_from_mesh) {
                if (spec.profile != ProfileKind::Mesh) {
                    throw std::invalid_argument("tool: contour_from_mesh needs a mesh profile");
                }
                inner = mesh_outline(mesh, spec.scale);
            } else {
                for (Vec2 p : spec.polygon)
                    inner.push_back(p * spec.scale);
            }
            break;
    }
    inner = normalise_contour(inner);
    double radius = 0.0;
    for (Vec2 p : inner)
        radius = std::max(radius, length(p));
    tool.radius_ = radius;

    require_non_negative(spec.gap, "gap");
    const double gap = spec.gap > 0.0 ? spec.gap : 0.025 * radius;
    tool.shape_ = make_tool_shape(inner, gap);

    require_non_negative(spec.rim_spacing, "rim_spacing");
    // The outer contour is the longer one; a hair of slack keeps rounding from splitting its
    // edges, so a circle tool has `control_points` vertices on both contours.
    tool.rim_spacing_ = spec.rim_spacing > 0.0 ? spec.rim_spacing
                                               : (1.0 + 1e-9) * perimeter(tool.shape_.outer) /
                                                     std::max(3, spec.control_points);
    require_non_negative(spec.rim_tolerance, "rim_tolerance");
    tool.rim_tolerance_ = spec.rim_tolerance > 0.0 ? spec.rim_tolerance : 0.01 * radius;
    require_non_negative(spec.extrusion_width, "extrusion_width");
    tool.extrusion_width_ = spec.extrusion_width > 0.0 ? spec.extrusion_width : radius;

    switch (spec.profile) {
        case ProfileKind::Flat:
            tool.profile_ = ToolProfile::flat();
            break;
        case ProfileKind::HalfSphere:
            require_non_negative(spec.sphere_radius, "sphere_radius");
            tool.profile_ =
                ToolProfile::half_sphere(spec.sphere_radius > 0.0 ? spec.sphere_radius : radius);
            break;
        case ProfileKind::Heightfield: {
            if (spec.profile_file.empty())
                throw std::invalid_argument(
                    "tool: a heightfield profile needs a profile file (PNG)");
            const PngImage image = read_png(spec.profile_file);
            const Rect extent = bounding_box(std::span<const Vec2>(tool.shape_.inner));
            tool.profile_ = ToolProfile::heightfield(image, extent, spec.relief);
            break;
        }
        case ProfileKind::Mesh:
            tool.profile_ = ToolProfile::mesh_imprint(mesh, spec.scale);
            break;
    }
    tool.max_stroke_spacing_ = 0.5 * tool.profile_.tip_length();
    if (!tool.profile_.is_flat()) {
        InteriorSamples& samples = tool.interior_samples_;
        samples.spacing = std::min(tool.rim_spacing_, tool.profile_.sample_spacing());
        // The lattice has about one sample per (sqrt(3)/2) spacing² of I's area. A contour far
        // larger than its profile's detail (a mistyped size) would sample for hours: an error.
        const double area = std::abs(signed_area(tool.shape_.inner));
        const double samples_needed =
            area / (0.5 * std::sqrt(3.0) * samples.spacing * samples.spacing);
        if (!(samples_needed <= kMaxInteriorSamples)) {
            char message[256];
            std::snprintf(message, sizeof message,
                          "tool: its curved profile needs about %.3g interior samples (%.3g m² "
                          "at a %.3g m spacing), more than %.0f: make the tool smaller or its "
                          "profile coarser",
                          samples_needed, area, samples.spacing, kMaxInteriorSamples);
            throw std::invalid_argument(message);
        }
        samples.local = interior_lattice(subdivide_contour(tool.shape_.inner, tool.rim_spacing_),
                                         samples.spacing);
        samples.offset.reserve(samples.local.size());
        for (Vec2 p : samples.local)
            samples.offset.push_back(tool.profile_.offset(p));
    }
    return tool;
}

}  // namespace sandtin
