#pragma once
// The greedy importer's measuring core, shared by its insertion (greedy_tin.cpp) and its
// decimation (greedy_decimation.cpp): a triangle's plane, evaluated bit for bit the same
// whichever corner a triangulation lists first, and the scan that finds the valid raster sample
// of a closed lattice triangle farthest from that plane. Units: lattice columns and rows for
// positions, metres for heights and errors.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "io/heightmap_raster.hpp"
#include "io/lattice_raster.hpp"

namespace sandtin::greedy_detail {

/// A triangle corner on the sample lattice: column i, lattice row j counted from the south
/// (j = height - 1 - raster row), and its height.
struct Corner {
    std::int64_t i = 0;
    std::int64_t j = 0;
    double z = 0.0;
};

/// The plane through three corners, evaluated the same way by the greedy scan and by the final
/// measurement, so both see bit-identical heights at a sample.
struct Plane {
    double z0 = 0.0;
    double i0 = 0.0;
    double j0 = 0.0;
    double gi = 0.0;  ///< dz per lattice column
    double gj = 0.0;  ///< dz per lattice row

    /// Corners (u, v) in lattice units, counter-clockwise, with positive doubled area. The
    /// corners are rotated to start at the smallest (u, v), so a triangle gets bit-identical
    /// heights whichever corner its triangulation lists first: errors that sit exactly on the
    /// bound (common with 0.1 m Terrain-RGB steps) then compare the same in both phases.
    static Plane through(std::array<double, 3> u, std::array<double, 3> v,
                         std::array<double, 3> z) {
        std::size_t first = 0;
        for (std::size_t k = 1; k < 3; ++k) {
            if (u[k] < u[first] || (u[k] == u[first] && v[k] < v[first])) first = k;
        }
        std::rotate(u.begin(), u.begin() + static_cast<std::ptrdiff_t>(first), u.end());
        std::rotate(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(first), v.end());
        std::rotate(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(first), z.end());
        const double area2 = (u[1] - u[0]) * (v[2] - v[0]) - (v[1] - v[0]) * (u[2] - u[0]);
        const double bz = z[1] - z[0];
        const double cz = z[2] - z[0];
        Plane p;
        p.z0 = z[0];
        p.i0 = u[0];
        p.j0 = v[0];
        p.gi = (bz * (v[2] - v[0]) - cz * (v[1] - v[0])) / area2;
        p.gj = (cz * (u[1] - u[0]) - bz * (u[2] - u[0])) / area2;
        return p;
    }
    double row_start(double j) const { return z0 + gj * (j - j0); }
    double at(double z_row, double i) const { return from_first(z_row, i - i0); }
    /// The height `di` columns from the first corner: for lattice columns i - i0 is an exact
    /// integer, so a running counter gives bit-identical heights to at().
    double from_first(double z_row, double di) const { return z_row + gi * di; }
};

struct Worst {
    double error = 0.0;
    std::uint32_t sample = 0;  ///< raster index of the worst sample
};

/// Raises `worst` to the largest error among columns lo..hi of one raster row (the first such
/// column on ties). Unmasked rows take a branch-free maximum with four accumulators first,
/// then look for the column only when the row beats `worst`: most rows do not.
template <bool kMasked>
inline void scan_row(const Plane& plane, double z_row, const HeightRaster& r, std::size_t row_start,
                     std::int64_t lo, std::int64_t hi, Worst& worst) {
    const double* h = r.heights.data() + row_start;
    auto error = [&](std::int64_t i) {
        return std::abs(plane.at(z_row, static_cast<double>(i)) - h[i]);
    };
    if constexpr (kMasked) {
        const std::uint8_t* valid = r.valid.data() + row_start;
        for (std::int64_t i = lo; i <= hi; ++i) {
            if (!valid[i]) continue;
            const double e = error(i);
            if (e > worst.error) {
                worst.error = e;
                worst.sample = static_cast<std::uint32_t>(row_start + static_cast<std::size_t>(i));
            }
        }
    } else {
        double m0 = 0.0;
        double m1 = 0.0;
        double m2 = 0.0;
        double m3 = 0.0;
        std::int64_t i = lo;
        double di = static_cast<double>(lo) - plane.i0;
        const auto fast_error = [&](std::int64_t k, double d) {
            return std::abs(plane.from_first(z_row, d) - h[k]);
        };
        for (; i + 3 <= hi; i += 4, di += 4.0) {
            m0 = std::max(m0, fast_error(i, di));
            m1 = std::max(m1, fast_error(i + 1, di + 1.0));
            m2 = std::max(m2, fast_error(i + 2, di + 2.0));
            m3 = std::max(m3, fast_error(i + 3, di + 3.0));
        }
        for (; i <= hi; ++i, di += 1.0)
            m0 = std::max(m0, fast_error(i, di));
        const double row_max = std::max(std::max(m0, m1), std::max(m2, m3));
        if (row_max <= worst.error) return;
        // The same arithmetic finds the column again; bounded all the same.
        for (i = lo, di = static_cast<double>(lo) - plane.i0;
             i < hi && fast_error(i, di) != row_max; ++i, di += 1.0) {
        }
        worst.error = row_max;
        worst.sample = static_cast<std::uint32_t>(row_start + static_cast<std::size_t>(i));
    }
}

/// The valid sample of the closed triangle a, b, c (counter-clockwise) farthest from the
/// triangle's plane. The hot loop of the whole import.
template <bool kMasked>
Worst scan_triangle(const Corner& a, const Corner& b, const Corner& c, const HeightRaster& r) {
    const auto d = [](std::int64_t x) { return static_cast<double>(x); };
    const Plane plane =
        Plane::through({d(a.i), d(b.i), d(c.i)}, {d(a.j), d(b.j), d(c.j)}, {a.z, b.z, c.z});
    const std::int64_t top = static_cast<std::int64_t>(r.height) - 1;
    Worst worst;
    for_each_lattice_span(
        {a.i, b.i, c.i}, {a.j, b.j, c.j}, [&](std::int64_t j, std::int64_t lo, std::int64_t hi) {
            const std::size_t row_start = static_cast<std::size_t>(top - j) * r.width;
            scan_row<kMasked>(plane, plane.row_start(static_cast<double>(j)), r, row_start, lo, hi,
                              worst);
        });
    // A corner's own sample has no error; only rounding can put the maximum there.
    for (const Corner* k : {&a, &b, &c}) {
        if (worst.sample == static_cast<std::size_t>(top - k->j) * r.width + k->i) worst.error = 0;
    }
    return worst;
}

inline Worst scan(const Corner& a, const Corner& b, const Corner& c, const HeightRaster& r) {
    return r.valid.empty() ? scan_triangle<false>(a, b, c, r) : scan_triangle<true>(a, b, c, r);
}

/// A triangle named by its corners' raster indices, rotated to start at the smallest.
using SampleTriangle = std::array<std::uint32_t, 3>;

inline SampleTriangle canonical(SampleTriangle t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
}

}  // namespace sandtin::greedy_detail
