#pragma once
// Independent oracles for the TIN tests. Everything here is re-derived from the public,
// CGAL-free view of a Tin (positions, heights, triangles()), in extended precision where it
// matters, so a test never compares the engine against itself.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin::test {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
/// The unit square, [0, 1] x [0, 1] m: the domain of most TIN and tool tests.
inline const Rect kUnitSquare = Rect::from_size(1.0, 1.0);

using Tri = std::array<VertexId, 3>;

/// The tests' random generator for a seed. Derived, not std::mt19937_64(seed): Tin::random_points
/// seeds its own generator with the plain seed, and drawing the same sequence would put query
/// and insertion points exactly on existing vertices.
inline std::mt19937_64 test_rng(std::uint64_t seed) {
    return std::mt19937_64(seed * 0x9E3779B97F4A7C15ull + 0x7E57ull);
}

/// z = a x + b y + c.
struct Plane {
    double a = 0.0;
    double b = 0.0;
    double c = 0.0;
    double operator()(Vec2 p) const { return a * p.x + b * p.y + c; }
    /// Exact integral of the plane over a rectangle: area * value at the centre.
    double integral(const Rect& r) const {
        return r.width() * r.height() * (a * r.centre().x + b * r.centre().y + c);
    }
};

inline long double ld(double x) {
    return static_cast<long double>(x);
}

/// Twice the signed area of (a, b, c) in extended precision.
inline long double orient2(Vec2 a, Vec2 b, Vec2 c) {
    return (ld(b.x) - ld(a.x)) * (ld(c.y) - ld(a.y)) - (ld(b.y) - ld(a.y)) * (ld(c.x) - ld(a.x));
}

/// Relative closeness with an absolute floor (for values that may legitimately be ~0).
inline bool close_rel(double a, double b, double rel, double abs_floor = 0.0) {
    return std::abs(a - b) <= std::max(rel * std::max(std::abs(a), std::abs(b)), abs_floor);
}

/// m³ of water the terrain holds: sum over live vertices of lumped area x water depth.
inline double water_volume(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    double sum = 0.0;
    for (std::size_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) sum += va.lumped_area[v] * va.water_depth[v];
    return sum;
}

inline std::vector<VertexId> live_ids(const Tin& tin) {
    std::vector<VertexId> out;
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t i = 0; i < va.size(); ++i) {
        if (va.alive[i]) out.push_back(VertexId{i});
    }
    return out;
}

inline bool on_domain_border(const Rect& d, Vec2 p) {
    return p.x == d.min.x || p.x == d.max.x || p.y == d.min.y || p.y == d.max.y;
}

/// Vertices lying on the domain border, counted from their positions.
inline std::size_t border_vertex_count(const Tin& tin) {
    std::size_t n = 0;
    for (VertexId v : live_ids(tin))
        n += on_domain_border(tin.domain(), tin.position(v)) ? 1 : 0;
    return n;
}

/// Euler's formula for a triangulated polygon with V vertices of which h lie on the hull.
inline std::size_t euler_triangle_count(std::size_t vertices, std::size_t hull_vertices) {
    return 2 * vertices - hull_vertices - 2;
}

/// Volume under the piecewise-linear surface, summed triangle by triangle:
/// sum area(t) * mean height of its corners.
inline double brute_force_volume(const Tin& tin, double datum = 0.0) {
    long double sum = 0.0L;
    for (const Tri& t : tin.triangles()) {
        const long double area2 =
            orient2(tin.position(t[0]), tin.position(t[1]), tin.position(t[2]));
        const long double h =
            ld(tin.height(t[0])) + ld(tin.height(t[1])) + ld(tin.height(t[2])) - 3.0L * ld(datum);
        sum += area2 * h / 6.0L;
    }
    return static_cast<double>(sum);
}

/// Lumped areas recomputed from triangles(): a third of every incident triangle's area.
/// The highest live vertex's height (m); -inf for no vertex.
inline double highest_height(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    double z = -std::numeric_limits<double>::infinity();
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) z = std::max(z, va.height[v]);
    }
    return z;
}

/// sum A m of the terrain's moisture (m²), in long double: a sum independent of the code's.
inline double brute_force_moisture(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    long double sum = 0.0L;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) {
            sum += static_cast<long double>(va.lumped_area[v]) *
                   static_cast<long double>(va.moisture[v]);
        }
    }
    return static_cast<double>(sum);
}

inline std::vector<double> brute_force_lumped_areas(const Tin& tin) {
    std::vector<long double> acc(tin.vertex_capacity(), 0.0L);
    for (const Tri& t : tin.triangles()) {
        const long double third =
            orient2(tin.position(t[0]), tin.position(t[1]), tin.position(t[2])) / 6.0L;
        for (VertexId v : t)
            acc[v.index()] += third;
    }
    std::vector<double> out(acc.size());
    for (std::size_t i = 0; i < acc.size(); ++i)
        out[i] = static_cast<double>(acc[i]);
    return out;
}

/// Barycentric coordinates of p in triangle (a, b, c), in extended precision.
inline std::array<long double, 3> barycentric(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
    const long double area2 = orient2(a, b, c);
    return {orient2(p, b, c) / area2, orient2(a, p, c) / area2, orient2(a, b, p) / area2};
}

/// Triangles (from triangles()) containing p, with a small tolerance for the border.
inline std::vector<Tri> triangles_containing(const Tin& tin, Vec2 p, long double eps = 1e-12L) {
    std::vector<Tri> out;
    for (const Tri& t : tin.triangles()) {
        const auto w = barycentric(p, tin.position(t[0]), tin.position(t[1]), tin.position(t[2]));
        if (w[0] >= -eps && w[1] >= -eps && w[2] >= -eps) out.push_back(t);
    }
    return out;
}

/// Height of the surface at p, interpolated in a triangle found by brute force.
inline double brute_force_height(const Tin& tin, Vec2 p) {
    const std::vector<Tri> ts = triangles_containing(tin, p);
    if (ts.empty()) return std::nan("");
    const Tri& t = ts.front();
    const auto w = barycentric(p, tin.position(t[0]), tin.position(t[1]), tin.position(t[2]));
    return static_cast<double>(w[0] * ld(tin.height(t[0])) + w[1] * ld(tin.height(t[1])) +
                               w[2] * ld(tin.height(t[2])));
}

/// Rotates a triangle so its smallest id comes first (keeps the orientation).
inline Tri canonical(Tri t) {
    while (!(t[0] < t[1] && t[0] < t[2]))
        t = {t[1], t[2], t[0]};
    return t;
}

inline std::set<Tri> triangle_set(const Tin& tin) {
    std::set<Tri> s;
    for (const Tri& t : tin.triangles())
        s.insert(canonical(t));
    return s;
}

/// In-circle determinant of `q` against the counter-clockwise triangle (p0, p1, p2), in extended
/// precision and relative to the squared spread of the points: positive when q lies strictly
/// inside the circumcircle, about zero when cocircular.
inline long double relative_in_circle(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 q) {
    const long double ax = ld(p0.x) - ld(q.x), ay = ld(p0.y) - ld(q.y);
    const long double bx = ld(p1.x) - ld(q.x), by = ld(p1.y) - ld(q.y);
    const long double cx = ld(p2.x) - ld(q.x), cy = ld(p2.y) - ld(q.y);
    const long double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const long double det =
        ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
    return det / ((a2 + b2 + c2) * (a2 + b2 + c2));
}
inline long double relative_in_circle(const Tin& tin, const Tri& t, VertexId q_id) {
    return relative_in_circle(tin.position(t[0]), tin.position(t[1]), tin.position(t[2]),
                              tin.position(q_id));
}

/// Interior edges, as (smaller id, larger id), whose two triangles are not clearly Delaunay:
/// the opposite vertex lies inside or (within `tolerance`) on the other triangle's circumcircle.
/// Releasing the constraint on such an edge would make CGAL flip it.
inline std::set<std::pair<std::uint32_t, std::uint32_t>> edges_not_clearly_delaunay(
    const Tin& tin, long double tolerance = 1e-12L) {
    const auto tris = tin.triangles();
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<std::size_t, int>> directed;
    for (std::size_t k = 0; k < tris.size(); ++k) {
        for (int i = 0; i < 3; ++i) {
            const VertexId a = tris[k][static_cast<std::size_t>((i + 1) % 3)];
            const VertexId b = tris[k][static_cast<std::size_t>((i + 2) % 3)];
            directed.emplace(std::make_pair(a.value, b.value), std::make_pair(k, i));
        }
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const auto& [edge, where] : directed) {
        if (edge.first > edge.second) continue;
        const auto twin = directed.find({edge.second, edge.first});
        if (twin == directed.end()) continue;
        const Tri& u = tris[twin->second.first];
        const VertexId opposite = u[static_cast<std::size_t>(twin->second.second)];
        if (relative_in_circle(tin, tris[where.first], opposite) > -tolerance) out.insert(edge);
    }
    return out;
}

/// Structural problems of the mesh found without CGAL: triangles counter-clockwise, every
/// directed edge used once, every undirected edge shared by at most two triangles, single-use
/// edges on the domain border, areas tiling the domain, lumped areas consistent, heights
/// finite, and unconstrained interior edges locally Delaunay.
inline std::vector<std::string> mesh_problems(const Tin& tin) {
    std::vector<std::string> problems;
    auto problem = [&](const std::string& s) {
        if (problems.size() < 10) problems.push_back(s);
    };
    const Rect d = tin.domain();
    const auto tris = tin.triangles();
    if (tris.size() != tin.triangle_count()) problem("triangles().size() != triangle_count()");
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<std::size_t, int>> directed;
    long double area = 0.0L;
    for (std::size_t k = 0; k < tris.size(); ++k) {
        const Tri& t = tris[k];
        for (VertexId v : t) {
            if (!tin.is_alive(v)) {
                problem("a triangle names a dead vertex");
                return problems;
            }
        }
        const long double a2 = orient2(tin.position(t[0]), tin.position(t[1]), tin.position(t[2]));
        if (!(a2 > 0.0L)) problem("triangle " + std::to_string(k) + " is not counter-clockwise");
        area += a2 / 2.0L;
        for (int i = 0; i < 3; ++i) {
            const VertexId a = t[static_cast<std::size_t>((i + 1) % 3)];
            const VertexId b = t[static_cast<std::size_t>((i + 2) % 3)];
            if (!directed.emplace(std::make_pair(a.value, b.value), std::make_pair(k, i)).second) {
                problem("a directed edge is used twice");
            }
        }
    }
    const long double domain_area = ld(d.width()) * ld(d.height());
    if (std::abs(area - domain_area) > 1e-10L * domain_area) problem("triangles do not tile");
    // Edges: twins, border, Delaunay.
    for (const auto& [edge, where] : directed) {
        const auto twin = directed.find({edge.second, edge.first});
        const Vec2 pa = tin.position(VertexId{edge.first});
        const Vec2 pb = tin.position(VertexId{edge.second});
        if (twin == directed.end()) {
            const bool border =
                (pa.x == d.min.x && pb.x == d.min.x) || (pa.x == d.max.x && pb.x == d.max.x) ||
                (pa.y == d.min.y && pb.y == d.min.y) || (pa.y == d.max.y && pb.y == d.max.y);
            if (!border) problem("an edge without twin is not on the domain border");
            continue;
        }
        if (edge.first > edge.second) continue;  // each interior edge once
        if (tin.is_constrained_edge(VertexId{edge.first}, VertexId{edge.second})) continue;
        const Tri& u = tris[twin->second.first];
        const VertexId opposite = u[static_cast<std::size_t>(twin->second.second)];
        if (relative_in_circle(tin, tris[where.first], opposite) > 1e-12L) {
            problem("edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) +
                    " is not locally Delaunay");
        }
    }
    // Attributes.
    const VertexArrays& va = tin.vertices();
    const std::vector<double> lumped = brute_force_lumped_areas(tin);
    for (VertexId v : live_ids(tin)) {
        if (!std::isfinite(va.height[v.index()])) problem("non-finite height");
        if (!d.contains(va.position[v.index()])) problem("vertex outside the domain");
        if (!close_rel(va.lumped_area[v.index()], lumped[v.index()], 1e-9)) {
            problem("lumped area of vertex " + std::to_string(v.value) + " differs from triangles");
        }
    }
    return problems;
}

inline std::string join(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines)
        s += l + "\n";
    return s;
}

/// What every TIN test expects after an edit: the Tin's own and CGAL's validity checks, the
/// independent checks of mesh_problems, and Euler's count of the triangles of a triangulated
/// rectangle (2V - B - 2, with B vertices on its border).
inline ::testing::AssertionResult tin_is_sound(const Tin& tin) {
    const ValidationReport r = tin.check_valid();
    if (!r.ok()) return ::testing::AssertionFailure() << "check_valid: " << r.summary();
    const std::vector<std::string> problems = mesh_problems(tin);
    if (!problems.empty()) return ::testing::AssertionFailure() << join(problems);
    const std::size_t expected = euler_triangle_count(tin.vertex_count(), border_vertex_count(tin));
    if (tin.triangle_count() != expected) {
        return ::testing::AssertionFailure() << tin.triangle_count() << " triangles, where Euler's "
                                             << "formula gives " << expected;
    }
    return ::testing::AssertionSuccess();
}

/// The expected content of take_changes(), from a brute-force diff of two states.
struct TinState {
    TinSnapshot snapshot;
    std::vector<std::uint8_t> masks;  ///< slot_constraint_mask per slot
};

inline TinState capture(const Tin& tin) {
    TinState s{tin.snapshot(), {}};
    for (TriangleSlot t = 0; t < tin.slot_capacity(); ++t)
        s.masks.push_back(tin.slot_constraint_mask(t));
    return s;
}

inline bool vertex_differs(const VertexArrays& a, const VertexArrays& b, std::size_t i) {
    const bool in_a = i < a.size();
    const bool in_b = i < b.size();
    if (!in_a || !in_b) {
        // An id beyond one side's capacity counts as dead there.
        return (in_a && a.alive[i]) || (in_b && b.alive[i]);
    }
    return !(a.position[i] == b.position[i]) || a.height[i] != b.height[i] ||
           a.bedrock[i] != b.bedrock[i] || a.material[i] != b.material[i] ||
           a.moisture[i] != b.moisture[i] || !(a.slide[i] == b.slide[i]) ||
           a.water_depth[i] != b.water_depth[i] || a.lumped_area[i] != b.lumped_area[i] ||
           a.alive[i] != b.alive[i];
}

inline std::vector<std::uint32_t> changed_vertices(const TinState& before, const TinState& after) {
    std::vector<std::uint32_t> out;
    const VertexArrays& a = before.snapshot.vertices;
    const VertexArrays& b = after.snapshot.vertices;
    const std::size_t n = std::max(a.size(), b.size());
    for (std::size_t i = 0; i < n; ++i) {
        if (vertex_differs(a, b, i)) out.push_back(static_cast<std::uint32_t>(i));
    }
    return out;
}

inline std::vector<std::uint32_t> changed_slots(const TinState& before, const TinState& after) {
    static constexpr std::array<std::uint32_t, 3> kFree = {kNoSlot, kNoSlot, kNoSlot};
    std::vector<std::uint32_t> out;
    const auto& a = before.snapshot.slots;
    const auto& b = after.snapshot.slots;
    const std::size_t n = std::max(a.size(), b.size());
    for (std::size_t i = 0; i < n; ++i) {
        const auto ta = i < a.size() ? a[i] : kFree;
        const auto tb = i < b.size() ? b[i] : kFree;
        const std::uint8_t ma = i < before.masks.size() ? before.masks[i] : 0;
        const std::uint8_t mb = i < after.masks.size() ? after.masks[i] : 0;
        if (ta != tb || ma != mb) out.push_back(static_cast<std::uint32_t>(i));
    }
    return out;
}

/// Expands ranges back into ids, checking they are sorted, disjoint and not adjacent.
inline std::vector<std::uint32_t> expand_ranges(const std::vector<IdRange>& ranges) {
    std::vector<std::uint32_t> out;
    for (std::size_t k = 0; k < ranges.size(); ++k) {
        EXPECT_LT(ranges[k].begin, ranges[k].end) << "empty range " << k;
        if (k > 0) {
            EXPECT_GT(ranges[k].begin, ranges[k - 1].end) << "ranges not merged/sorted";
        }
        for (std::uint32_t i = ranges[k].begin; i < ranges[k].end; ++i)
            out.push_back(i);
    }
    return out;
}

inline std::string list(const std::vector<std::uint32_t>& ids) {
    std::ostringstream s;
    s << "[";
    for (std::size_t i = 0; i < ids.size() && i < 40; ++i)
        s << (i ? " " : "") << ids[i];
    if (ids.size() > 40) s << " ...(" << ids.size() << ")";
    s << "]";
    return s.str();
}

/// Field-by-field snapshot equality. lumped_area is recomputed on restore, so it may differ in
/// the last bits from incrementally maintained values; it is compared to `lumped_rel`.
inline void expect_snapshots_equal(const TinSnapshot& a, const TinSnapshot& b,
                                   double lumped_rel = 0.0) {
    EXPECT_EQ(a.domain, b.domain);
    const VertexArrays& va = a.vertices;
    const VertexArrays& vb = b.vertices;
    ASSERT_EQ(va.size(), vb.size());
    EXPECT_EQ(va.position, vb.position);
    EXPECT_EQ(va.height, vb.height);
    EXPECT_EQ(va.bedrock, vb.bedrock);
    EXPECT_EQ(va.material, vb.material);
    EXPECT_EQ(va.moisture, vb.moisture);
    EXPECT_EQ(va.slide, vb.slide);
    EXPECT_EQ(va.water_depth, vb.water_depth);
    EXPECT_EQ(va.alive, vb.alive);
    ASSERT_EQ(va.lumped_area.size(), vb.lumped_area.size());
    std::size_t lumped_mismatches = 0;
    for (std::size_t i = 0; i < va.lumped_area.size(); ++i) {
        if (!close_rel(va.lumped_area[i], vb.lumped_area[i], lumped_rel)) ++lumped_mismatches;
    }
    EXPECT_EQ(lumped_mismatches, 0u) << "lumped areas differ beyond " << lumped_rel;
    EXPECT_EQ(a.vertex_free_list, b.vertex_free_list);
    EXPECT_EQ(a.slots, b.slots);
    EXPECT_EQ(a.slot_free_list, b.slot_free_list);
    EXPECT_EQ(a.constraints, b.constraints);
    EXPECT_EQ(a.constraint_capacity, b.constraint_capacity);
    EXPECT_EQ(a.constraint_free_list, b.constraint_free_list);
}

/// Intersection of segments [a,b] and [c,d] (assumed to cross properly); returns the point
/// and the parameter t along [a,b].
inline std::pair<Vec2, double> segment_intersection(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const long double den =
        (ld(b.x) - ld(a.x)) * (ld(d.y) - ld(c.y)) - (ld(b.y) - ld(a.y)) * (ld(d.x) - ld(c.x));
    const long double t =
        ((ld(c.x) - ld(a.x)) * (ld(d.y) - ld(c.y)) - (ld(c.y) - ld(a.y)) * (ld(d.x) - ld(c.x))) /
        den;
    const Vec2 p{static_cast<double>(ld(a.x) + t * (ld(b.x) - ld(a.x))),
                 static_cast<double>(ld(a.y) + t * (ld(b.y) - ld(a.y)))};
    return {p, static_cast<double>(t)};
}

/// Distance from p to the closed segment [a,b], in extended precision.
inline double distance_to_segment_ld(Vec2 p, Vec2 a, Vec2 b) {
    const long double abx = ld(b.x) - ld(a.x), aby = ld(b.y) - ld(a.y);
    const long double apx = ld(p.x) - ld(a.x), apy = ld(p.y) - ld(a.y);
    const long double len2 = abx * abx + aby * aby;
    long double t = len2 > 0.0L ? (apx * abx + apy * aby) / len2 : 0.0L;
    t = std::clamp(t, 0.0L, 1.0L);
    const long double dx = apx - t * abx, dy = apy - t * aby;
    return static_cast<double>(std::sqrt(dx * dx + dy * dy));
}

}  // namespace sandtin::test
