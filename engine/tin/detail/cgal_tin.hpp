#pragma once
// Private to engine/tin: the CGAL types behind Tin and its implementation state. Only the
// translation units of engine/tin include this header, which keeps CGAL's compile cost in them.
//
// Change tracking works through CGAL's own object lifetimes. Our vertex and face bases hook
// their constructors, destructors and the TDS mutators (set_vertex, set_constraint, reorient,
// ...). While an edit runs, a thread-local pointer names the TdsEvents of the Tin being edited,
// and the hooks record which ids and slots were born, died or changed. CGAL calls these
// mutators on the most-derived face type, so nothing escapes; check_valid() verifies the cached
// slot contents against CGAL's faces to prove it.

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_vertex_base_2.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>
#include <vector>

#include "geom/box_grid.hpp"
#include "tin/change_journal.hpp"
#include "tin/detail/journal_readers.hpp"
#include "tin/id_allocator.hpp"
#include "tin/tin.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

inline Point to_point(Vec2 p) {
    return {p.x, p.y};
}

inline constexpr std::uint32_t kNoId = std::numeric_limits<std::uint32_t>::max();

/// Receives lifetime events from the CGAL objects of one Tin during an edit.
struct TdsEvents {
    IdAllocator vertex_ids;
    std::vector<void*> vertex_of_id;  ///< VertexId -> CGAL vertex (nullptr when dead)
    std::vector<std::uint32_t> born_vertices;
    std::vector<std::uint32_t> died_vertices;

    IdAllocator slots;
    std::vector<void*> face_of_slot;  ///< slot -> CGAL face (nullptr when free)
    DirtySet op_slots;                ///< slots touched by the current edit

    std::uint32_t vertex_born(void* vertex) {
        const std::uint32_t id = vertex_ids.allocate();
        if (id >= vertex_of_id.size())
            vertex_of_id.resize(static_cast<std::size_t>(id) + 1, nullptr);
        vertex_of_id[id] = vertex;
        born_vertices.push_back(id);
        return id;
    }
    void vertex_died(std::uint32_t id) {
        vertex_of_id[id] = nullptr;
        died_vertices.push_back(id);
        vertex_ids.release(id);
    }
    std::uint32_t face_born(void* face) {
        const std::uint32_t slot = slots.allocate();
        if (slot >= face_of_slot.size())
            face_of_slot.resize(static_cast<std::size_t>(slot) + 1, nullptr);
        face_of_slot[slot] = face;
        op_slots.mark(slot);
        return slot;
    }
    void face_died(std::uint32_t slot) {
        face_of_slot[slot] = nullptr;
        op_slots.mark(slot);
        slots.release(slot);
    }
    void face_touched(std::uint32_t slot) { op_slots.mark(slot); }
};

/// The Tin being edited on this thread, or nullptr outside edits (bulk builds, destruction).
inline thread_local TdsEvents* t_events = nullptr;

/// Scope of one edit: routes CGAL lifetime events to `events`.
class EventScope {
  public:
    explicit EventScope(TdsEvents& events) : previous_(t_events) { t_events = &events; }
    ~EventScope() { t_events = previous_; }
    EventScope(const EventScope&) = delete;
    EventScope& operator=(const EventScope&) = delete;

  private:
    TdsEvents* previous_;
};

/// Scope that routes no events at all: for bulk builds, restores and destruction, so that a Tin
/// built or destroyed inside another Tin's edit never writes into the other's journal.
class NoEventScope {
  public:
    NoEventScope() : previous_(t_events) { t_events = nullptr; }
    ~NoEventScope() { t_events = previous_; }
    NoEventScope(const NoEventScope&) = delete;
    NoEventScope& operator=(const NoEventScope&) = delete;

  private:
    TdsEvents* previous_;
};

template <class Gt, class Vb = CGAL::Triangulation_vertex_base_2<Gt>>
class TinVertexBase : public Vb {
  public:
    using Face_handle = typename Vb::Face_handle;
    using Point = typename Vb::Point;

    template <class Tds2>
    struct Rebind_TDS {
        using Vb2 = typename Vb::template Rebind_TDS<Tds2>::Other;
        using Other = TinVertexBase<Gt, Vb2>;
    };

    TinVertexBase() : Vb() { born(); }
    explicit TinVertexBase(const Point& p) : Vb(p) { born(); }
    TinVertexBase(const Point& p, Face_handle f) : Vb(p, f) { born(); }
    explicit TinVertexBase(Face_handle f) : Vb(f) { born(); }
    // A copy is a new vertex with its own id.
    TinVertexBase(const TinVertexBase& other) : Vb(other) { born(); }
    TinVertexBase& operator=(const TinVertexBase& other) {
        Vb::operator=(other);
        return *this;
    }
    ~TinVertexBase() {
        if (t_events != nullptr && id != kNoId) t_events->vertex_died(id);
    }

    std::uint32_t id = kNoId;  ///< VertexId value; kNoId for the vertex at infinity

  private:
    void born() {
        if (t_events != nullptr) id = t_events->vertex_born(this);
    }
};

template <class Gt, class Fb = CGAL::Constrained_triangulation_face_base_2<Gt>>
class TinFaceBase : public Fb {
  public:
    using Vertex_handle = typename Fb::Vertex_handle;
    using Face_handle = typename Fb::Face_handle;

    template <class Tds2>
    struct Rebind_TDS {
        using Fb2 = typename Fb::template Rebind_TDS<Tds2>::Other;
        using Other = TinFaceBase<Gt, Fb2>;
    };

    TinFaceBase() : Fb() { born(); }
    TinFaceBase(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2) : Fb(v0, v1, v2) { born(); }
    TinFaceBase(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Face_handle n0,
                Face_handle n1, Face_handle n2)
        : Fb(v0, v1, v2, n0, n1, n2) {
        born();
    }
    TinFaceBase(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Face_handle n0,
                Face_handle n1, Face_handle n2, bool c0, bool c1, bool c2)
        : Fb(v0, v1, v2, n0, n1, n2, c0, c1, c2) {
        born();
    }
    // A copy is a new face with its own slot.
    TinFaceBase(const TinFaceBase& other) : Fb(other) { born(); }
    TinFaceBase& operator=(const TinFaceBase& other) {
        Fb::operator=(other);
        touched();
        return *this;
    }
    ~TinFaceBase() {
        if (t_events != nullptr && slot != kNoId) t_events->face_died(slot);
    }

    // The TDS mutators that change what the slot holds.
    void set_vertex(int i, Vertex_handle v) {
        Fb::set_vertex(i, v);
        touched();
    }
    void set_vertices() {
        Fb::set_vertices();
        touched();
    }
    void set_vertices(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2) {
        Fb::set_vertices(v0, v1, v2);
        touched();
    }
    void set_constraint(int i, bool b) {
        Fb::set_constraint(i, b);
        touched();
    }
    void set_constraints(bool c0, bool c1, bool c2) {
        Fb::set_constraints(c0, c1, c2);
        touched();
    }
    void reorient() {
        Fb::reorient();
        touched();
    }
    void ccw_permute() {
        Fb::ccw_permute();
        touched();
    }
    void cw_permute() {
        Fb::cw_permute();
        touched();
    }

    std::uint32_t slot = kNoId;  ///< TriangleSlot

  private:
    void born() {
        if (t_events != nullptr) slot = t_events->face_born(this);
    }
    void touched() {
        if (t_events != nullptr && slot != kNoId) t_events->face_touched(slot);
    }
};

using VertexBase = TinVertexBase<Kernel>;
using FaceBase = TinFaceBase<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
/// How far off a segment, relative to its length, a point within the snap distance of it may
/// lie and still count as on it (1 mrad). The offsets met are rounding errors (4e-18 m off a
/// 2.6 cm rim segment) and the snapping of rim points to vertices up to the snap distance away
/// (measured on grooves eroded with r_S = 1 cm, with the snap distance as the only bound: 318
/// threadings, offsets up to 9.4e-7 m and 3.6e-5 of the segment).
inline constexpr double kOnSegmentOffset = 1e-3;

/// Whether the point a + c lies on the segment from a to a + e up to snapping (snap2: the snap
/// distance squared): off it by at most the snap distance and kOnSegmentOffset of its length,
/// farther than the snap distance from both ends, and closer to each end than they are to each
/// other. (The snap distance alone is no test for a short segment: three vertices 1.3e-6 m
/// apart each lie within 1e-6 m of the others' edge, and threading each edge through the third
/// vertex went round in a circle.) A segment split at such a point gives two strictly shorter
/// ones.
inline bool on_segment_up_to_snap(double ex, double ey, double cx, double cy, double snap2) {
    const double len2 = ex * ex + ey * ey;
    const double along = cx * ex + cy * ey;
    const double off = ex * cy - ey * cx;  // the distance from the line times the length
    const double limit2 = std::min(snap2, kOnSegmentOffset * kOnSegmentOffset * len2);
    if (!(off * off <= limit2 * len2) || !(along > 0.0 && along < len2)) return false;
    const double wx = cx - ex, wy = cy - ey;  // from the far end
    const double uc2 = cx * cx + cy * cy, cw2 = wx * wx + wy * wy;
    return uc2 > snap2 && cw2 > snap2 && uc2 < len2 && cw2 < len2;
}

/// CGAL's constraint hierarchy over the CDT, plus one operation CGAL only offers for points.
class CdtPlus : public CGAL::Constrained_triangulation_plus_2<Cdt> {
  public:
    using Base = CGAL::Constrained_triangulation_plus_2<Cdt>;
    using Base::Base;

    /// Crossing points within this distance (m) of an end of the crossed constraint, or of the
    /// constraint being inserted, snap to that end instead of becoming a new vertex a rounding
    /// error away from it.
    double snap_distance = 0.0;

    /// CGAL's hook where the constraint being inserted, vaa-vbb, crosses the constrained edge
    /// (f, i); returns the vertex at the crossing.
    Vertex_handle intersect(Face_handle f, int i, Vertex_handle vaa, Vertex_handle vbb) override;

    /// Constrains a polyline through existing vertices. CGAL's polyline insertion takes points
    /// and re-inserts them, and re-inserting an existing point runs flip_around(), which can
    /// flip away an edge that a later segment of the same restore needs. `thread` passes the
    /// constraint through vertices within snap_distance of it (thread_through_near_vertices);
    /// a restore, which rebuilds a triangulation as it was saved, does not.
    Constraint_id insert_polyline(const std::vector<Vertex_handle>& vs, bool thread = true);

  private:
    /// The apex of the triangle (f, i) when it lies on the edge opposite it up to snapping
    /// (on_segment_up_to_snap), else a null handle.
    Vertex_handle near_apex(Face_handle f, int i) const;

    /// A constrained edge u-w with a vertex c a rounding error off it (a midpoint that an edge
    /// bisection put a hair off the segment, before the segment was constrained again by a
    /// later stamp along the same line) leaves a sliver (u, w, c): CGAL's exact predicates put
    /// c beside the constraint, not on it. The constraint then passes through c instead, as
    /// CGAL does for a vertex exactly on it. Measured after a groove stroked with erosion and
    /// r_S = 1 cm: such a sliver made c's long edge to u unsplittable (every split point folded
    /// the sliver over), so sand could never reach c and the terrain came to rest with edges up
    /// to 3.5e4 times steeper than repose (a 2 cm step over 1 um).
    void thread_through_near_vertices(Constraint_id id);

  public:
};
using VertexHandle = CdtPlus::Vertex_handle;
using FaceHandle = CdtPlus::Face_handle;
using Vertex = Tds::Vertex;
using Face = Tds::Face;
using CgalConstraintId = CdtPlus::Constraint_id;

/// Cached content of a slot: the CPU mirror of the GPU triangle buffer.
struct SlotRecord {
    std::array<std::uint32_t, 3> corners{kNoId, kNoId, kNoId};  ///< kOutsideCorner at infinity
    std::uint8_t constraint_mask = 0;
    bool finite() const {
        return corners[0] < kOutsideCorner && corners[1] < kOutsideCorner &&
               corners[2] < kOutsideCorner;
    }
    friend bool operator==(const SlotRecord&, const SlotRecord&) = default;
};

struct ConstraintEntry {
    CgalConstraintId cgal_id;
    Generation generation = 0;
    bool alive = false;
    Rect bounds;  ///< bounding box of the polyline (crossing vertices lie on it)
};

}  // namespace sandtin::detail

namespace sandtin {

struct Tin::Impl {
    using Vh = detail::VertexHandle;
    using Fh = detail::FaceHandle;

    Rect domain;
    TinOptions options;
    double snap_distance = 0.0;  ///< m: inserted points this close to a vertex reuse it
    detail::CdtPlus cdt;
    detail::TdsEvents events;
    VertexArrays va;
    std::vector<detail::SlotRecord> slot_cache;
    std::uint32_t live_triangles = 0;
    CompensatedSum volume_ledger;  ///< running sum of every volume change (m³)
    /// The change journal's readers; the default one (take_changes()) is open while
    /// options.track_changes holds.
    detail::JournalReaders journal;
    static constexpr std::uint32_t kNoReader = ~std::uint32_t{0};
    std::uint32_t default_reader = kNoReader;
    /// Tin::hold_id_recycling: takes leave dead ids and slots pending.
    bool recycling_held = false;
    /// Opens the default reader when options.track_changes asks for it. Before anything is
    /// built: the builders mark what they create.
    void open_default_reader() {
        if (options.track_changes && default_reader == kNoReader)
            default_reader = journal.open_range_reader(false);
    }
    /// Recycles the dead ids and slots every open range reader has seen die.
    void recycle_seen_deaths() {
        const detail::JournalReaders::Recyclable r = journal.recyclable(
            events.vertex_ids.pending_list().size(), events.slots.pending_list().size());
        events.vertex_ids.flush_deferred(r.vertices);
        events.slots.flush_deferred(r.slots);
        journal.recycled(r);
    }

    /// A vertex's height or other attribute changed (or it was born or died).
    void note_attribute(std::uint32_t id) { journal.note_vertex(id); }
    /// A vertex's star (its triangles or neighbours) changed.
    void note_topology(std::uint32_t id) { journal.note_topology(id); }
    /// Every vertex and slot is new (a terrain just built or restored): each range reader
    /// reports them all at its next take, dead ids and free slots too, as a reader opened on a
    /// terrain with holes does. Id by id only while a vertex feed is open, which a terrain
    /// being built or restored has not (marking 3·10⁶ ids one by one took 3-5 % of a build).
    void note_all_new() {
        if (!journal.has_range_readers() || journal.note_everything()) return;
        for (std::uint32_t id = 0; id < va.size(); ++id) {
            if (va.alive[id]) journal.note_vertex(id);
        }
        for (std::uint32_t s = 0; s < slot_cache.size(); ++s)
            journal.note_slot(s);
    }

    std::vector<detail::ConstraintEntry> constraints;  ///< indexed by ConstraintId value
    IdAllocator constraint_ids{false};
    std::unordered_map<const void*, std::uint32_t> constraint_of_cgal;  ///< Vertex_list* -> id
    /// The live constraints' bounds by id, over the domain: a tool finds the constraints under
    /// its footprint without reading every constraint in the terrain. Every live entry is filed
    /// with its current bounds: file_constraint() after setting an entry, unfile_constraint()
    /// before changing its bounds or clearing it.
    BoxGrid constraint_boxes;
    void file_constraint(std::uint32_t id) { constraint_boxes.insert(id, constraints[id].bounds); }
    void unfile_constraint(std::uint32_t id) { constraint_boxes.erase(id, constraints[id].bounds); }
    /// Ids of the constraints whose bounding boxes meet `box`, ascending: every constraint whose
    /// polyline meets the box is among them. Read from the grid of constraint bounds, so a tool
    /// pays for the constraints near its footprint, not for every constraint in the terrain.
    std::vector<std::uint32_t> constraints_meeting_box(const Rect& box) const {
        std::vector<std::uint32_t> ids;
        constraint_boxes.query(box, ids);
        return ids;
    }

    /// Constraints by when they are next due for Tin::expire_constraints(): first when their
    /// generation falls below the limit, then (if they could not go) after a wait that
    /// doubles each time. An entry goes stale when its constraint is refreshed to a newer
    /// generation or released (and its id perhaps reused); stale entries are skipped when
    /// they reach the top.
    struct Expiry {
        Generation due = 0;
        Generation generation = 0;
        Generation wait = 0;
        std::uint32_t id = 0;
        friend bool operator>(const Expiry& a, const Expiry& b) {
            return a.due != b.due ? a.due > b.due : a.id > b.id;
        }
    };
    std::priority_queue<Expiry, std::vector<Expiry>, std::greater<Expiry>> expiry;
    /// Call whenever constraint `id` is created or its generation changes.
    void note_constraint(std::uint32_t id) {
        const Generation g = constraints[id].generation;
        expiry.push({g, g, 16, id});
    }

    // ---- helpers shared by the translation units ----
    Vh handle(std::uint32_t id) const {
        return detail::Tds::Vertex_range::s_iterator_to(
            *static_cast<detail::Vertex*>(events.vertex_of_id[id]));
    }
    Vh handle(VertexId v) const { return handle(v.value); }
    bool alive(VertexId v) const {
        return v.valid() && v.value < events.vertex_of_id.size() &&
               events.vertex_of_id[v.value] != nullptr;
    }
    std::uint32_t corner_id(Vh v) const { return cdt.is_infinite(v) ? kOutsideCorner : v->id; }
    detail::SlotRecord read_face(const detail::Face& f) const;
    /// A third of the areas of the finite faces around vertex id (m²). With `near_snapped`,
    /// the same walk also sets it when a neighbour lies within sqrt(snap2) metres (and leaves
    /// it alone otherwise).
    double recompute_lumped_area(std::uint32_t id, double snap2 = 0.0,
                                 bool* near_snapped = nullptr) const;
    void ensure_vertex_capacity();
    void ensure_slot_capacity();
    /// After a build without events: gives every face a slot, every vertex its lumped area,
    /// and marks everything dirty for the first take_changes().
    void finish_bulk_build();
    /// Rewrites the faces of a freshly built triangulation in place, in memory order, so that
    /// they follow the order of their lowest corner id, with their neighbours and constraint
    /// flags (vertices, and so constraints, are untouched). Only without events and before
    /// slots are handed out: it uses the slot field.
    void lay_out_faces_by_vertex();
};

}  // namespace sandtin
