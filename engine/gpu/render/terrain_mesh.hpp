#pragma once
// The terrain as the renderer draws it, kept on the CPU and updated from the TIN's change
// journal: a vertex array indexed by VertexId (position relative to the domain centre, smooth
// normal, material albedo, overlay values, texture-sliding offset) and an index array with
// three entries per triangle slot (a free slot is the degenerate triangle 0, 0, 0). An update
// recomputes only the vertices the journal names plus their neighbours (whose normals and
// slopes depend on them) and reports the ranges to upload, so a stamp on a large terrain
// uploads a few kilobytes.

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gpu/render/wet_triangles.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin::render {

struct RenderVertex {
    float position[3];  ///< metres: x, y relative to the domain centre, z = height
    float normal[3];    ///< unit, area-weighted mean of the incident faces
    float albedo[3];    ///< linear RGB, darkened by moisture
    /// x: tan(angle of repose) of the vertex's material and moisture (the Slope overlay
    /// compares each face's gradient with it); y: sand thickness above bedrock (m; 0 without
    /// bedrock); z: 1 when the vertex is active (eroding)
    float overlay[3];
    float slide[2];  ///< texture-sliding offset, texture units
    float water;     ///< metres of water standing on the vertex (VertexArrays::water_depth)
    float speed;     ///< m/s: how fast that water flows (set_water_speed), for the Speed overlay
    float sediment;  ///< m³ of sand per m³ of that water (set_water_sediment): Sediment overlay
    /// Metres: the water's surface here, for the surface drawn over the terrain. A wet vertex:
    /// its height plus its water. A dry one: the highest surface of its wet neighbours, but
    /// never above its own height, so a shore face's surface runs level into the bank and the
    /// bank, drawn first, hides what lies under it: the waterline is where the water's plane
    /// meets the sand. (On dry ground with no wet neighbour: its height.)
    float surface;
};
static_assert(sizeof(RenderVertex) == 18 * sizeof(float));

/// What an update changed, as ranges into vertices() and (per slot) indices().
struct MeshUpdate {
    std::vector<IdRange> vertices;
    std::vector<IdRange> slots;
    /// The arrays were rebuilt or grew: everything must be uploaded (the ranges name only
    /// what was recomputed, not the new tail).
    bool resized = false;
    bool edges_changed = false;   ///< constrained_edges() changed
    bool water_changed = false;   ///< water_indices() changed
    std::uint64_t bytes() const;  ///< bytes to upload for these ranges
};

class TerrainMesh {
  public:
    explicit TerrainMesh(MaterialTable materials);

    /// Everything from scratch.
    MeshUpdate rebuild(const Tin& tin);
    /// Applies `changes` (from tin.take_changes()) and the vertices whose active flag flipped.
    MeshUpdate update(const Tin& tin, const ChangeSet& changes,
                      std::span<const VertexId> active_flipped = {});
    /// New material table (colours, angles of repose). Returns the indices whose entries draw
    /// differently from before (colour, or tan of the angle of repose at some moisture), for
    /// recolour().
    std::vector<std::uint16_t> set_materials(MaterialTable materials);
    /// The material-dependent parts (albedo, tan of the angle of repose) of every live vertex
    /// whose material is one of `changed` (material indices), from the table set last; the
    /// geometry is left alone. O(vertices), with no walk of the triangulation: a material edit
    /// at 10^6 vertices took a 405 ms rebuild of the whole mesh on the UI thread.
    MeshUpdate recolour(const Tin& tin, std::span<const std::uint16_t> changed);
    /// Active (eroding) flags by VertexId, read by update() for the vertices it recomputes.
    void set_active(std::span<const std::uint8_t> active) { active_ = active; }
    /// Flow speeds (m/s) by VertexId (water/live_water.hpp speeds()), read by update() for
    /// the vertices it recomputes; ids past its end flow at 0.
    void set_water_speed(std::span<const float> speed) { speed_ = speed; }
    /// Sand carried per volume of water by VertexId (water/live_water.hpp sediment()), read
    /// as set_water_speed's speeds are.
    void set_water_sediment(std::span<const float> sediment) { sediment_ = sediment; }

    const std::vector<RenderVertex>& vertices() const { return vertices_; }
    const std::vector<std::uint32_t>& indices() const { return indices_; }
    /// Constrained edges as a line list (pairs of VertexIds).
    const std::vector<std::uint32_t>& constrained_edges() const { return constrained_; }
    /// The triangles with a wet corner, each once (three VertexIds each): what the water
    /// surface is drawn on. Empty on a dry terrain.
    const std::vector<std::uint32_t>& water_indices() const { return wet_.indices(); }
    /// Changes whenever water_indices() does.
    std::uint64_t water_version() const { return wet_.version(); }
    /// Every triangle edge once, as a line list (for the wireframe overlay; built on demand).
    std::vector<std::uint32_t> all_edges() const;

  private:
    void compute_vertex(const Tin& tin, std::uint32_t id, std::vector<VertexId>& ring);
    void colour_vertex(const Tin& tin, std::uint32_t id);
    void write_slot(const Tin& tin, TriangleSlot slot);
    void collect_constrained(const Tin& tin);

    MaterialTable materials_;
    std::span<const std::uint8_t> active_;
    std::span<const float> speed_;
    std::span<const float> sediment_;
    std::vector<RenderVertex> vertices_;
    std::vector<std::uint32_t> indices_;
    std::vector<std::uint32_t> constrained_;
    std::vector<std::uint8_t> mark_;
    WetTriangles wet_;
};

}  // namespace sandtin::render
