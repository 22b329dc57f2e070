#include "raw_cgal.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <memory>

namespace sandtin::bench {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Default, CGAL::Exact_predicates_tag>;

struct RawCgalTin::Impl {
    Cdt cdt;
    Cdt::Vertex_handle last;
};

RawCgalTin::RawCgalTin() : impl_(std::make_unique<Impl>()) {}
RawCgalTin::~RawCgalTin() = default;

void RawCgalTin::insert(std::span<const Vec2> points) {
    std::vector<Kernel::Point_2> pts;
    pts.reserve(points.size());
    for (Vec2 p : points)
        pts.emplace_back(p.x, p.y);
    impl_->cdt.insert(pts.begin(), pts.end());
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
    std::vector<Cdt::Vertex_handle> vs;
    Cdt::Face_handle hint =
        impl_->last != Cdt::Vertex_handle() ? impl_->last->face() : Cdt::Face_handle();
    for (Vec2 p : ring) {
        vs.push_back(impl_->cdt.insert(Kernel::Point_2(p.x, p.y), hint));
        hint = vs.back()->face();
    }
    for (std::size_t i = 0; i < vs.size(); ++i) {
        impl_->cdt.insert_constraint(vs[i], vs[(i + 1) % vs.size()]);
    }
    impl_->last = vs.front();
}

std::size_t RawCgalTin::vertex_count() const {
    return impl_->cdt.number_of_vertices();
}

using CdtPlus = CGAL::Constrained_triangulation_plus_2<Cdt>;

struct RawCgalPlusTin::Impl {
    CdtPlus cdt;
    CdtPlus::Vertex_handle last;
};

RawCgalPlusTin::RawCgalPlusTin() : impl_(std::make_unique<Impl>()) {}
RawCgalPlusTin::~RawCgalPlusTin() = default;

void RawCgalPlusTin::insert(std::span<const Vec2> points) {
    std::vector<Kernel::Point_2> pts;
    pts.reserve(points.size());
    for (Vec2 p : points)
        pts.emplace_back(p.x, p.y);
    impl_->cdt.insert(pts.begin(), pts.end());
}

void RawCgalPlusTin::constrain_ring(std::span<const Vec2> ring) {
    std::vector<CdtPlus::Vertex_handle> vs;
    CdtPlus::Face_handle hint =
        impl_->last != CdtPlus::Vertex_handle() ? impl_->last->face() : CdtPlus::Face_handle();
    for (Vec2 p : ring) {
        vs.push_back(impl_->cdt.insert(Kernel::Point_2(p.x, p.y), hint));
        hint = vs.back()->face();
    }
    // Segment by segment, each a constraint of its own: CGAL's polyline insertion takes points
    // and locates them again without a hint.
    for (std::size_t i = 0; i < vs.size(); ++i)
        impl_->cdt.insert_constraint(vs[i], vs[(i + 1) % vs.size()]);
    impl_->last = vs.front();
}

std::size_t RawCgalPlusTin::vertex_count() const {
    return impl_->cdt.number_of_vertices();
}

}  // namespace sandtin::bench
