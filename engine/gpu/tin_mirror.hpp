#pragma once
// The GPU copy of the TIN, fed by a change reader of its own (tin/change_reader.hpp, so it never
// takes changes from another consumer): only dirty vertex
// ranges, dirty triangle slots and the adjacency rows around them are uploaded, through a
// staging ring. Buffers are indexed exactly like the CPU arrays and grow by reallocation (×1.5,
// old contents copied on the GPU), so growth never re-uploads from the CPU.
//
// Device buffers (all storage buffers; std430 arrays):
//   per vertex id v (capacity vertex_capacity()):
//     position  vec2  metres, relative to origin() (float keeps µm precision near the terrain)
//     height    float metres above height_origin()   bedrock float, the same (rounded up)
//               (float keeps its precision for the heights that matter, the differences
//               between neighbours, on an elevation model hundreds of metres up)
//     area      float m², lumped      tan_alpha float (tan of the angle of repose, from materials)
//     material  uint                  moisture float [0, 1]
//     slide     vec2  texture units in [0, 1), written by the relaxation (texture sliding)
//     water_depth float metres of water over the height, >= 0 (gpu_water.hpp writes it)
//     row_offset, row_degree uint (CSR)   longest float metres (longest edge of the row)
//   per triangle slot s (capacity slot_capacity()):
//     triangles uint[3] counter-clockwise corners (0, 0, 0 for a free slot: degenerate), also
//               usable as an index buffer
//     slot_flags uint: bits 0-2 = edge opposite corner i constrained, bit 3 = live
//   per directed edge k of the CSR pool (capacity edge_capacity()):
//     target uint, reverse uint (slot of the opposite direction), length float metres,
//     edge_flags uint (bit 0: constrained edge), across float metres (AdjacencyGraph::across:
//     the edge between this slot's target and the next slot's when they make a face with the
//     row's vertex, else 0; the face rule's kernel reads it)
// Rows list neighbours counter-clockwise (AdjacencyGraph's invariant), which the normal kernels
// rely on.
//
// Invariant after sync(): every buffer equals the TIN (converted to float) for all live ids and
// slots; the CPU-side graph() equals the GPU CSR.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "geom/vec2.hpp"
#include "gpu/buffer.hpp"
#include "gpu/mirror_seed.hpp"
#include "gpu/staging_ring.hpp"
#include "physics/adjacency_graph.hpp"
#include "physics/material.hpp"
#include "tin/change_reader.hpp"
#include "tin/tin.hpp"

namespace sandtin::gpu {

class VulkanContext;

enum class VertexBuffer : uint32_t {
    Position,
    Height,
    Bedrock,
    Area,
    TanAlpha,
    Material,
    Moisture,
    Slide,
    WaterDepth,
    RowOffset,
    RowDegree,
    Longest,
    Count
};
enum class SlotBuffer : uint32_t { Triangles, SlotFlags, Count };
enum class EdgeBuffer : uint32_t { Target, Reverse, Length, EdgeFlags, Across, Count };

// What one sync() did.
struct SyncStats {
    uint64_t bytes = 0;         // staged for upload
    uint64_t copy_regions = 0;  // buffer copy regions those bytes went in
    uint32_t vertex_ranges = 0;
    uint32_t slot_ranges = 0;
    uint32_t rows = 0;         // adjacency rows uploaded
    bool reallocated = false;  // some buffer grew
};

class TinMirror {
  public:
    // Mirrors `tin`, which must outlive it and stay where it is. `materials` gives tan(angle of
    // repose) per vertex; `staging_bytes` sizes the ring. Nothing is uploaded before sync().
    TinMirror(VulkanContext& context, Tin& tin, MaterialTable materials = MaterialTable::presets(),
              VkDeviceSize staging_bytes = VkDeviceSize{8} << 20);
    // Mirrors the TIN `seed` was prepared from (prepare_mirror_seed, maybe on another thread):
    // the first sync takes the seed's graph, flags and origins instead of computing them, and
    // catches up through the seed's reader with whatever changed since it was built.
    TinMirror(VulkanContext& context, MirrorSeed seed,
              MaterialTable materials = MaterialTable::presets(),
              VkDeviceSize staging_bytes = VkDeviceSize{8} << 20);
    ~TinMirror();
    TinMirror(const TinMirror&) = delete;
    TinMirror& operator=(const TinMirror&) = delete;

    // Uploads what changed in the TIN since the previous sync (everything the first time), from
    // the mirror's own change reader. Submits the copies without waiting. Whoever needs the
    // mirror current calls it (the GPU physics before a step, the editor before a bake): a
    // second call with nothing changed uploads nothing.
    SyncStats sync();
    Tin& tin() const { return changes_->tin(); }
    // Materials changed: tan_alpha of every live vertex is re-uploaded at the next sync.
    void set_materials(MaterialTable materials);

    VkBuffer vertex_buffer(VertexBuffer b) const;
    VkBuffer slot_buffer(SlotBuffer b) const;
    VkBuffer edge_buffer(EdgeBuffer b) const;
    uint32_t vertex_capacity() const { return vertex_capacity_; }
    uint32_t slot_capacity() const { return slot_capacity_; }
    uint32_t edge_capacity() const { return edge_capacity_; }
    // Bumped whenever a buffer is reallocated: descriptor sets must be rebound.
    uint64_t generation() const { return generation_; }
    Vec2 origin() const { return origin_; }
    // Metres subtracted from every height and bedrock on the GPU: the mean height at the first
    // sync. Read-backs add it again.
    double height_origin() const { return height_origin_; }

    // Sum of the sizes of the mirrored buffers (bytes), the denominator of upload ratios.
    uint64_t mirrored_bytes() const;
    // Every byte staged since construction (per-sync figures are in SyncStats::bytes).
    uint64_t total_uploaded_bytes() const { return ring_.total_bytes(); }

    // The CSR graph as on the GPU (CPU copy, for the CPU reference and the physics).
    const AdjacencyGraph& graph() const { return graph_; }
    const std::vector<float>& tan_alpha() const { return tan_alpha_cpu_; }
    const MaterialTable& materials() const { return materials_; }

    VulkanContext& context() const { return context_; }
    StagingRing& staging() { return ring_; }

  private:
    // Counts of ids, slots and pool entries a sync uploads in full from 0 (none after the first).
    struct Uploaded {
        uint32_t vertices = 0, slots = 0, edges = 0;
    };
    void grow(uint32_t vertices, uint32_t slots, uint32_t edges, const Uploaded& uploaded,
              SyncStats& stats);
    void upload_vertex_range(const Tin& tin, IdRange r);
    // tan(repose) of the ids in `r` (0 for dead ones), computed and uploaded.
    void upload_tan_alpha(const Tin& tin, IdRange r);
    // `flags`: the rows' constrained flags by pool slot, when known (the seed's), else read
    // from the TIN.
    void upload_rows(const Tin& tin, const std::vector<uint32_t>& rows,
                     const std::vector<uint32_t>* flags);
    // Rewrites the graph rows around `changes` (the stars that changed).
    void update_graph(const Tin& tin, const ChangeSet& changes);
    // The first sync: the seed (built now when there is none) becomes the graph and origins.
    void adopt_seed(Tin& tin, const ChangeSet& changes);

    VulkanContext& context_;
    std::unique_ptr<ChangeReader> changes_;
    std::optional<MirrorSeed> seed_;  ///< until the first sync
    MaterialTable materials_;
    StagingRing ring_;
    AdjacencyGraph graph_{RowSlack::Some, FaceShapes::Skip};  ///< the shader needs no shapes
    bool first_sync_ = true;
    bool materials_dirty_ = false;
    Vec2 origin_{};
    double height_origin_ = 0.0;
    uint32_t vertex_capacity_ = 0;
    uint32_t slot_capacity_ = 0;
    uint32_t edge_capacity_ = 0;
    uint64_t generation_ = 0;
    std::array<Buffer, static_cast<size_t>(VertexBuffer::Count)> vertex_;
    std::array<Buffer, static_cast<size_t>(SlotBuffer::Count)> slot_;
    std::array<Buffer, static_cast<size_t>(EdgeBuffer::Count)> edge_;
    std::vector<float> tan_alpha_cpu_;
    // Scratch for conversions, kept to avoid reallocating per range.
    std::vector<float> f_;
    std::vector<float> f2_;
    std::vector<uint32_t> u_;
};

// Element size (bytes) of each buffer.
uint32_t element_size(VertexBuffer b);
uint32_t element_size(SlotBuffer b);
uint32_t element_size(EdgeBuffer b);

}  // namespace sandtin::gpu
