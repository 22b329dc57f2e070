#pragma once
// Triangulations of lattice points as sets of corner triples, so that two triangulations of
// the same points (the importer's lattice passes, CGAL's TIN) compare whatever their vertex
// numbering and corner order; and an engine raster as the import oracle's copy.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>

#include "io/heightmap_raster.hpp"
#include "support/raster_oracle.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

using LatticeTriple = std::array<std::pair<std::int64_t, std::int64_t>, 3>;

/// The same triangle whichever corner is listed first.
inline LatticeTriple rotated_to_smallest(LatticeTriple t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
}

/// The TIN's triangles, its vertex positions rounded to the lattice.
inline std::set<LatticeTriple> lattice_triples(const Tin& tin) {
    std::set<LatticeTriple> out;
    for (const auto& t : tin.triangles()) {
        LatticeTriple tri;
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec2 p = tin.position(t[k]);
            tri[k] = {std::llround(p.x), std::llround(p.y)};
        }
        out.insert(rotated_to_smallest(tri));
    }
    return out;
}

/// The oracle's copy of an engine raster (heights, validity and cell size).
inline OracleRaster oracle_raster_of(const HeightRaster& r) {
    OracleRaster o;
    o.width = r.width;
    o.height = r.height;
    o.cell = r.cell_size;
    o.heights = r.heights;
    o.valid = r.valid;
    return o;
}

}  // namespace sandtin::test
