#include "io/greedy_decimation.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <utility>

#include "io/greedy_scan.hpp"

namespace sandtin {

namespace {

using greedy_detail::Corner;
using greedy_detail::Plane;
using Triangle = std::array<std::uint32_t, 3>;

/// A triangle slot freed by a removal (a fill has fewer triangles than the star it replaces).
constexpr Triangle kDeadTriangle = {UINT32_MAX, UINT32_MAX, UINT32_MAX};

/// Stop once a round removes fewer than this share of the points left: later rounds only pick
/// up stragglers (on a rough 2048² tile at 3 m, rounds removed 258 142, 103 594, 30 262, 5 767
/// and 887 vertices), each at the price of a pass over the mesh.
constexpr double kLeastShareWorthARound = 0.01;
constexpr std::size_t kMostRounds = 12;

/// Per vertex, the triangles around it (compressed rows).
struct Incidence {
    std::vector<std::uint32_t> start;  ///< points + 1 offsets into `triangles`
    std::vector<std::uint32_t> triangles;

    void build(std::size_t points, const std::vector<Triangle>& tris) {
        start.assign(points + 1, 0);
        for (const Triangle& t : tris) {
            if (t == kDeadTriangle) continue;
            for (std::uint32_t v : t)
                ++start[v + 1];
        }
        std::partial_sum(start.begin(), start.end(), start.begin());
        triangles.resize(start.back());
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::uint32_t t = 0; t < tris.size(); ++t) {
            if (tris[t] == kDeadTriangle) continue;
            for (std::uint32_t v : tris[t])
                triangles[fill[v]++] = t;
        }
    }
};

/// Whether one vertex can go, and the largest error of a sample in its hole once filled.
struct Removal {
    bool possible = false;
    double error = 0.0;
};

class Decimator {
  public:
    Decimator(LatticeMesh& mesh, const HeightRaster& raster, double max_error)
        : mesh_(mesh), r_(raster), max_error_(max_error) {}

    DecimationStats run(const ProgressCallback& progress);

  private:
    // --- one vertex ---
    bool is_domain_corner(std::uint32_t v) const {
        const LatticePoint p = mesh_.points[v];
        return (p.x == 0 || p.x == max_x_) && (p.y == 0 || p.y == max_y_);
    }
    Corner corner(std::uint32_t v) const {
        const LatticePoint p = mesh_.points[v];
        return {p.x, p.y, r_.heights[sample(p)]};
    }
    std::size_t sample(LatticePoint p) const {
        return static_cast<std::size_t>(max_y_ - p.y) * r_.width + static_cast<std::size_t>(p.x);
    }
    /// The link of v counter-clockwise; for a vertex on the rectangle's border, the open chain
    /// from one border neighbour to the other. Empty when the star is not a fan (never for a
    /// valid mesh).
    void link(std::uint32_t v, std::vector<std::uint32_t>& ring);
    /// Re-triangulates the polygon `ring` (counter-clockwise) by clipping Delaunay ears into
    /// `out` (cleared first).
    bool fill_hole(const std::vector<std::uint32_t>& ring, std::vector<Triangle>& out);
    /// Measures v's removal; its hole's fill is left in fill_.
    Removal measure(std::uint32_t v);

    /// Renumbers the points along a Z-order curve and sorts the triangles by their first
    /// corner, so that a round's sweep over the vertices walks the mesh and the raster in
    /// space rather than in the insertion's scattered order.
    void order_by_space();

    // --- one round ---
    void measure_dirty();
    std::vector<std::uint32_t> choose_independent() const;
    /// Removes the chosen vertices: their stars' slots take the fills, the vertices stay
    /// numbered (marked gone) until compact().
    void remove(const std::vector<std::uint32_t>& chosen);
    /// Drops the gone vertices (renumbering the rest in order) and the dead triangle slots.
    void compact();

    LatticeMesh& mesh_;
    const HeightRaster& r_;
    double max_error_;
    std::int32_t max_x_ = 0;
    std::int32_t max_y_ = 0;
    Incidence incidence_;
    std::vector<std::uint8_t> gone_;       ///< per vertex: removed
    std::vector<std::uint8_t> dirty_;      ///< per vertex: its star changed since it was measured
    std::vector<std::uint8_t> removable_;  ///< per vertex, as last measured
    std::vector<double> error_;            ///< per vertex: its removal's error, as last measured
    // Scratch, reused from vertex to vertex.
    std::vector<std::uint32_t> ring_;
    std::vector<std::uint32_t> polygon_;
    std::vector<Triangle> fill_;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> link_edges_;
};

void Decimator::link(std::uint32_t v, std::vector<std::uint32_t>& ring) {
    ring.clear();
    // Each triangle (v, a, b) gives the link edge a -> b.
    auto& edges = link_edges_;
    edges.clear();
    for (std::uint32_t k = incidence_.start[v]; k < incidence_.start[v + 1]; ++k) {
        const Triangle& t = mesh_.triangles[incidence_.triangles[k]];
        const std::size_t at = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
        edges.emplace_back(t[(at + 1) % 3], t[(at + 2) % 3]);
    }
    // An open chain (a vertex on the rectangle's border) starts at the edge whose tail is no
    // edge's head; a closed one anywhere.
    std::uint32_t first = edges.front().first;
    for (const auto& e : edges) {
        bool is_head = false;
        for (const auto& f : edges)
            is_head = is_head || f.second == e.first;
        if (!is_head) {
            first = e.first;
            break;
        }
    }
    ring.push_back(first);
    for (std::size_t steps = 0; steps < edges.size(); ++steps) {
        const std::uint32_t at = ring.back();
        const auto next =
            std::find_if(edges.begin(), edges.end(), [at](const auto& e) { return e.first == at; });
        if (next == edges.end()) {
            ring.clear();
            return;
        }
        ring.push_back(next->second);
    }
    if (ring.back() == ring.front()) ring.pop_back();  // closed: an interior vertex
}

bool Decimator::fill_hole(const std::vector<std::uint32_t>& ring, std::vector<Triangle>& out) {
    out.clear();
    std::vector<std::uint32_t>& poly = polygon_;
    poly.assign(ring.begin(), ring.end());
    const auto& pts = mesh_.points;
    while (poly.size() > 3) {
        const std::size_t m = poly.size();
        bool clipped = false;
        for (std::size_t i = 0; i < m && !clipped; ++i) {
            const std::uint32_t a = poly[(i + m - 1) % m];
            const std::uint32_t b = poly[i];
            const std::uint32_t c = poly[(i + 1) % m];
            if (LatticeDelaunay::orient(pts[a], pts[b], pts[c]) <= 0) continue;
            bool empty = true;
            for (std::uint32_t d : poly) {
                if (d == a || d == b || d == c) continue;
                if (LatticeDelaunay::perturbed_in_circle(pts[a], pts[b], pts[c], pts[d]) > 0) {
                    empty = false;
                    break;
                }
            }
            if (!empty) continue;
            out.push_back({a, b, c});
            poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(i));
            clipped = true;
        }
        if (!clipped) return false;
    }
    if (LatticeDelaunay::orient(pts[poly[0]], pts[poly[1]], pts[poly[2]]) <= 0) return false;
    out.push_back({poly[0], poly[1], poly[2]});
    return true;
}

Removal Decimator::measure(std::uint32_t v) {
    Removal removal;
    if (is_domain_corner(v)) return removal;
    link(v, ring_);
    if (ring_.size() < 3) return removal;
    const LatticePoint p = mesh_.points[v];
    const bool own_valid = r_.is_valid(sample(p));
    // Fast rejections by the vertex's own sample, which is most often what put it in: the
    // filled surface at v lies between its link's lowest and highest corner...
    if (own_valid) {
        double lo = corner(ring_[0]).z;
        double hi = lo;
        for (std::uint32_t u : ring_) {
            const double z = corner(u).z;
            lo = std::min(lo, z);
            hi = std::max(hi, z);
        }
        const double z = r_.heights[sample(p)];
        if (z > hi + max_error_ || z < lo - max_error_) return removal;
    }
    if (!fill_hole(ring_, fill_)) return removal;
    // ... and exactly on the fill triangle that holds it.
    if (own_valid) {
        const auto d = [](std::int64_t x) { return static_cast<double>(x); };
        for (const Triangle& t : fill_) {
            const LatticePoint pa = mesh_.points[t[0]];
            const LatticePoint pb = mesh_.points[t[1]];
            const LatticePoint pc = mesh_.points[t[2]];
            if (LatticeDelaunay::orient(pa, pb, p) < 0 || LatticeDelaunay::orient(pb, pc, p) < 0 ||
                LatticeDelaunay::orient(pc, pa, p) < 0)
                continue;
            const Corner a = corner(t[0]);
            const Corner b = corner(t[1]);
            const Corner c = corner(t[2]);
            const Plane plane =
                Plane::through({d(a.i), d(b.i), d(c.i)}, {d(a.j), d(b.j), d(c.j)}, {a.z, b.z, c.z});
            const double z = plane.at(plane.row_start(d(p.y)), d(p.x));
            if (std::abs(z - r_.heights[sample(p)]) > max_error_) return removal;
            break;
        }
    }
    for (const Triangle& t : fill_) {
        const double e = greedy_detail::scan(corner(t[0]), corner(t[1]), corner(t[2]), r_).error;
        removal.error = std::max(removal.error, e);
        if (removal.error > max_error_) return removal;
    }
    removal.possible = true;
    return removal;
}

void Decimator::measure_dirty() {
    for (std::uint32_t v = 0; v < mesh_.points.size(); ++v) {
        if (!dirty_[v]) continue;
        dirty_[v] = 0;
        if (gone_[v]) continue;
        const Removal removal = measure(v);
        removable_[v] = removal.possible ? 1 : 0;
        error_[v] = removal.error;
    }
}

std::vector<std::uint32_t> Decimator::choose_independent() const {
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t v = 0; v < mesh_.points.size(); ++v) {
        if (removable_[v]) candidates.push_back(v);
    }
    // Cheapest first; ties by id, so the result does not depend on the sort.
    std::sort(candidates.begin(), candidates.end(), [&](std::uint32_t a, std::uint32_t b) {
        return error_[a] < error_[b] || (error_[a] == error_[b] && a < b);
    });
    std::vector<std::uint8_t> blocked(mesh_.points.size(), 0);
    std::vector<std::uint32_t> chosen;
    for (std::uint32_t v : candidates) {
        if (blocked[v]) continue;
        chosen.push_back(v);
        blocked[v] = 1;
        for (std::uint32_t k = incidence_.start[v]; k < incidence_.start[v + 1]; ++k) {
            for (std::uint32_t u : mesh_.triangles[incidence_.triangles[k]])
                blocked[u] = 1;
        }
    }
    return chosen;
}

void Decimator::remove(const std::vector<std::uint32_t>& chosen) {
    for (std::uint32_t v : chosen) {
        gone_[v] = 1;
        removable_[v] = 0;
        const std::uint32_t* star = incidence_.triangles.data() + incidence_.start[v];
        const std::uint32_t degree = incidence_.start[v + 1] - incidence_.start[v];
        // The neighbours' stars change: measure them again next round.
        for (std::uint32_t k = 0; k < degree; ++k) {
            for (std::uint32_t u : mesh_.triangles[star[k]])
                dirty_[u] = 1;
        }
        // Measured on this very star (no neighbour of v is removed in this round). A fill has
        // fewer triangles than the star (two fewer inside, one on the border): it takes the
        // star's first slots and the rest are left dead until the end.
        link(v, ring_);
        fill_hole(ring_, fill_);
        for (std::uint32_t k = 0; k < degree; ++k)
            mesh_.triangles[star[k]] = k < fill_.size() ? fill_[k] : kDeadTriangle;
    }
}

void Decimator::compact() {
    const std::size_t n = mesh_.points.size();
    std::vector<std::uint32_t> renumber(n, 0);
    std::uint32_t kept = 0;
    for (std::uint32_t v = 0; v < n; ++v) {
        if (gone_[v]) continue;
        renumber[v] = kept;
        mesh_.points[kept++] = mesh_.points[v];
    }
    mesh_.points.resize(kept);
    std::size_t live = 0;
    for (const Triangle& t : mesh_.triangles) {
        if (t == kDeadTriangle) continue;
        mesh_.triangles[live++] = {renumber[t[0]], renumber[t[1]], renumber[t[2]]};
    }
    mesh_.triangles.resize(live);
}

/// Interleaves the bits of x and y (each below 2^24, LatticeDelaunay::kMaxCoordinate).
std::uint64_t z_order(LatticePoint p) {
    const auto spread = [](std::uint64_t v) {
        v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
        v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
        v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
        v = (v | (v << 2)) & 0x3333333333333333ull;
        v = (v | (v << 1)) & 0x5555555555555555ull;
        return v;
    };
    return spread(static_cast<std::uint64_t>(p.x)) | spread(static_cast<std::uint64_t>(p.y)) << 1;
}

void Decimator::order_by_space() {
    const std::size_t n = mesh_.points.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    for (std::uint32_t v = 0; v < n; ++v)
        keyed[v] = {z_order(mesh_.points[v]), v};
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> renumber(n);
    std::vector<LatticePoint> points(n);
    for (std::uint32_t k = 0; k < n; ++k) {
        renumber[keyed[k].second] = k;
        points[k] = mesh_.points[keyed[k].second];
    }
    mesh_.points = std::move(points);
    // A counting sort of the renumbered triangles by their smallest corner.
    std::vector<std::uint32_t> start(n + 1, 0);
    for (Triangle& t : mesh_.triangles) {
        for (std::uint32_t& v : t)
            v = renumber[v];
        ++start[std::min({t[0], t[1], t[2]}) + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<Triangle> triangles(mesh_.triangles.size());
    for (const Triangle& t : mesh_.triangles)
        triangles[start[std::min({t[0], t[1], t[2]})]++] = t;
    mesh_.triangles = std::move(triangles);
}

DecimationStats Decimator::run(const ProgressCallback& progress) {
    for (const LatticePoint& p : mesh_.points) {
        max_x_ = std::max(max_x_, p.x);
        max_y_ = std::max(max_y_, p.y);
    }
    order_by_space();
    const std::size_t n = mesh_.points.size();
    gone_.assign(n, 0);
    dirty_.assign(n, 1);
    removable_.assign(n, 0);
    error_.assign(n, 0.0);
    DecimationStats stats;
    while (stats.rounds < kMostRounds) {
        ++stats.rounds;
        incidence_.build(mesh_.points.size(), mesh_.triangles);
        measure_dirty();
        const std::vector<std::uint32_t> chosen = choose_independent();
        if (chosen.empty()) break;
        remove(chosen);
        stats.removed += chosen.size();
        if (progress) {
            char stage[96];
            std::snprintf(stage, sizeof stage, "decimating: %zu points removed", stats.removed);
            progress({static_cast<double>(stats.rounds) / kMostRounds, stage});
        }
        if (static_cast<double>(chosen.size()) <
            kLeastShareWorthARound * static_cast<double>(n - stats.removed))
            break;
    }
    compact();
    if (progress) progress({1.0, "decimated"});
    return stats;
}

}  // namespace

DecimationStats decimate_within_bound(LatticeMesh& mesh, const HeightRaster& raster,
                                      double max_error, const ProgressCallback& progress) {
    return Decimator(mesh, raster, max_error).run(progress);
}

}  // namespace sandtin
