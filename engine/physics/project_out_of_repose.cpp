#include "physics/project_out_of_repose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sandtin {

namespace {

/// A rim face within this share of its bound is at it, and a change of gradient above this share
/// of the bound is a change: ten times the projection's relative tolerance (1e-4).
constexpr double kRimSlack = 1e-3;

/// Each vertex's neighbours over the faces, as compressed rows.
struct Neighbours {
    std::vector<std::uint32_t> start;  // per vertex + 1
    std::vector<std::uint32_t> ids;

    Neighbours(std::size_t n, std::span<const std::array<std::uint32_t, 3>> faces) {
        start.assign(n + 1, 0);
        for (const auto& f : faces) {
            for (std::uint32_t v : f)
                start[v + 1] += 2;
        }
        for (std::size_t v = 0; v < n; ++v)
            start[v + 1] += start[v];
        ids.resize(start[n]);
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (const auto& f : faces) {
            for (int k = 0; k < 3; ++k) {
                ids[fill[f[k]]++] = f[(k + 1) % 3];
                ids[fill[f[k]]++] = f[(k + 2) % 3];
            }
        }
    }
    std::span<const std::uint32_t> of(std::uint32_t v) const {
        return {ids.data() + start[v], ids.data() + start[v + 1]};
    }
};

bool held_by_input(const ProjectionInput& in, std::size_t v) {
    return !in.held.empty() && in.held[v] != 0;
}

/// Phase 1: the corners (not held by the input) of the faces out of repose, and their count.
/// One face's gradient of `height` and its bound (tan(alpha), or its rock's own steepness
/// where that is steeper), as the projection sees them; nothing for a face of (near) zero area,
/// which the projection leaves to the local rule.
struct FaceSlope {
    Vec2 gradient;
    double bound = 0.0;
};
std::optional<FaceSlope> face_slope(const ProjectionInput& in, std::size_t f,
                                    std::span<const double> height) {
    const auto& c = in.faces[f];
    const Vec2 a = in.position[c[0]], b = in.position[c[1]], e = in.position[c[2]];
    const double scale = std::max({dot(b - a, b - a), dot(e - b, e - b), dot(a - e, a - e)});
    const double twice_area = cross(b - a, e - a);
    if (!(std::abs(twice_area) > 1e-12 * scale)) return std::nullopt;
    FaceSlope out;
    Vec2 rock_gradient;
    for (int k = 0; k < 3; ++k) {
        const Vec2 edge = in.position[c[(k + 2) % 3]] - in.position[c[(k + 1) % 3]];
        const Vec2 g = Vec2{-edge.y, edge.x} / twice_area;
        out.gradient += g * height[c[k]];
        rock_gradient += g * in.bedrock[c[k]];
    }
    const double rock = std::isfinite(length(rock_gradient)) ? length(rock_gradient) : 0.0;
    out.bound = std::max(in.face_tan_alpha[f], rock);
    return out;
}

std::vector<std::uint32_t> seeds_out_of_repose(const ProjectionInput& in, double tolerance,
                                               std::size_t& steep_faces) {
    std::vector<std::uint8_t> seeded(in.height.size(), 0);
    std::vector<std::uint32_t> seeds;
    steep_faces = 0;
    for (std::size_t f = 0; f < in.faces.size(); ++f) {
        const std::optional<FaceSlope> s = face_slope(in, f, in.height);
        if (!s || !(length(s->gradient) > s->bound * (1.0 + tolerance))) continue;
        ++steep_faces;
        for (std::uint32_t v : in.faces[f]) {
            if (!seeded[v] && !held_by_input(in, v)) {
                seeded[v] = 1;
                seeds.push_back(v);
            }
        }
    }
    return seeds;
}

/// Phase 2: the seeds and `rings` rings of their neighbours (never a vertex the input holds).
std::vector<std::uint8_t> grow_region(const ProjectionInput& in, const Neighbours& nb,
                                      const std::vector<std::uint32_t>& seeds, int rings) {
    std::vector<std::uint8_t> free(in.height.size(), 0);
    std::vector<std::uint32_t> frontier = seeds, next;
    for (std::uint32_t v : seeds)
        free[v] = 1;
    for (int ring = 0; ring < rings && !frontier.empty(); ++ring) {
        next.clear();
        for (std::uint32_t v : frontier) {
            for (std::uint32_t w : nb.of(v)) {
                if (free[w] || held_by_input(in, w)) continue;
                free[w] = 1;
                next.push_back(w);
            }
        }
        frontier.swap(next);
    }
    return free;
}

/// Does the region hold a vertex next to it that the input does not?
bool has_rim_around(const ProjectionInput& in, const Neighbours& nb,
                    const std::vector<std::uint8_t>& free) {
    for (std::uint32_t v = 0; v < free.size(); ++v) {
        if (free[v]) continue;
        if (held_by_input(in, v)) continue;
        for (std::uint32_t w : nb.of(v)) {
            if (free[w]) return true;
        }
    }
    return false;
}

/// Phase 3, first: can the region hold its sand at all? No surface in it stands above the
/// held vertices plus tan(alpha) times the path length from them (along edges: at least the
/// straight distance, so this bound errs on the side of room), or below its rock. Sand beyond
/// that bound has no feasible surface, and the projection would spend its whole iteration
/// budget finding out: such a region grows at once.
bool can_hold(const ProjectionInput& in, const Neighbours& nb,
              const std::vector<std::uint8_t>& free, const std::vector<double>& vertex_tan) {
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    std::vector<double> top(free.size(), std::numeric_limits<double>::infinity());
    for (std::uint32_t v = 0; v < free.size(); ++v) {
        if (free[v]) continue;
        for (std::uint32_t w : nb.of(v)) {
            if (!free[w]) continue;
            top[v] = in.height[v];  // a held vertex next to the region: a source
            queue.push({top[v], v});
            break;
        }
    }
    if (queue.empty()) return true;  // nothing held around it: any volume fits
    while (!queue.empty()) {
        const auto [h, v] = queue.top();
        queue.pop();
        if (h > top[v]) continue;
        for (std::uint32_t w : nb.of(v)) {
            if (!free[w]) continue;
            const double reach = h + std::max(vertex_tan[v], vertex_tan[w]) *
                                         length(in.position[w] - in.position[v]);
            if (reach < top[w]) {
                top[w] = reach;
                queue.push({reach, w});
            }
        }
    }
    double sand = 0.0, room = 0.0;
    for (std::uint32_t v = 0; v < free.size(); ++v) {
        if (!free[v]) continue;
        sand += in.area[v] * in.height[v];
        room += in.area[v] * std::max(top[v], in.bedrock[v]);
    }
    return sand <= room;
}

/// Phase 4: does the settled sand press against the region's rim? The held vertices change
/// the answer only through the faces they share with free ones: where each such face is below
/// its bound, or stands at it as it already stood in the input, the region's projection
/// satisfies the whole terrain's optimality conditions (zero multipliers on those faces), and
/// holding the rim changed nothing. A face the projection brought up to its bound is pressed.
/// (Judged on gradients against the bound, not on heights: ADMM's tolerance left heights at the
/// rim of a 0.1 m step moving by 5e-5 m with no face near its bound.) Also says whether the
/// region has a rim at all (a vertex it holds that the input does not).
bool rim_pressed(const ProjectionInput& in, const std::vector<std::uint8_t>& free,
                 const std::vector<double>& height, bool& has_rim) {
    has_rim = false;
    bool pressed = false;
    for (std::size_t f = 0; f < in.faces.size() && !pressed; ++f) {
        bool any_free = false, any_rim = false;
        for (std::uint32_t v : in.faces[f]) {
            any_free = any_free || free[v];
            any_rim = any_rim || (!free[v] && !held_by_input(in, v));
        }
        if (!any_free || !any_rim) continue;
        has_rim = true;
        const std::optional<FaceSlope> now = face_slope(in, f, height);
        if (!now || length(now->gradient) < now->bound * (1.0 - kRimSlack)) continue;
        const std::optional<FaceSlope> before = face_slope(in, f, in.height);
        pressed = length(now->gradient - before->gradient) > kRimSlack * now->bound;
    }
    return pressed;
}

}  // namespace

ReposeProjection project_out_of_repose(const ProjectionInput& input,
                                       const ReposeProjectionOptions& options,
                                       const OutOfReposeOptions& region_options,
                                       OutOfReposeReport* report) {
    if (!(region_options.steepness_tolerance >= 0.0) || region_options.first_rings < 1)
        throw std::invalid_argument(
            "settle out of repose: steepness_tolerance must be >= 0 and first_rings >= 1");
    const std::size_t n = input.height.size();
    if (input.position.size() != n || input.bedrock.size() != n || input.area.size() != n ||
        input.face_tan_alpha.size() != input.faces.size() ||
        (!input.held.empty() && input.held.size() != n))
        throw std::invalid_argument("settle out of repose: the input's arrays disagree in size");
    for (const auto& f : input.faces) {
        for (std::uint32_t v : f) {
            if (v >= n) throw std::invalid_argument("settle out of repose: a face names no vertex");
        }
    }
    OutOfReposeReport local;
    OutOfReposeReport& r = report != nullptr ? *report : local;
    r = {};
    const std::vector<std::uint32_t> seeds =
        seeds_out_of_repose(input, region_options.steepness_tolerance, r.steep_faces);
    if (seeds.empty()) {
        ReposeProjection rest;
        rest.height = input.height;
        rest.converged = true;
        if (options.on_progress) options.on_progress(1.0);
        return rest;
    }
    const Neighbours nb(n, input.faces);
    // Each vertex's steepest bound over its faces, for can_hold's (generous) room.
    std::vector<double> vertex_tan(n, 0.0);
    for (std::size_t f = 0; f < input.faces.size(); ++f) {
        for (std::uint32_t v : input.faces[f])
            vertex_tan[v] = std::max(vertex_tan[v], input.face_tan_alpha[f]);
    }
    double shown = 0.0;  // the bar: each round fills half of what is left of it
    ReposeProjection result;
    std::size_t last_size = 0;
    for (int rings = region_options.first_rings;; rings *= 2) {
        const std::vector<std::uint8_t> free = grow_region(input, nb, seeds, rings);
        // Too small: grow first (unless it can grow no more, walled in by held vertices).
        const auto size = static_cast<std::size_t>(std::count(free.begin(), free.end(), 1));
        const bool grew = std::exchange(last_size, size) != size;
        if (grew && !can_hold(input, nb, free, vertex_tan)) continue;
        std::vector<std::uint8_t> held(n);
        for (std::size_t v = 0; v < n; ++v)
            held[v] = free[v] ? 0 : 1;
        ReposeProjectionOptions round = options;
        round.rho_per_area = region_options.rho_per_area;
        bool has_rim = false, reached = false;
        const auto project_region = [&](int max_iterations) {
            round.max_iterations = max_iterations;
            const double from = shown;
            if (options.on_progress) {
                round.on_progress = [&, from](double f) {
                    shown = std::max(shown, from + 0.5 * (0.99 - from) * f);
                    options.on_progress(shown);
                };
            }
            result = project_onto_repose({input.position, input.faces, input.face_tan_alpha,
                                          input.area, input.height, input.bedrock, held},
                                         round);
            ++r.rounds;
            r.rings = rings;
            r.free_vertices = result.free_vertices;
            reached = rim_pressed(input, free, result.height, has_rim);
            r.whole_terrain = !has_rim;
        };
        // A region with a rim first has a quarter of the budget: one too small for the settled
        // pile has no feasible surface, and ADMM would spend the whole budget finding out (a
        // face pressed between held vertices and the rock stayed 1.0002 steep for 20 000
        // iterations on a rock slope; grown, it converged in 1 242).
        const bool rimmed = has_rim_around(input, nb, free);
        project_region(rimmed ? std::max(1, options.max_iterations / 4) : options.max_iterations);
        // Not converged, but the sand kept off the rim: slow (a random TIN's slivers), not too
        // small. The same region again with the whole budget.
        if (rimmed && !result.converged && !reached) project_region(options.max_iterations);
        if (!has_rim || (result.converged && !reached)) break;
        // The sand pressed against the rim, or found no room: grow.
    }
    if (options.on_progress) options.on_progress(1.0);
    return result;
}

}  // namespace sandtin
