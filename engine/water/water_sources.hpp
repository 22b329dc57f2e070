#pragma once
// Water that comes and goes (issue 40, item 2): rain over the whole terrain or a disc, nozzles
// at points, and evaporation, applied to either water scheme's state (VirtualPipes or
// ShallowWater) over a time step, with the volumes they moved counted so that the balance can
// be checked exactly:
//   volume now = volume before + added - evaporated - volume_left().
// Rain and nozzle water arrive with no horizontal momentum; evaporation leaves the rest of
// the water moving as it did.

#include <vector>

#include "geom/vec2.hpp"
#include "water/shallow_water.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

/// s: the longest step between two applications of the sources, whatever the scheme's CFL
/// step: rain and nozzles arrive in steps no longer than this even on shallow, slow water.
inline constexpr double kLongestSourceStep = 0.05;

struct Rain {
    double mm_per_hour = 0.0;  ///< >= 0
    Vec2 centre;               ///< with radius > 0: rain on the vertices within the disc
    double radius = 0.0;       ///< m; 0: on the whole terrain
};

struct Nozzle {
    Vec2 at;                         ///< m: where the jet lands
    double litres_per_second = 0.0;  ///< >= 0
    /// m, >= 0: the jet's radius. The water enters the vertices within it, each rising by the
    /// same depth (the volume over their lumped areas), as a jet that wide lands; 0, or no
    /// vertex within it, the vertex nearest to `at` takes it all (a column of water rising at
    /// one vertex while the pipes drain it, on a fine mesh).
    double radius = 0.0;
};

struct WaterSources {
    std::vector<Rain> rain;
    std::vector<Nozzle> nozzles;
    double evaporation_mm_per_hour = 0.0;  ///< >= 0, from every wet vertex
};

struct SourceReport {
    double added = 0.0;       ///< m³ of rain and nozzles
    double evaporated = 0.0;  ///< m³
};

/// Adds the rain and the nozzles' water for `dt` seconds, then evaporates (a vertex loses at
/// most the water it holds). Throws std::invalid_argument for a negative or non-finite rate,
/// radius or dt, and leaves the water as it was.
template <class Water>
SourceReport apply_sources(Water& water, const WaterSources& sources, double dt);
extern template SourceReport apply_sources(VirtualPipes&, const WaterSources&, double);
extern template SourceReport apply_sources(ShallowWater&, const WaterSources&, double);

}  // namespace sandtin
