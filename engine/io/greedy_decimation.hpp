#pragma once
// Decimation after greedy insertion: removes the vertices a greedy TIN does not need.
//
// Greedy insertion never takes a point back, so points inserted early for a large error often
// become redundant once their neighbours are in. This pass removes such vertices while the
// error bound keeps holding. A vertex is removable when, with it gone and its hole
// re-triangulated, every valid raster sample of the hole is still within the bound. Removal
// runs in rounds; each round measures every vertex whose neighbourhood changed, then removes,
// cheapest first, a set of removable vertices no two of which are neighbours (their holes are
// then disjoint, so each hole is the one that was measured).
//
// The hole of a Delaunay vertex is re-triangulated from its link alone (Devillers, "On deletion
// in Delaunay triangulations", 1999), by clipping ears whose circumcircles hold no other link
// vertex. Circles are decided by CGAL's perturbed in-circle test (LatticeDelaunay), so the
// mesh stays the unique triangulation Tin::from_points builds for its points.
//
// Units: lattice columns and rows (integers) for positions, metres for heights and errors.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/heightmap_raster.hpp"
#include "io/lattice_delaunay.hpp"
#include "io/progress.hpp"

namespace sandtin {

/// A triangulation of raster samples: lattice points (column, row counted from the south) and
/// counter-clockwise triangles over them covering the raster's rectangle [0, w-1] x [0, h-1].
struct LatticeMesh {
    std::vector<LatticePoint> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct DecimationStats {
    std::size_t removed = 0;  ///< vertices removed
    std::size_t rounds = 0;   ///< rounds run (the last one may remove nothing)
};

/// Removes vertices of `mesh`, never the rectangle's four corners, as long as every valid
/// sample stays within `max_error` (metres, >= 0) of the surface. Preconditions: `mesh` is the
/// perturbed Delaunay triangulation of its points (as LatticeDelaunay builds it), each of its
/// triangles within the bound. Postconditions: the same holds for the points left, which come
/// in Z-order (renumbered along a space-filling curve, not in their old order); every triangle
/// of the result was measured within the bound, either before this call or when its hole was.
DecimationStats decimate_within_bound(LatticeMesh& mesh, const HeightRaster& raster,
                                      double max_error, const ProgressCallback& progress = {});

}  // namespace sandtin
