#pragma once
// A Delaunay triangulation of integer lattice points inside a rectangle, built one point at a
// time: the fast core of greedy heightmap import.
//
// Lattice points are very often cocircular (any four corners of a lattice rectangle), so the
// Delaunay triangulation is not unique. Cocircular cases are decided by CGAL's symbolic
// perturbation (Triangulation_2::side_of_oriented_circle with perturb = true), which makes the
// result the same unique triangulation CGAL, and so Tin::from_points, builds for the same
// points. Predicates are exact (128-bit integers where products need them).
//
// Invariants: triangles are counter-clockwise (x right, y up); every half-edge's twin is its
// reverse or -1 on the rectangle's border; every interior edge is (perturbed) Delaunay.

#include <array>
#include <cstdint>
#include <vector>

namespace sandtin {

struct LatticePoint {
    std::int32_t x = 0;
    std::int32_t y = 0;
    friend constexpr bool operator==(LatticePoint, LatticePoint) = default;
};

class LatticeDelaunay {
  public:
    static constexpr std::int32_t kMaxCoordinate = 1 << 24;

    /// The rectangle [0, width] x [0, height] as two triangles. Throws std::invalid_argument
    /// for a side below 1 or above kMaxCoordinate.
    LatticeDelaunay(std::int32_t width, std::int32_t height);

    std::size_t point_count() const { return points_.size(); }
    std::size_t triangle_count() const { return corners_.size() / 3; }
    LatticePoint point(std::uint32_t v) const { return points_[v]; }
    /// Corner vertex ids of triangle t, counter-clockwise.
    std::array<std::uint32_t, 3> triangle(std::uint32_t t) const {
        return {corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]};
    }

    /// Inserts p, which must lie in the closed triangle t and on none of its corners. Appends
    /// to `changed` every triangle id whose corners changed (new ones included); an id may
    /// appear more than once. Returns the new vertex id.
    std::uint32_t insert(LatticePoint p, std::uint32_t t, std::vector<std::uint32_t>& changed);

    /// Same-orientation exact predicates, exposed for tests: twice the signed area of
    /// (a, b, c), and CGAL's perturbed in-circle test (> 0: d is inside the circle through the
    /// counter-clockwise a, b, c, after perturbation; never 0 for distinct points).
    static std::int64_t orient(LatticePoint a, LatticePoint b, LatticePoint c);
    static int perturbed_in_circle(LatticePoint a, LatticePoint b, LatticePoint c, LatticePoint d);

  private:
    std::uint32_t add_point(LatticePoint p);
    /// Appends room for new triangles; returns the first new half-edge.
    std::size_t grow(std::size_t triangles);
    /// Writes triangle (a, b, c) with the given twins at half-edge base e and links the twins
    /// back. Returns e.
    std::uint32_t set_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::int64_t ab,
                               std::int64_t bc, std::int64_t ca, std::size_t e);
    void split_edge(std::uint32_t pn, std::uint32_t a);
    void legalise(std::uint32_t a);

    std::vector<LatticePoint> points_;
    std::vector<std::uint32_t> corners_;  ///< 3 vertex ids per triangle
    std::vector<std::int64_t> twins_;     ///< per half-edge: opposite half-edge or -1
    std::vector<std::uint32_t> stack_;    ///< half-edges waiting for legalisation
    std::vector<std::uint32_t>* changed_ = nullptr;
};

}  // namespace sandtin
