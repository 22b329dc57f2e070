#include "water/shallow_water.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace sandtin {

namespace {

/// A flux across a unit of interface: m²/s of water and m³/s² of momentum.
struct Flux {
    double mass = 0.0;
    Vec2 momentum;
};

Flux physical_flux(double h, Vec2 u, Vec2 n, double g) {
    const double un = dot(u, n);
    return {h * un, (h * un) * u + (0.5 * g * h * h) * n};
}

/// The HLL flux across unit normal n between a left state (h_l, u_l) and a right one, with
/// Einfeldt's wave speeds, or Toro's when one side is dry.
Flux hll(double h_l, Vec2 u_l, double h_r, Vec2 u_r, Vec2 n, double g) {
    if (!(h_l > 0.0) && !(h_r > 0.0)) return {};
    const double un_l = dot(u_l, n), un_r = dot(u_r, n);
    const double c_l = std::sqrt(g * h_l), c_r = std::sqrt(g * h_r);
    double s_l, s_r;
    if (!(h_l > 0.0)) {
        s_l = un_r - 2.0 * c_r;
        s_r = un_r + c_r;
    } else if (!(h_r > 0.0)) {
        s_l = un_l - c_l;
        s_r = un_l + 2.0 * c_l;
    } else {
        const double w_l = std::sqrt(h_l), w_r = std::sqrt(h_r);
        const double un_roe = (w_l * un_l + w_r * un_r) / (w_l + w_r);
        const double c_roe = std::sqrt(0.5 * g * (h_l + h_r));
        s_l = std::min(un_l - c_l, un_roe - c_roe);
        s_r = std::max(un_r + c_r, un_roe + c_roe);
    }
    const Flux f_l = physical_flux(h_l, u_l, n, g);
    if (s_l >= 0.0) return f_l;
    const Flux f_r = physical_flux(h_r, u_r, n, g);
    if (s_r <= 0.0) return f_r;
    const double scale = 1.0 / (s_r - s_l);
    const double jump = s_l * s_r;
    return {(s_r * f_l.mass - s_l * f_r.mass + jump * (h_r - h_l)) * scale,
            (s_r * f_l.momentum - s_l * f_r.momentum + jump * (h_r * u_r - h_l * u_l)) * scale};
}

void check_options(const ShallowWaterOptions& o) {
    if (!(o.gravity > 0.0) || !std::isfinite(o.gravity) || !(o.manning >= 0.0) ||
        !std::isfinite(o.manning) || !(o.courant > 0.0) || !(o.courant <= 0.5) ||
        !(o.dry_depth > 0.0) || !std::isfinite(o.dry_depth) || (o.order != 1 && o.order != 2))
        throw std::invalid_argument(
            "shallow water: gravity must be > 0, manning >= 0, courant in (0, 0.5], "
            "dry_depth > 0 and order 1 or 2");
}

/// Vec2 rotated a quarter turn clockwise.
Vec2 clockwise(Vec2 v) {
    return {v.y, -v.x};
}

}  // namespace

ShallowWater::ShallowWater(WaterMesh mesh, ShallowWaterOptions options)
    : mesh_(std::move(mesh)), options_(options) {
    check_options(options_);
    // The same checks as the pipes' (sizes, corners, finite values), by building none.
    const std::size_t n = mesh_.position.size();
    if (mesh_.area.size() != n || mesh_.bed.size() != n)
        throw std::invalid_argument(
            "shallow water: position, area and bed must have one entry per vertex");
    for (const auto& f : mesh_.faces) {
        for (std::uint32_t v : f) {
            if (v >= n)
                throw std::invalid_argument("shallow water: face corner " + std::to_string(v) +
                                            " is not a vertex");
        }
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (!is_finite(mesh_.position[v]) || !std::isfinite(mesh_.bed[v]))
            throw std::invalid_argument("shallow water: vertex " + std::to_string(v) +
                                        " has a non-finite position or bed");
    }
    build_cells();
}

void ShallowWater::build_cells() {
    const std::size_t n = mesh_.position.size();
    mesh_.area.assign(n, 0.0);
    wall_.assign(n, Vec2{});
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<Vec2, int>> edges;
    for (auto f : mesh_.faces) {
        const Vec2 p0 = mesh_.position[f[0]], p1 = mesh_.position[f[1]], p2 = mesh_.position[f[2]];
        double twice = cross(p1 - p0, p2 - p0);
        if (twice < 0.0) {
            std::swap(f[1], f[2]);
            twice = -twice;
        }
        if (!(twice > 0.0)) continue;  // no area: no cell part, no interface
        const Vec2 centroid =
            (1.0 / 3.0) * (mesh_.position[f[0]] + mesh_.position[f[1]] + mesh_.position[f[2]]);
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[k], b = f[(k + 1) % 3];
            mesh_.area[a] += twice / 6.0;
            // Counter-clockwise, the centroid lies left of a -> b: the segment from the edge's
            // midpoint to it, turned clockwise, points from a's side to b's.
            const Vec2 mid = 0.5 * (mesh_.position[a] + mesh_.position[b]);
            const Vec2 from_a = clockwise(centroid - mid);
            auto& [normal, faces] = edges[{std::min(a, b), std::max(a, b)}];
            normal = normal + (a < b ? from_a : -1.0 * from_a);
            ++faces;
        }
    }
    interfaces_.clear();
    interfaces_.reserve(edges.size());
    for (const auto& [ends, value] : edges)
        interfaces_.push_back({ends.first, ends.second, value.first, 0.0});
    // A border vertex's cell owns half of each of its border edges, facing out. The cell
    // closes, so that part is B_i = -sum_j N_ij: taken from the closure rather than from a
    // second geometric path, a lake at rest balances to rounding at every border vertex.
    for (const Interface& f : interfaces_) {
        wall_[f.a] = wall_[f.a] - f.normal;
        wall_[f.b] = wall_[f.b] + f.normal;
    }
    for (Interface& f : interfaces_)
        f.span = length(f.normal);
    // Interior cells close exactly in exact arithmetic; what rounding leaves is not border.
    std::vector<std::uint8_t> border(n, 0);
    for (const auto& [ends, value] : edges) {
        if (value.second == 1) border[ends.first] = border[ends.second] = 1;
    }
    wall_span_.assign(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        if (!border[v]) wall_[v] = Vec2{};
        wall_span_[v] = length(wall_[v]);
    }
    depth_.assign(n, 0.0);
    discharge_.assign(n, Vec2{});
    open_.assign(n, 0);
    residual_.assign(n, {0.0, 0.0, 0.0});
    slopes_.assign(n, Slopes{});
    outgoing_.assign(n, 0.0);
    scratch_.resize(n);
    half_.resize(interfaces_.size());
    for (std::size_t k = 0; k < interfaces_.size(); ++k) {
        const Interface& f = interfaces_[k];
        half_[k] = 0.5 * (mesh_.position[f.b] - mesh_.position[f.a]);
    }
    border_.assign(n, BorderFlux{});
    flux_.assign(interfaces_.size(), InterfaceFlux{});
}

Vec2 ShallowWater::velocity(std::size_t v) const {
    return velocity_of(depth_[v], discharge_[v]);
}

Vec2 ShallowWater::velocity_of(double h, Vec2 q) const {
    return h > options_.dry_depth ? (1.0 / h) * q : Vec2{};
}

void ShallowWater::set_state(std::size_t v, double depth, Vec2 velocity) {
    if (v >= depth_.size())
        throw std::invalid_argument("shallow water: no vertex " + std::to_string(v));
    if (!(depth >= 0.0) || !std::isfinite(depth) || !is_finite(velocity))
        throw std::invalid_argument(
            "shallow water: a depth must be finite and >= 0, a velocity finite");
    if (depth > 0.0 && !(mesh_.area[v] > 0.0))
        throw std::invalid_argument("shallow water: vertex " + std::to_string(v) +
                                    " has no cell to hold water");
    depth_[v] = depth;
    discharge_[v] = depth * velocity;
    moving_ = moving_ || depth > 0.0;
}

void ShallowWater::add_water(std::size_t v, double volume) {
    if (v >= depth_.size())
        throw std::invalid_argument("shallow water: no vertex " + std::to_string(v));
    if (!(mesh_.area[v] > 0.0))
        throw std::invalid_argument("shallow water: vertex " + std::to_string(v) +
                                    " has no cell to hold water");
    const Vec2 q = discharge_[v];
    set_state(v, depth_[v] + volume / mesh_.area[v]);
    discharge_[v] = q;  // the new water brings no momentum; the old keeps its own
}

double ShallowWater::volume() const {
    double sum = 0.0;
    for (std::size_t v = 0; v < depth_.size(); ++v)
        sum += mesh_.area[v] * depth_[v];
    return sum;
}

void ShallowWater::set_open_border(std::size_t v, bool open) {
    if (v >= depth_.size())
        throw std::invalid_argument("shallow water: no vertex " + std::to_string(v));
    open_[v] = open && on_border(v) ? 1 : 0;
}

void ShallowWater::set_bed(std::size_t v, double z) {
    if (v >= depth_.size())
        throw std::invalid_argument("shallow water: no vertex " + std::to_string(v));
    if (!std::isfinite(z)) throw std::invalid_argument("shallow water: a bed must be finite");
    mesh_.bed[v] = z;
}

double ShallowWater::stable_time_step() const {
    const double g = options_.gravity;
    // Per cell: the fastest wave it meets (a dry neighbour's front runs at |u| + 2c) times
    // its perimeter, against its area.
    std::vector<double>& reach = scratch_.reach;
    std::fill(reach.begin(), reach.end(), 0.0);
    bool wet = false;
    for (std::size_t v = 0; v < depth_.size(); ++v) {
        if (!(depth_[v] > 0.0)) continue;
        wet = true;
        const Vec2 u = velocity(v);
        reach[v] = std::sqrt(dot(u, u)) + 2.0 * std::sqrt(g * depth_[v]);
    }
    if (!wet) return std::numeric_limits<double>::infinity();
    double limit = std::numeric_limits<double>::infinity();
    std::vector<double>& sum = scratch_.sum;
    std::fill(sum.begin(), sum.end(), 0.0);
    for (const Interface& f : interfaces_) {
        const double s = std::max(reach[f.a], reach[f.b]) * f.span;
        sum[f.a] += s;
        sum[f.b] += s;
    }
    for (std::size_t v = 0; v < depth_.size(); ++v) {
        sum[v] += reach[v] * wall_span_[v];
        if (sum[v] > 0.0 && mesh_.area[v] > 0.0) limit = std::min(limit, mesh_.area[v] / sum[v]);
    }
    return options_.courant * limit;
}

void ShallowWater::reconstruct(std::span<const double> h) {
    // Green-Gauss gradients over the median dual, of the surface eta = z + h, the depth and
    // the two velocities; then Barth and Jespersen's limiter, which keeps every reconstructed
    // value within the cell's and its neighbours' (so depths stay >= 0). A cell that is dry
    // or has a dry neighbour stays first order: at a shore the surface's slope is the bed's.
    const std::size_t n = h.size();
    auto& value = scratch_.value;
    auto& lo = scratch_.lo;
    auto& hi = scratch_.hi;
    auto& gradient = scratch_.gradient;
    auto& limiter = scratch_.limiter;
    for (std::size_t v = 0; v < n; ++v) {
        const Vec2 u = scratch_.velocity[v];
        value[v] = {mesh_.bed[v] + h[v], h[v], u.x, u.y};
        lo[v] = value[v];
        hi[v] = value[v];
        gradient[v] = {};
        limiter[v] = {1.0, 1.0, 1.0, 1.0};
        slopes_[v] = Slopes{};
        slopes_[v].first_order = !(h[v] > options_.dry_depth);
    }
    for (const Interface& f : interfaces_) {
        const bool dry = !(h[f.a] > options_.dry_depth) || !(h[f.b] > options_.dry_depth);
        slopes_[f.a].first_order = slopes_[f.a].first_order || dry;
        slopes_[f.b].first_order = slopes_[f.b].first_order || dry;
        for (int k = 0; k < 4; ++k) {
            const double mean = 0.5 * (value[f.a][k] + value[f.b][k]);
            gradient[f.a][k] += mean * f.normal;
            gradient[f.b][k] -= mean * f.normal;
            lo[f.a][k] = std::min(lo[f.a][k], value[f.b][k]);
            hi[f.a][k] = std::max(hi[f.a][k], value[f.b][k]);
            lo[f.b][k] = std::min(lo[f.b][k], value[f.a][k]);
            hi[f.b][k] = std::max(hi[f.b][k], value[f.a][k]);
        }
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (slopes_[v].first_order || !(mesh_.area[v] > 0.0)) continue;
        for (int k = 0; k < 4; ++k)
            gradient[v][k] = (1.0 / mesh_.area[v]) * (gradient[v][k] + value[v][k] * wall_[v]);
    }
    const auto limit_side = [&](std::size_t v, Vec2 r) {
        if (slopes_[v].first_order) return;
        for (int k = 0; k < 4; ++k) {
            const double change = dot(gradient[v][k], r);
            double phi = 1.0;
            if (change > 0.0) phi = (hi[v][k] - value[v][k]) / change;
            if (change < 0.0) phi = (lo[v][k] - value[v][k]) / change;
            limiter[v][k] = std::min(limiter[v][k], std::max(0.0, phi));
        }
    };
    for (std::size_t k = 0; k < interfaces_.size(); ++k) {
        const Interface& f = interfaces_[k];
        limit_side(f.a, half_[k]);
        limit_side(f.b, -1.0 * half_[k]);
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (slopes_[v].first_order) continue;
        slopes_[v].surface = limiter[v][0] * gradient[v][0];
        slopes_[v].depth = limiter[v][1] * gradient[v][1];
        slopes_[v].u = limiter[v][2] * gradient[v][2];
        slopes_[v].v = limiter[v][3] * gradient[v][3];
    }
}

ShallowWater::Side ShallowWater::side_at(std::span<const double> h, std::size_t v, Vec2 r) const {
    const Slopes& s = slopes_[v];
    Side side;
    side.velocity = scratch_.velocity[v];
    side.depth = h[v];
    side.bed = mesh_.bed[v];
    if (second_order() && !s.first_order) {
        side.depth = std::max(0.0, h[v] + dot(s.depth, r));
        const double surface = mesh_.bed[v] + h[v] + dot(s.surface, r);
        side.bed = surface - side.depth;
        side.velocity = side.velocity + Vec2{dot(s.u, r), dot(s.v, r)};
    }
    return side;
}

double ShallowWater::residual(std::span<const double> h, std::span<const Vec2> q, double dt,
                              double weight) {
    const double g = options_.gravity;
    for (auto& r : residual_)
        r = {0.0, 0.0, 0.0};
    for (std::size_t v = 0; v < h.size(); ++v)
        scratch_.velocity[v] = velocity_of(h[v], q[v]);
    if (second_order()) reconstruct(h);
    // Phase 1: interfaces, with the hydrostatic reconstruction.
    for (std::size_t k = 0; k < interfaces_.size(); ++k) {
        const Interface& f = interfaces_[k];
        InterfaceFlux& out = flux_[k];
        out = InterfaceFlux{};
        if (!(h[f.a] > 0.0) && !(h[f.b] > 0.0)) continue;
        const double span = f.span;
        if (!(span > 0.0)) continue;
        const Vec2 n = (1.0 / span) * f.normal;
        const Side a = side_at(h, f.a, half_[k]);
        const Side b = side_at(h, f.b, -1.0 * half_[k]);
        const double top = std::max(a.bed, b.bed);
        const double star_a = std::max(0.0, a.depth + a.bed - top);
        const double star_b = std::max(0.0, b.depth + b.bed - top);
        const Flux flux = hll(star_a, a.velocity, star_b, b.velocity, n, g);
        // Each side's pressure correction, and (second order) the bed's slope within its cell
        // (Audusse et al.): g (h + h_side) / 2 (z_side - z); together, at rest, they sum to
        // g/2 h² over the closed cell.
        const Vec2 push_a = (0.5 * g * (a.depth * a.depth - star_a * star_a) +
                             0.5 * g * (h[f.a] + a.depth) * (a.bed - mesh_.bed[f.a])) *
                            f.normal;
        const Vec2 push_b = (0.5 * g * (b.depth * b.depth - star_b * star_b) +
                             0.5 * g * (h[f.b] + b.depth) * (b.bed - mesh_.bed[f.b])) *
                            f.normal;
        out = {span * flux.mass, span * flux.momentum, push_a, push_b};
    }
    // Phase 2: the border: walls reflect, open parts let the water leave as it comes.
    for (std::size_t v = 0; v < h.size(); ++v) {
        border_[v] = BorderFlux{};
        const double span = wall_span_[v];
        if (!(h[v] > 0.0) || !(span > 0.0)) continue;
        const Vec2 n = (1.0 / span) * wall_[v];
        const Vec2 u = scratch_.velocity[v];
        const double un = dot(u, n);
        Flux f;
        if (open_[v] && un > 0.0) {
            f = physical_flux(h[v], u, n, g);  // free outflow
        } else {
            f = hll(h[v], u, h[v], u - (2.0 * un) * n, n, g);  // a wall: the mirrored state
            f.mass = 0.0;  // by symmetry; rounding must not leak water through a wall
        }
        border_[v] = {span * f.mass, span * f.momentum};
    }
    // Phase 3: no cell gives more water than it holds. Under the time step the first-order
    // scheme never does; the reconstruction can (a thin film beside a deep cell), and then the
    // cell's outflows are scaled down together, as the pipes' are, and the volume stays exact.
    for (std::size_t v = 0; v < h.size(); ++v)
        outgoing_[v] = border_[v].mass;
    for (std::size_t k = 0; k < interfaces_.size(); ++k) {
        const double mass = flux_[k].mass;
        if (mass > 0.0) outgoing_[interfaces_[k].a] += mass;
        if (mass < 0.0) outgoing_[interfaces_[k].b] -= mass;
    }
    for (std::size_t v = 0; v < h.size(); ++v) {
        const double wanted = outgoing_[v] * dt;
        const double held = h[v] * mesh_.area[v];
        outgoing_[v] = wanted > held ? held / wanted : 1.0;
    }
    // Phase 4: the residuals.
    for (std::size_t k = 0; k < interfaces_.size(); ++k) {
        Interface& f = interfaces_[k];
        InterfaceFlux& x = flux_[k];
        if (x.mass == 0.0 && x.momentum == Vec2{} && x.push_a == Vec2{} && x.push_b == Vec2{})
            continue;
        const double scale = outgoing_[x.mass > 0.0 ? f.a : f.b];
        const double mass = scale * x.mass;
        const Vec2 momentum = scale * x.momentum;
        f.flux += weight * mass;
        residual_[f.a][0] -= mass;
        residual_[f.a][1] -= momentum.x + x.push_a.x;
        residual_[f.a][2] -= momentum.y + x.push_a.y;
        residual_[f.b][0] += mass;
        residual_[f.b][1] += momentum.x + x.push_b.x;
        residual_[f.b][2] += momentum.y + x.push_b.y;
    }
    double leaving = 0.0;  // m³/s through open borders
    for (std::size_t v = 0; v < h.size(); ++v) {
        const BorderFlux& b = border_[v];
        if (b.mass == 0.0 && b.momentum == Vec2{}) continue;
        const double scale = b.mass > 0.0 ? outgoing_[v] : 1.0;
        leaving += scale * b.mass;
        residual_[v][0] -= scale * b.mass;
        residual_[v][1] -= scale * b.momentum.x;
        residual_[v][2] -= scale * b.momentum.y;
    }
    return leaving;
}

std::size_t ShallowWater::advance(double dt, std::span<const double> h, std::span<const Vec2> q,
                                  std::vector<double>& out_h, std::vector<Vec2>& out_q) const {
    const double n2g = options_.manning * options_.manning * options_.gravity;
    std::size_t clamped = 0;
    for (std::size_t v = 0; v < h.size(); ++v) {
        const auto& r = residual_[v];
        if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0 && q[v] == Vec2{}) {
            out_h[v] = h[v];
            out_q[v] = q[v];
            continue;
        }
        const double scale = dt / mesh_.area[v];
        double depth = h[v] + scale * r[0];
        if (depth < 0.0) {
            // A cell its outflows emptied (phase 3) lands within rounding of 0; anything more
            // is a time step too long, counted for the caller.
            if (depth < -1e-9 * h[v]) ++clamped;
            depth = 0.0;
        }
        Vec2 discharge = q[v] + Vec2{scale * r[1], scale * r[2]};
        if (depth > options_.dry_depth) {
            if (n2g > 0.0) {
                // Manning's friction, semi-implicit: stable however shallow the water.
                const double speed = std::sqrt(dot(discharge, discharge)) / depth;
                discharge =
                    (1.0 / (1.0 + dt * n2g * speed / std::pow(depth, 4.0 / 3.0))) * discharge;
            }
        } else {
            discharge = Vec2{};  // too shallow to move
        }
        out_h[v] = depth;
        out_q[v] = discharge;
    }
    return clamped;
}

WaterStepReport ShallowWater::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::invalid_argument("shallow water: a time step must be finite and > 0");
    WaterStepReport report;
    if (!moving_) return report;  // dry: nothing to do
    for (Interface& f : interfaces_)
        f.flux = 0.0;
    if (!second_order()) {
        volume_left_ += dt * residual(depth_, discharge_, dt, 1.0);
        report.outflows_limited = advance(dt, depth_, discharge_, depth_, discharge_);
    } else {
        // Heun's method (SSP Runge-Kutta 2): U1 = U + dt L(U), U = (U + U1 + dt L(U1)) / 2.
        // Each stage moves water between cells only, so the average keeps the volume.
        stage_h_ = depth_;
        stage_q_ = discharge_;
        double leaving = residual(depth_, discharge_, dt, 0.5);
        report.outflows_limited = advance(dt, depth_, discharge_, stage_h_, stage_q_);
        leaving += residual(stage_h_, stage_q_, dt, 0.5);
        report.outflows_limited += advance(dt, stage_h_, stage_q_, stage_h_, stage_q_);
        for (std::size_t v = 0; v < depth_.size(); ++v) {
            depth_[v] = 0.5 * (depth_[v] + stage_h_[v]);
            discharge_[v] = 0.5 * (discharge_[v] + stage_q_[v]);
            if (!(depth_[v] > options_.dry_depth)) discharge_[v] = Vec2{};
        }
        volume_left_ += 0.5 * dt * leaving;
    }
    bool wet = false;
    for (double d : depth_)
        wet = wet || d > 0.0;
    for (const Interface& f : interfaces_)
        report.pipes_updated += f.flux != 0.0 ? 1 : 0;
    moving_ = wet;
    return report;
}

}  // namespace sandtin
