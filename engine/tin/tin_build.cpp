// Tin: construction. A bulk build inserts the points in Hilbert order without change events,
// then lays the faces out in memory in the order of their vertices and hands out slots.

#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "util/prepare_for_writing.hpp"

namespace sandtin {

using detail::describe, detail::kNoId, detail::NoEventScope, detail::require,
    detail::require_inside, detail::SlotRecord, detail::to_point;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

// ---- Construction -------------------------------------------------------------------------

Tin::Tin(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Tin::Tin(Tin&&) noexcept = default;
Tin& Tin::operator=(Tin&& other) noexcept {
    if (this != &other) {
        NoEventScope quiet;
        impl_ = std::move(other.impl_);
    }
    return *this;
}
Tin::~Tin() {
    NoEventScope quiet;
    impl_.reset();
}

namespace {

/// A point to insert in a bulk build, with its position in the input (the corners first). Its
/// height stays out of the record: the spatial sort moves the records many times over, and
/// 24 bytes move faster than 32 (the sort is a sixth of a 10^6-point build; the build went
/// from 1.40 to 1.37 s).
struct Record {
    detail::Point point;
    std::uint32_t input_index;
};

/// Property map giving CGAL's spatial sort the point of a Record.
struct RecordPoint {
    using key_type = Record;
    using value_type = detail::Point;
    using reference = const detail::Point&;
    using category = boost::readable_property_map_tag;
    friend reference get(const RecordPoint&, const Record& r) { return r.point; }
};

/// Throws std::invalid_argument unless the domain is a usable rectangle and every point lies in
/// it with a finite height within reach.
void check_build_input(Rect domain, std::span<const Vec2> positions,
                       std::span<const double> heights) {
    require(!domain.empty() && is_finite(domain.min) && is_finite(domain.max) &&
                domain.width() > 0.0 && domain.height() > 0.0,
            "terrain domain must be a finite rectangle with positive width and height");
    // Beyond these, areas (side squared) and the snap distance (1e-6 of the side) leave the
    // range where the lumped areas and the volume can be computed: a 1e160 m terrain was
    // built and saved, and then refused when loaded.
    constexpr double kMinSide = 1e-9, kMaxSide = 1e9, kMaxCoordinate = 1e12;
    if (!(std::min(domain.width(), domain.height()) >= kMinSide &&
          std::max(domain.width(), domain.height()) <= kMaxSide &&
          std::max({std::abs(domain.min.x), std::abs(domain.min.y), std::abs(domain.max.x),
                    std::abs(domain.max.y)}) <= kMaxCoordinate)) {
        throw std::invalid_argument(
            "terrain domain " + describe(domain.min) + " to " + describe(domain.max) +
            ": its sides must lie between 1e-9 m and 1e9 m, and its corners within 1e12 m of "
            "the origin");
    }
    require(positions.size() == heights.size(), "positions and heights differ in length");
    for (std::size_t i = 0; i < positions.size(); ++i) {
        require_inside(domain, positions[i], "point");
        if (!std::isfinite(heights[i])) {
            throw std::invalid_argument("point " + describe(positions[i]) +
                                        ": height is not finite");
        }
        if (!(std::abs(heights[i]) <= kMaxHeight)) {
            std::ostringstream what;
            what << "point " << describe(positions[i]) << ": height " << heights[i]
                 << " m is beyond the " << kMaxHeight << " m a terrain may reach";
            throw std::invalid_argument(what.str());
        }
    }
}

std::unique_ptr<Tin::Impl> bulk_build(Rect domain, std::span<const Vec2> positions,
                                      std::span<const double> heights, TinOptions options) {
    check_build_input(domain, positions, heights);

    NoEventScope quiet;
    auto impl = std::make_unique<Tin::Impl>();
    impl->domain = domain;
    impl->constraint_boxes = BoxGrid(domain);
    impl->options = options;
    impl->open_default_reader();
    impl->snap_distance = default_snap_distance(domain);
    impl->cdt.snap_distance = impl->snap_distance;
    Tin::Impl& m = *impl;

    // Corners first so the triangulation is the domain from the start; a corner missing from
    // the input takes the height of the nearest input point (one pass for the four).
    const std::array<Vec2, 4> corners = {domain.min, Vec2{domain.max.x, domain.min.y}, domain.max,
                                         Vec2{domain.min.x, domain.max.y}};
    std::array<double, 4> corner_height{};
    std::array<double, 4> nearest;
    nearest.fill(std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        for (std::size_t c = 0; c < 4; ++c) {
            const double d2 = length_squared(positions[i] - corners[c]);
            if (d2 < nearest[c]) {
                nearest[c] = d2;
                corner_height[c] = heights[i];
            }
        }
    }
    const std::size_t count = positions.size() + 4;
    // Input index k: corner k below 4, else positions[k - 4].
    auto height_of = [&](std::uint32_t k) { return k < 4 ? corner_height[k] : heights[k - 4]; };
    // Hilbert order: fast insertion with hints, and neighbouring ids are neighbours in space,
    // which keeps physics and GPU buffers cache-friendly. The records carry their input
    // positions, so a duplicate position can keep the height that came first in the input (the
    // sort does not keep equal points in input order); the heights are then read once in the
    // sorted order, so the insertion reads memory sequentially.
    std::vector<Record> sorted;
    reserve_for_writing(sorted, count);
    for (std::uint32_t c = 0; c < 4; ++c)
        sorted.push_back({to_point(corners[c]), c});
    for (std::size_t i = 0; i < positions.size(); ++i)
        sorted.push_back({to_point(positions[i]), static_cast<std::uint32_t>(i + 4)});
    using SortTraits = CGAL::Spatial_sort_traits_adapter_2<detail::Kernel, RecordPoint>;
    CGAL::spatial_sort(sorted.begin() + 4, sorted.end(), SortTraits());
    std::vector<double> sorted_height;
    reserve_for_writing(sorted_height, count);
    for (const Record& r : sorted)
        sorted_height.push_back(height_of(r.input_index));

    m.va.resize(count);
    reserve_for_writing(m.events.vertex_of_id, count);
    m.events.vertex_of_id.resize(count, nullptr);
    std::vector<std::uint32_t> source;
    reserve_for_writing(source, count);
    source.assign(count, kNoId);
    auto insert_one = [&](const Record& r, double height, Fh& hint) {
        const Vh v = m.cdt.insert(r.point, hint);
        hint = v->face();
        if (v->id != kNoId) {
            // Duplicate position: the earlier input point's height wins.
            if (r.input_index < source[v->id]) {
                source[v->id] = r.input_index;
                m.va.height[v->id] = height;
            }
            return;
        }
        const std::uint32_t id = m.events.vertex_ids.allocate();
        v->id = id;
        source[id] = r.input_index;
        m.events.vertex_of_id[id] = &*v;
        m.va.position[id] = {r.point.x(), r.point.y()};
        m.va.height[id] = height;
        m.va.alive[id] = 1;
    };
    Fh hint;
    for (std::size_t k = 0; k < sorted.size(); ++k)
        insert_one(sorted[k], sorted_height[k], hint);
    // Duplicates leave unused tail entries; trim the arrays to the ids handed out.
    m.va.resize(m.events.vertex_ids.capacity());
    m.events.vertex_of_id.resize(m.events.vertex_ids.capacity());
    m.finish_bulk_build();
    return impl;
}

}  // namespace

Tin Tin::flat_rectangle(Rect domain, double height, TinOptions options) {
    require(std::isfinite(height), "flat terrain height is not finite");
    const std::array<Vec2, 4> corners = {domain.min, Vec2{domain.max.x, domain.min.y}, domain.max,
                                         Vec2{domain.min.x, domain.max.y}};
    const std::array<double, 4> heights = {height, height, height, height};
    return Tin(bulk_build(domain, corners, heights, options));
}

Tin Tin::regular_grid(Rect domain, int cells_x, int cells_y, const HeightFunction& height,
                      TinOptions options) {
    require(cells_x >= 1 && cells_y >= 1,
            "a regular grid needs at least one cell in each direction");
    require(static_cast<std::uint64_t>(cells_x + 1) * static_cast<std::uint64_t>(cells_y + 1) <
                (1ull << 31),
            "regular grid has too many vertices");
    std::vector<Vec2> pts;
    std::vector<double> hs;
    pts.reserve(static_cast<std::size_t>(cells_x + 1) * static_cast<std::size_t>(cells_y + 1));
    for (int j = 0; j <= cells_y; ++j) {
        for (int i = 0; i <= cells_x; ++i) {
            // Exact border coordinates, so the hull is exactly the domain.
            const double x =
                i == cells_x ? domain.max.x : domain.min.x + domain.width() * i / cells_x;
            const double y =
                j == cells_y ? domain.max.y : domain.min.y + domain.height() * j / cells_y;
            pts.push_back({x, y});
            hs.push_back(height ? height({x, y}) : 0.0);
        }
    }
    return Tin(bulk_build(domain, pts, hs, options));
}

Tin Tin::random_points(Rect domain, std::size_t count, std::uint64_t seed,
                       const HeightFunction& height, TinOptions options) {
    require(!domain.empty(), "terrain domain is empty");
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> ux(domain.min.x, domain.max.x);
    std::uniform_real_distribution<double> uy(domain.min.y, domain.max.y);
    std::vector<Vec2> pts;
    std::vector<double> hs;
    reserve_for_writing(pts, count + 4);
    reserve_for_writing(hs, count + 4);
    const std::array<Vec2, 4> corners = {domain.min, Vec2{domain.max.x, domain.min.y}, domain.max,
                                         Vec2{domain.min.x, domain.max.y}};
    for (Vec2 c : corners) {
        pts.push_back(c);
        hs.push_back(height ? height(c) : 0.0);
    }
    for (std::size_t i = 0; i < count; ++i) {
        const Vec2 p{ux(rng), uy(rng)};
        pts.push_back(p);
        hs.push_back(height ? height(p) : 0.0);
    }
    return Tin(bulk_build(domain, pts, hs, options));
}

Tin Tin::from_points(Rect domain, std::span<const Vec2> positions, std::span<const double> heights,
                     TinOptions options) {
    require(!positions.empty(), "from_points: no points given, so the terrain heights are unknown");
    return Tin(bulk_build(domain, positions, heights, options));
}

double Tin::snap_distance() const {
    return impl_->snap_distance;
}

void Tin::set_snap_distance(double d) {
    require(d >= 0.0 && std::isfinite(d), "set_snap_distance: distance must be finite and >= 0");
    impl_->snap_distance = d;
    impl_->cdt.snap_distance = d;
}

// ---- Bulk build bookkeeping ----------------------------------------------------------------

void Tin::Impl::lay_out_faces_by_vertex() {
    detail::Tds& tds = cdt.tds();
    const std::size_t vertex_count = va.size();
    // Counting sort of the faces by their lowest corner id (the vertex at infinity has the
    // largest id, so it never is the key of a face with a finite corner).
    std::vector<std::uint32_t> first;
    reserve_for_writing(first, vertex_count + 2);
    first.assign(vertex_count + 2, 0);
    auto key = [&](const detail::Face& f) {
        const std::uint32_t k = std::min({f.vertex(0)->id, f.vertex(1)->id, f.vertex(2)->id});
        return k == kNoId ? static_cast<std::uint32_t>(vertex_count) : k;
    };
    // The faces where they lie, in memory order: the k-th receives the k-th face of the sorted
    // order. The faces are rewritten in place rather than destroyed and created again, which
    // freed their whole storage and mapped it again page by page: the layout took 225 ms of a
    // 1.4 s build of 10^6 points that way, and the build takes 1.29 s with this one.
    std::vector<Fh> storage;
    reserve_for_writing(storage, tds.faces().size());
    for (auto f = tds.faces().begin(); f != tds.faces().end(); ++f) {
        storage.push_back(f);
        ++first[key(*f) + 1];
    }
    for (std::size_t k = 1; k < first.size(); ++k)
        first[k] += first[k - 1];
    const std::size_t face_count = storage.size();
    struct FaceRecord {
        std::array<Vh, 3> corner;
        std::array<std::uint32_t, 3> neighbour;  ///< new positions
        std::array<bool, 3> constrained;
    };
    std::vector<FaceRecord> records;
    reserve_for_writing(records, face_count);
    records.resize(face_count);
    // The slot field is unused until the slots are handed out: it holds the new position.
    for (const Fh f : storage)
        f->slot = first[key(*f)]++;
    for (const Fh f : storage) {
        FaceRecord& r = records[f->slot];
        for (int i = 0; i < 3; ++i) {
            r.corner[static_cast<std::size_t>(i)] = f->vertex(i);
            r.neighbour[static_cast<std::size_t>(i)] = f->neighbor(i)->slot;
            r.constrained[static_cast<std::size_t>(i)] = f->is_constrained(i);
        }
    }
    for (std::size_t k = 0; k < face_count; ++k) {
        const FaceRecord& r = records[k];
        const Fh f = storage[k];
        f->set_vertices(r.corner[0], r.corner[1], r.corner[2]);
        f->set_neighbors(storage[r.neighbour[0]], storage[r.neighbour[1]], storage[r.neighbour[2]]);
        f->set_constraints(r.constrained[0], r.constrained[1], r.constrained[2]);
        f->slot = kNoId;
        for (int i = 0; i < 3; ++i)
            f->vertex(i)->set_face(f);
    }
}

void Tin::Impl::finish_bulk_build() {
    // A fresh Delaunay triangulation leaves its faces scattered in memory (insertion frees and
    // reuses them all over): laid out again in the order of their vertices' ids, which follow
    // the Hilbert insertion order, a local edit reads neighbouring memory instead of one cache
    // miss per face.
    lay_out_faces_by_vertex();
    // Headroom: the first edits of a fresh terrain would otherwise grow these per-slot arrays
    // at once, copying them whole in the middle of a stroke (measured: 15 ms at 10^6 points).
    const std::size_t faces = cdt.tds().number_of_full_dim_faces();
    reserve_for_writing(slot_cache, faces + faces / 8 + 1024);
    reserve_for_writing(events.face_of_slot, faces + faces / 8 + 1024);
    const Vh infinite = cdt.infinite_vertex();
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) {
        const std::uint32_t slot = events.slots.allocate();
        f->slot = slot;
        events.face_of_slot.push_back(&*f);
        const Vh a = f->vertex(0);
        const Vh b = f->vertex(1);
        const Vh c = f->vertex(2);
        if (a == infinite || b == infinite || c == infinite) {
            slot_cache.push_back(read_face(*f));
            continue;
        }
        // Points straight from the vertices just loaded: no second random access by id.
        const double third =
            (cross(Vec2{b->point().x() - a->point().x(), b->point().y() - a->point().y()},
                   Vec2{c->point().x() - a->point().x(), c->point().y() - a->point().y()})) /
            6.0;
        va.lumped_area[a->id] += third;
        va.lumped_area[b->id] += third;
        va.lumped_area[c->id] += third;
        ++live_triangles;
        SlotRecord r;
        r.corners = {a->id, b->id, c->id};
        slot_cache.push_back(r);
    }
    note_all_new();
}

}  // namespace sandtin
