#pragma once
// Shallow water on a triangulated terrain by virtual pipes (issue 40, item 1): each vertex
// holds a water depth over its lumped area, and each edge of the triangulation is a pipe that
// carries a flux driven by the difference of the water surface at its ends. It is Mei,
// Decaudin & Hu's GPU scheme (2007) taken off the grid: a pipe's width is the edge's dual
// (Voronoi) edge length and its length the edge's own, so on a square grid it is theirs, and
// on a TIN each vertex exchanges water with its neighbours through the boundary of its cell.
//
// Per step of dt seconds (symplectic Euler, fluxes first):
//  1. flux: Q += dt g w h (eta_i - eta_j) / L, with eta = bed + depth the water surface, h the
//     upwind depth (the depth at the end whose surface is higher), then damped by friction;
//  2. positivity: a vertex's outflows are scaled down together so that they never take more
//     than it holds (Mei et al.'s K factor), so depths never go negative;
//  3. depth: each vertex gains its inflows and loses its outflows over dt, through its area.
// Properties, each tested:
//  - volume: every flux leaves one vertex and enters another, so sum(area x depth) is exact
//    to rounding;
//  - well balanced: a lake at rest over any bed (a flat surface, dry land above it) has no
//    surface difference across a wet pipe and none out of a dry vertex, so it stays at rest;
//  - wet/dry fronts: the upwind depth of a dry vertex is 0, so water flows onto dry land only
//    from the wet side;
//  - the time step comes from the CFL condition of the pipe network (stable_time_step);
//  - dry terrain costs nothing: with no water and no flux, step() returns at once.
// The domain's border is a closed wall (no pipe leaves it), except where set_outflow_width
// opens it: there water leaves at the critical discharge of a free overfall, width x h x
// sqrt(g h), and is counted (volume_left). Units: metres, seconds, m³.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geom/vec2.hpp"

namespace sandtin {

class ThreadPool;

/// The pipes' estimate of the flow speed at a vertex (m/s): its discharge (m³/s: half the sum
/// of |flux| over its pipes for the sediment's capacity, half the length of
/// VirtualPipes::flow_vectors for the editor's overlay) through a cross-section of its depth
/// by the width of its cell, sqrt(area). The pipes carry no velocity of their own; 0 where the
/// vertex is dry. (A depth of a few hundred zeptometres times the width underflows to 0: such a
/// film has no speed either, where 0 / 0 would have made it NaN and the sediment's capacity with
/// it.)
inline double pipe_flow_speed(double discharge, double depth, double area) {
    const double section = depth > 0.0 && area > 0.0 ? depth * std::sqrt(area) : 0.0;
    return section > 0.0 ? discharge / section : 0.0;
}

/// What the water flows over, CGAL-free: a triangulation with a bed height per vertex.
struct WaterMesh {
    std::vector<Vec2> position;                       ///< per vertex (m)
    std::vector<std::array<std::uint32_t, 3>> faces;  ///< vertex indices, either orientation
    std::vector<double> area;  ///< per vertex: a third of its faces' areas (m²), > 0 to hold water
    std::vector<double> bed;   ///< per vertex: the terrain's height under the water (m)
};

struct VirtualPipeOptions {
    double gravity = 9.81;  ///< m/s²
    /// Linear friction (1/s): each flux is divided by (1 + dt friction) per step, so a lake
    /// sloshes down to rest. 0: none (waves travel undamped).
    double friction = 0.5;
    /// stable_time_step's fraction of the pipe network's stability limit, in (0, 1].
    double courant = 0.5;
};

struct WaterStepReport {
    std::size_t pipes_updated = 0;     ///< 0 when there was no water to move
    std::size_t outflows_limited = 0;  ///< vertices whose outflows were scaled to what they held
};

class VirtualPipes {
  public:
    /// Builds the pipes of `mesh` (one per edge of its faces). Throws std::invalid_argument
    /// when the arrays disagree in size, a face names no vertex, or a value is not finite or
    /// an area is negative. Every depth starts at 0.
    explicit VirtualPipes(WaterMesh mesh, VirtualPipeOptions options = {});

    std::size_t vertex_count() const { return mesh_.area.size(); }
    std::size_t pipe_count() const { return pipes_.size(); }
    const WaterMesh& mesh() const { return mesh_; }

    /// Water depth at vertex v (m), >= 0.
    double depth(std::size_t v) const { return depth_[v]; }
    std::span<const double> depths() const { return depth_; }
    /// The water surface at v: bed + depth (m).
    double surface(std::size_t v) const { return mesh_.bed[v] + depth_[v]; }
    /// Sets the depth at v (m, finite, >= 0; throws std::invalid_argument otherwise), for
    /// sources and for loading a state.
    void set_depth(std::size_t v, double depth);
    /// Adds `volume` m³ at v (a source): its depth rises by volume / area. Throws for a vertex
    /// without area or a volume that would leave a negative depth.
    void add_water(std::size_t v, double volume);
    /// sum(area x depth) (m³).
    double volume() const;
    /// Opens the border at vertex v over `metres` of its length (0 closes it again): water
    /// there leaves the terrain (water_borders.hpp sets this for whole sides). Throws
    /// std::invalid_argument for a negative or non-finite width or a vertex that does not exist.
    void set_outflow_width(std::size_t v, double metres);
    /// m³ that left through open borders since construction.
    double volume_left() const { return volume_left_; }

    /// The longest step (s) the scheme is stable for with the water now, times the courant
    /// option: the least over the vertices of sqrt(area / (g h sum(w / L) over its pipes)),
    /// h the deepest water at the vertex or its neighbours (each pipe's upwind depth is one of
    /// its ends'), the 2D wave CFL condition (s / (2 sqrt(g h)) on a square grid of spacing s).
    /// Dry vertices with dry neighbours set no limit; infinite when there is no water.
    double stable_time_step() const;
    /// Advances the water by `dt` seconds (finite, > 0; throws otherwise). Stable for
    /// dt <= stable_time_step() / courant.
    WaterStepReport step(double dt);
    /// The same step on `pool`'s threads: pipes and vertices in equal contiguous chunks, each
    /// extra thread scattering into an array of its own that is added into the first's per
    /// vertex, in thread order. Deterministic for a thread count; its sums differ from one
    /// thread's by rounding only (a vertex's pipes are added in another grouping), and volume
    /// is kept as exactly. One thread: step(dt) itself.
    WaterStepReport step(double dt, ThreadPool& pool);

    struct Pipe {
        std::uint32_t a = 0, b = 0;
        double conductance = 0.0;  ///< w / L: dual edge width over length (dimensionless)
        double flux = 0.0;         ///< m³/s, positive from a to b, as the last step left it
    };
    std::span<const Pipe> pipes() const { return pipes_; }
    /// Per vertex: the sum over its pipes of the flux out of it along the pipe's unit
    /// direction (m³/s, a vector). A flow through a vertex counts twice (in from one side,
    /// out to the other, both pointing downstream); fluxes that slosh back and forth around
    /// it cancel, which |discharges| would count.
    std::vector<Vec2> flow_vectors() const;
    /// Moves the bed under vertex v to `z` (m, finite; throws std::invalid_argument
    /// otherwise): sand the water carried away or dropped (sediment_transport.hpp).
    void set_bed(std::size_t v, double z);

  private:
    void build_pipes();
    /// A dry pipe at rest stays so (its upwind depth is 0): most of a terrain, skipped.
    bool at_rest(const Pipe& p) const {
        return p.flux == 0.0 && depth_[p.a] == 0.0 && depth_[p.b] == 0.0;
    }
    /// Phase 1 of a step for one pipe: its flux from the surface difference through the
    /// upwind depth, damped by friction (`damping` = 1 / (1 + dt friction)).
    double next_flux(const Pipe& p, double dt, double damping) const {
        const double drop = surface(p.a) - surface(p.b);
        const double upwind = drop >= 0.0 ? depth_[p.a] : depth_[p.b];
        return (p.flux + dt * options_.gravity * upwind * p.conductance * drop) * damping;
    }
    /// m³/s over the open border at v: a free overfall's critical discharge, width h sqrt(g h).
    double overfall(std::uint32_t v) const;
    /// Phase 3 for one pipe: its flux scaled by its sending end's K (outflow_), and the volume
    /// it moves over dt taken from one end of `change` and added to the other. Returns
    /// whether it still flows.
    bool move_volume(Pipe& p, double dt, std::vector<double>& change) const;
    /// Phase 3 at the open border: what went over it leaves inflow_ and counts as left.
    void drain_borders(double dt);

    WaterMesh mesh_;
    VirtualPipeOptions options_;
    std::vector<Pipe> pipes_;
    std::vector<double> depth_;
    std::vector<double> conductance_sum_;   ///< per vertex: sum of its pipes' w / L
    std::vector<double> outflow_, inflow_;  ///< per vertex, scratch of step()
    /// Per extra thread of step(dt, pool): its scatter array, all zeros between steps.
    std::vector<std::vector<double>> scatter_;
    std::vector<double> border_width_;            ///< per vertex: open border (m), mostly 0
    std::vector<std::uint32_t> border_vertices_;  ///< those with an open border
    double volume_left_ = 0.0;
    bool moving_ = false;  ///< some water or some flux: step() has work
};

}  // namespace sandtin
