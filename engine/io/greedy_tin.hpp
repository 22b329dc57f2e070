#pragma once
// Error-bounded TIN from a height raster by greedy insertion, after Garland & Heckbert, "Fast
// polygonal approximation of terrains and height fields" (1995).
//
// Start from the four domain corners. Every triangle keeps a candidate: the raster sample
// inside it (closed triangle) with the largest vertical error |surface - sample|. A priority
// queue hands out the worst candidate, which is inserted into the Delaunay triangulation; only
// the triangles the insertion changed are rescanned. Stop when the worst error is <= max_error
// or there are max_points vertices.
//
// Two phases. The insertions run on a lean lattice Delaunay triangulation (LatticeDelaunay),
// which breaks cocircular ties exactly as CGAL does; the chosen points then become the TIN in
// one bulk build. Phase 2 rescans every TIN triangle that is not a triangle of phase 1 (the
// same corners give bit-identical errors) and, driven by the TIN's change journal, inserts
// whatever the bound still needs, so the bound never rests on the two triangulations agreeing.
// Between the two phases a decimation pass (io/greedy_decimation.hpp) removes the vertices the
// bound no longer needs: greedy insertion never takes a point back, and its early points are
// often made redundant by later ones. A final pass measures every sample once (max error,
// RMSD).
//
// Units: metres. Invariants of the result: every vertex lies on a raster sample and has that
// sample's height; the TIN is the TIN that was measured, so when `reached_error` is true every
// valid sample lies within max_error of the surface. No-data samples (HeightRaster::valid)
// are ignored by the error and never become vertices, except the four domain corners, which
// take their (filled) heights.

#include <cstddef>
#include <cstdint>

#include "io/heightmap_raster.hpp"
#include "io/progress.hpp"
#include "tin/tin.hpp"

namespace sandtin {

struct GreedyOptions {
    double max_error = 1.0;      ///< metres; >= 0
    std::size_t max_points = 0;  ///< stop at this many vertices (0: no limit; else >= 4)
    /// After the insertion, remove the vertices the bound no longer needs
    /// (io/greedy_decimation.hpp). Off only to compare with plain greedy insertion.
    bool decimate = true;
};

struct GreedyStats {
    std::size_t points = 0;
    std::size_t triangles = 0;
    double max_error = 0.0;      ///< metres, over all valid samples, measured on the final TIN
    double rmsd = 0.0;           ///< metres, root mean square of the errors of all valid samples
    std::size_t samples = 0;     ///< valid samples measured
    bool reached_error = false;  ///< false when max_points stopped the insertion first
    /// Points the TIN needed beyond the fast lattice pass (0 when the two triangulations
    /// agree, as they should).
    std::size_t fix_up_points = 0;
    /// Vertices the decimation removed after the insertion (0 when it did not run).
    std::size_t decimated_points = 0;
    double build_ms = 0.0;     ///< insertion, decimation and the TIN's build (wall time)
    double decimate_ms = 0.0;  ///< the decimation's part of build_ms
    double measure_ms = 0.0;   ///< the final measurement pass
};

struct GreedyResult {
    Tin tin;
    GreedyStats stats;
};

/// Throws std::invalid_argument for a negative or non-finite max_error or max_points in
/// 1..3, and std::runtime_error (via check_raster) for an invalid raster. The raster's no-data
/// samples must have been filled (fill_nodata) so the corners have heights. The TIN tracks
/// changes (its journal is what phase 2 runs on), so its first take_changes() reports
/// everything, as for any new TIN. `progress` (io/progress.hpp) hears the insertion, the
/// build of the TIN and the final measurement; the share of the insertion done is estimated
/// from the worst error left (see GreedyProgress in greedy_tin.cpp).
GreedyResult greedy_tin(const HeightRaster& raster, const GreedyOptions& options,
                        const ProgressCallback& progress = {});

/// Maximum error and RMSD of any TIN over the raster's domain against the raster's valid
/// samples, each sample measured once. The TIN must cover raster.domain().
GreedyStats measure_tin_error(const Tin& tin, const HeightRaster& raster);

}  // namespace sandtin
