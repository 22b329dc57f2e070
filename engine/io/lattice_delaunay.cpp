#include "io/lattice_delaunay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sandtin {

namespace {

__extension__ using Wide = __int128;

std::size_t next(std::size_t e) {
    return e - e % 3 + (e + 1) % 3;
}
std::size_t prev(std::size_t e) {
    return e - e % 3 + (e + 2) % 3;
}

bool less_xy(LatticePoint a, LatticePoint b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

int sign(Wide v) {
    return (v > 0) - (v < 0);
}

}  // namespace

std::int64_t LatticeDelaunay::orient(LatticePoint a, LatticePoint b, LatticePoint c) {
    return (static_cast<std::int64_t>(b.x) - a.x) * (static_cast<std::int64_t>(c.y) - a.y) -
           (static_cast<std::int64_t>(b.y) - a.y) * (static_cast<std::int64_t>(c.x) - a.x);
}

int LatticeDelaunay::perturbed_in_circle(LatticePoint p0, LatticePoint p1, LatticePoint p2,
                                         LatticePoint p) {
    {
        // Floating-point filter: differences and squared lengths are exact in doubles (below
        // 2^52); the determinant's rounding error is at most about 10 epsilon times its
        // permanent (Shewchuk's incircle bound), taken 10 times wider. Only near-cocircular
        // cases fall through to the exact arithmetic below.
        const double ax = double(p0.x) - p.x;
        const double ay = double(p0.y) - p.y;
        const double bx = double(p1.x) - p.x;
        const double by = double(p1.y) - p.y;
        const double cx = double(p2.x) - p.x;
        const double cy = double(p2.y) - p.y;
        const double a2 = ax * ax + ay * ay;
        const double b2 = bx * bx + by * by;
        const double c2 = cx * cx + cy * cy;
        const double det =
            a2 * (bx * cy - by * cx) + b2 * (cx * ay - cy * ax) + c2 * (ax * by - ay * bx);
        const double permanent = a2 * (std::abs(bx * cy) + std::abs(by * cx)) +
                                 b2 * (std::abs(cx * ay) + std::abs(cy * ax)) +
                                 c2 * (std::abs(ax * by) + std::abs(ay * bx));
        const double bound = 1e-14 * permanent;
        if (det > bound) return 1;
        if (det < -bound) return -1;
    }
    const Wide ax = p0.x - p.x;
    const Wide ay = p0.y - p.y;
    const Wide bx = p1.x - p.x;
    const Wide by = p1.y - p.y;
    const Wide cx = p2.x - p.x;
    const Wide cy = p2.y - p.y;
    const Wide a2 = ax * ax + ay * ay;
    const Wide b2 = bx * bx + by * by;
    const Wide c2 = cx * cx + cy * cy;
    const Wide det = ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
    if (det != 0) return sign(det);
    // Cocircular: CGAL's symbolic perturbation. Look at the points from the largest in xy
    // order down; the first decisive one settles the sign.
    std::array<const LatticePoint*, 4> order = {&p0, &p1, &p2, &p};
    std::sort(order.begin(), order.end(),
              [](const LatticePoint* u, const LatticePoint* v) { return less_xy(*u, *v); });
    for (int i = 3; i > 0; --i) {
        const LatticePoint* q = order[static_cast<std::size_t>(i)];
        if (q == &p) return -1;
        std::int64_t o = 0;
        if (q == &p2 && (o = orient(p0, p1, p)) != 0) return o > 0 ? 1 : -1;
        if (q == &p1 && (o = orient(p0, p, p2)) != 0) return o > 0 ? 1 : -1;
        if (q == &p0 && (o = orient(p, p1, p2)) != 0) return o > 0 ? 1 : -1;
    }
    return -1;
}

LatticeDelaunay::LatticeDelaunay(std::int32_t width, std::int32_t height) {
    if (width < 1 || height < 1 || width > kMaxCoordinate || height > kMaxCoordinate) {
        throw std::invalid_argument("lattice Delaunay: a " + std::to_string(width) + " x " +
                                    std::to_string(height) + " rectangle is out of range");
    }
    const std::uint32_t c0 = add_point({0, 0});
    const std::uint32_t c1 = add_point({width, 0});
    const std::uint32_t c2 = add_point({width, height});
    const std::uint32_t c3 = add_point({0, height});
    std::vector<std::uint32_t> ignored;
    changed_ = &ignored;
    grow(2);
    set_triangle(c0, c1, c2, -1, -1, -1, 0);
    set_triangle(c0, c2, c3, 2, -1, -1, 3);  // twin of c2->c0 is c0->c2
    legalise(2);
    changed_ = nullptr;
}

std::uint32_t LatticeDelaunay::add_point(LatticePoint p) {
    points_.push_back(p);
    return static_cast<std::uint32_t>(points_.size() - 1);
}

std::size_t LatticeDelaunay::grow(std::size_t triangles) {
    const std::size_t n = corners_.size();
    corners_.resize(n + 3 * triangles);
    twins_.resize(n + 3 * triangles, -1);
    return n;
}

std::uint32_t LatticeDelaunay::set_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                            std::int64_t ab, std::int64_t bc, std::int64_t ca,
                                            std::size_t e) {
    corners_[e] = a;
    corners_[e + 1] = b;
    corners_[e + 2] = c;
    const std::array<std::int64_t, 3> twins = {ab, bc, ca};
    for (std::size_t k = 0; k < 3; ++k) {
        twins_[e + k] = twins[k];
        if (twins[k] >= 0)
            twins_[static_cast<std::size_t>(twins[k])] = static_cast<std::int64_t>(e + k);
    }
    const auto t = static_cast<std::uint32_t>(e / 3);
    changed_->push_back(t);
    return static_cast<std::uint32_t>(e);
}

std::uint32_t LatticeDelaunay::insert(LatticePoint p, std::uint32_t t,
                                      std::vector<std::uint32_t>& changed) {
    changed_ = &changed;
    const std::size_t e0 = 3 * static_cast<std::size_t>(t);
    const std::uint32_t v0 = corners_[e0];
    const std::uint32_t v1 = corners_[e0 + 1];
    const std::uint32_t v2 = corners_[e0 + 2];
    const std::uint32_t pn = add_point(p);
    if (orient(points_[v0], points_[v1], p) == 0) {
        split_edge(pn, static_cast<std::uint32_t>(e0));
    } else if (orient(points_[v1], points_[v2], p) == 0) {
        split_edge(pn, static_cast<std::uint32_t>(e0 + 1));
    } else if (orient(points_[v2], points_[v0], p) == 0) {
        split_edge(pn, static_cast<std::uint32_t>(e0 + 2));
    } else {
        const std::int64_t h0 = twins_[e0];
        const std::int64_t h1 = twins_[e0 + 1];
        const std::int64_t h2 = twins_[e0 + 2];
        const std::size_t n = grow(2);
        // Three triangles fanning around pn; the first reuses t's slot.
        const std::uint32_t t0 = set_triangle(v0, v1, pn, h0, static_cast<std::int64_t>(n + 2),
                                              static_cast<std::int64_t>(n + 4), e0);
        const std::uint32_t t1 = set_triangle(v1, v2, pn, h1, static_cast<std::int64_t>(n + 5),
                                              static_cast<std::int64_t>(e0 + 1), n);
        const std::uint32_t t2 = set_triangle(v2, v0, pn, h2, static_cast<std::int64_t>(e0 + 2),
                                              static_cast<std::int64_t>(n + 1), n + 3);
        legalise(t0);
        legalise(t1);
        legalise(t2);
    }
    changed_ = nullptr;
    return pn;
}

void LatticeDelaunay::split_edge(std::uint32_t pn, std::uint32_t a) {
    // Half-edge a runs pr -> pl in triangle (pr, pl, p0); pn lies on it.
    const std::size_t a0 = a - a % 3;
    const std::size_t al = next(a);
    const std::size_t ar = prev(a);
    const std::uint32_t pr = corners_[a];
    const std::uint32_t pl = corners_[al];
    const std::uint32_t p0 = corners_[ar];
    const std::int64_t hal = twins_[al];
    const std::int64_t har = twins_[ar];
    const std::int64_t b = twins_[a];
    if (b < 0) {
        // On the border: two triangles.
        const std::size_t n = grow(1);
        const std::uint32_t t0 =
            set_triangle(pr, pn, p0, -1, static_cast<std::int64_t>(n + 2), har, a0);
        const std::uint32_t t1 =
            set_triangle(pn, pl, p0, -1, hal, static_cast<std::int64_t>(a0 + 1), n);
        legalise(t0 + 2);
        legalise(t1 + 1);
        return;
    }
    // Interior: the neighbour (pl, pr, p1) splits too, four triangles around pn.
    const auto bb = static_cast<std::size_t>(b);
    const std::size_t b0 = bb - bb % 3;
    const std::size_t bl = prev(bb);
    const std::size_t br = next(bb);
    const std::uint32_t p1 = corners_[bl];
    const std::int64_t hbl = twins_[bl];
    const std::int64_t hbr = twins_[br];
    const std::size_t n = grow(2);
    const auto i = [](std::size_t v) { return static_cast<std::int64_t>(v); };
    const std::uint32_t t0 = set_triangle(p0, pr, pn, har, i(b0 + 2), i(n + 2), a0);
    const std::uint32_t t1 = set_triangle(pr, p1, pn, hbr, i(n + 5), i(a0 + 1), b0);
    const std::uint32_t t2 = set_triangle(pn, pl, p0, i(n + 4), hal, i(a0 + 2), n);
    const std::uint32_t t3 = set_triangle(p1, pl, pn, hbl, i(n), i(b0 + 1), n + 3);
    legalise(t0);
    legalise(t1);
    legalise(t2 + 1);
    legalise(t3);
}

void LatticeDelaunay::legalise(std::uint32_t start) {
    stack_.push_back(start);
    while (!stack_.empty()) {
        const std::size_t a = stack_.back();
        stack_.pop_back();
        const std::int64_t tb = twins_[a];
        if (tb < 0) continue;
        // Triangle A = (pr, pl, p0) holds half-edge a = pr -> pl; B = (pl, pr, p1) its twin.
        const auto b = static_cast<std::size_t>(tb);
        const std::size_t a0 = a - a % 3;
        const std::size_t b0 = b - b % 3;
        const std::size_t al = next(a);
        const std::size_t ar = prev(a);
        const std::size_t bl = prev(b);
        const std::size_t br = next(b);
        const std::uint32_t p0 = corners_[ar];
        const std::uint32_t pr = corners_[a];
        const std::uint32_t pl = corners_[al];
        const std::uint32_t p1 = corners_[bl];
        // CGAL's test: the vertex opposite the edge in A against B's circle.
        if (perturbed_in_circle(points_[pl], points_[pr], points_[p1], points_[p0]) <= 0) {
            continue;
        }
        const std::int64_t hal = twins_[al];
        const std::int64_t har = twins_[ar];
        const std::int64_t hbl = twins_[bl];
        const std::int64_t hbr = twins_[br];
        const auto i = [](std::size_t v) { return static_cast<std::int64_t>(v); };
        // Flip a-b to p0-p1.
        const std::uint32_t t0 = set_triangle(p0, p1, pl, -1, hbl, hal, a0);
        const std::uint32_t t1 = set_triangle(p1, p0, pr, i(t0), har, hbr, b0);
        stack_.push_back(t0 + 1);
        stack_.push_back(t1 + 2);
    }
}

}  // namespace sandtin
