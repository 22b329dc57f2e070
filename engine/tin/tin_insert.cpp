// Tin: insertion of points and splits of edges. A point a rounding error from a vertex is that
// vertex, and one a hair off a constrained edge goes into the edge, so that no edit leaves a
// sliver the sand physics and the renderer choke on.

#include <cmath>
#include <limits>
#include <stdexcept>

#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/edit_finisher.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "tin/detail/walks.hpp"

namespace sandtin {

using detail::CdtPlus, detail::describe, detail::EditFinisher, detail::finite_location,
    detail::FiniteLocation, detail::near_line, detail::require, detail::require_inside,
    detail::start_face, detail::to_point;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

namespace {

/// Whether splitting edge (f, i) at p leaves every triangle around it counterclockwise (exact
/// predicate).
bool split_keeps_orientation(const Tin::Impl& m, Fh f, int i, const detail::Point& p) {
    const auto orientation = detail::Kernel().orientation_2_object();
    auto side_ok = [&](Fh face, int k) {
        const Vh c = face->vertex(k);
        if (m.cdt.is_infinite(c)) return true;
        const Vh u = face->vertex(CdtPlus::ccw(k));
        const Vh w = face->vertex(CdtPlus::cw(k));
        return orientation(c->point(), u->point(), p) == CGAL::LEFT_TURN &&
               orientation(c->point(), p, w->point()) == CGAL::LEFT_TURN;
    };
    const Fh g = f->neighbor(i);
    return side_ok(f, i) && side_ok(g, g->index(f));
}

/// After a point was inserted into an edge it lies a rounding error (or, snapped, up to the
/// snap distance) off: an edge from it may miss the Delaunay criterion that CGAL's flips
/// around a new vertex do not look at.
void flip_around_split(Tin::Impl& m, Vh v) {
    CdtPlus::List_edges incident;
    auto ec = m.cdt.incident_edges(v);
    const auto done = ec;
    do {
        if (!m.cdt.is_infinite(*ec) && !m.cdt.is_constrained(*ec)) incident.push_back(*ec);
    } while (++ec != done);
    m.cdt.propagating_flip(incident);
}

/// Inserts one point inside an edit (no finish): at `height`, or on the current surface when
/// height is NaN. Returns the id and whether a new vertex was created. A point on an existing
/// vertex returns that vertex (its height set when one is given).
std::pair<VertexId, bool> insert_one(Tin& tin, Tin::Impl& m, EditFinisher& finisher, Vec2 p,
                                     double height, LocateHint* hint) {
    CdtPlus::Locate_type lt;
    int li = 0;
    const Fh f = m.cdt.locate(to_point(p), lt, li, start_face(m, p, hint));
    if (lt == CdtPlus::VERTEX) {
        const VertexId existing{f->vertex(li)->id};
        if (!std::isnan(height)) tin.set_height(existing, height);
        if (hint != nullptr) hint->vertex = existing;
        return {existing, false};
    }
    const FiniteLocation loc = finite_location(m, p, lt, f, li);
    // A point a rounding error away from a vertex (a rim crossing computed at a vertex, say)
    // would make a sliver the physics and the renderer choke on: it is that vertex. The vertex
    // may be a corner of the face or, when the point lies a hair inside one of the face's
    // edges, the far corner of the face across it (two vertices that close, at different
    // heights, are a vertical step the sand physics can never level).
    const double snap2 = m.snap_distance * m.snap_distance;
    std::array<std::uint32_t, 6> near_ids{};
    std::size_t near_count = 0;
    for (std::size_t i = 0; i < 3; ++i)
        near_ids[near_count++] = loc.corners[i];
    std::array<bool, 3> near_edge{};  // p within the snap distance of the edge opposite corner i
    for (std::size_t i = 0; i < 3; ++i) {
        // Only across an edge p is within the snap distance of (corner i is opposite it).
        if (!near_line(m.va.position[loc.corners[(i + 1) % 3]],
                       m.va.position[loc.corners[(i + 2) % 3]], p, snap2)) {
            continue;
        }
        near_edge[i] = true;
        const Fh g = loc.face->neighbor(static_cast<int>(i));
        const Vh far = g->vertex(g->index(loc.face));
        if (!m.cdt.is_infinite(far)) near_ids[near_count++] = far->id;
    }
    for (std::size_t i = 0; i < near_count; ++i) {
        if (length_squared(m.va.position[near_ids[i]] - p) <= snap2) {
            // The vertex keeps its own height: the point was not quite there, and what the
            // caller computed for its spot (a rim or profile height) is not the vertex's.
            const VertexId existing{near_ids[i]};
            if (hint != nullptr) hint->vertex = existing;
            return {existing, false};
        }
    }
    // A point a hair off a constrained edge goes into the edge, as a point exactly on it does,
    // splitting the constraint: beside it, it would make a sliver with the constrained edge that
    // no Delaunay flip removes, whose long edges no later split can take apart (each split point
    // folds the sliver over; see CdtPlus::thread_through_near_vertices for the constraints').
    bool onto_edge = false;
    for (int i = 0; i < 3 && lt == CdtPlus::FACE; ++i) {
        const auto k = static_cast<std::size_t>(i);
        // Not on the domain's border: there the vertex would dent the convex hull.
        if (!near_edge[k] || !loc.face->is_constrained(i) ||
            m.cdt.is_infinite(loc.face->neighbor(i)))
            continue;
        const Vec2 a = m.va.position[loc.corners[(k + 1) % 3]];
        const Vec2 e = m.va.position[loc.corners[(k + 2) % 3]] - a;
        const Vec2 c = p - a;
        if (detail::on_segment_up_to_snap(e.x, e.y, c.x, c.y, snap2) &&
            split_keeps_orientation(m, loc.face, i, to_point(p))) {
            lt = CdtPlus::EDGE;
            li = i;
            onto_edge = true;
        }
    }
    if (std::isnan(height)) {
        height = 0.0;
        for (std::size_t i = 0; i < 3; ++i)
            height += loc.weights[i] * m.va.height[loc.corners[i]];
    }
    const Vh v = m.cdt.insert(to_point(p), lt, f, li);
    if (onto_edge) flip_around_split(m, v);
    finisher.prepare_born();
    m.va.height[v->id] = height;
    finisher.inherit(v->id, loc.corners, loc.weights);
    // A vertex placed below the interpolated bedrock takes the bedrock down with it: the sand
    // thickness is never negative.
    if (m.va.bedrock[v->id] > height) m.va.bedrock[v->id] = height;
    if (hint != nullptr) hint->vertex = VertexId{v->id};
    return {VertexId{v->id}, true};
}

}  // namespace

VertexId Tin::insert_point(Vec2 p, double height, LocateHint* hint, EditReport* report) {
    const std::array<Vec2, 1> ps = {p};
    const std::array<double, 1> hs = {height};
    return insert_points(ps, hs, hint, report).front();
}

VertexId Tin::insert_point_on_surface(Vec2 p, LocateHint* hint, VolumePolicy policy,
                                      EditReport* report) {
    const std::array<Vec2, 1> ps = {p};
    return insert_points_on_surface(ps, hint, policy, report).front();
}

std::vector<VertexId> Tin::insert_points(std::span<const Vec2> points,
                                         std::span<const double> heights, LocateHint* hint,
                                         EditReport* report) {
    Impl& m = *impl_;
    require(points.size() == heights.size(), "insert_points: points and heights differ in length");
    for (std::size_t i = 0; i < points.size(); ++i) {
        require_inside(m.domain, points[i], "insert_points");
        if (!std::isfinite(heights[i])) {
            throw std::invalid_argument("insert_points " + describe(points[i]) +
                                        ": height is not finite");
        }
    }
    std::vector<VertexId> ids;
    ids.reserve(points.size());
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    for (std::size_t i = 0; i < points.size(); ++i) {
        ids.push_back(insert_one(*this, m, finisher, points[i], heights[i], hint).first);
    }
    finisher.finish(VolumePolicy::Report, {}, report);
    return ids;
}

std::vector<VertexId> Tin::insert_points_on_surface(std::span<const Vec2> points, LocateHint* hint,
                                                    VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    for (Vec2 p : points)
        require_inside(m.domain, p, "insert_points_on_surface");
    std::vector<VertexId> ids;
    std::vector<std::uint32_t> created;
    ids.reserve(points.size());
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    for (Vec2 p : points) {
        const auto [id, is_new] =
            insert_one(*this, m, finisher, p, std::numeric_limits<double>::quiet_NaN(), hint);
        ids.push_back(id);
        if (is_new) created.push_back(id.value);
    }
    finisher.finish(policy, created, report);
    return ids;
}

std::vector<VertexId> Tin::split_edges(std::span<const EdgeSplit> splits, VolumePolicy policy,
                                       EditReport* report) {
    Impl& m = *impl_;
    std::vector<VertexId> ids;
    std::vector<std::uint32_t> created;
    ids.reserve(splits.size());
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    for (const EdgeSplit& split : splits) {
        Fh f;
        int i = 0;
        if (!m.alive(split.a) || !m.alive(split.b) || !(split.t > 0.0 && split.t < 1.0) ||
            !m.cdt.is_edge(m.handle(split.a), m.handle(split.b), f, i)) {
            ids.push_back(VertexId{});  // an earlier split in this batch removed the edge
            continue;
        }
        const Vec2 pa = m.va.position[split.a.value];
        const Vec2 pb = m.va.position[split.b.value];
        const Vec2 p = lerp(pa, pb, split.t);
        // Nor next to the far corner of either triangle: a vertex there (a sliver's apex a hair
        // off the segment) would make the new one its near-duplicate. The relocation radius's
        // bisections did that again and again beside a tool's rim, each new midpoint beside the
        // last at half the distance, down to 1e-9 m at different heights (a step the sand
        // could never level: a groove eroded with r_S = 1 cm never came to rest).
        const Fh across = f->neighbor(i);
        const Vh far_corners[] = {f->vertex(i), across->vertex(across->index(f))};
        auto too_close = [&](Vec2 q) {
            return length_squared(p - q) <= m.snap_distance * m.snap_distance;
        };
        bool crowded = too_close(pa) || too_close(pb);
        for (const Vh c : far_corners)
            crowded = crowded || (!m.cdt.is_infinite(c) && too_close(m.va.position[c->id]));
        if (crowded) {
            ids.push_back(VertexId{});
            continue;
        }
        // Inserted into the edge itself (CGAL trusts the locate type), so the surface is unchanged
        // and a constrained edge is split like any other, even when rounding puts p a hair off
        // the segment. Trusting it is only safe while both halves of both triangles keep their
        // orientation: next to a sliver, the rounded p can fall on the far side of the opposite
        // vertex and fold a face over (found by `sandtin stress`). Such a split is skipped.
        if (!split_keeps_orientation(m, f, i, to_point(p))) {
            ids.push_back(VertexId{});
            continue;
        }
        const Vh v = m.cdt.insert(to_point(p), CdtPlus::EDGE, f, i);
        flip_around_split(m, v);
        finisher.prepare_born();
        m.va.height[v->id] =
            (1.0 - split.t) * m.va.height[split.a.value] + split.t * m.va.height[split.b.value];
        const std::array<std::uint32_t, 2> sources = {split.a.value, split.b.value};
        const std::array<double, 2> weights = {1.0 - split.t, split.t};
        finisher.inherit(v->id, sources, weights);
        if (m.va.bedrock[v->id] > m.va.height[v->id]) m.va.bedrock[v->id] = m.va.height[v->id];
        ids.push_back(VertexId{v->id});
        created.push_back(v->id);
    }
    finisher.finish(policy, created, report);
    return ids;
}

}  // namespace sandtin
