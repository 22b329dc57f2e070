#include "water/virtual_pipes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "util/thread_pool.hpp"

namespace sandtin {

namespace {

void check(const WaterMesh& m) {
    const std::size_t n = m.position.size();
    if (m.area.size() != n || m.bed.size() != n)
        throw std::invalid_argument("water: position, area and bed must have one entry per vertex");
    for (const auto& f : m.faces) {
        for (std::uint32_t v : f) {
            if (v >= n)
                throw std::invalid_argument("water: face corner " + std::to_string(v) +
                                            " is not a vertex");
        }
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (!std::isfinite(m.position[v].x) || !std::isfinite(m.position[v].y) ||
            !std::isfinite(m.bed[v]) || !std::isfinite(m.area[v]) || m.area[v] < 0.0)
            throw std::invalid_argument("water: vertex " + std::to_string(v) +
                                        " has a non-finite position, bed or area, or a "
                                        "negative area");
    }
}

/// Half the cotangent of the angle at `apex` of the triangle (apex, p, q): one face's part of
/// the dual (Voronoi) edge length of edge pq, over the edge's length.
double half_cotangent(Vec2 apex, Vec2 p, Vec2 q) {
    const Vec2 u = p - apex, v = q - apex;
    const double sine = std::abs(cross(u, v));
    return sine > 0.0 ? 0.5 * dot(u, v) / sine : 0.0;
}

}  // namespace

VirtualPipes::VirtualPipes(WaterMesh mesh, VirtualPipeOptions options)
    : mesh_(std::move(mesh)), options_(options) {
    check(mesh_);
    if (!(options_.gravity > 0.0) || !std::isfinite(options_.gravity) ||
        !(options_.friction >= 0.0) || !std::isfinite(options_.friction) ||
        !(options_.courant > 0.0) || !(options_.courant <= 1.0))
        throw std::invalid_argument(
            "water: gravity must be > 0, friction >= 0 and courant in (0, 1]");
    depth_.assign(mesh_.area.size(), 0.0);
    border_width_.assign(mesh_.area.size(), 0.0);
    build_pipes();
}

void VirtualPipes::build_pipes() {
    // One pipe per edge; its conductance w / L is the sum over the edge's faces of half the
    // cotangent of the angle opposite it (the cotangent formula of the dual edge length).
    // A non-Delaunay edge (a constrained one) can sum below 0: it conducts nothing.
    std::map<std::pair<std::uint32_t, std::uint32_t>, double> edges;
    for (const auto& f : mesh_.faces) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[(k + 1) % 3], b = f[(k + 2) % 3];
            edges[{std::min(a, b), std::max(a, b)}] +=
                half_cotangent(mesh_.position[f[k]], mesh_.position[a], mesh_.position[b]);
        }
    }
    pipes_.clear();
    pipes_.reserve(edges.size());
    conductance_sum_.assign(mesh_.area.size(), 0.0);
    for (const auto& [ends, conductance] : edges) {
        // A vertex without area (no faces of any size) can hold no water: no pipe reaches it.
        if (!(mesh_.area[ends.first] > 0.0) || !(mesh_.area[ends.second] > 0.0)) continue;
        Pipe p;
        p.a = ends.first;
        p.b = ends.second;
        p.conductance = std::max(conductance, 0.0);
        conductance_sum_[p.a] += p.conductance;
        conductance_sum_[p.b] += p.conductance;
        pipes_.push_back(p);
    }
    outflow_.assign(mesh_.area.size(), 0.0);
    inflow_.assign(mesh_.area.size(), 0.0);
}

void VirtualPipes::set_depth(std::size_t v, double depth) {
    if (v >= depth_.size()) throw std::invalid_argument("water: no vertex " + std::to_string(v));
    if (!(depth >= 0.0) || !std::isfinite(depth))
        throw std::invalid_argument("water: a depth must be finite and >= 0");
    if (depth > 0.0 && !(mesh_.area[v] > 0.0))
        throw std::invalid_argument("water: vertex " + std::to_string(v) +
                                    " has no area to hold water");
    depth_[v] = depth;
    moving_ = moving_ || depth > 0.0;
}

void VirtualPipes::add_water(std::size_t v, double volume) {
    if (v >= depth_.size()) throw std::invalid_argument("water: no vertex " + std::to_string(v));
    if (!(mesh_.area[v] > 0.0))
        throw std::invalid_argument("water: vertex " + std::to_string(v) +
                                    " has no area to hold water");
    set_depth(v, depth_[v] + volume / mesh_.area[v]);
}

void VirtualPipes::set_outflow_width(std::size_t v, double metres) {
    if (v >= depth_.size()) throw std::invalid_argument("water: no vertex " + std::to_string(v));
    if (!(metres >= 0.0) || !std::isfinite(metres))
        throw std::invalid_argument("water: an outflow width must be finite and >= 0");
    const bool listed = border_width_[v] > 0.0;
    border_width_[v] = metres;
    if (metres > 0.0 && !listed) border_vertices_.push_back(static_cast<std::uint32_t>(v));
    if (metres == 0.0 && listed) std::erase(border_vertices_, static_cast<std::uint32_t>(v));
}

void VirtualPipes::set_bed(std::size_t v, double z) {
    if (v >= depth_.size()) throw std::invalid_argument("water: no vertex " + std::to_string(v));
    if (!std::isfinite(z)) throw std::invalid_argument("water: a bed height must be finite");
    mesh_.bed[v] = z;
}

double VirtualPipes::volume() const {
    double sum = 0.0;
    for (std::size_t v = 0; v < depth_.size(); ++v)
        sum += mesh_.area[v] * depth_[v];
    return sum;
}

std::vector<Vec2> VirtualPipes::flow_vectors() const {
    std::vector<Vec2> flow(depth_.size(), Vec2{0.0, 0.0});
    for (const Pipe& p : pipes_) {
        if (p.flux == 0.0) continue;
        const Vec2 d = mesh_.position[p.b] - mesh_.position[p.a];
        const double l = length(d);
        if (!(l > 0.0)) continue;
        const Vec2 along = (p.flux / l) * d;  // flux out of a towards b, and out of b towards a
        flow[p.a] = flow[p.a] + along;
        flow[p.b] = flow[p.b] + along;
    }
    return flow;
}

double VirtualPipes::stable_time_step() const {
    // Each vertex's own limit, with the deepest water at either end of its pipes: a pipe's
    // flux grows with its upwind depth, which is one of its ends'. (The deepest water anywhere
    // bounds that too, but made a column at a nozzle hold the whole terrain to its step.)
    double limit = std::numeric_limits<double>::infinity();
    const auto vertex_limit = [&](std::uint32_t v, double h) {
        if (!(conductance_sum_[v] > 0.0) || !(mesh_.area[v] > 0.0)) return;
        limit = std::min(limit,
                         std::sqrt(mesh_.area[v] / (options_.gravity * h * conductance_sum_[v])));
    };
    for (const Pipe& p : pipes_) {
        const double h = std::max(depth_[p.a], depth_[p.b]);
        if (!(h > 0.0)) continue;
        vertex_limit(p.a, h);
        vertex_limit(p.b, h);
    }
    return options_.courant * limit;
}

double VirtualPipes::overfall(std::uint32_t v) const {
    const double h = depth_[v];
    return border_width_[v] * h * std::sqrt(options_.gravity * h);
}

bool VirtualPipes::move_volume(Pipe& p, double dt, std::vector<double>& change) const {
    if (p.flux == 0.0) return false;
    p.flux *= outflow_[p.flux > 0.0 ? p.a : p.b];
    const double moved = p.flux * dt;
    change[p.a] -= moved;
    change[p.b] += moved;
    return p.flux != 0.0;
}

void VirtualPipes::drain_borders(double dt) {
    for (std::uint32_t v : border_vertices_) {
        const double left = overfall(v) * outflow_[v] * dt;
        inflow_[v] -= left;
        volume_left_ += left;
    }
}

WaterStepReport VirtualPipes::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::invalid_argument("water: a time step must be finite and > 0");
    WaterStepReport report;
    if (!moving_) return report;  // dry and still: nothing to do
    const double damping = 1.0 / (1.0 + dt * options_.friction);
    // Phase 1: fluxes from the surface difference, through the upwind depth.
    std::fill(outflow_.begin(), outflow_.end(), 0.0);
    for (Pipe& p : pipes_) {
        if (at_rest(p)) continue;
        p.flux = next_flux(p, dt, damping);
        if (p.flux > 0.0) outflow_[p.a] += p.flux;
        if (p.flux < 0.0) outflow_[p.b] -= p.flux;
    }
    // ...and over the open border: a free overfall's critical discharge (m³/s).
    for (std::uint32_t v : border_vertices_)
        outflow_[v] += overfall(v);
    // Phase 2: no vertex gives more than it holds (outflow_ becomes the scale K in [0, 1]).
    for (std::size_t v = 0; v < depth_.size(); ++v) {
        const double wanted = outflow_[v] * dt;
        const double held = depth_[v] * mesh_.area[v];
        const bool limited = wanted > held;
        report.outflows_limited += limited ? 1 : 0;
        outflow_[v] = limited ? held / wanted : 1.0;
    }
    // Phase 3: each pipe moves its (scaled) volume from one end to the other.
    std::fill(inflow_.begin(), inflow_.end(), 0.0);
    std::vector<double>& change = inflow_;  // m³ over this step, per vertex
    bool any_flux = false;
    for (Pipe& p : pipes_)
        any_flux = move_volume(p, dt, change) || any_flux;
    drain_borders(dt);
    bool any_water = false;
    for (std::size_t v = 0; v < depth_.size(); ++v) {
        if (change[v] != 0.0) depth_[v] = std::max(0.0, depth_[v] + change[v] / mesh_.area[v]);
        any_water = any_water || depth_[v] > 0.0;
    }
    report.pipes_updated = pipes_.size();
    moving_ = any_water || any_flux;
    return report;
}

WaterStepReport VirtualPipes::step(double dt, ThreadPool& pool) {
    const int threads = pool.threads();
    if (threads <= 1) return step(dt);
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::invalid_argument("water: a time step must be finite and > 0");
    WaterStepReport report;
    if (!moving_) return report;
    const std::size_t n = depth_.size();
    scatter_.resize(static_cast<std::size_t>(threads - 1));
    for (std::vector<double>& s : scatter_)
        s.resize(n, 0.0);
    const auto into = [&](int thread) -> std::vector<double>& {
        return thread == 0 ? outflow_ : scatter_[static_cast<std::size_t>(thread - 1)];
    };
    const double damping = 1.0 / (1.0 + dt * options_.friction);
    // Phase 1: fluxes, each thread scattering its pipes' outflows into its own array.
    std::fill(outflow_.begin(), outflow_.end(), 0.0);
    pool.parallel_for(pipes_.size(), [&](std::size_t begin, std::size_t end, int thread) {
        std::vector<double>& out = into(thread);
        for (std::size_t i = begin; i < end; ++i) {
            Pipe& p = pipes_[i];
            if (at_rest(p)) continue;
            p.flux = next_flux(p, dt, damping);
            if (p.flux > 0.0) out[p.a] += p.flux;
            if (p.flux < 0.0) out[p.b] -= p.flux;
        }
    });
    // Phase 2, per vertex: the outflows added up (the other threads' arrays left at 0), the
    // border's overfall, and the scale K.
    std::vector<std::size_t> limited(static_cast<std::size_t>(threads), 0);
    pool.parallel_for(n, [&](std::size_t begin, std::size_t end, int thread) {
        std::size_t count = 0;
        for (std::size_t v = begin; v < end; ++v) {
            double total = outflow_[v];
            for (std::vector<double>& s : scatter_) {
                total += s[v];
                s[v] = 0.0;
            }
            if (border_width_[v] > 0.0) total += overfall(static_cast<std::uint32_t>(v));
            const double wanted = total * dt;
            const double held = depth_[v] * mesh_.area[v];
            const bool is_limited = wanted > held;
            count += is_limited ? 1 : 0;
            outflow_[v] = is_limited ? held / wanted : 1.0;
        }
        limited[static_cast<std::size_t>(thread)] = count;
    });
    for (const std::size_t c : limited)
        report.outflows_limited += c;
    // Phase 3: each pipe's scaled volume leaves one end and enters the other, scattered per
    // thread as in phase 1.
    std::fill(inflow_.begin(), inflow_.end(), 0.0);
    const auto change_of = [&](int thread) -> std::vector<double>& {
        return thread == 0 ? inflow_ : scatter_[static_cast<std::size_t>(thread - 1)];
    };
    std::vector<std::uint8_t> fluxes(static_cast<std::size_t>(threads), 0);
    pool.parallel_for(pipes_.size(), [&](std::size_t begin, std::size_t end, int thread) {
        std::vector<double>& change = change_of(thread);
        bool any = false;
        for (std::size_t i = begin; i < end; ++i)
            any = move_volume(pipes_[i], dt, change) || any;
        fluxes[static_cast<std::size_t>(thread)] = any ? 1 : 0;
    });
    drain_borders(dt);
    std::vector<std::uint8_t> wet(static_cast<std::size_t>(threads), 0);
    pool.parallel_for(n, [&](std::size_t begin, std::size_t end, int thread) {
        bool any = false;
        for (std::size_t v = begin; v < end; ++v) {
            double change = inflow_[v];
            for (std::vector<double>& s : scatter_) {
                change += s[v];
                s[v] = 0.0;
            }
            if (change != 0.0) depth_[v] = std::max(0.0, depth_[v] + change / mesh_.area[v]);
            any = any || depth_[v] > 0.0;
        }
        wet[static_cast<std::size_t>(thread)] = any ? 1 : 0;
    });
    report.pipes_updated = pipes_.size();
    moving_ = std::find(wet.begin(), wet.end(), 1) != wet.end() ||
              std::find(fluxes.begin(), fluxes.end(), 1) != fluxes.end();
    return report;
}

}  // namespace sandtin
