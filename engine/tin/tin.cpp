// Tin: construction, queries and edits over CGAL's constrained Delaunay triangulation.
// See tin/detail/cgal_tin.hpp for how CGAL object lifetimes feed the change journal.

#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "geom/polygon.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin {

using detail::CdtPlus;
using detail::kNoId;
using detail::SlotRecord;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

namespace {

/// Routes no events at all: used for bulk builds and destruction, so that a Tin built or
/// destroyed inside another Tin's edit never writes into the other's journal.
class NoEventScope {
public:
    NoEventScope() : previous_(detail::t_events) { detail::t_events = nullptr; }
    ~NoEventScope() { detail::t_events = previous_; }
    NoEventScope(const NoEventScope&) = delete;
    NoEventScope& operator=(const NoEventScope&) = delete;

private:
    detail::TdsEvents* previous_;
};

detail::Point to_point(Vec2 p) { return {p.x, p.y}; }

double triangle_area(Vec2 a, Vec2 b, Vec2 c) { return 0.5 * cross(b - a, c - a); }

void require(bool condition, const char* message) {
    if (!condition) throw std::invalid_argument(message);
}

std::string describe(Vec2 p) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << p.x << ", " << p.y << ")";
    return s.str();
}

void require_inside(const Rect& domain, Vec2 p, const char* what) {
    // Messages are built only on failure: this runs once per inserted point.
    if (!is_finite(p)) {
        throw std::invalid_argument(std::string(what) + ": coordinates " + describe(p) +
                                    " are not finite");
    }
    if (!domain.contains(p)) {
        throw std::invalid_argument(std::string(what) + ": point " + describe(p) +
                                    " lies outside the terrain domain [" + describe(domain.min) +
                                    ", " + describe(domain.max) + "]");
    }
}

std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

}  // namespace

// ---- Impl helpers -------------------------------------------------------------------------

SlotRecord Tin::Impl::read_face(const detail::Face& f) const {
    SlotRecord r;
    for (int i = 0; i < 3; ++i) {
        r.corners[static_cast<std::size_t>(i)] = corner_id(f.vertex(i));
        if (f.is_constrained(i)) r.constraint_mask |= static_cast<std::uint8_t>(1u << i);
    }
    if (!r.finite()) r.constraint_mask = 0;  // edges at infinity carry no meaning
    return r;
}

double Tin::Impl::recompute_lumped_area(std::uint32_t id) const {
    const Vh v = handle(id);
    auto fc = cdt.incident_faces(v);
    const auto done = fc;
    double area = 0.0;
    do {
        if (!cdt.is_infinite(fc)) {
            area += triangle_area(va.position[fc->vertex(0)->id], va.position[fc->vertex(1)->id],
                                  va.position[fc->vertex(2)->id]);
        }
    } while (++fc != done);
    return area / 3.0;
}

void Tin::Impl::ensure_vertex_capacity() {
    const std::size_t n = events.vertex_ids.capacity();
    if (va.size() < n) va.resize(n);
    if (events.vertex_of_id.size() < n) events.vertex_of_id.resize(n, nullptr);
}

void Tin::Impl::ensure_slot_capacity() {
    const std::size_t n = events.slots.capacity();
    if (slot_cache.size() < n) slot_cache.resize(n);
    if (events.face_of_slot.size() < n) events.face_of_slot.resize(n, nullptr);
}

void Tin::Impl::finish_bulk_build() {
    const std::size_t faces = cdt.tds().number_of_full_dim_faces();
    slot_cache.reserve(faces);
    events.face_of_slot.reserve(faces);
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
        const double third = (cross(Vec2{b->point().x() - a->point().x(), b->point().y() - a->point().y()},
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
    if (options.track_changes) {
        for (std::uint32_t id = 0; id < va.size(); ++id) {
            if (va.alive[id]) journal_vertices.mark(id);
        }
        for (std::uint32_t s = 0; s < slot_cache.size(); ++s) journal_slots.mark(s);
    }
}

// ---- Edit bookkeeping ---------------------------------------------------------------------

namespace {

/// Bookkeeping shared by all edits: turns the CGAL events of one edit into attribute, area,
/// journal and volume updates.
class EditFinisher {
public:
    explicit EditFinisher(Tin::Impl& impl) : impl_(impl) {}

    void mark_vertex(std::uint32_t id) {
        if (impl_.options.track_changes) impl_.journal_vertices.mark(id);
    }

    /// Gives the vertices CGAL created in this edit their position and default attributes.
    /// Their heights are NaN until the edit resolves them.
    void prepare_born() {
        impl_.ensure_vertex_capacity();
        for (std::uint32_t id : impl_.events.born_vertices) {
            if (impl_.events.vertex_of_id[id] == nullptr) continue;
            const Vh v = impl_.handle(id);
            VertexArrays& va = impl_.va;
            if (va.alive[id]) continue;  // already prepared
            va.position[id] = {v->point().x(), v->point().y()};
            va.height[id] = std::numeric_limits<double>::quiet_NaN();
            va.bedrock[id] = kNoBedrock;
            va.material[id] = 0;
            va.moisture[id] = 0.0f;
            va.slide[id] = {};
            va.lumped_area[id] = 0.0;
            va.alive[id] = 1;
        }
    }

    /// Attributes of a new vertex from weighted existing vertices: moisture and bedrock are
    /// interpolated, the material and texture offset come from the heaviest source.
    void inherit(std::uint32_t id, std::span<const std::uint32_t> sources,
                 std::span<const double> weights) {
        VertexArrays& va = impl_.va;
        double moisture = 0.0;
        double bedrock = 0.0;
        bool has_bedrock = true;
        std::size_t heaviest = 0;
        for (std::size_t i = 0; i < sources.size(); ++i) {
            const std::uint32_t s = sources[i];
            moisture += weights[i] * static_cast<double>(va.moisture[s]);
            if (va.bedrock[s] <= kNoBedrock) has_bedrock = false;
            bedrock += weights[i] * va.bedrock[s];
            if (weights[i] > weights[heaviest]) heaviest = i;
        }
        va.moisture[id] = static_cast<float>(std::clamp(moisture, 0.0, 1.0));
        va.bedrock[id] = has_bedrock ? bedrock : kNoBedrock;
        if (!sources.empty()) {
            va.material[id] = va.material[sources[heaviest]];
            va.slide[id] = va.slide[sources[heaviest]];
        }
    }

    /// Completes the edit: slot cache, lumped areas, journal, volume accounting and, with
    /// VolumePolicy::Conserve, compensation (into `absorb` when valid, else spread uniformly
    /// over the re-triangulated vertices).
    void finish(VolumePolicy policy, std::uint32_t absorb, EditReport* report) {
        Tin::Impl& m = impl_;
        VertexArrays& va = m.va;
        m.ensure_vertex_capacity();
        m.ensure_slot_capacity();
        prepare_born();

        EditReport local;
        // Slots: compare the cached content with CGAL's face now.
        affected_.clear();
        for (std::uint32_t slot : m.events.op_slots.ids()) {
            const SlotRecord before = m.slot_cache[slot];
            const void* face = m.events.face_of_slot[slot];
            const SlotRecord after =
                face != nullptr ? m.read_face(*static_cast<const detail::Face*>(face)) : SlotRecord{};
            if (before == after) continue;
            ++local.triangles_changed;
            if (m.options.track_changes) m.journal_slots.mark(slot);
            if (before.finite()) {
                --m.live_triangles;
                for (std::uint32_t c : before.corners) affected_.mark(c);
            }
            if (after.finite()) {
                ++m.live_triangles;
                for (std::uint32_t c : after.corners) affected_.mark(c);
            }
            m.slot_cache[slot] = after;
        }
        m.events.op_slots.clear();

        CompensatedSum dv;
        for (std::uint32_t id : m.events.died_vertices) {
            dv.add(-va.lumped_area[id] * va.height[id]);
            va.alive[id] = 0;
            va.lumped_area[id] = 0.0;
            mark_vertex(id);
            ++local.vertices_removed;
        }
        for (std::uint32_t id : m.events.born_vertices) {
            if (!va.alive[id]) continue;
            if (!std::isfinite(va.height[id])) resolve_height_from_neighbours(id);
            mark_vertex(id);
            ++local.vertices_created;
        }
        double affected_area = 0.0;
        for (std::uint32_t id : affected_.ids()) {
            if (!va.alive[id]) continue;
            const double a_new = m.recompute_lumped_area(id);
            const double a_old = va.lumped_area[id];
            if (a_new != a_old) {
                dv.add((a_new - a_old) * va.height[id]);
                va.lumped_area[id] = a_new;
                mark_vertex(id);
            }
            affected_area += a_new;
        }
        local.volume_change = dv.value();

        if (policy == VolumePolicy::Conserve && local.volume_change != 0.0) {
            if (absorb != kNoId && va.alive[absorb] && va.lumped_area[absorb] > 0.0) {
                va.height[absorb] -= local.volume_change / va.lumped_area[absorb];
                clamp_bedrock(absorb);
            } else if (affected_area > 0.0) {
                const double dh = -local.volume_change / affected_area;
                for (std::uint32_t id : affected_.ids()) {
                    if (!va.alive[id]) continue;
                    va.height[id] += dh;
                    clamp_bedrock(id);
                    mark_vertex(id);
                }
            }
        }
        affected_.clear();
        m.events.born_vertices.clear();
        m.events.died_vertices.clear();
        if (!m.options.track_changes) {
            m.events.vertex_ids.flush_deferred();
            m.events.slots.flush_deferred();
        }
        if (report != nullptr) report->accumulate(local);
    }

private:
    void clamp_bedrock(std::uint32_t id) {
        VertexArrays& va = impl_.va;
        if (va.bedrock[id] > va.height[id]) va.bedrock[id] = va.height[id];
    }

    /// Last resort for a vertex CGAL created whose height no rule determined: the mean of its
    /// neighbours with known heights. The edits resolve every case they create, so this only
    /// guards against leaving NaN in the terrain.
    void resolve_height_from_neighbours(std::uint32_t id) {
        Tin::Impl& m = impl_;
        const Vh v = m.handle(id);
        double sum = 0.0;
        int n = 0;
        auto vc = m.cdt.incident_vertices(v);
        const auto done = vc;
        do {
            if (!m.cdt.is_infinite(vc) && std::isfinite(m.va.height[vc->id])) {
                sum += m.va.height[vc->id];
                ++n;
            }
        } while (++vc != done);
        m.va.height[id] = n > 0 ? sum / n : 0.0;
    }

    Tin::Impl& impl_;
    static thread_local DirtySet affected_;
};

thread_local DirtySet EditFinisher::affected_;

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

Fh start_face(const Tin::Impl& m, Vec2 p, const LocateHint* hint) {
    if (hint != nullptr && m.alive(hint->vertex)) return m.handle(hint->vertex)->face();
    return jump_start_face(m, p);
}

/// A finite face containing the located point, with the point's barycentric coordinates.
struct FiniteLocation {
    Fh face;
    std::array<std::uint32_t, 3> corners{};
    std::array<double, 3> weights{};
};

FiniteLocation finite_location(const Tin::Impl& m, Vec2 p, CdtPlus::Locate_type lt, Fh f, int li) {
    if (m.cdt.is_infinite(f)) {
        // On the border the walk may report the outer face; the neighbour across the
        // finite edge (EDGE) or any finite incident face (VERTEX) holds the point too.
        if (lt == CdtPlus::EDGE) {
            f = f->neighbor(li);
        } else {
            const Vh v = f->vertex(li);
            auto fc = m.cdt.incident_faces(v);
            while (m.cdt.is_infinite(fc)) ++fc;
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

}  // namespace

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

std::unique_ptr<Tin::Impl> bulk_build(Rect domain, std::span<const Vec2> positions,
                                      std::span<const double> heights, TinOptions options) {
    require(!domain.empty() && is_finite(domain.min) && is_finite(domain.max) &&
                domain.width() > 0.0 && domain.height() > 0.0,
            "terrain domain must be a finite rectangle with positive width and height");
    require(positions.size() == heights.size(), "positions and heights differ in length");
    for (std::size_t i = 0; i < positions.size(); ++i) {
        require_inside(domain, positions[i], "point");
        if (!std::isfinite(heights[i])) {
            throw std::invalid_argument("point " + describe(positions[i]) + ": height is not finite");
        }
    }

    NoEventScope quiet;
    auto impl = std::make_unique<Tin::Impl>();
    impl->domain = domain;
    impl->options = options;
    Tin::Impl& m = *impl;

    // Corners first so the triangulation is the domain from the start; a corner missing from
    // the input takes the height of the nearest input point.
    const std::array<Vec2, 4> corners = {domain.min, Vec2{domain.max.x, domain.min.y}, domain.max,
                                         Vec2{domain.min.x, domain.max.y}};
    std::vector<Vec2> pts;
    std::vector<double> hs;
    pts.reserve(positions.size() + 4);
    hs.reserve(positions.size() + 4);
    for (Vec2 c : corners) {
        double h = 0.0;
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < positions.size(); ++i) {
            const double d2 = length_squared(positions[i] - c);
            if (d2 < best) {
                best = d2;
                h = heights[i];
            }
            if (d2 == 0.0) break;
        }
        pts.push_back(c);
        hs.push_back(h);
    }
    for (std::size_t i = 0; i < positions.size(); ++i) {
        pts.push_back(positions[i]);
        hs.push_back(heights[i]);
    }
    // Hilbert order: fast insertion with hints, and neighbouring ids are neighbours in space,
    // which keeps physics and GPU buffers cache-friendly. The sorted records carry their
    // heights, so insertion reads memory sequentially.
    using Record = std::pair<detail::Point, double>;
    std::vector<Record> sorted;
    sorted.reserve(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) sorted.emplace_back(to_point(pts[i]), hs[i]);
    using SortTraits = CGAL::Spatial_sort_traits_adapter_2<
        detail::Kernel, CGAL::First_of_pair_property_map<Record>>;
    CGAL::spatial_sort(sorted.begin() + 4, sorted.end(), SortTraits());

    m.va.resize(pts.size());
    m.events.vertex_of_id.resize(pts.size(), nullptr);
    auto insert_one = [&](const Record& r, Fh& hint) {
        const Vh v = m.cdt.insert(r.first, hint);
        hint = v->face();
        if (v->id != kNoId) return;  // duplicate position: the first height wins
        const std::uint32_t id = m.events.vertex_ids.allocate();
        v->id = id;
        m.events.vertex_of_id[id] = &*v;
        m.va.position[id] = {r.first.x(), r.first.y()};
        m.va.height[id] = r.second;
        m.va.alive[id] = 1;
    };
    Fh hint;
    for (const Record& r : sorted) insert_one(r, hint);
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
    require(cells_x >= 1 && cells_y >= 1, "a regular grid needs at least one cell in each direction");
    require(static_cast<std::uint64_t>(cells_x + 1) * static_cast<std::uint64_t>(cells_y + 1) <
                (1ull << 31),
            "regular grid has too many vertices");
    std::vector<Vec2> pts;
    std::vector<double> hs;
    pts.reserve(static_cast<std::size_t>(cells_x + 1) * static_cast<std::size_t>(cells_y + 1));
    for (int j = 0; j <= cells_y; ++j) {
        for (int i = 0; i <= cells_x; ++i) {
            // Exact border coordinates, so the hull is exactly the domain.
            const double x = i == cells_x ? domain.max.x
                                          : domain.min.x + domain.width() * i / cells_x;
            const double y = j == cells_y ? domain.max.y
                                          : domain.min.y + domain.height() * j / cells_y;
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
    pts.reserve(count + 4);
    hs.reserve(count + 4);
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

// ---- Queries ------------------------------------------------------------------------------

Rect Tin::domain() const { return impl_->domain; }
std::size_t Tin::vertex_count() const { return impl_->events.vertex_ids.live(); }
std::size_t Tin::triangle_count() const { return impl_->live_triangles; }
std::size_t Tin::constrained_edge_count() const {
    // number_of_subconstraints() only reads a map size but is not declared const.
    return const_cast<CdtPlus&>(impl_->cdt).number_of_subconstraints();
}
std::size_t Tin::constraint_count() const { return impl_->constraint_ids.live(); }
std::uint32_t Tin::vertex_capacity() const { return impl_->events.vertex_ids.capacity(); }
std::uint32_t Tin::slot_capacity() const { return impl_->events.slots.capacity(); }
bool Tin::is_alive(VertexId v) const { return impl_->alive(v); }
const VertexArrays& Tin::vertices() const { return impl_->va; }

Vec2 Tin::position(VertexId v) const {
    require(is_alive(v), "position: vertex id is not alive");
    return impl_->va.position[v.value];
}

double Tin::height(VertexId v) const {
    require(is_alive(v), "height: vertex id is not alive");
    return impl_->va.height[v.value];
}

std::array<VertexId, 3> Tin::slot_triangle(TriangleSlot slot) const {
    if (slot >= impl_->slot_cache.size()) return {};
    const SlotRecord& r = impl_->slot_cache[slot];
    if (!r.finite()) return {};
    return {VertexId{r.corners[0]}, VertexId{r.corners[1]}, VertexId{r.corners[2]}};
}

std::uint8_t Tin::slot_constraint_mask(TriangleSlot slot) const {
    if (slot >= impl_->slot_cache.size()) return 0;
    return impl_->slot_cache[slot].constraint_mask;
}

std::vector<std::array<VertexId, 3>> Tin::triangles() const {
    std::vector<std::array<VertexId, 3>> out;
    out.reserve(impl_->live_triangles);
    for (const SlotRecord& r : impl_->slot_cache) {
        if (r.finite()) {
            out.push_back({VertexId{r.corners[0]}, VertexId{r.corners[1]}, VertexId{r.corners[2]}});
        }
    }
    return out;
}

Location Tin::locate(Vec2 p, LocateHint* hint) const {
    Location out;
    const Impl& m = *impl_;
    if (!is_finite(p) || !m.domain.contains(p)) return out;
    CdtPlus::Locate_type lt;
    int li = 0;
    const Fh f = m.cdt.locate(to_point(p), lt, li, start_face(m, p, hint));
    if (lt == CdtPlus::OUTSIDE_CONVEX_HULL || lt == CdtPlus::OUTSIDE_AFFINE_HULL) return out;
    const FiniteLocation loc = finite_location(m, p, lt, f, li);
    out.kind = lt == CdtPlus::VERTEX ? Location::Kind::OnVertex
               : lt == CdtPlus::EDGE ? Location::Kind::OnEdge
                                     : Location::Kind::InTriangle;
    out.slot = loc.face->slot;
    for (std::size_t i = 0; i < 3; ++i) {
        out.corners[i] = VertexId{loc.corners[i]};
        out.barycentric[i] = loc.weights[i];
    }
    update_hint(hint, loc);
    return out;
}

std::optional<double> Tin::height_at(Vec2 p, LocateHint* hint) const {
    const Location loc = locate(p, hint);
    if (!loc.inside()) return std::nullopt;
    const VertexArrays& va = impl_->va;
    return loc.barycentric[0] * va.height[loc.corners[0].value] +
           loc.barycentric[1] * va.height[loc.corners[1].value] +
           loc.barycentric[2] * va.height[loc.corners[2].value];
}

void Tin::neighbours(VertexId v, std::vector<VertexId>& out) const {
    out.clear();
    require(is_alive(v), "neighbours: vertex id is not alive");
    const Impl& m = *impl_;
    auto vc = m.cdt.incident_vertices(m.handle(v));
    const auto done = vc;
    do {
        if (!m.cdt.is_infinite(vc)) out.push_back(VertexId{vc->id});
    } while (++vc != done);
}

bool Tin::is_boundary(VertexId v) const {
    require(is_alive(v), "is_boundary: vertex id is not alive");
    const Impl& m = *impl_;
    auto vc = m.cdt.incident_vertices(m.handle(v));
    const auto done = vc;
    do {
        if (m.cdt.is_infinite(vc)) return true;
    } while (++vc != done);
    return false;
}

bool Tin::is_on_constraint(VertexId v) const {
    require(is_alive(v), "is_on_constraint: vertex id is not alive");
    return impl_->cdt.are_there_incident_constraints(impl_->handle(v));
}

bool Tin::is_constrained_edge(VertexId a, VertexId b) const {
    if (!is_alive(a) || !is_alive(b)) return false;
    Fh f;
    int i = 0;
    if (!impl_->cdt.is_edge(impl_->handle(a), impl_->handle(b), f, i)) return false;
    return f->is_constrained(i);
}

double Tin::volume(double datum) const {
    const VertexArrays& va = impl_->va;
    CompensatedSum sum;
    for (std::size_t id = 0; id < va.size(); ++id) {
        if (va.alive[id]) sum.add(va.lumped_area[id] * (va.height[id] - datum));
    }
    return sum.value();
}

std::optional<ConstraintInfo> Tin::constraint(ConstraintId id) const {
    const Impl& m = *impl_;
    if (!id.valid() || id.value >= m.constraints.size() || !m.constraints[id.value].alive) {
        return std::nullopt;
    }
    const detail::ConstraintEntry& e = m.constraints[id.value];
    ConstraintInfo info;
    info.id = id;
    info.generation = e.generation;
    for (Vh v : m.cdt.vertices_in_constraint(e.cgal_id)) info.vertices.push_back(VertexId{v->id});
    return info;
}

std::vector<ConstraintInfo> Tin::constraints() const {
    std::vector<ConstraintInfo> out;
    for (std::uint32_t i = 0; i < impl_->constraints.size(); ++i) {
        if (auto c = constraint(ConstraintId{i})) out.push_back(std::move(*c));
    }
    return out;
}

std::string ValidationReport::summary() const {
    std::string s;
    for (const std::string& p : problems) {
        s += p;
        s += '\n';
    }
    return s;
}

// ---- Edits --------------------------------------------------------------------------------

VertexId Tin::insert_point(Vec2 p, double height, LocateHint* hint, EditReport* report) {
    Impl& m = *impl_;
    require_inside(m.domain, p, "insert_point");
    if (!std::isfinite(height)) {
        throw std::invalid_argument("insert_point " + describe(p) + ": height is not finite");
    }
    CdtPlus::Locate_type lt;
    int li = 0;
    const Fh f = m.cdt.locate(to_point(p), lt, li, start_face(m, p, hint));
    if (lt == CdtPlus::VERTEX) {
        const VertexId existing{f->vertex(li)->id};
        set_height(existing, height);
        if (hint != nullptr) hint->vertex = existing;
        return existing;
    }
    const FiniteLocation loc = finite_location(m, p, lt, f, li);
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    const Vh v = m.cdt.insert(to_point(p), lt, f, li);
    finisher.prepare_born();
    m.va.height[v->id] = height;
    finisher.inherit(v->id, loc.corners, loc.weights);
    finisher.finish(VolumePolicy::Report, kNoId, report);
    if (hint != nullptr) hint->vertex = VertexId{v->id};
    return VertexId{v->id};
}

VertexId Tin::insert_point_on_surface(Vec2 p, LocateHint* hint, VolumePolicy policy,
                                      EditReport* report) {
    Impl& m = *impl_;
    require_inside(m.domain, p, "insert_point_on_surface");
    CdtPlus::Locate_type lt;
    int li = 0;
    const Fh f = m.cdt.locate(to_point(p), lt, li, start_face(m, p, hint));
    if (lt == CdtPlus::VERTEX) {
        const VertexId existing{f->vertex(li)->id};
        if (hint != nullptr) hint->vertex = existing;
        return existing;
    }
    const FiniteLocation loc = finite_location(m, p, lt, f, li);
    double h = 0.0;
    for (std::size_t i = 0; i < 3; ++i) h += loc.weights[i] * m.va.height[loc.corners[i]];
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    const Vh v = m.cdt.insert(to_point(p), lt, f, li);
    finisher.prepare_born();
    m.va.height[v->id] = h;
    finisher.inherit(v->id, loc.corners, loc.weights);
    finisher.finish(policy, v->id, report);
    if (hint != nullptr) hint->vertex = VertexId{v->id};
    return VertexId{v->id};
}

bool Tin::remove_vertex(VertexId v, VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    require(is_alive(v), "remove_vertex: vertex id is not alive");
    if (is_boundary(v) || is_on_constraint(v)) return false;
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    m.cdt.remove(m.handle(v));
    finisher.finish(policy, kNoId, report);
    return true;
}

namespace {

/// Gives the vertices CGAL created at constraint crossings the height of the constraint they
/// split: linear along it between the nearest vertices of known height. Constraints other than
/// `inserted` are preferred, because they were already part of the surface.
void resolve_crossing_heights(Tin::Impl& m, detail::CgalConstraintId inserted) {
    for (std::uint32_t id : m.events.born_vertices) {
        if (m.events.vertex_of_id[id] == nullptr || std::isfinite(m.va.height[id])) continue;
        const Vh x = m.handle(id);
        double best_height = std::numeric_limits<double>::quiet_NaN();
        bool best_is_old = false;
        std::array<std::uint32_t, 2> best_sources{};
        std::array<double, 2> best_weights{};
        auto ec = m.cdt.incident_edges(x);
        const auto done = ec;
        do {
            if (!m.cdt.is_constrained(*ec)) continue;
            const Fh f = ec->first;
            const int i = ec->second;
            const Vh a = f->vertex(CdtPlus::cw(i));
            const Vh b = f->vertex(CdtPlus::ccw(i));
            const Vh y = a == x ? b : a;
            for (auto ctx : m.cdt.contexts(x, y)) {
                const bool is_old = ctx.id() != inserted;
                if (std::isfinite(best_height) && (best_is_old || !is_old)) continue;
                // Walk to known heights on both sides of x along this constraint.
                auto here = ctx.current();
                if (*here != x) {
                    // current() names the subconstraint's first vertex, which may be y.
                    auto next = here;
                    ++next;
                    if (next != ctx.vertices_end() && *next == x) here = next;
                }
                if (*here != x) continue;
                auto back = here;
                std::uint32_t lo = kNoId;
                while (back != ctx.vertices_begin()) {
                    --back;
                    if (std::isfinite(m.va.height[(*back)->id])) {
                        lo = (*back)->id;
                        break;
                    }
                }
                auto fwd = here;
                std::uint32_t hi = kNoId;
                for (++fwd; fwd != ctx.vertices_end(); ++fwd) {
                    if (std::isfinite(m.va.height[(*fwd)->id])) {
                        hi = (*fwd)->id;
                        break;
                    }
                }
                if (lo == kNoId || hi == kNoId) continue;
                const Vec2 px = m.va.position[id];
                const double da = distance(px, m.va.position[lo]);
                const double db = distance(px, m.va.position[hi]);
                const double t = da + db > 0.0 ? da / (da + db) : 0.5;
                best_height = (1.0 - t) * m.va.height[lo] + t * m.va.height[hi];
                best_is_old = is_old;
                best_sources = {lo, hi};
                best_weights = {1.0 - t, t};
            }
        } while (++ec != done);
        if (std::isfinite(best_height)) {
            m.va.height[id] = best_height;
            EditFinisher(m).inherit(id, best_sources, best_weights);
        }
    }
}

}  // namespace

ConstraintId Tin::insert_constraint(VertexId a, VertexId b, Generation generation,
                                    VolumePolicy policy, EditReport* report) {
    const std::array<VertexId, 2> polyline = {a, b};
    return insert_constraint(polyline, false, generation, policy, report);
}

ConstraintId Tin::insert_constraint(std::span<const VertexId> polyline, bool closed,
                                    Generation generation, VolumePolicy policy,
                                    EditReport* report) {
    Impl& m = *impl_;
    require(polyline.size() >= 2, "insert_constraint: a constraint needs at least two vertices");
    for (VertexId v : polyline) {
        if (!is_alive(v)) {
            throw std::invalid_argument("insert_constraint: vertex id " + std::to_string(v.value) +
                                        " is not alive");
        }
    }
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        require(polyline[i] != polyline[i + 1],
                "insert_constraint: consecutive vertices are the same (zero-length segment)");
    }
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    detail::CgalConstraintId cid;
    if (polyline.size() == 2 && !closed) {
        cid = m.cdt.insert_constraint(m.handle(polyline[0]), m.handle(polyline[1]));
    } else {
        std::vector<detail::Point> pts;
        pts.reserve(polyline.size());
        for (VertexId v : polyline) pts.push_back(m.handle(v)->point());
        cid = m.cdt.insert_constraint(pts.begin(), pts.end(), closed);
    }
    finisher.prepare_born();
    ConstraintId result;
    if (cid == detail::CgalConstraintId(nullptr)) {
        // CGAL refuses duplicates: refresh the generation of the existing constraint.
        for (auto ctx : m.cdt.contexts(m.handle(polyline[0]), m.handle(polyline[1]))) {
            const auto it = m.constraint_of_cgal.find(ctx.id().vl_ptr());
            if (it != m.constraint_of_cgal.end()) {
                result = ConstraintId{it->second};
                auto& entry = m.constraints[it->second];
                entry.generation = std::max(entry.generation, generation);
                break;
            }
        }
    } else {
        const std::uint32_t id = m.constraint_ids.allocate();
        if (id >= m.constraints.size()) m.constraints.resize(static_cast<std::size_t>(id) + 1);
        m.constraints[id] = {cid, generation, true};
        m.constraint_of_cgal[cid.vl_ptr()] = id;
        result = ConstraintId{id};
        resolve_crossing_heights(m, cid);
    }
    finisher.finish(policy, kNoId, report);
    return result;
}

std::size_t Tin::release_constraints(const ReleaseFilter& filter, VolumePolicy policy,
                                     EditReport* report) {
    Impl& m = *impl_;
    std::vector<std::uint32_t> doomed;
    for (std::uint32_t id = 0; id < m.constraints.size(); ++id) {
        const detail::ConstraintEntry& e = m.constraints[id];
        if (!e.alive) continue;
        if (filter.generation && e.generation != *filter.generation) continue;
        if (filter.older_than && e.generation >= *filter.older_than) continue;
        if (!filter.touching_polygon.empty()) {
            bool touches = false;
            const Vh* previous = nullptr;
            for (const Vh& v : m.cdt.vertices_in_constraint(e.cgal_id)) {
                if (previous != nullptr &&
                    segment_touches_polygon(m.va.position[(*previous)->id], m.va.position[v->id],
                                            filter.touching_polygon)) {
                    touches = true;
                    break;
                }
                previous = &v;
            }
            if (!touches) continue;
        }
        doomed.push_back(id);
    }
    if (doomed.empty()) return 0;
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    for (std::uint32_t id : doomed) {
        detail::ConstraintEntry& e = m.constraints[id];
        m.constraint_of_cgal.erase(e.cgal_id.vl_ptr());
        m.cdt.remove_constraint(e.cgal_id);
        e = {};
        m.constraint_ids.release(id);
    }
    finisher.finish(policy, kNoId, report);
    return doomed.size();
}

bool Tin::release_constraint(ConstraintId id, VolumePolicy policy, EditReport* report) {
    Impl& m = *impl_;
    if (!id.valid() || id.value >= m.constraints.size() || !m.constraints[id.value].alive) {
        return false;
    }
    detail::EventScope scope(m.events);
    EditFinisher finisher(m);
    detail::ConstraintEntry& e = m.constraints[id.value];
    m.constraint_of_cgal.erase(e.cgal_id.vl_ptr());
    m.cdt.remove_constraint(e.cgal_id);
    e = {};
    m.constraint_ids.release(id.value);
    finisher.finish(policy, kNoId, report);
    return true;
}

// ---- Attributes ---------------------------------------------------------------------------

namespace {

template <class T>
void set_attribute(Tin::Impl& m, VertexId v, std::vector<T>& array, T value, const char* what) {
    if (!m.alive(v)) {
        throw std::invalid_argument(std::string(what) + ": vertex id " + std::to_string(v.value) +
                                    " is not alive");
    }
    if (array[v.value] == value) return;
    array[v.value] = value;
    if (m.options.track_changes) m.journal_vertices.mark(v.value);
}

}  // namespace

void Tin::set_height(VertexId v, double height) {
    require(std::isfinite(height), "set_height: height is not finite");
    set_attribute(*impl_, v, impl_->va.height, height, "set_height");
}

void Tin::set_bedrock(VertexId v, double bedrock) {
    require(std::isfinite(bedrock), "set_bedrock: bedrock is not finite");
    set_attribute(*impl_, v, impl_->va.bedrock, bedrock, "set_bedrock");
}

void Tin::set_material(VertexId v, std::uint16_t material) {
    set_attribute(*impl_, v, impl_->va.material, material, "set_material");
}

void Tin::set_moisture(VertexId v, float moisture) {
    require(std::isfinite(moisture) && moisture >= 0.0f && moisture <= 1.0f,
            "set_moisture: moisture must lie in [0, 1]");
    set_attribute(*impl_, v, impl_->va.moisture, moisture, "set_moisture");
}

void Tin::set_slide(VertexId v, Vec2f slide) {
    require(std::isfinite(slide.x) && std::isfinite(slide.y), "set_slide: offset is not finite");
    set_attribute(*impl_, v, impl_->va.slide, slide, "set_slide");
}

// ---- Journal ------------------------------------------------------------------------------

ChangeSet Tin::take_changes() {
    Impl& m = *impl_;
    ChangeSet cs;
    cs.vertices = merge_into_ranges(m.journal_vertices.take());
    cs.triangles = merge_into_ranges(m.journal_slots.take());
    cs.vertex_capacity = m.events.vertex_ids.capacity();
    cs.slot_capacity = m.events.slots.capacity();
    cs.live_vertices = m.events.vertex_ids.live();
    cs.live_slots = m.live_triangles;
    cs.dead_slots = cs.slot_capacity - cs.live_slots;
    // The deaths are reported: their ids and slots may now be reused.
    m.events.vertex_ids.flush_deferred();
    m.events.slots.flush_deferred();
    return cs;
}

bool Tin::tracks_changes() const { return impl_->options.track_changes; }

}  // namespace sandtin
