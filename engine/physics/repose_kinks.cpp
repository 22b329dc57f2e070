#include "physics/repose_kinks.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "geom/plane_gradient.hpp"
#include "geom/vec3.hpp"

namespace sandtin {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

}  // namespace

std::vector<Vec2> find_repose_kinks(std::span<const Vec2> position,
                                    std::span<const std::array<std::uint32_t, 3>> faces,
                                    std::span<const double> face_tan_alpha,
                                    std::span<const double> height,
                                    const ReposeKinkOptions& options) {
    const std::size_t n = position.size();
    if (height.size() != n || face_tan_alpha.size() != faces.size())
        throw std::invalid_argument(
            "repose kinks: height must be per vertex and face_tan_alpha per face");
    for (const auto& f : faces) {
        for (std::uint32_t v : f) {
            if (v >= n) throw std::invalid_argument("repose kinks: a face corner is not a vertex");
        }
    }
    // Phase 1: each face's gradient; each vertex's steepest face at repose and gentlest gentle
    // face.
    const auto corner = [&](std::uint32_t v) {
        return Vec3{position[v].x, position[v].y, height[v]};
    };
    std::vector<Vec2> gradient(faces.size());
    std::vector<std::uint32_t> slope_face(n, kNone), gentle_face(n, kNone);
    std::vector<double> slope_ratio(n, 0.0), gentle_ratio(n, 0.0);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& c = faces[f];
        // Slivers left out: their gradient is rounding noise.
        const std::optional<Vec2> g =
            plane_gradient(corner(c[0]), corner(c[1]), corner(c[2]), 1e-12);
        if (!g) continue;
        gradient[f] = *g;
        const double ratio = length(gradient[f]) / face_tan_alpha[f];
        const auto face = static_cast<std::uint32_t>(f);
        for (std::uint32_t v : c) {
            if (ratio >= 1.0 - options.at_repose &&
                (slope_face[v] == kNone || ratio > slope_ratio[v])) {
                slope_face[v] = face;
                slope_ratio[v] = ratio;
            }
            if (ratio <= options.gentle && (gentle_face[v] == kNone || ratio < gentle_ratio[v])) {
                gentle_face[v] = face;
                gentle_ratio[v] = ratio;
            }
        }
    }
    // Phase 2: along each edge from a slope vertex to a gentle-ground vertex, where the two
    // planes meet. A toe vertex has several edges down to the ground, each its own bend; a
    // bend closer than `near` of its edge to one already put beside either end is the same.
    std::unordered_map<std::uint32_t, std::vector<Vec2>> placed;  // by vertex: bends beside it
    const auto clear_of = [&](std::uint32_t v, Vec2 p, double spacing) {
        const auto it = placed.find(v);
        if (it == placed.end()) return true;
        for (const Vec2 q : it->second) {
            if (distance(p, q) < spacing) return false;
        }
        return true;
    };
    std::vector<Vec2> kinks;
    for (const auto& c : faces) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = c[static_cast<std::size_t>(k)];
            const std::uint32_t b = c[static_cast<std::size_t>((k + 1) % 3)];
            for (const auto& [s, g] : {std::pair{a, b}, std::pair{b, a}}) {
                if (slope_face[s] == kNone || gentle_face[g] == kNone || slope_face[g] != kNone)
                    continue;
                const Vec2 d = position[g] - position[s];
                const double along_slope = dot(gradient[slope_face[s]], d);
                const double along_gentle = dot(gradient[gentle_face[g]], d);
                const double denom = along_slope - along_gentle;
                // The planes must cross the edge at clearly different slopes.
                if (!(std::abs(denom) >= 0.25 * std::abs(along_slope))) continue;
                const double t = (height[g] - along_gentle - height[s]) / denom;
                if (!(t > options.near && t < 1.0 - options.near)) continue;
                const Vec2 p = position[s] + d * t;
                const double spacing = options.near * length(d);
                if (!clear_of(s, p, spacing) || !clear_of(g, p, spacing)) continue;
                kinks.push_back(p);
                placed[s].push_back(p);
                placed[g].push_back(p);
            }
        }
    }
    return kinks;
}

}  // namespace sandtin
