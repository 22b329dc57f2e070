#include "stress/random_operation.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace sandtin {

namespace {

nlohmann::json xy(Vec2 p) {
    return nlohmann::json::array({p.x, p.y});
}

}  // namespace

RandomOperations::RandomOperations(std::uint64_t seed, Rect domain, std::string save_path)
    : rng_(seed), domain_(domain), save_path_(std::move(save_path)) {}

double RandomOperations::uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
}

bool RandomOperations::chance(double p) {
    return uniform(0.0, 1.0) < p;
}

Vec2 RandomOperations::point(double outside_margin) {
    return {uniform(domain_.min.x - outside_margin, domain_.max.x + outside_margin),
            uniform(domain_.min.y - outside_margin, domain_.max.y + outside_margin)};
}

nlohmann::json RandomOperations::random_tool() {
    const double size = std::max(domain_.width(), domain_.height());
    const double r = size * uniform(0.006, 0.03);
    nlohmann::json t;
    switch (std::uniform_int_distribution<int>(0, 9)(rng_)) {
        case 0:
            t = {{"asset", "circle"}, {"radius", r}};
            break;
        case 1:
            t = {{"asset", "box"}, {"width", 2 * r}, {"length", uniform(0.5, 2.0) * r}};
            break;
        case 2:
            t = {{"asset", "lambda"}, {"scale", r / 5.0}};  // its polygon spans ±5 units
            break;
        case 3:
            t = {{"asset", "ball"}, {"radius", r}};
            break;
        case 4:
            t = {{"asset", "foot"}, {"scale", uniform(0.5, 1.5)}};
            break;
        case 5:
            t = {{"asset", "rake"}, {"scale", uniform(0.5, 1.5)}};
            break;
        case 6: {  // a random star-shaped polygon, convex or not
            const int n = std::uniform_int_distribution<int>(3, 9)(rng_);
            nlohmann::json poly = nlohmann::json::array();
            for (int k = 0; k < n; ++k) {
                const double a = 2.0 * std::numbers::pi * (k + uniform(0.0, 0.8)) / n;
                const double rr = r * uniform(0.4, 1.0);
                poly.push_back({rr * std::cos(a), rr * std::sin(a)});
            }
            t = {{"contour", "polygon"}, {"polygon", poly}, {"profile", "flat"}};
            break;
        }
        case 7:  // degenerate: self-intersecting bow tie (must be rejected with a clear error)
            t = {{"contour", "polygon"},
                 {"polygon", {{-r, -r}, {r, r}, {r, -r}, {-r, r}}},
                 {"profile", "flat"}};
            break;
        case 8:  // degenerate: zero radius (rejected) or a tool at the snapping scale
            t = {{"asset", "circle"}, {"radius", chance(0.5) ? 0.0 : size * 2e-6}};
            break;
        default:
            t = {{"contour", "rectangle"},
                 {"width", r},
                 {"length", 2 * r},
                 {"profile", "half_sphere"},
                 {"sphere_radius", 2 * r}};
            break;
    }
    if (chance(0.15)) t["extrude"] = true;
    if (chance(0.1)) t["mode"] = "level";
    return t;
}

nlohmann::json RandomOperations::stamp() {
    nlohmann::json op = {{"op", "stamp"}, {"tool", random_tool()}};
    const double size = std::max(domain_.width(), domain_.height());
    // Mostly inside; some straddle the border, a few are wholly outside.
    op["at"] = xy(chance(0.05) ? Vec2{domain_.max.x + 0.5 * size, domain_.min.y - 0.5 * size}
                               : point(0.05 * size));
    op["angle"] = uniform(-std::numbers::pi, std::numbers::pi);
    if (chance(0.2)) {
        op["bottom"] = uniform(-0.02, 0.2);
    } else {
        op["depth"] = chance(0.1) ? 0.0 : uniform(0.0, 0.05);
    }
    return op;
}

nlohmann::json RandomOperations::stroke(const Tin& tin) {
    nlohmann::json op = {{"op", "stroke"}, {"tool", random_tool()}};
    const double size = std::max(domain_.width(), domain_.height());
    nlohmann::json path = nlohmann::json::array();
    const double kind = uniform(0.0, 1.0);
    if (kind < 0.15 && tin.constraint_count() > 0) {
        // Exactly along an existing constrained polyline.
        const std::vector<ConstraintInfo> all = tin.constraints();
        const ConstraintInfo& c =
            all[std::uniform_int_distribution<std::size_t>(0, all.size() - 1)(rng_)];
        for (VertexId v : c.vertices)
            path.push_back(xy(tin.position(v)));
        op["spacing"] = size * uniform(0.03, 0.08);
    } else if (kind < 0.22) {
        // Straight across the whole domain: crosses many old constraints.
        const double y0 = uniform(domain_.min.y, domain_.max.y);
        const double y1 = uniform(domain_.min.y, domain_.max.y);
        path.push_back(xy({domain_.min.x, y0}));
        path.push_back(xy({domain_.max.x, y1}));
        op["spacing"] = size * uniform(0.08, 0.2);
    } else {
        const int n = std::uniform_int_distribution<int>(2, 5)(rng_);
        Vec2 p = point(0.05 * size);
        for (int k = 0; k < n; ++k) {
            path.push_back(xy(p));
            p = p + Vec2{uniform(-0.03, 0.03), uniform(-0.03, 0.03)} * size;
        }
        op["curve"] = chance(0.5);
    }
    op["path"] = path;
    if (!op.contains("spacing")) op["spacing"] = size * uniform(0.01, 0.04);
    op["depth"] = uniform(0.0, 0.04);
    op["follow_path"] = chance(0.8);
    if (chance(0.2)) {
        op["erode"] = true;
        op["erode_iterations"] = std::uniform_int_distribution<int>(1, 4)(rng_);
    }
    return op;
}

nlohmann::json RandomOperations::pour() {
    const double size = std::max(domain_.width(), domain_.height());
    const bool remove = chance(0.35);
    nlohmann::json op = {{"op", remove ? "remove" : "pour"},
                         {"volume", size * size * size * uniform(0.0, 2e-4)},
                         {"radius", size * uniform(0.01, 0.08)}};
    if (chance(0.3)) {
        op["path"] = {xy(point(0.0)), xy(point(0.0))};
        op["spacing"] = size * 0.02;
    } else {
        op["at"] = xy(point(0.02 * size));
    }
    return op;
}

nlohmann::json RandomOperations::brush() {
    static constexpr std::array<const char*, 5> kinds = {"raise", "lower", "smooth", "flatten",
                                                         "paint"};
    const double size = std::max(domain_.width(), domain_.height());
    const char* kind = kinds[std::uniform_int_distribution<std::size_t>(0, kinds.size() - 1)(rng_)];
    nlohmann::json op = {{"op", "brush"},
                         {"kind", kind},
                         {"at", xy(point(0.03 * size))},
                         {"radius", size * uniform(0.01, 0.08)}};
    const std::string k = kind;
    if (k == "raise" || k == "lower") op["strength"] = size * uniform(0.0, 0.004);
    if (k == "smooth" || k == "flatten") op["strength"] = uniform(0.0, 1.0);
    if (k == "paint") op["material"] = std::uniform_int_distribution<int>(0, 2)(rng_);
    return op;
}

nlohmann::json RandomOperations::erode() {
    if (chance(0.05)) return {{"op", "erode"}, {"until_rest", true}, {"max_iterations", 100}};
    return {{"op", "erode"}, {"iterations", std::uniform_int_distribution<int>(1, 12)(rng_)}};
}

nlohmann::json RandomOperations::next(const Tin& tin) {
    const double x = uniform(0.0, 100.0);
    if (x < 35) return stamp();
    if (x < 50) return stroke(tin);
    if (x < 61) return pour();
    if (x < 76) return brush();
    if (x < 92) return erode();
    if (x < 99) {
        nlohmann::json op = {{"op", "simplify"}};
        if (chance(0.5)) op["tolerance"] = uniform(1e-4, 5e-3);
        return op;
    }
    return {{"op", "save"}, {"path", save_path_}};
}

}  // namespace sandtin
