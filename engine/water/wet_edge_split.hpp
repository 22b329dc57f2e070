#pragma once
// Detail where the water flows (issue 40, item 1): edges under the water longer than a length
// are split at their midpoints, so water crossing a coarse terrain (an elevation model's flats
// are metres across) gets the triangles it flows through, as r_S gives the sand detail where
// it slides. The sand's volume is kept by the split (VolumePolicy::Conserve), the water's by
// interpolating the new vertices' depths along their edges and then spreading what the flips
// around them changed over the new vertices in proportion to their lumped areas. Once the
// ground is dry again the simplifier, which leaves wet ground alone, takes the detail away.
// Used by the editor's water (live_water.hpp) and the scripts' water operations.

#include <cstddef>
#include <span>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

/// Whether an edge longer than `max_length` (m) has at least `film` m of water at both ends,
/// by `depth` (m per vertex id: a water scheme's depths, which may be ahead of the terrain's).
bool has_long_wet_edge(const Tin& tin, std::span<const double> depth, double max_length,
                       double film);

/// Splits at most `max_splits` edges longer than `max_length` (m) with at least `film` m of
/// water at both ends (by the terrain's water depths), lowest vertex ids first; returns the
/// vertices born. Water and sand volumes are kept as above.
std::vector<VertexId> split_wet_edges(Tin& tin, double max_length, std::size_t max_splits,
                                      double film);

}  // namespace sandtin
