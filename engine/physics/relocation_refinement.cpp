#include "physics/relocation_refinement.hpp"

#include <algorithm>
#include <cmath>

#include "physics/talus_kernel.hpp"

namespace sandtin {

namespace {

/// Spacing of the refinement lattice as a fraction of r_S: Delaunay edges between lattice
/// neighbours are s long, and those next to skipped points stay below about 1.3 s <= r_S.
constexpr double kLatticeSpacing = 0.75;
/// Largest displacement of a lattice point, as a fraction of the spacing: neighbours stay at
/// least (1 - 2 * 0.25) s apart.
constexpr double kLatticeJitter = 0.25;

}  // namespace

std::size_t RelocationRefiner::refine(Tin& tin, std::vector<std::uint32_t>& around, double rs,
                                      std::vector<VertexId>* inserted) {
    if (around.empty()) return 0;
    const VertexArrays& va = tin.vertices();
    if (requested_.size() < va.size()) requested_.resize(va.size(), 0);
    const std::size_t before = tin.vertex_count();
    // The ids the TIN returns: a point within the snap distance of a vertex returns that
    // vertex (listed too: it is where the refinement was), a skipped split an invalid id.
    auto note = [&](std::span<const VertexId> ids) {
        if (inserted == nullptr) return;
        for (VertexId v : ids) {
            if (v.valid()) inserted->push_back(v);
        }
    };
    // New vertices come from one hexagonal lattice of spacing s over the whole domain (seed 000
    // §7.2 puts them on the circle of radius r_S around each eroding vertex instead; done for
    // every vertex that meets sand, those circles and the fans of edges they leave towards far
    // vertices put new vertices a fraction of a millimetre apart (measured: 0.05 mm edges with
    // r_S = 1 cm), and the stiff, irregular graph then creeps towards rest thousands of times
    // slower). Lattice points are at least s apart, so the refined region is well shaped
    // whichever vertices asked first. Lattice points within s / 2 of a corner are skipped;
    // when that leaves an edge longer than r_S, it is bisected instead.
    const double s = kLatticeSpacing * rs;
    const double row = s * 0.8660254037844386;
    const Rect domain = tin.domain();
    // A fixed pseudo-random jitter of each lattice point: a regular lattice has six edge
    // directions, and a pile resting on it is a hexagonal pyramid whose faces are steeper than
    // alpha between them (measured: the apex 4-5 % above the cone's, at any r_S).
    auto lattice_point = [&](long long i, long long j) {
        const auto key =
            static_cast<std::uint64_t>(i) * 0x100000001B3ull ^ static_cast<std::uint64_t>(j);
        const double shift = (j & 1) != 0 ? 0.5 * s : 0.0;
        return Vec2{domain.min.x + shift + static_cast<double>(i) * s +
                        kLatticeJitter * s * signed_unit_hash(0x5A17, key, 1),
                    domain.min.y + static_cast<double>(j) * row +
                        kLatticeJitter * s * signed_unit_hash(0x5A17, key, 2)};
    };
    std::vector<VertexId> ring;
    std::vector<Vec2> points;
    std::vector<EdgeSplit> bisect;
    for (std::uint32_t v : around) {
        if (v >= requested_.size() || requested_[v] || !va.alive[v]) continue;
        requested_[v] = 1;
        tin.neighbours(VertexId{v}, ring);
        const Vec2 pv = va.position[v];
        points.clear();
        bool long_edge = false;
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const Vec2 a = va.position[ring[k].value];
            const Vec2 b = va.position[ring[(k + 1) % ring.size()].value];
            long_edge = long_edge || distance(pv, a) > rs * (1.0 + 1e-9);
            // The fan triangle (v, a, b); the gap of a border vertex is not a triangle.
            if (!(cross(a - pv, b - pv) > 0.0)) continue;
            if (std::max(distance(pv, a), distance(pv, b)) <= rs * (1.0 + 1e-9)) continue;
            // Lattice points of the triangle within 1.5 r_S of v: enough for v's new
            // neighbours to be lattice-close, without filling a huge far triangle.
            const double reach = 1.5 * rs;
            const double x0 = std::max({std::min({pv.x, a.x, b.x}), pv.x - reach, domain.min.x});
            const double x1 = std::min({std::max({pv.x, a.x, b.x}), pv.x + reach, domain.max.x});
            const double y0 = std::max({std::min({pv.y, a.y, b.y}), pv.y - reach, domain.min.y});
            const double y1 = std::min({std::max({pv.y, a.y, b.y}), pv.y + reach, domain.max.y});
            const auto j0 = static_cast<long long>(std::ceil((y0 - domain.min.y) / row));
            const auto j1 = static_cast<long long>(std::floor((y1 - domain.min.y) / row));
            for (long long j = j0 - 1; j <= j1 + 1; ++j) {  // +-1: the jitter
                const double shift = (j & 1) != 0 ? 0.5 * s : 0.0;
                const auto i0 = static_cast<long long>(std::ceil((x0 - domain.min.x - shift) / s));
                const auto i1 = static_cast<long long>(std::floor((x1 - domain.min.x - shift) / s));
                for (long long i = i0 - 1; i <= i1 + 1; ++i) {
                    const Vec2 p = lattice_point(i, j);
                    if (distance(p, pv) > reach) continue;
                    // Strictly inside (v, a, b), and not crowding a corner.
                    if (!(cross(a - pv, p - pv) > 0.0 && cross(b - a, p - a) > 0.0 &&
                          cross(pv - b, p - b) > 0.0))
                        continue;
                    if (distance(p, pv) < 0.5 * s || distance(p, a) < 0.5 * s ||
                        distance(p, b) < 0.5 * s)
                        continue;
                    points.push_back(p);
                }
            }
        }
        if (!points.empty()) {
            // One call per vertex: the compensation for the Delaunay flips is shared by these
            // new vertices only, all within 1.5 r_S of v (a call over many piles would move
            // volume from a tall pile onto new vertices far away at another's toe).
            note(tin.insert_points_on_surface(points, &hint_, VolumePolicy::Conserve));
        } else if (long_edge) {
            for (std::size_t k = 0; k < ring.size(); ++k) {
                if (distance(pv, va.position[ring[k].value]) > rs * (1.0 + 1e-9))
                    bisect.push_back({VertexId{v}, ring[k], 0.5});
            }
        }
    }
    for (std::uint32_t v : around) {
        if (v < requested_.size()) requested_[v] = 0;
    }
    around.clear();
    // One edge at a time, for the same reason as above. A long edge gets the lattice point
    // nearest its midpoint when that point lies well inside the edge's diametral circle (so
    // the edge will not stay Delaunay) and clear of both ends; the exact midpoint only
    // otherwise, or when the edge survived. Plain midpoints are off the lattice, the lattice
    // points next to them are then skipped as crowded, the holes leave edges longer than r_S,
    // and those were bisected again. Measured on the pile from two triangles: with r_S = 2 cm,
    // 2347 bisections against 807 lattice points and edges down to 0.3 mm; snapping to the
    // lattice took the iterations to rest from 35 935 to 12 498 (sequential) and from 25 508
    // to 9 817 (Jacobi), and with r_S = 1 cm from 103 487 to 53 866 and 119 791 to 60 656.
    std::vector<VertexId> ends;
    for (const EdgeSplit& e : bisect) {
        if (!tin.is_alive(e.a) || !tin.is_alive(e.b)) continue;
        const Vec2 pa = va.position[e.a.value];
        const Vec2 pb = va.position[e.b.value];
        const double len = distance(pa, pb);
        const Vec2 m = 0.5 * (pa + pb);
        const auto jm = static_cast<long long>(std::floor((m.y - domain.min.y) / row + 0.5));
        Vec2 best{};
        double best_d = 1e300;
        for (long long j = jm - 2; j <= jm + 2; ++j) {
            const double shift = (j & 1) != 0 ? 0.5 * s : 0.0;
            const auto im =
                static_cast<long long>(std::floor((m.x - domain.min.x - shift) / s + 0.5));
            for (long long i = im - 2; i <= im + 2; ++i) {
                const Vec2 p = lattice_point(i, j);
                if (distance(p, m) < best_d) {
                    best_d = distance(p, m);
                    best = p;
                }
            }
        }
        const bool inside = best.x > domain.min.x && best.x < domain.max.x &&
                            best.y > domain.min.y && best.y < domain.max.y;
        if (inside && best_d < 0.45 * len && distance(best, pa) > 0.5 * s &&
            distance(best, pb) > 0.5 * s) {
            const Vec2 one[] = {best};
            note(tin.insert_points_on_surface(one, &hint_, VolumePolicy::Conserve));
            tin.neighbours(e.a, ends);
            if (std::find(ends.begin(), ends.end(), e.b) == ends.end()) continue;
        }
        note(tin.split_edges(std::span<const EdgeSplit>(&e, 1), VolumePolicy::Conserve));
    }
    return tin.vertex_count() - before;
}

}  // namespace sandtin
