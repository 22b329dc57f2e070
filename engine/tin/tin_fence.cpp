// Tin: bent-edge fencing. Before points and segments go into a coarse, curved TIN, the edges
// their insertion would remove whose two faces are bent against each other are constrained, so
// the insertion only subdivides those faces and the surface stays where it was beyond the edit.

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <utility>
#include <vector>

#include "geom/polygon_inclusion.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "tin/detail/walks.hpp"

namespace sandtin {

using detail::CdtPlus, detail::near_line, detail::start_face, detail::to_point,
    detail::walk_faces_along;
using Fh = Tin::Impl::Fh;

namespace {

/// Height of the plane through the three vertices at p.
double plane_height_at(const Tin::Impl& m, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                       Vec2 p) {
    const Vec2 pa = m.va.position[a];
    const Vec2 u = m.va.position[b] - pa;
    const Vec2 w = m.va.position[c] - pa;
    const double area = cross(u, w);
    const double beta = cross(p - pa, w) / area;
    const double gamma = cross(u, p - pa) / area;
    return m.va.height[a] + beta * (m.va.height[b] - m.va.height[a]) +
           gamma * (m.va.height[c] - m.va.height[a]);
}

/// Where the segment from `p` (height `hp`) to the vertex across edge (f, i) crosses that edge:
/// the vertical gap there between the edge and the segment; nullopt when they do not cross
/// (or p lies on the line through the edge).
std::optional<double> gap_at_crossing(const Tin::Impl& m, Fh f, int i, Vec2 p, double hp) {
    const Fh g = f->neighbor(i);
    const std::uint32_t a = f->vertex(CdtPlus::ccw(i))->id;
    const std::uint32_t b = f->vertex(CdtPlus::cw(i))->id;
    const std::uint32_t d = g->vertex(g->index(f))->id;
    const Vec2 pa = m.va.position[a];
    const Vec2 e = m.va.position[b] - pa;
    const Vec2 k = m.va.position[d] - p;
    const double denom = cross(e, k);
    const double t = cross(p - pa, k) / denom;
    const double s = cross(p - pa, e) / denom;
    if (!(t >= 0.0 && t <= 1.0 && s >= 0.0 && s <= 1.0)) return std::nullopt;  // NaN too
    const double on_edge = (1.0 - t) * m.va.height[a] + t * m.va.height[b];
    const double on_segment = (1.0 - s) * hp + s * m.va.height[d];
    return std::abs(on_edge - on_segment);
}

/// How far the surface over the quadrilateral of edge (f, i) moves if the edge gives way to
/// the other diagonal: the vertical gap between the two diagonals where they cross. A
/// non-convex quadrilateral cannot flip, but a re-triangulation can still remove its edge:
/// there, how far each far corner stands off the plane of the other face. 0 for coplanar
/// faces either way.
double edge_bend(const Tin::Impl& m, Fh f, int i) {
    const std::uint32_t c = f->vertex(i)->id;
    if (const auto gap = gap_at_crossing(m, f, i, m.va.position[c], m.va.height[c])) return *gap;
    const std::uint32_t a = f->vertex(CdtPlus::ccw(i))->id;
    const std::uint32_t b = f->vertex(CdtPlus::cw(i))->id;
    const Fh g = f->neighbor(i);
    const std::uint32_t d = g->vertex(g->index(f))->id;
    return std::max(std::abs(m.va.height[d] - plane_height_at(m, a, b, c, m.va.position[d])),
                    std::abs(m.va.height[c] - plane_height_at(m, a, b, d, m.va.position[c])));
}

/// A point inserted at `p` (height `hp`, on the surface) re-triangulates its cavity into a fan
/// from p: edge (f, i) of the cavity, seen from p, gives way to a segment from p to the vertex
/// of g = f->neighbor(i) across it, and the surface moves by the gap where the two cross (0
/// when they do not). This differs from edge_bend, which sees the edge from f's own third
/// vertex: after an edge split the faces are (a, p, c) and the flips that follow measure
/// against p.
double edge_bend_toward(const Tin::Impl& m, Fh f, int i, Vec2 p, double hp) {
    return gap_at_crossing(m, f, i, p, hp).value_or(0.0);
}

}  // namespace

std::size_t Tin::fence_bent_edges(std::span<const Vec2> points,
                                  std::span<const std::array<Vec2, 2>> segments, double tolerance,
                                  Generation generation, const PolygonInclusion* within,
                                  LocateHint* hint, EditReport* report) {
    Impl& m = *impl_;
    if (m.cdt.dimension() != 2) return 0;
    std::vector<std::array<VertexId, 2>> bent;
    // While walking a point's cavity: the point and its height on the surface.
    const Vec2* from = nullptr;
    double from_height = 0.0;
    auto consider = [&](Fh f, int i) {
        const Fh g = f->neighbor(i);
        if (m.cdt.is_infinite(f) || m.cdt.is_infinite(g) || m.cdt.is_constrained({f, i})) return;
        std::uint32_t a = f->vertex(CdtPlus::ccw(i))->id;
        std::uint32_t b = f->vertex(CdtPlus::cw(i))->id;
        if (!(edge_bend(m, f, i) > tolerance) &&
            !(from != nullptr && edge_bend_toward(m, f, i, *from, from_height) > tolerance)) {
            return;
        }
        if (within != nullptr) {
            const std::uint32_t c = f->vertex(i)->id;
            const std::uint32_t d = g->vertex(g->index(f))->id;
            if (within->contains(m.va.position[a]) && within->contains(m.va.position[b]) &&
                within->contains(m.va.position[c]) && within->contains(m.va.position[d])) {
                return;
            }
        }
        if (b < a) std::swap(a, b);
        bent.push_back({VertexId{a}, VertexId{b}});
    };
    // A point: the insertion removes the edges between faces in conflict with it. Walking
    // out from the face that holds it, a bent edge is fenced and not crossed, so faces beyond
    // it stay out of the cavity and their edges need no fence.
    std::vector<Fh> zone, reached, far_side;
    for (const Vec2 p : points) {
        if (!is_finite(p) || !m.domain.contains(p)) continue;
        zone.clear();
        m.cdt.get_conflicts(to_point(p), std::back_inserter(zone), start_face(m, p, hint));
        if (zone.empty()) continue;  // on a vertex
        auto in = [](const std::vector<Fh>& set, Fh f) {
            return std::find(set.begin(), set.end(), f) != set.end();
        };
        reached.assign(1, zone.front());  // the face holding p (CGAL lists it first)
        // A point on an edge, or within the snap distance of one (rim samples are crossings
        // of edges), goes into that edge, and the flips after the split start on both sides.
        const double snap2 = m.snap_distance * m.snap_distance;
        const Fh holder = zone.front();
        from = &p;
        from_height = plane_height_at(m, holder->vertex(0)->id, holder->vertex(1)->id,
                                      holder->vertex(2)->id, p);
        for (int i = 0; i < 3; ++i) {
            const Fh g = holder->neighbor(i);
            if (m.cdt.is_infinite(g)) continue;
            if (near_line(m.va.position[holder->vertex(CdtPlus::ccw(i))->id],
                          m.va.position[holder->vertex(CdtPlus::cw(i))->id], p, snap2)) {
                consider(holder, i);
                if (!in(reached, g)) reached.push_back(g);
                // CGAL's conflict zone stops at a constrained edge, but a split of that edge
                // flips faces on its far side too: their conflicts join the zone. (CGAL's
                // get_conflicts would locate p again and start on this side.)
                if (m.cdt.is_constrained({holder, i})) {
                    far_side.assign(1, g);
                    while (!far_side.empty()) {
                        const Fh h = far_side.back();
                        far_side.pop_back();
                        if (m.cdt.is_infinite(h) || in(zone, h) ||
                            !m.cdt.test_conflict(to_point(p), h)) {
                            continue;
                        }
                        zone.push_back(h);
                        for (int j = 0; j < 3; ++j)
                            if (!m.cdt.is_constrained({h, j})) far_side.push_back(h->neighbor(j));
                    }
                }
            }
        }
        for (std::size_t next = 0; next < reached.size(); ++next) {
            const Fh f = reached[next];
            for (int i = 0; i < 3; ++i) {
                const Fh g = f->neighbor(i);
                if (!in(zone, g) || in(reached, g) || m.cdt.is_constrained({f, i})) continue;
                const std::size_t before = bent.size();
                consider(f, i);
                if (bent.size() == before) reached.push_back(g);
            }
        }
    }
    from = nullptr;
    // A segment: every edge of the faces it crosses (those it removes, and the rims of the
    // pockets it leaves, which the flips after it may take).
    for (const auto& s : segments) {
        if (!is_finite(s[0]) || !is_finite(s[1]) || !m.domain.contains(s[0]) ||
            !m.domain.contains(s[1]) || s[0] == s[1]) {
            continue;
        }
        const detail::Point pb = to_point(s[1]);
        walk_faces_along(m, s[0], s[1], hint, [&](Fh f) {
            for (int i = 0; i < 3; ++i)
                consider(f, i);
            return m.cdt.oriented_side(f, pb) != CGAL::ON_NEGATIVE_SIDE;
        });
    }
    if (bent.empty()) return 0;
    std::sort(bent.begin(), bent.end(), [](const auto& x, const auto& y) {
        return std::pair(x[0].value, x[1].value) < std::pair(y[0].value, y[1].value);
    });
    bent.erase(std::unique(bent.begin(), bent.end()), bent.end());
    // Constraining an existing edge re-triangulates nothing.
    insert_constraints(bent, generation, VolumePolicy::Report, report);
    return bent.size();
}

}  // namespace sandtin
