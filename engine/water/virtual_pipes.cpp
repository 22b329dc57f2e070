#include "water/virtual_pipes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

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
        !(options_.courant > 0.0) || !(options_.courant <= 1.0) || options_.threads < 1)
        throw std::invalid_argument(
            "water: gravity must be > 0, friction >= 0, courant in (0, 1] and threads >= 1");
    if (options_.threads > 1) pool_ = std::make_unique<ThreadPool>(options_.threads);
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
    // Incidence lists by counting sort: each vertex's pipes come in pipe order.
    incident_offset_.assign(mesh_.area.size() + 1, 0);
    for (const Pipe& p : pipes_) {
        ++incident_offset_[p.a + 1];
        ++incident_offset_[p.b + 1];
    }
    for (std::size_t v = 0; v < mesh_.area.size(); ++v)
        incident_offset_[v + 1] += incident_offset_[v];
    incident_.assign(2 * pipes_.size(), 0);
    std::vector<std::uint32_t> next(incident_offset_.begin(), incident_offset_.end() - 1);
    for (std::uint32_t i = 0; i < pipes_.size(); ++i) {
        incident_[next[pipes_[i].a]++] = i;
        incident_[next[pipes_[i].b]++] = i;
    }
}

void VirtualPipes::for_chunks(std::size_t n,
                              const std::function<void(std::size_t, std::size_t, int)>& body) {
    if (pool_)
        pool_->parallel_for(n, body);
    else
        body(0, n, 0);
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

std::vector<double> VirtualPipes::discharges() const {
    std::vector<double> through(depth_.size(), 0.0);
    for (const Pipe& p : pipes_) {
        through[p.a] += 0.5 * std::abs(p.flux);
        through[p.b] += 0.5 * std::abs(p.flux);
    }
    return through;
}

double VirtualPipes::stable_time_step() const {
    // Each vertex's own limit, with the deepest water at either end of its pipes: a pipe's
    // flux grows with its upwind depth, which is one of its ends'. (The deepest water anywhere
    // bounds that too, but made a column at a nozzle hold the whole terrain to its step.)
    // Per vertex through its pipes, so that threads take vertices; the least of the limits
    // does not depend on the order.
    std::vector<double> least(static_cast<std::size_t>(options_.threads),
                              std::numeric_limits<double>::infinity());
    const auto body = [&](std::size_t begin, std::size_t end, int thread) {
        double& limit = least[static_cast<std::size_t>(thread)];
        for (std::size_t v = begin; v < end; ++v) {
            if (!(conductance_sum_[v] > 0.0) || !(mesh_.area[v] > 0.0)) continue;
            double h = 0.0;
            for (std::uint32_t k = incident_offset_[v]; k < incident_offset_[v + 1]; ++k) {
                const Pipe& p = pipes_[incident_[k]];
                h = std::max({h, depth_[p.a], depth_[p.b]});
            }
            if (!(h > 0.0)) continue;
            limit = std::min(
                limit, std::sqrt(mesh_.area[v] / (options_.gravity * h * conductance_sum_[v])));
        }
    };
    if (pool_)
        pool_->parallel_for(depth_.size(), body);
    else
        body(0, depth_.size(), 0);
    return options_.courant * *std::min_element(least.begin(), least.end());
}

void VirtualPipes::update_fluxes(std::size_t begin, std::size_t end, double dt, double damping) {
    for (std::size_t i = begin; i < end; ++i) {
        Pipe& p = pipes_[i];
        // A dry pipe at rest stays so (its upwind depth is 0): most of a terrain, skipped.
        if (p.flux == 0.0 && depth_[p.a] == 0.0 && depth_[p.b] == 0.0) continue;
        const double drop = surface(p.a) - surface(p.b);
        const double upwind = drop >= 0.0 ? depth_[p.a] : depth_[p.b];
        p.flux = (p.flux + dt * options_.gravity * upwind * p.conductance * drop) * damping;
    }
}

std::size_t VirtualPipes::scale_outflows(std::size_t begin, std::size_t end, double dt) {
    std::size_t limited = 0;
    for (std::size_t v = begin; v < end; ++v) {
        double out = 0.0;
        for (std::uint32_t k = incident_offset_[v]; k < incident_offset_[v + 1]; ++k) {
            const Pipe& p = pipes_[incident_[k]];
            if (p.a == v && p.flux > 0.0) out += p.flux;
            if (p.b == v && p.flux < 0.0) out -= p.flux;
        }
        // ...and over the open border: a free overfall's critical discharge (m³/s).
        const double h = depth_[v];
        if (border_width_[v] > 0.0) out += border_width_[v] * h * std::sqrt(options_.gravity * h);
        const double wanted = out * dt;
        const double held = h * mesh_.area[v];
        const bool over = wanted > held;
        limited += over ? 1 : 0;
        outflow_[v] = over ? held / wanted : 1.0;
    }
    return limited;
}

bool VirtualPipes::update_depths(std::size_t begin, std::size_t end, double dt) {
    bool any_water = false;
    for (std::size_t v = begin; v < end; ++v) {
        double change = 0.0;  // m³ over this step
        for (std::uint32_t k = incident_offset_[v]; k < incident_offset_[v + 1]; ++k) {
            const Pipe& p = pipes_[incident_[k]];
            if (p.flux == 0.0) continue;
            const double moved = p.flux * dt;
            change += p.a == v ? -moved : moved;
        }
        if (border_width_[v] > 0.0) {
            const double h = depth_[v];
            inflow_[v] = border_width_[v] * h * std::sqrt(options_.gravity * h) * outflow_[v] * dt;
            change -= inflow_[v];
        }
        if (change != 0.0) depth_[v] = std::max(0.0, depth_[v] + change / mesh_.area[v]);
        any_water = any_water || depth_[v] > 0.0;
    }
    return any_water;
}

WaterStepReport VirtualPipes::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::invalid_argument("water: a time step must be finite and > 0");
    WaterStepReport report;
    if (!moving_) return report;  // dry and still: nothing to do
    const double damping = 1.0 / (1.0 + dt * options_.friction);
    const std::size_t threads = static_cast<std::size_t>(options_.threads);
    // Phase 1: fluxes from the surface difference, through the upwind depth.
    for_chunks(pipes_.size(),
               [&](std::size_t b, std::size_t e, int) { update_fluxes(b, e, dt, damping); });
    // Phase 2: no vertex gives more than it holds (outflow_ becomes the scale K in [0, 1]).
    std::vector<std::size_t> limited(threads, 0);
    for_chunks(depth_.size(), [&](std::size_t b, std::size_t e, int t) {
        limited[static_cast<std::size_t>(t)] = scale_outflows(b, e, dt);
    });
    for (const std::size_t n : limited)
        report.outflows_limited += n;
    // Phase 3: each pipe's flux scaled by its upwind end's K.
    std::vector<std::uint8_t> any_flux(threads, 0);
    for_chunks(pipes_.size(), [&](std::size_t b, std::size_t e, int t) {
        bool flowing = false;
        for (std::size_t i = b; i < e; ++i) {
            Pipe& p = pipes_[i];
            if (p.flux == 0.0) continue;
            p.flux *= outflow_[p.flux > 0.0 ? p.a : p.b];
            flowing = flowing || p.flux != 0.0;
        }
        any_flux[static_cast<std::size_t>(t)] = flowing ? 1 : 0;
    });
    // Phase 4: each vertex gains its inflows and loses its outflows (in pipe order) and what
    // went over the border (inflow_ keeps it for the count below).
    std::vector<std::uint8_t> any_water(threads, 0);
    for_chunks(depth_.size(), [&](std::size_t b, std::size_t e, int t) {
        any_water[static_cast<std::size_t>(t)] = update_depths(b, e, dt) ? 1 : 0;
    });
    for (std::uint32_t v : border_vertices_)
        volume_left_ += inflow_[v];
    report.pipes_updated = pipes_.size();
    moving_ = std::find(any_water.begin(), any_water.end(), 1) != any_water.end() ||
              std::find(any_flux.begin(), any_flux.end(), 1) != any_flux.end();
    return report;
}

}  // namespace sandtin
