// Point location and walks over the faces of the triangulation (tin/detail/walks.hpp).

#include "tin/detail/walks.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace sandtin::detail {

using Fh = FaceHandle;
using Vh = VertexHandle;

namespace {

std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

Fh jump_start_face(const Tin::Impl& m, Vec2 p) {
    // Mücke et al.'s jump-and-walk: start from the closest of ~n^(1/3) sampled vertices.
    const std::uint32_t capacity = m.events.vertex_ids.capacity();
    const std::uint32_t live = m.events.vertex_ids.live();
    if (live == 0) return Fh();
    const int samples = std::clamp(static_cast<int>(std::cbrt(static_cast<double>(live))), 1, 256);
    std::uint64_t state = std::hash<double>{}(p.x) * 31u + std::hash<double>{}(p.y);
    std::uint32_t best = kNoId;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int tries = 0, found = 0; found < samples && tries < samples * 8; ++tries) {
        const auto id = static_cast<std::uint32_t>(splitmix64(state) % capacity);
        if (m.events.vertex_of_id[id] == nullptr) continue;
        ++found;
        const double d2 = length_squared(m.va.position[id] - p);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = id;
        }
    }
    return best == kNoId ? Fh() : m.handle(best)->face();
}

}  // namespace

Fh start_face(const Tin::Impl& m, Vec2 p, const LocateHint* hint) {
    if (hint != nullptr && m.alive(hint->vertex)) return m.handle(hint->vertex)->face();
    return jump_start_face(m, p);
}

FiniteLocation finite_location(const Tin::Impl& m, Vec2 p, CdtPlus::Locate_type lt, Fh f, int li) {
    if (m.cdt.is_infinite(f)) {
        // On the border the walk may report the outer face; the neighbour across the
        // finite edge (EDGE) or any finite incident face (VERTEX) holds the point too.
        if (lt == CdtPlus::EDGE) {
            f = f->neighbor(li);
        } else {
            const Vh v = f->vertex(li);
            auto fc = m.cdt.incident_faces(v);
            while (m.cdt.is_infinite(fc))
                ++fc;
            f = fc;
        }
    }
    FiniteLocation out;
    out.face = f;
    std::array<Vec2, 3> c;
    for (int i = 0; i < 3; ++i) {
        out.corners[static_cast<std::size_t>(i)] = f->vertex(i)->id;
        c[static_cast<std::size_t>(i)] = m.va.position[f->vertex(i)->id];
    }
    const double area2 = cross(c[1] - c[0], c[2] - c[0]);
    double w0 = cross(c[1] - p, c[2] - p) / area2;
    double w1 = cross(c[2] - p, c[0] - p) / area2;
    // Exactly on a vertex or edge, rounding can make a weight a hair negative.
    w0 = std::clamp(w0, 0.0, 1.0);
    w1 = std::clamp(w1, 0.0, 1.0 - w0);
    out.weights = {w0, w1, 1.0 - w0 - w1};
    return out;
}

void update_hint(LocateHint* hint, const FiniteLocation& loc) {
    if (hint == nullptr) return;
    std::size_t best = 0;
    for (std::size_t i = 1; i < 3; ++i) {
        if (loc.weights[i] > loc.weights[best]) best = i;
    }
    hint->vertex = VertexId{loc.corners[best]};
}

std::optional<FiniteLocation> walk_to(const Tin::Impl& m, Vec2 p, Fh start,
                                      CdtPlus::Locate_type& lt) {
    int li = 0;
    const Fh f = m.cdt.locate(to_point(p), lt, li, start);
    if (lt == CdtPlus::OUTSIDE_CONVEX_HULL || lt == CdtPlus::OUTSIDE_AFFINE_HULL)
        return std::nullopt;
    return finite_location(m, p, lt, f, li);
}

Fh face_at(const Tin::Impl& m, Vec2 p, LocateHint* hint) {
    CdtPlus::Locate_type lt;
    int li = 0;
    const Fh f = m.cdt.locate(to_point(p), lt, li, start_face(m, p, hint));
    if (lt == CdtPlus::OUTSIDE_CONVEX_HULL || lt == CdtPlus::OUTSIDE_AFFINE_HULL) return Fh();
    const FiniteLocation loc = finite_location(m, p, lt, f, li);
    update_hint(hint, loc);
    return loc.face;
}

}  // namespace sandtin::detail
