#pragma once
// Refinement at the relocation radius r_S (seed 000 §7.2, "prevention of long edges"): sand
// never moves along an edge longer than r_S, so where it meets one the TIN grows vertices from
// one jittered hexagonal lattice of spacing 0.75 r_S over the whole domain (see the .cpp for
// why a lattice and not the seed's circles). The CPU physics and the GPU physics refine through
// the same object, so they insert the same vertices for the same requests.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

class RelocationRefiner {
  public:
    /// Refines around the TIN vertices in `around` (ids; dead ones are skipped): lattice points
    /// in their fan triangles within 1.5 r_S, or, where none fits, their edges longer than
    /// `relocation_radius` (m, > 0) bisected. Heights are interpolated and the volume
    /// conserved (VolumePolicy::Conserve). Returns how many vertices it inserted, and appends
    /// their ids to `inserted` when given; empties `around`.
    std::size_t refine(Tin& tin, std::vector<std::uint32_t>& around, double relocation_radius,
                       std::vector<VertexId>* inserted = nullptr);

  private:
    std::vector<std::uint8_t> requested_;  ///< per TIN id: already refined in this call
    LocateHint hint_;
};

}  // namespace sandtin
