#pragma once
// The terrain: a constrained Delaunay triangulation of points in the plane, with a height per
// vertex (a TIN). CGAL keeps the triangulation; this class keeps everything else.
//
// Units: metres for positions and heights, m² for areas, m³ for volumes.
//
// Invariants (checked by check_valid()):
//  - The triangulated region is exactly the domain rectangle; every vertex lies inside it.
//  - Each live vertex has a unique VertexId; per-vertex data lives in vertices() at that index.
//  - Each finite triangle has a unique TriangleSlot; slot_triangle(s) gives its corners in
//    counter-clockwise order.
//  - Every edge that is not constrained is locally Delaunay (exact predicates).
//  - lumped_area[v] = (sum of the areas of the triangles around v) / 3, so the exact volume
//    under the piecewise-linear surface is sum(lumped_area[v] * height[v]).
//  - All attributes are finite.
//
// Not thread-safe: one thread edits and queries; other threads read copies (GPU mirror,
// haptic snapshots).

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geom/height_limit.hpp"
#include "geom/rect.hpp"
#include "geom/vec2.hpp"
#include "tin/change_journal.hpp"
#include "tin/ids.hpp"
#include "tin/tin_snapshot.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {

class PolygonInclusion;

struct TinOptions {
    /// Open the default change reader, which take_changes() reads. Like every range reader it
    /// delays the recycling of dead ids and slots until it has taken their deaths, so turn it
    /// off when nothing calls take_changes() (consumers with readers of their own, ChangeReader,
    /// need no default reader).
    bool track_changes = true;
};

/// Where a point lies in the triangulation.
struct Location {
    enum class Kind : std::uint8_t { Outside, OnVertex, OnEdge, InTriangle };
    Kind kind = Kind::Outside;
    TriangleSlot slot = kNoSlot;          ///< a finite triangle containing the point
    std::array<VertexId, 3> corners{};    ///< that triangle's corners, counter-clockwise
    std::array<double, 3> barycentric{};  ///< weights of the corners; they sum to 1
    bool inside() const { return kind != Kind::Outside; }
};

/// A vertex near the last query. Point location walks from it, so successive queries along a
/// tool path cost a few steps each. Vertices, unlike CGAL faces, survive edits; a dead hint is
/// ignored.
struct LocateHint {
    VertexId vertex;
};

/// What a topology change does to the volume under the surface. Delaunay flips, vertex removal
/// and constraint changes re-triangulate the surface, which changes its volume slightly.
enum class VolumePolicy : std::uint8_t {
    /// Shift the heights of the re-triangulated vertices so the total volume is unchanged. The
    /// bedrock is not erodible: a vertex stops on it and the others take its share; only when
    /// every re-triangulated vertex lies on its bedrock does some of the change remain (it is
    /// in the volume ledger, Tin::volume_ledger()).
    Conserve,
    /// Leave heights alone; only report the change.
    Report,
};

/// What a topology-changing edit did.
struct EditReport {
    double volume_change = 0.0;  ///< m³ changed by re-triangulation, before any compensation
    std::uint32_t vertices_created = 0;  ///< includes vertices CGAL created at constraint crossings
    std::uint32_t vertices_removed = 0;
    std::uint32_t triangles_changed = 0;  ///< slots whose triangle changed

    void accumulate(const EditReport& o) {
        volume_change += o.volume_change;
        vertices_created += o.vertices_created;
        vertices_removed += o.vertices_removed;
        triangles_changed += o.triangles_changed;
    }
};

/// A constrained polyline: the vertices it passes through in order, including vertices
/// inserted where it crossed other constraints.
struct ConstraintInfo {
    ConstraintId id;
    Generation generation = 0;
    std::vector<VertexId> vertices;
};

/// An edge a-b to split at fraction t from a (Tin::split_edges).
struct EdgeSplit {
    VertexId a;
    VertexId b;
    double t = 0.5;
};

/// What Tin::take_vertex_changes() reports.
struct VertexChanges {
    std::vector<VertexId> attributes;  ///< height or other attribute changed, born or died
    std::vector<VertexId> topology;    ///< neighbours or triangles changed, born or died
};

struct ValidationReport {
    std::vector<std::string> problems;
    bool ok() const { return problems.empty(); }
    /// The problems joined into one line each (empty when ok).
    std::string summary() const;
};

/// Which constraints release_constraints() removes. All given conditions must hold.
struct ReleaseFilter {
    std::optional<Generation> generation;    ///< exactly this generation
    std::optional<Generation> older_than;    ///< generation < older_than
    std::span<const Vec2> touching_polygon;  ///< some segment touches this closed polygon
    /// Only the parts inside this closed polygon: a constraint that crosses its border is first
    /// split at its vertices there (pieces are classified by their midpoints), and only the
    /// inside pieces are released, so what lies outside keeps its constraint. Crossings
    /// without a vertex keep the whole piece; constrain the border first. A piece along the
    /// border (its midpoint within the snap distance of it) counts as inside.
    std::span<const Vec2> inside_polygon;
    /// Only constraints whose edges are all locally Delaunay already: releasing them
    /// re-triangulates nothing, so the surface cannot change anywhere.
    bool only_if_delaunay = false;
};

/// 1e-6 of the larger side of the domain.
inline double default_snap_distance(const Rect& domain) {
    return 1e-6 * std::max(domain.width(), domain.height());
}

class Tin {
  public:
    using HeightFunction = std::function<double(Vec2)>;

    /// Two triangles covering `domain` at a constant height.
    static Tin flat_rectangle(Rect domain, double height = 0.0, TinOptions options = {});
    /// A regular grid of (cells_x + 1) x (cells_y + 1) vertices. Without a height function the
    /// terrain is flat at 0.
    static Tin regular_grid(Rect domain, int cells_x, int cells_y,
                            const HeightFunction& height = {}, TinOptions options = {});
    /// The domain corners plus `count` uniformly random points (deterministic for a seed).
    static Tin random_points(Rect domain, std::size_t count, std::uint64_t seed,
                             const HeightFunction& height = {}, TinOptions options = {});
    /// The given points (positions in metres, heights in metres). Domain corners that are not
    /// among them are added at the height of the nearest given point. Duplicate positions keep
    /// the first height. Throws std::invalid_argument for points outside the domain or
    /// non-finite values.
    static Tin from_points(Rect domain, std::span<const Vec2> positions,
                           std::span<const double> heights, TinOptions options = {});
    /// Rebuilds exactly the saved triangulation, ids and slots. Throws std::runtime_error with a
    /// description when the snapshot is inconsistent (corrupted or crafted input): whatever it
    /// accepts passes check_valid(). Takes the snapshot by value: a caller done with it moves
    /// it in, and its vertex arrays become the TIN's. Its checks run on every core.
    static Tin from_snapshot(TinSnapshot snapshot, TinOptions options = {});

    Tin(Tin&&) noexcept;
    Tin& operator=(Tin&&) noexcept;
    Tin(const Tin&) = delete;
    Tin& operator=(const Tin&) = delete;
    ~Tin();

    // ---- Queries -------------------------------------------------------------------------
    Rect domain() const;
    std::size_t vertex_count() const;    ///< live vertices
    std::size_t triangle_count() const;  ///< finite triangles
    std::size_t constrained_edge_count() const;
    std::size_t constraint_count() const;   ///< registered constrained polylines
    std::uint32_t vertex_capacity() const;  ///< one past the largest VertexId ever used
    std::uint32_t slot_capacity() const;    ///< one past the largest TriangleSlot ever used

    bool is_alive(VertexId v) const;
    const VertexArrays& vertices() const;
    Vec2 position(VertexId v) const;
    double height(VertexId v) const;

    /// Corners (counter-clockwise) of the triangle in a slot; all invalid when the slot is free
    /// or holds no finite triangle.
    std::array<VertexId, 3> slot_triangle(TriangleSlot slot) const;
    /// Bit i set: the edge opposite corner i is constrained.
    std::uint8_t slot_constraint_mask(TriangleSlot slot) const;
    /// All finite triangles, for export.
    std::vector<std::array<VertexId, 3>> triangles() const;

    /// Locates p, walking from the hint when given and updating it to a nearby vertex.
    Location locate(Vec2 p, LocateHint* hint = nullptr) const;
    /// Height of the piecewise-linear surface at p, or nullopt outside the domain.
    std::optional<double> height_at(Vec2 p, LocateHint* hint = nullptr) const;
    /// height_at for each point, in order, into `out` (NaN where height_at gives nullopt), with
    /// the same values. Made for runs of nearby points (a lattice in row order, a contour): a
    /// point strictly inside the previous point's triangle or one of its neighbours costs a
    /// few orientation tests instead of a walk. With `corners` (empty, or one per point), also
    /// the corners of the triangle each height was interpolated in (invalid ids where NaN):
    /// the height stays the same until one of them changes height or star. Throws
    /// std::invalid_argument when the spans differ in size.
    void heights_at(std::span<const Vec2> points, std::span<double> out, LocateHint* hint = nullptr,
                    std::span<std::array<VertexId, 3>> corners = {}) const;

    /// The finite neighbours of v in counter-clockwise order (replaces the contents of out).
    void neighbours(VertexId v, std::vector<VertexId>& out) const;
    bool is_boundary(VertexId v) const;       ///< on the domain border
    bool is_on_constraint(VertexId v) const;  ///< incident to a constrained edge
    /// What one walk around a vertex finds: Tin::star.
    struct VertexStar {
        bool boundary = false;     ///< as is_boundary()
        bool constrained = false;  ///< as is_on_constraint()
    };
    /// neighbours(), is_boundary() and is_on_constraint() in one walk around v, for loops that
    /// need all three on many vertices.
    VertexStar star(VertexId v, std::vector<VertexId>& neighbours_out) const;
    /// True when the edge (a, b) exists and is constrained.
    bool is_constrained_edge(VertexId a, VertexId b) const;

    /// Exact volume between the surface and the plane z = datum, sum(A_i (h_i - datum)), in m³
    /// (compensated summation).
    double volume(double datum = 0.0) const;

    /// Running sum of every volume change since construction (m³): heights set times lumped
    /// areas, plus re-triangulation changes left after compensation. O(1); it equals
    /// volume() minus the initial volume up to rounding, so tools measure what an edit did
    /// without summing over the whole terrain.
    double volume_ledger() const;

    /// Vertices within `radius` metres of `centre`, found by walking the faces that meet the
    /// disc (constrained edges do not stop the walk).
    std::vector<VertexId> vertices_in_disc(Vec2 centre, double radius,
                                           LocateHint* hint = nullptr) const;
    /// Vertices inside (and on) the polygon of `region`, as region.contains() decides, found
    /// by walking the faces that meet it (constrained edges do not stop the walk): a tool's
    /// footprint without the rest of its bounding disc. The polygon must be connected.
    std::vector<VertexId> vertices_in_polygon(const PolygonInclusion& region,
                                              LocateHint* hint = nullptr) const;
    /// Corners of the faces reachable from the faces containing `seeds` without crossing a
    /// constrained edge and whose centroids lie inside the closed polygon `bound`: the
    /// vertices inside (and on) a constrained contour.
    std::vector<VertexId> vertices_in_region(std::span<const Vec2> seeds,
                                             std::span<const Vec2> bound,
                                             LocateHint* hint = nullptr) const;
    /// The surface along the segment a-b: (t, z) pairs with t in [0, 1] along the segment, at
    /// a, at every crossing with a triangle edge, and at b, in order. The piecewise-linear
    /// surface restricted to the segment is exactly the polyline through these points. Points
    /// outside the domain are clamped into it.
    std::vector<std::pair<double, double>> section(Vec2 a, Vec2 b,
                                                   LocateHint* hint = nullptr) const;
    /// Edges longer than `max_length` metres among the faces that meet the disc.
    std::vector<std::array<VertexId, 2>> edges_longer_than(Vec2 centre, double radius,
                                                           double max_length,
                                                           LocateHint* hint = nullptr) const;

    std::vector<ConstraintInfo> constraints() const;
    /// The newest generation among the live constraints (nullopt: none). Cheaper than
    /// constraints(), which lists every constraint's vertices.
    std::optional<Generation> newest_constraint_generation() const;
    /// The pieces (consecutive vertex pairs) of constraints older than `older_than` whose
    /// bounding boxes meet `box`, as segments in metres.
    std::vector<std::array<Vec2, 2>> constrained_segments(const Rect& box,
                                                          Generation older_than) const;
    std::optional<ConstraintInfo> constraint(ConstraintId id) const;

    ValidationReport check_valid() const;

    // ---- Edits ---------------------------------------------------------------------------
    /// Inserts a vertex at p with the given height. If a vertex already sits exactly at p its
    /// height is set and its id returned. Throws std::invalid_argument when p is outside the
    /// domain or a value is not finite.
    VertexId insert_point(Vec2 p, double height, LocateHint* hint = nullptr,
                          EditReport* report = nullptr);
    /// Inserts a vertex at p on the current surface. With VolumePolicy::Conserve the new
    /// vertex's height absorbs the volume change of the Delaunay flips, so refinement never
    /// creates or destroys material.
    VertexId insert_point_on_surface(Vec2 p, LocateHint* hint = nullptr,
                                     VolumePolicy policy = VolumePolicy::Conserve,
                                     EditReport* report = nullptr);
    /// Batch forms of the two insertions: one re-triangulation bookkeeping pass for all points,
    /// which is what tools use for a contour. Points are inserted in order; ids are returned in
    /// the same order. With Conserve, the new vertices share the volume compensation.
    std::vector<VertexId> insert_points(std::span<const Vec2> points,
                                        std::span<const double> heights, LocateHint* hint = nullptr,
                                        EditReport* report = nullptr);
    std::vector<VertexId> insert_points_on_surface(std::span<const Vec2> points,
                                                   LocateHint* hint = nullptr,
                                                   VolumePolicy policy = VolumePolicy::Conserve,
                                                   EditReport* report = nullptr);
    /// Splits edges at a fraction t in (0, 1) from a towards b, topologically inside the edge
    /// (so a constrained edge stays constrained in two pieces), with the height interpolated
    /// along it. Splits whose edge no longer exists, or that would land within the snap
    /// distance of an end, are skipped (invalid id). Used for long-edge refinement.
    std::vector<VertexId> split_edges(std::span<const EdgeSplit> splits,
                                      VolumePolicy policy = VolumePolicy::Conserve,
                                      EditReport* report = nullptr);
    /// Removes v. Returns false (and changes nothing) for border vertices and vertices on a
    /// constraint. With VolumePolicy::Conserve the ring around the hole absorbs the volume change.
    bool remove_vertex(VertexId v, VolumePolicy policy = VolumePolicy::Conserve,
                       EditReport* report = nullptr);
    /// Removes a vertex on the domain border that lies on a straight stretch of it: both of
    /// its border neighbours are on the same side of the domain rectangle, so the border stays
    /// where it was. Returns false (and changes nothing) for interior vertices, the domain's
    /// corners, and vertices on a constraint. For undo, which must take out the vertices an
    /// edit created on the border; the tools never remove border vertices.
    bool remove_border_vertex(VertexId v, VolumePolicy policy = VolumePolicy::Conserve,
                              EditReport* report = nullptr);

    /// Removes a connected set of interior vertices in one step when the triangles around them
    /// form a disc whose boundary, together with the set, lies within `tolerance` metres
    /// (vertically) of one plane: the hole is re-triangulated from its boundary and made
    /// constrained-Delaunay again. Cost O(set size), versus a Delaunay hole fill per vertex.
    /// Returns false and changes nothing when the set does not qualify (a vertex on the border
    /// or a constraint, a ring with holes or pinches, curvature beyond the tolerance).
    bool remove_planar_patch(std::span<const VertexId> vertices, double tolerance,
                             VolumePolicy policy = VolumePolicy::Conserve,
                             EditReport* report = nullptr);
    /// remove_planar_patch without the planarity test: removes a connected set of interior
    /// vertices whose triangles form a disc, whatever their heights, and fills the hole from its
    /// boundary. For edits that overwrite the surface there anyway (a stamp clears the sand its
    /// imprint replaces before enforcing its contours through it). Same conditions otherwise.
    bool remove_patch(std::span<const VertexId> vertices,
                      VolumePolicy policy = VolumePolicy::Report, EditReport* report = nullptr);

    /// Constrains the segment a-b. Crossings with existing constraints become new vertices at
    /// the height of the crossed constraint. Re-inserting an existing constraint refreshes its
    /// generation and returns its id.
    ConstraintId insert_constraint(VertexId a, VertexId b, Generation generation,
                                   VolumePolicy policy = VolumePolicy::Conserve,
                                   EditReport* report = nullptr);
    /// Constrains a polyline through the vertices (closed: last joins first).
    ConstraintId insert_constraint(std::span<const VertexId> polyline, bool closed,
                                   Generation generation,
                                   VolumePolicy policy = VolumePolicy::Conserve,
                                   EditReport* report = nullptr);
    /// Constrains each segment as its own constraint, in one edit: what tools use for a rim,
    /// so that later stamps can release the part of it they cover. Segments whose ends are the
    /// same vertex are skipped (invalid id in the result).
    std::vector<ConstraintId> insert_constraints(std::span<const std::array<VertexId, 2>> segments,
                                                 Generation generation,
                                                 VolumePolicy policy = VolumePolicy::Conserve,
                                                 EditReport* report = nullptr);
    /// Guards the surface before points and segments go in. Inserting a point re-triangulates
    /// the faces whose circumcircles hold it, and constraining a segment the faces it crosses;
    /// on a coarse, curved TIN (an imported elevation model) that bends the surface far beyond
    /// the edit (4.6 cm up to 23 m away under a 0.5 m tool, on a 500 m model of 400 points).
    /// This constrains each existing edge those operations would remove whose two faces are
    /// bent against each other by more than `tolerance` metres (the vertical gap between the
    /// edge and the other diagonal of its quadrilateral where they cross): the insertions then
    /// only subdivide those faces, and crossings of the segments with them get the edge's own
    /// height. Left free: edges bent by less, and, with `within`, an edge whose quadrilateral lies
    /// wholly inside that region (re-shaping it cannot reach past it: a footprint). The new
    /// constraints carry `generation`, so later footprints release them and they expire where
    /// releasing re-triangulates nothing. Points and segments outside the domain are ignored.
    /// Returns how many edges were constrained.
    std::size_t fence_bent_edges(std::span<const Vec2> points,
                                 std::span<const std::array<Vec2, 2>> segments, double tolerance,
                                 Generation generation, const PolygonInclusion* within = nullptr,
                                 LocateHint* hint = nullptr, EditReport* report = nullptr);
    /// Unconstrains every constraint that matches the filter; Delaunay flips follow. Returns how
    /// many constraints were released; their vertices are appended to `released_vertices`.
    std::size_t release_constraints(const ReleaseFilter& filter,
                                    VolumePolicy policy = VolumePolicy::Conserve,
                                    EditReport* report = nullptr,
                                    std::vector<VertexId>* released_vertices = nullptr);
    bool release_constraint(ConstraintId id, VolumePolicy policy = VolumePolicy::Conserve,
                            EditReport* report = nullptr);
    /// Lets constraints of generations below `older_than` come of age, oldest first. A
    /// constraint is released when that re-triangulates nothing (all its edges are locally
    /// Delaunay already, so the surface cannot change anywhere). One that cannot go is looked
    /// at again after 16, 32, 64, ... more generations (limits passed in later calls), or
    /// released by a later footprint. Cost O(log n) looks per constraint, not a scan of every
    /// constraint per call, so a stamp stays local however long the stroke. After a load,
    /// the waits start again.
    std::size_t expire_constraints(Generation older_than,
                                   VolumePolicy policy = VolumePolicy::Conserve,
                                   EditReport* report = nullptr,
                                   std::vector<VertexId>* released_vertices = nullptr);

    /// Attribute setters record the vertex in the change journal when the value changes.
    /// They throw std::invalid_argument for dead ids and non-finite values. set_height lowers
    /// the bedrock with the surface, so sand thickness never goes negative.
    void set_height(VertexId v, double height);
    /// Many heights at once (the physics writes every changed vertex each iteration); the same
    /// effect as set_height for each entry.
    void set_heights(std::span<const VertexId> vertices, std::span<const double> heights);
    void set_bedrock(VertexId v, double bedrock);
    void set_material(VertexId v, std::uint16_t material);
    void set_moisture(VertexId v, float moisture);
    void set_slide(VertexId v, Vec2f slide);
    /// Water standing on v (m, finite and >= 0; throws std::invalid_argument otherwise).
    void set_water_depth(VertexId v, double depth);

    // ---- Change journal and snapshots ----------------------------------------------------
    /// The default reader's dirty vertex and slot ranges since its last take (everything built,
    /// the first time); no ranges when the TIN does not track changes. Dead ids and slots are
    /// recycled once every open range reader has taken their deaths.
    ChangeSet take_changes();
    bool tracks_changes() const;
    /// Opens or closes the default reader (closing it lets its unread deaths be recycled).
    void set_track_changes(bool on);

    /// A range reader of its own for a consumer that copies the TIN (the render mesh, the GPU
    /// mirror, the normal map): take_changes(reader) reports what changed since that reader's
    /// previous take, whatever other readers took; its first take reports everything. Prefer the
    /// RAII ChangeReader (tin/change_reader.hpp).
    std::uint32_t open_change_reader();
    void close_change_reader(std::uint32_t reader);
    ChangeSet take_changes(std::uint32_t reader);
    /// While held, a take leaves the dead ids and slots it has seen pending instead of making
    /// them free again, and so writes nothing but the journal: another thread may then read
    /// the TIN through its const methods (snapshot(), vertex_count(), an export) while this one
    /// takes changes, as long as nothing edits it. The first take after it is let go recycles
    /// what was held.
    void hold_id_recycling(bool held);

    /// Inserted points within this distance (m) of an existing vertex reuse that vertex (which
    /// keeps its height), so rounding-level near-duplicates never make sliver triangles.
    /// Default: 1e-6 of the larger domain side (1 µm on a 1 m sandbox).
    double snap_distance() const;
    void set_snap_distance(double metres);

    /// Opens a vertex feed for a consumer that follows vertices (the physics, the undo
    /// recorder). It reports vertices whose height or attributes changed and vertices whose star
    /// changed. Unlike a range reader it never delays id recycling: a reported id only means
    /// "look at this id again". Prefer the RAII VertexChangeFeed.
    std::uint32_t subscribe_vertex_changes();
    void unsubscribe_vertex_changes(std::uint32_t subscription);
    VertexChanges take_vertex_changes(std::uint32_t subscription);

    /// A complete copy: vertices by id, triangles by slot, constraints and free lists.
    TinSnapshot snapshot() const;
    /// Brings `copy`, a snapshot of this TIN taken earlier, up to date for what `changes` names
    /// (every change since then, as a range reader reported them): the named vertex ids and
    /// slots are copied again and the arrays take the present capacities. The free lists and
    /// constraints are left for copy_lists_into(); the lumped areas, which a restore
    /// recomputes, are not kept. O(changes): a copy kept this way costs what the edits touched.
    void copy_changes_into(TinSnapshot& copy, const ChangeSet& changes) const;
    /// The free lists and constraints of `copy`, from this TIN (O(free ids + constraints)).
    void copy_lists_into(TinSnapshot& copy) const;

    struct Impl;

  private:
    explicit Tin(std::unique_ptr<Impl> impl);
    /// The part of check_valid() that from_snapshot's own checks leave: the constraint
    /// registry against CGAL's constraint hierarchy and the box grid.
    ValidationReport check_constraint_registry() const;
    std::unique_ptr<Impl> impl_;
};

}  // namespace sandtin
