#pragma once
// Shallow water on a triangulated terrain by finite volumes (issue 40, item 1, the second of
// its two designs): the Saint-Venant equations with momentum, on the median-dual cells of the
// TIN's vertices, with Audusse et al.'s hydrostatic reconstruction (2004) over the HLL
// Riemann solver. Unlike the virtual pipes (virtual_pipes.hpp), which carry no momentum and so
// move fronts at the linear wave speed, this scheme follows the analytic dam breaks (Stoker,
// Ritter) and Thacker's oscillating lake (tests/water/shallow_water_test.cpp).
//
// Cells. Vertex i's cell is its median dual: in each of its triangles, the quadrilateral from
// the vertex to its two edge midpoints and the centroid. Its area is a third of its triangles'
// areas (the TIN's lumped area, tin/vertex_arrays.hpp, so the water's volume and the sand's
// are measured alike), and its boundary between i and a neighbour j is the two segments from
// the edge's midpoint to the centroids of the edge's triangles: the interface vector N_ij
// (normal times length) from i to j. The cell closes: sum_j N_ij + B_i = 0, where B_i is the
// outward normal times length of the cell's part of the domain border (half of each border
// edge at i). Any triangulation gives positive, closed cells; a circumcentric dual would not
// (negative widths across obtuse angles, common at a random TIN's border).
//
// Per step of dt seconds (order 2, the default: Heun's method over two evaluations of 1-2;
// order 1: forward Euler and no reconstruction):
//  0. (order 2) MUSCL: each cell's surface, depth and velocity get a Green-Gauss gradient over
//     its dual cell, limited by Barth and Jespersen's rule, and each side of an interface
//     takes its cell's values at the edge's midpoint. Cells at a shore stay first order;
//  1. at each interface, each side's depth is reconstructed against the higher bed,
//     h* = max(0, h + z - max(z_i, z_j)), with its own velocity; the HLL flux of those two
//     states (Einfeldt's wave speeds, Toro's for a dry side) crosses |N_ij|, and each side
//     adds the pressure correction g/2 (h² - h*²) along N (the reconstruction's source term)
//     and, at order 2, its bed's slope inside the cell, g (h + h_side)/2 (z_side - z) N;
//  2. no cell gives more than it holds: its outflows are scaled down together (the
//     reconstruction can ask more of a thin film than it has; the first-order scheme never
//     does under the time step), so depths stay >= 0 and the volume exact;
//  3. a closed border is a wall: the HLL flux against the mirrored state (mass flux 0); an
//     open border lets water out with its own flux (free outflow) and lets none in;
//  4. U += dt / A x (the sum of the fluxes into the cell); friction (Manning) is applied
//     semi-implicitly; a cell shallower than dry_depth holds its water still.
// Properties, each tested: the volume is exact to rounding (every flux leaves one cell and
// enters another); a lake at rest over any bed stays at rest (the reconstruction's pressure
// terms cancel through the cell's closure); depths stay >= 0 under the time step below (the
// scheme is positive for CFL <= 1/2); a dry terrain costs nothing. Units: metres, seconds.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geom/vec2.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

struct ShallowWaterOptions {
    double gravity = 9.81;  ///< m/s²
    /// Manning's roughness n (s/m^(1/3)); 0: frictionless. A sand bed is about 0.02–0.03.
    double manning = 0.0;
    /// stable_time_step's fraction of the scheme's positivity limit, in (0, 0.5].
    double courant = 0.45;
    /// m: a cell holding less water than this keeps it still (no velocity), which keeps the
    /// velocity q / h finite at wet/dry fronts.
    double dry_depth = 1e-7;
    /// 2: MUSCL reconstruction and Heun's method (3.6x the CPU time of order 1 per step on
    /// the 4 cm dam break, `sandtin bench water`); 1: first order. On Thacker's sloshing
    /// lake, order 1's depth error after one period is 33 % on a 5 cm mesh, order 2's 3.9 %.
    int order = 2;
};

class ShallowWater {
  public:
    /// Builds the median-dual cells of `mesh`'s faces; mesh.area is replaced by the cells'
    /// areas (a third of each vertex's faces). Throws std::invalid_argument as VirtualPipes
    /// does, or for options out of range. Every depth and velocity starts at 0.
    explicit ShallowWater(WaterMesh mesh, ShallowWaterOptions options = {});

    std::size_t vertex_count() const { return mesh_.area.size(); }
    const WaterMesh& mesh() const { return mesh_; }

    double depth(std::size_t v) const { return depth_[v]; }  ///< m, >= 0
    std::span<const double> depths() const { return depth_; }
    double surface(std::size_t v) const { return mesh_.bed[v] + depth_[v]; }  ///< m
    /// Depth-averaged velocity (m/s); 0 in a cell shallower than dry_depth.
    Vec2 velocity(std::size_t v) const;
    /// Sets the depth (m, finite, >= 0) and velocity (m/s, finite) at v, for sources, initial
    /// conditions and loading a state. Throws std::invalid_argument otherwise, or for water on
    /// a vertex with no cell.
    void set_state(std::size_t v, double depth, Vec2 velocity = {});
    /// Sets the depth at v (m, finite, >= 0) keeping its velocity: evaporation takes water
    /// and leaves the rest moving as it did.
    void set_depth(std::size_t v, double depth) { set_state(v, depth, velocity(v)); }
    /// Adds `volume` m³ at v with no momentum (a source): its depth rises by volume / area,
    /// its momentum stays, so its velocity falls.
    void add_water(std::size_t v, double volume);
    double volume() const;  ///< sum(area x depth), m³
    /// Opens (or closes) vertex v's part of the domain border: water leaves there with its
    /// own flux. A vertex not on the border has no part to open.
    void set_open_border(std::size_t v, bool open);
    bool on_border(std::size_t v) const { return wall_[v].x != 0.0 || wall_[v].y != 0.0; }
    double volume_left() const { return volume_left_; }  ///< m³ out through open borders

    /// The longest step (s) the scheme stays positive and stable for with the water as it is
    /// now, times the courant option; infinite with no water.
    double stable_time_step() const;
    /// Advances by `dt` seconds (finite, > 0; throws otherwise). Depths stay >= 0 for
    /// dt <= stable_time_step().
    WaterStepReport step(double dt);
    /// Moves the bed under v to z (m, finite), for sand the water moved.
    void set_bed(std::size_t v, double z);

    /// An interface between two cells: `normal` is N_ab, the normal from a to b times the
    /// interface's length (m); `flux` the m³/s that crossed from a to b in the last step.
    struct Interface {
        std::uint32_t a = 0, b = 0;
        Vec2 normal;
        double span = 0.0;  ///< |normal| (m)
        double flux = 0.0;
    };
    std::span<const Interface> interfaces() const { return interfaces_; }

  private:
    /// Per cell, the limited gradients of the surface, depth and velocity components.
    struct Slopes {
        Vec2 surface, depth, u, v;
        bool first_order = true;
    };
    /// One side of an interface: the values its cell reconstructs there.
    struct Side {
        double depth = 0.0, bed = 0.0;
        Vec2 velocity;
    };
    void build_cells();
    bool second_order() const { return options_.order == 2; }
    Vec2 velocity_of(double h, Vec2 q) const;
    /// Fills slopes_ for the depths h and the velocities in scratch_.velocity.
    void reconstruct(std::span<const double> h);
    Side side_at(std::span<const double> h, std::size_t v, Vec2 r) const;
    /// Fills residual_ with the fluxes into each cell for the state (h, q), adds `weight`
    /// times each interface's mass flux to Interface::flux, and returns the m³/s leaving
    /// through open borders.
    double residual(std::span<const double> h, std::span<const Vec2> q, double dt, double weight);
    /// out = (h, q) + dt / A residual_, with friction and still shallow water; returns the
    /// cells whose depth went below 0 by rounding and were clamped (0 under the CFL bound).
    std::size_t advance(double dt, std::span<const double> h, std::span<const Vec2> q,
                        std::vector<double>& out_h, std::vector<Vec2>& out_q) const;

    WaterMesh mesh_;
    ShallowWaterOptions options_;
    std::vector<Interface> interfaces_;
    std::vector<double> depth_;
    std::vector<Vec2> discharge_;  ///< q = h u per vertex (m²/s)
    std::vector<Vec2> wall_;       ///< B_i: the cell's border, outward normal x length (m)
    std::vector<std::uint8_t> open_;
    std::vector<double> wall_span_;                ///< per vertex: |B_i| (m)
    std::vector<std::array<double, 3>> residual_;  ///< per vertex, scratch of step()
    std::vector<Slopes> slopes_;                   ///< per vertex, scratch of step()
    /// Per interface, scratch of residual(): the mass (m³/s) and momentum fluxes from a to b,
    /// and each side's pressure and bed terms.
    struct InterfaceFlux {
        double mass = 0.0;
        Vec2 momentum, push_a, push_b;
    };
    std::vector<InterfaceFlux> flux_;
    struct BorderFlux {
        double mass = 0.0;  ///< m³/s out through an open border
        Vec2 momentum;
    };
    std::vector<BorderFlux> border_;  ///< per vertex, scratch of residual()
    std::vector<double> outgoing_;
    std::vector<Vec2> half_;  ///< per interface: from a to the edge's midpoint (m)
    /// Per-cell work arrays of step() and stable_time_step(), kept between calls (mutable:
    /// stable_time_step() is logically const).
    struct Scratch {
        std::vector<Vec2> velocity;                 ///< of the state being evaluated
        std::vector<std::array<double, 4>> value;   ///< surface, depth, u, v
        std::vector<std::array<double, 4>> lo, hi;  ///< over the cell and its neighbours
        std::vector<std::array<Vec2, 4>> gradient;
        std::vector<std::array<double, 4>> limiter;
        std::vector<double> reach, sum;
        void resize(std::size_t n) {
            velocity.resize(n);
            value.resize(n);
            lo.resize(n);
            hi.resize(n);
            gradient.resize(n);
            limiter.resize(n);
            reach.resize(n);
            sum.resize(n);
        }
    };
    mutable Scratch scratch_;      ///< per vertex: outflow (m³/s), then its scale in [0, 1]
    std::vector<double> stage_h_;  ///< Heun's intermediate state
    std::vector<Vec2> stage_q_;
    double volume_left_ = 0.0;
    bool moving_ = false;
};

}  // namespace sandtin
