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
};
static_assert(sizeof(RenderVertex) == 14 * sizeof(float));

/// What an update changed, as ranges into vertices() and (per slot) indices().
struct MeshUpdate {
    std::vector<IdRange> vertices;
    std::vector<IdRange> slots;
    /// The arrays were rebuilt or grew: everything must be uploaded (the ranges name only
    /// what was recomputed, not the new tail).
    bool resized = false;
    bool edges_changed = false;   ///< constrained_edges() changed
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
    /// New material table (colours, angles of repose); call rebuild() afterwards.
    void set_materials(MaterialTable materials) { materials_ = std::move(materials); }
    /// Active (eroding) flags by VertexId, read by update() for the vertices it recomputes.
    void set_active(std::span<const std::uint8_t> active) { active_ = active; }

    const std::vector<RenderVertex>& vertices() const { return vertices_; }
    const std::vector<std::uint32_t>& indices() const { return indices_; }
    /// Constrained edges as a line list (pairs of VertexIds).
    const std::vector<std::uint32_t>& constrained_edges() const { return constrained_; }
    /// Every triangle edge once, as a line list (for the wireframe overlay; built on demand).
    std::vector<std::uint32_t> all_edges() const;

  private:
    void compute_vertex(const Tin& tin, std::uint32_t id, std::vector<VertexId>& ring);
    void write_slot(const Tin& tin, TriangleSlot slot);
    void collect_constrained(const Tin& tin);

    MaterialTable materials_;
    std::span<const std::uint8_t> active_;
    std::vector<RenderVertex> vertices_;
    std::vector<std::uint32_t> indices_;
    std::vector<std::uint32_t> constrained_;
    std::vector<std::uint8_t> mark_;
};

}  // namespace sandtin::render
