#pragma once
// Sand carried by the water (issue 40, item 3): flowing water picks sand up to a transport
// capacity, carries it with the flow, and drops it where the capacity falls (Mei, Decaudin &
// Hu 2007, and Benes's real-time hydraulic erosion, on the TIN's pipes).
//
// Law, per vertex v and step dt:
//   capacity  C = min(K_c x |u| x max(slope, s_min) x area, c_max x depth x area)
//             (m³ of sand the water can hold: no more than c_max of its own volume)
//   |u|       = (half the sum of |Q| through v's pipes) / (depth x sqrt(area))   (m/s)
//             (the pipes carry no velocity; under the finite-volume scheme, |u| is its own)
//   slope     = the steepest bed slope along v's pipes
//   if the water holds less than C: it takes min(K_s (C - held) dt, the sand above the rock)
//   else it drops K_d (held - C) dt
// then the suspended sand moves along each pipe with the water, at the concentration of the
// vertex the water leaves (upwind), never more than that vertex holds.
// Constants (defaults below, documented in the README's "water" row): K_c = 0.05, K_s = 0.5/s,
// K_d = 1/s, s_min = 0.01, c_max = 0.3 (a dense slurry; without it a thin jet at a nozzle,
// tens of m/s through a millimetre of water by this speed estimate, held more sand than
// water).
//
// Conservation: sand taken from the bed is suspended, suspended sand moved between vertices or
// dropped on the bed; so sum(area x bed) + suspended is exact to rounding. The rock is never
// eroded: a vertex gives at most the sand above its bedrock.
//
// Materials travel with the sand: what the water picks up is of the bed's material there,
// the suspension keeps a volume per material (moved and dropped in proportion), and each
// vertex counts the volume of each material dropped on it, so gravel washed out of a gravel
// bed and laid down over sand is known as gravel (deposited_material).

#include <cstdint>
#include <vector>

#include "water/shallow_water.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

struct SedimentOptions {
    double capacity = 0.05;          ///< K_c (s/m x m/s: dimensionless per unit of slope and speed)
    double pick_up_rate = 0.5;       ///< K_s (1/s)
    double drop_rate = 1.0;          ///< K_d (1/s)
    double least_slope = 0.01;       ///< s_min: flat beds still carry some sand
    double max_concentration = 0.3;  ///< c_max: sand per volume of water, in [0, 1]
};

class SedimentTransport {
  public:
    /// Sediment on `mesh` (a water scheme's mesh()), with `bedrock` per vertex (m; -inf where
    /// there is none), which must lie at or below the bed. Throws std::invalid_argument
    /// otherwise.
    /// `material`: the bed's material index per vertex (empty: all 0).
    SedimentTransport(const WaterMesh& mesh, std::vector<double> bedrock,
                      SedimentOptions options = {}, std::vector<std::uint16_t> material = {});

    /// After water.step(dt): picks up, drops and carries sand over dt seconds, and writes the
    /// new bed into `water` (set_bed). Either scheme: the pipes' fluxes or the finite
    /// volumes' interface fluxes carry the sand; the speed is the scheme's own (the pipes'
    /// estimate below, or the finite volumes' velocity).
    template <class Water>
    void step(Water& water, double dt);
    /// Drops every grain still suspended where it is (the end of a run).
    template <class Water>
    void settle_all(Water& water);

    double suspended() const;  ///< m³ in the water
    double suspended(std::size_t v) const { return held_[v]; }
    /// m³ of sand dropped at v since construction (settle_all included), of all materials.
    double dropped(std::size_t v) const;
    /// The material that makes up most of the sand dropped at v; the bed's own where none was.
    std::uint16_t deposited_material(std::size_t v) const;

  private:
    /// Moves `share` of v's suspension, material by material, into `into` (a vertex's counts
    /// in change_by_kind_ or dropped_by_kind_); v's own counts lose it at apply_changes().
    void move_suspension(std::size_t v, double share, double* into);
    void apply_changes();
    /// k of the material on top at v: what was dropped there most, else the bed's.
    std::size_t top_kind(std::size_t v) const;

    std::vector<double> bedrock_;
    std::vector<double> held_;  ///< m³ suspended per vertex
    SedimentOptions options_;
    std::vector<std::uint16_t> palette_;   ///< the materials present, by index k
    std::vector<std::uint16_t> bed_kind_;  ///< per vertex: k of its bed's material
    std::vector<double> held_by_kind_;     ///< per vertex and k: m³ suspended
    std::vector<double> dropped_by_kind_;  ///< per vertex and k: m³ dropped
    std::vector<double> change_by_kind_;   ///< scratch of step()
};

extern template void SedimentTransport::step(VirtualPipes&, double);
extern template void SedimentTransport::step(ShallowWater&, double);
extern template void SedimentTransport::settle_all(VirtualPipes&);
extern template void SedimentTransport::settle_all(ShallowWater&);

}  // namespace sandtin
