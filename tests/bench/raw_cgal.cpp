#include "raw_cgal.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <memory>

namespace sandtin::bench {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Default, CGAL::Exact_predicates_tag>;
using CdtPlus = CGAL::Constrained_triangulation_plus_2<Cdt>;

namespace {

/// The operations both baselines share, on either triangulation.
template <class Triangulation>
struct Baseline {
    Triangulation cdt;
    typename Triangulation::Vertex_handle last;

    void insert(std::span<const Vec2> points) {
        std::vector<Kernel::Point_2> pts;
        pts.reserve(points.size());
        for (Vec2 p : points)
            pts.emplace_back(p.x, p.y);
        cdt.insert(pts.begin(), pts.end());
    }

    /// The ring's points, each located from the last one inserted, then its closed polygon
    /// segment by segment, each a constraint of its own (CGAL_plus's polyline insertion takes
    /// points and would locate them again without a hint).
    void constrain_ring(std::span<const Vec2> ring) {
        using Vh = typename Triangulation::Vertex_handle;
        using Fh = typename Triangulation::Face_handle;
        std::vector<Vh> vs;
        Fh hint = last != Vh() ? last->face() : Fh();
        for (Vec2 p : ring) {
            vs.push_back(cdt.insert(Kernel::Point_2(p.x, p.y), hint));
            hint = vs.back()->face();
        }
        for (std::size_t i = 0; i < vs.size(); ++i)
            cdt.insert_constraint(vs[i], vs[(i + 1) % vs.size()]);
        last = vs.front();
    }
};

}  // namespace

struct RawCgalTin::Impl : Baseline<Cdt> {};

RawCgalTin::RawCgalTin() : impl_(std::make_unique<Impl>()) {}
RawCgalTin::~RawCgalTin() = default;

void RawCgalTin::insert(std::span<const Vec2> points) {
    impl_->insert(points);
}

std::size_t RawCgalTin::locate_all(std::span<const Vec2> queries) const {
    std::size_t sum = 0;
    for (Vec2 q : queries) {
        const auto f = impl_->cdt.locate(Kernel::Point_2(q.x, q.y));
        sum += reinterpret_cast<std::uintptr_t>(&*f) & 0xff;
    }
    return sum;
}

void RawCgalTin::constrain_ring(std::span<const Vec2> ring) {
    impl_->constrain_ring(ring);
}

std::size_t RawCgalTin::vertex_count() const {
    return impl_->cdt.number_of_vertices();
}

struct RawCgalPlusTin::Impl : Baseline<CdtPlus> {};

RawCgalPlusTin::RawCgalPlusTin() : impl_(std::make_unique<Impl>()) {}
RawCgalPlusTin::~RawCgalPlusTin() = default;

void RawCgalPlusTin::insert(std::span<const Vec2> points) {
    impl_->insert(points);
}

void RawCgalPlusTin::constrain_ring(std::span<const Vec2> ring) {
    impl_->constrain_ring(ring);
}

std::size_t RawCgalPlusTin::vertex_count() const {
    return impl_->cdt.number_of_vertices();
}

}  // namespace sandtin::bench
