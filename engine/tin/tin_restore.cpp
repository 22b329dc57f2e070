// Tin: snapshots, and exact restore from a snapshot (the validity check is tin_validate.cpp).
//
// Restoring rebuilds CGAL's triangulation data structure face by face instead of re-inserting
// the points: on cocircular input (grids, imported rasters) re-insertion may choose other
// diagonals, and a loaded session must equal the saved one. Because snapshots come from files,
// every structural property is verified (on the plain arrays of detail/triangle_soup.hpp, on
// every core) before CGAL is asked anything about the triangulation; what the checks accept
// passes check_valid().

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "tin/detail/triangle_soup.hpp"
#include "util/compensated_sum.hpp"
#include "util/prepare_for_writing.hpp"
#include "util/thread_pool.hpp"

namespace sandtin {

using detail::CdtPlus, detail::kNoId, detail::NoEventScope, detail::SlotRecord,
    detail::triangle_area;
using Vh = Tin::Impl::Vh;
using Fh = Tin::Impl::Fh;

namespace {

[[noreturn]] void corrupt(const std::string& what) {
    throw std::runtime_error("invalid terrain data: " + what);
}

std::vector<std::uint32_t> handout_order(const IdAllocator& a) {
    // The order in which the allocator will hand ids out after the pending ones are flushed.
    std::vector<std::uint32_t> out = a.free_list();
    const auto& pending = a.pending_list();
    out.insert(out.end(), pending.rbegin(), pending.rend());
    return out;
}

}  // namespace

TinSnapshot Tin::snapshot() const {
    const Impl& m = *impl_;
    TinSnapshot s;
    s.domain = m.domain;
    s.vertices = m.va;
    s.vertices.resize(m.events.vertex_ids.capacity());
    reserve_for_writing(s.slots, m.events.slots.capacity());
    s.slots.resize(m.events.slots.capacity(), {kNoSlot, kNoSlot, kNoSlot});
    for (std::uint32_t slot = 0; slot < s.slots.size(); ++slot) {
        if (m.events.face_of_slot[slot] != nullptr) s.slots[slot] = m.slot_cache[slot].corners;
    }
    copy_lists_into(s);
    return s;
}

void Tin::copy_changes_into(TinSnapshot& copy, const ChangeSet& changes) const {
    const Impl& m = *impl_;
    copy.domain = m.domain;
    // Ids past the live arrays' end (capacity reserved ahead) hold the defaults, as in
    // snapshot().
    const std::uint32_t vertex_capacity = m.events.vertex_ids.capacity();
    copy.vertices.resize(vertex_capacity);
    const auto known = static_cast<std::uint32_t>(m.va.size());
    VertexArrays& to = copy.vertices;
    for (const IdRange r : changes.vertices) {
        const std::uint32_t end = std::min({r.end, vertex_capacity, known});
        for (std::uint32_t v = r.begin; v < end; ++v) {
            to.position[v] = m.va.position[v];
            to.height[v] = m.va.height[v];
            to.bedrock[v] = m.va.bedrock[v];
            to.material[v] = m.va.material[v];
            to.moisture[v] = m.va.moisture[v];
            to.slide[v] = m.va.slide[v];
            to.water_depth[v] = m.va.water_depth[v];
            to.alive[v] = m.va.alive[v];
        }
    }
    const std::uint32_t slot_capacity = m.events.slots.capacity();
    copy.slots.resize(slot_capacity, {kNoSlot, kNoSlot, kNoSlot});
    for (const IdRange r : changes.triangles) {
        for (std::uint32_t slot = r.begin; slot < std::min(r.end, slot_capacity); ++slot) {
            copy.slots[slot] = m.events.face_of_slot[slot] != nullptr
                                   ? m.slot_cache[slot].corners
                                   : std::array<std::uint32_t, 3>{kNoSlot, kNoSlot, kNoSlot};
        }
    }
}

void Tin::copy_lists_into(TinSnapshot& s) const {
    const Impl& m = *impl_;
    s.vertex_free_list = handout_order(m.events.vertex_ids);
    s.slot_free_list = handout_order(m.events.slots);
    s.constraints.clear();
    for (const ConstraintInfo& c : constraints()) {
        ConstraintRecord r;
        r.id = c.id.value;
        r.generation = c.generation;
        for (VertexId v : c.vertices)
            r.vertices.push_back(v.value);
        s.constraints.push_back(std::move(r));
    }
    s.constraint_capacity = m.constraint_ids.capacity();
    s.constraint_free_list = handout_order(m.constraint_ids);
}

namespace {

void check_free_list(const std::vector<std::uint32_t>& free_list, std::uint32_t capacity,
                     const std::vector<std::uint8_t>& in_use, const char* what) {
    std::vector<std::uint8_t> seen(capacity, 0);
    std::size_t free_count = 0;
    for (std::uint32_t i = 0; i < capacity; ++i)
        free_count += in_use[i] ? 0 : 1;
    if (free_list.size() != free_count)
        corrupt(std::string(what) + " free list has the wrong size");
    for (std::uint32_t id : free_list) {
        if (id >= capacity || in_use[id] || seen[id]) {
            corrupt(std::string(what) + " free list names a used, repeated or out-of-range id");
        }
        seen[id] = 1;
    }
}

/// The vertex arrays: equal lengths, and every live vertex inside the domain with finite
/// attributes in range; the free list names exactly the unused ids.
void check_snapshot_vertices(const TinSnapshot& s) {
    const Rect& d = s.domain;
    const VertexArrays& sv = s.vertices;
    const std::size_t n = sv.height.size();
    if (n >= (1u << 31)) corrupt("too many vertices");
    if (sv.position.size() != n || sv.bedrock.size() != n || sv.material.size() != n ||
        sv.moisture.size() != n || sv.slide.size() != n || sv.water_depth.size() != n ||
        sv.alive.size() != n) {
        corrupt("vertex arrays differ in length");
    }
    const auto vertex_capacity = static_cast<std::uint32_t>(n);
    std::vector<std::uint8_t> vertex_used(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (sv.alive[i] > 1) corrupt("vertex alive flag is neither 0 nor 1");
        if (!sv.alive[i]) continue;
        vertex_used[i] = 1;
        const Vec2 p = sv.position[i];
        if (!is_finite(p) || !d.contains(p))
            corrupt("vertex " + std::to_string(i) + " lies outside the domain");
        if (!std::isfinite(sv.height[i]) || !std::isfinite(sv.bedrock[i])) {
            corrupt("vertex " + std::to_string(i) + " has a non-finite height or bedrock");
        }
        if (sv.bedrock[i] > sv.height[i])
            corrupt("vertex " + std::to_string(i) + " has bedrock above its surface");
        if (!(sv.moisture[i] >= 0.0f && sv.moisture[i] <= 1.0f)) {
            corrupt("vertex " + std::to_string(i) + " has moisture outside [0, 1]");
        }
        if (!std::isfinite(sv.slide[i].x) || !std::isfinite(sv.slide[i].y)) {
            corrupt("vertex " + std::to_string(i) + " has a non-finite texture offset");
        }
        if (!(sv.water_depth[i] >= 0.0 && std::isfinite(sv.water_depth[i]))) {
            corrupt("vertex " + std::to_string(i) + " has a negative or non-finite water depth");
        }
    }
    check_free_list(s.vertex_free_list, vertex_capacity, vertex_used, "vertex");
}

/// The slots: each free, or a triangle of three distinct live corners at most one of which is
/// at infinity; the free list names exactly the unused slots. Returns which slots are used.
std::vector<std::uint8_t> check_snapshot_slots(const TinSnapshot& s) {
    const VertexArrays& sv = s.vertices;
    const std::size_t n = sv.height.size();
    const std::size_t slot_count = s.slots.size();
    // Three half-edges per slot must be numbered in 32 bits (detail::pair_half_edges).
    if (slot_count >= (1u << 30)) corrupt("too many triangle slots");
    std::vector<std::uint8_t> slot_used(slot_count, 0);
    for (std::size_t t = 0; t < slot_count; ++t) {
        const auto& c = s.slots[t];
        if (c[0] == kNoSlot && c[1] == kNoSlot && c[2] == kNoSlot) continue;
        slot_used[t] = 1;
        int outside = 0;
        for (std::uint32_t v : c) {
            if (v == kOutsideCorner) {
                ++outside;
            } else if (v >= n || !sv.alive[v]) {
                corrupt("triangle slot " + std::to_string(t) + " names a dead or unknown vertex");
            }
        }
        if (outside > 1)
            corrupt("triangle slot " + std::to_string(t) + " has two corners at infinity");
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) {
            corrupt("triangle slot " + std::to_string(t) + " repeats a corner");
        }
    }
    check_free_list(s.slot_free_list, static_cast<std::uint32_t>(slot_count), slot_used, "slot");
    return slot_used;
}

/// Gives `m` the snapshot's domain, options, ids and vertex attributes (moved out of the
/// snapshot); no triangles yet.
void start_restore(Tin::Impl& m, TinSnapshot& s, TinOptions options) {
    const std::size_t n = s.vertices.size();
    const std::size_t slot_count = s.slots.size();
    m.domain = s.domain;
    m.constraint_boxes = BoxGrid(s.domain);
    m.options = options;
    m.open_default_reader();
    m.snap_distance = default_snap_distance(s.domain);
    m.cdt.snap_distance = m.snap_distance;
    m.events.vertex_ids.restore(static_cast<std::uint32_t>(n), s.vertex_free_list);
    m.events.slots.restore(static_cast<std::uint32_t>(slot_count), s.slot_free_list);
    m.va = std::move(s.vertices);
    m.va.lumped_area.assign(n, 0.0);
    reserve_for_writing(m.events.vertex_of_id, n);
    m.events.vertex_of_id.assign(n, nullptr);
    reserve_for_writing(m.slot_cache, slot_count);
    m.slot_cache.assign(slot_count, SlotRecord{});
    reserve_for_writing(m.events.face_of_slot, slot_count);
    m.events.face_of_slot.assign(slot_count, nullptr);
}

/// CGAL's vertices, and a face per used slot with its corners; no neighbours yet. Returns the
/// faces in slot order (the soup's triangle order).
std::vector<Fh> build_faces(Tin::Impl& m, const std::vector<std::array<std::uint32_t, 3>>& slots,
                            const std::vector<std::uint8_t>& slot_used) {
    const VertexArrays& va = m.va;
    const auto vertex_capacity = static_cast<std::uint32_t>(va.size());
    detail::Tds& tds = m.cdt.tds();
    tds.clear();
    tds.set_dimension(2);
    const std::size_t used =
        static_cast<std::size_t>(std::count(slot_used.begin(), slot_used.end(), std::uint8_t{1}));
    const Vh infinite = tds.create_vertex();
    m.cdt.set_infinite_vertex(infinite);
    for (std::uint32_t i = 0; i < vertex_capacity; ++i) {
        if (!va.alive[i]) continue;
        const Vh v = tds.create_vertex();
        v->set_point(detail::Point(va.position[i].x, va.position[i].y));
        v->id = i;
        m.events.vertex_of_id[i] = &*v;
    }
    auto vertex_handle = [&](std::uint32_t c) {
        return c == kOutsideCorner ? infinite : m.handle(c);
    };
    std::vector<Fh> faces;
    reserve_for_writing(faces, used);
    for (std::uint32_t t = 0; t < slots.size(); ++t) {
        if (!slot_used[t]) continue;
        const auto& c = slots[t];
        const Fh f = tds.create_face(vertex_handle(c[0]), vertex_handle(c[1]), vertex_handle(c[2]));
        f->slot = t;
        m.events.face_of_slot[t] = &*f;
        faces.push_back(f);
        // The last face naming a vertex is its face, as the soup's fan_start says.
        for (int i = 0; i < 3; ++i)
            f->vertex(i)->set_face(f);
    }
    if (faces.empty()) corrupt("no triangles");
    return faces;
}

/// The soup's checks, spread over the pool: fans and lumped areas per vertex range; tiling,
/// orientation and the in-circle test per triangle range, with CGAL's neighbours set from the
/// twins on the way. Returns the edges that are not locally Delaunay (fine if constrained).
std::vector<std::pair<std::uint32_t, std::uint32_t>> check_soup(Tin::Impl& m,
                                                                const detail::TriangleSoup& soup,
                                                                const std::vector<Fh>& faces,
                                                                ThreadPool& pool) {
    const auto parts = static_cast<std::size_t>(pool.threads());
    std::vector<std::string> problems(parts);
    std::vector<CompensatedSum> areas(parts);
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> not_delaunay(parts);
    pool.parallel_for(soup.size(), [&](std::size_t begin, std::size_t end, int part) {
        const auto k = static_cast<std::size_t>(part);
        for (std::size_t t = begin; t < end; ++t) {
            for (int i = 0; i < 3; ++i)
                faces[t]->set_neighbor(i,
                                       faces[soup.twin[3 * t + static_cast<std::size_t>(i)] / 3]);
        }
        problems[k] = detail::check_tiling(soup, m.va.position, m.domain, begin, end, areas[k]);
        detail::find_non_delaunay_edges(soup, m.va.position, begin, end, not_delaunay[k]);
    });
    for (const std::string& p : problems)
        if (!p.empty()) corrupt(p);
    CompensatedSum area;
    for (const CompensatedSum& a : areas)
        area.add(a.value());
    const double domain_area = m.domain.width() * m.domain.height();
    if (std::abs(area.value() - domain_area) > 1e-9 * domain_area)
        corrupt("the triangles do not tile the domain (overlaps or holes)");

    pool.parallel_for(std::size_t{soup.vertex_count} + 1,
                      [&](std::size_t begin, std::size_t end, int part) {
                          problems[static_cast<std::size_t>(part)] = detail::check_fans(
                              soup, m.va.alive, m.va.position, static_cast<std::uint32_t>(begin),
                              static_cast<std::uint32_t>(end), m.va.lumped_area);
                      });
    for (const std::string& p : problems)
        if (!p.empty()) corrupt(p);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& part : not_delaunay)
        edges.insert(edges.end(), part.begin(), part.end());
    return edges;
}

/// Constraints: every segment must already be an edge, so inserting them changes nothing.
void restore_constraints(Tin::Impl& m, const TinSnapshot& s) {
    const VertexArrays& va = m.va;
    const std::size_t n = va.size();
    if (s.constraint_capacity >= (1u << 31)) corrupt("too many constraints");
    std::vector<std::uint8_t> constraint_used(s.constraint_capacity, 0);
    m.constraints.assign(s.constraint_capacity, {});
    for (const ConstraintRecord& r : s.constraints) {
        if (r.id >= s.constraint_capacity || constraint_used[r.id]) {
            corrupt("constraint id " + std::to_string(r.id) + " is repeated or out of range");
        }
        constraint_used[r.id] = 1;
        if (r.vertices.size() < 2)
            corrupt("constraint " + std::to_string(r.id) + " has fewer than two vertices");
        std::vector<Vh> handles;
        for (std::size_t i = 0; i < r.vertices.size(); ++i) {
            const std::uint32_t v = r.vertices[i];
            if (v >= n || !va.alive[v])
                corrupt("constraint " + std::to_string(r.id) + " names a dead vertex");
            if (i > 0) {
                Fh f;
                int li = 0;
                if (r.vertices[i - 1] == v ||
                    !m.cdt.is_edge(m.handle(r.vertices[i - 1]), m.handle(v), f, li)) {
                    corrupt("constraint " + std::to_string(r.id) + " follows no triangle edge");
                }
            }
            handles.push_back(m.handle(v));
        }
        // As saved: threading it through nearby vertices would change the triangulation.
        const detail::CgalConstraintId cid = m.cdt.insert_polyline(handles, false);
        Rect bounds;
        for (std::uint32_t v : r.vertices)
            bounds.expand(va.position[v]);
        m.constraints[r.id] = {cid, r.generation, true, bounds};
        m.file_constraint(r.id);
        m.constraint_of_cgal[cid.vl_ptr()] = r.id;
        m.note_constraint(r.id);
    }
    check_free_list(s.constraint_free_list, s.constraint_capacity, constraint_used, "constraint");
    m.constraint_ids.restore(s.constraint_capacity, s.constraint_free_list);
    if (m.cdt.number_of_vertices() != m.events.vertex_ids.live()) {
        corrupt("constraints created vertices that the triangulation lacks");
    }
}

/// An edge whose far corner lies inside a triangle's circumcircle is fine only when it is
/// constrained (the constrained Delaunay property).
void check_delaunay_exceptions(const Tin::Impl& m,
                               const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
    for (const auto& [a, b] : edges) {
        Fh f;
        int i = 0;
        if (!m.cdt.is_edge(m.handle(a), m.handle(b), f, i) || !f->is_constrained(i)) {
            corrupt("edge " + std::to_string(a) + "-" + std::to_string(b) +
                    " is not locally Delaunay");
        }
    }
}

/// The slot cache, and everything dirty for the first take_changes().
void fill_caches(Tin::Impl& m, const std::vector<Fh>& faces, ThreadPool& pool) {
    std::vector<std::uint32_t> finite(static_cast<std::size_t>(pool.threads()), 0);
    pool.parallel_for(faces.size(), [&](std::size_t begin, std::size_t end, int part) {
        std::uint32_t count = 0;
        for (std::size_t k = begin; k < end; ++k) {
            const SlotRecord r = m.read_face(*faces[k]);
            m.slot_cache[faces[k]->slot] = r;
            count += r.finite() ? 1 : 0;
        }
        finite[static_cast<std::size_t>(part)] = count;
    });
    for (std::uint32_t c : finite)
        m.live_triangles += c;
    m.note_all_new();
}

int restore_threads() {
    return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
}

}  // namespace

Tin Tin::from_snapshot(TinSnapshot s, TinOptions options) {
    NoEventScope quiet;
    // Phase 1: the snapshot's own arrays, before anything is built from them.
    const Rect& d = s.domain;
    if (!(is_finite(d.min) && is_finite(d.max) && d.width() > 0.0 && d.height() > 0.0)) {
        corrupt("domain is not a finite rectangle with positive size");
    }
    check_snapshot_vertices(s);
    const std::vector<std::uint8_t> slot_used = check_snapshot_slots(s);
    const auto vertex_capacity = static_cast<std::uint32_t>(s.vertices.size());

    // Phase 2: the triangle soup and its twins on a worker, while this thread builds CGAL's
    // vertices and faces (its containers cannot be filled from two threads).
    auto soup_job = std::async(std::launch::async, [&] {
        detail::TriangleSoup soup =
            detail::make_triangle_soup(s.slots, slot_used, vertex_capacity, kOutsideCorner);
        std::string problem = detail::pair_soup_twins(soup);
        return std::make_pair(std::move(soup), std::move(problem));
    });
    auto impl = std::make_unique<Impl>();
    Impl& m = *impl;
    std::vector<Fh> faces;
    try {
        start_restore(m, s, options);
        faces = build_faces(m, s.slots, slot_used);
    } catch (...) {
        soup_job.wait();  // it reads the snapshot
        throw;
    }
    auto [soup, twin_problem] = soup_job.get();
    if (!twin_problem.empty()) corrupt(twin_problem);

    // Phase 3: the soup's checks on every core; CGAL's neighbours from the twins.
    ThreadPool pool(restore_threads());
    const auto not_delaunay = check_soup(m, soup, faces, pool);

    // Phase 4: the constraints, then what needed them.
    restore_constraints(m, s);
    check_delaunay_exceptions(m, not_delaunay);
    fill_caches(m, faces, pool);

    Tin tin(std::move(impl));
    const ValidationReport report = tin.check_constraint_registry();
    if (!report.ok()) corrupt(report.problems.front());
    return tin;
}

}  // namespace sandtin
