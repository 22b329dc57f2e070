#pragma once
// Normals and map bakes on the GPU from a TinMirror:
//  - compute_normals(): smooth per-vertex normals (area-weighted, the twin of
//    maps/vertex_normals) and creased normals per triangle corner (slot * 3 + corner; the fan
//    around the corner's vertex up to constrained edges, so tool walls keep their crease).
//  - bake(): height map and normal map on a MapGrid (maps/map_grid.hpp) at any resolution,
//    returned as MapImage for the existing exporters (io/export_maps).
// Normal buffers are device-local vec4 arrays (xyz, w = 0) the renderer can bind directly.

#include <cstdint>
#include <vector>

#include "geom/vec3.hpp"
#include "gpu/buffer.hpp"
#include "gpu/compute_kernel.hpp"
#include "gpu/tin_mirror.hpp"
#include "maps/map_grid.hpp"

namespace sandtin::gpu {

enum class BakeNormals : uint32_t { Smooth = 0, Creased = 1 };

struct BakedMaps {
    MapImage height;  // 1 channel, metres
    MapImage normal;  // 3 channels, unit, z > 0
};

class SurfaceMaps {
  public:
    explicit SurfaceMaps(TinMirror& mirror);

    // Recomputes vertex and corner normals from the mirror's current heights (z_scale
    // exaggerates heights first). Waits for completion.
    void compute_normals(double z_scale = 1.0);
    VkBuffer vertex_normals() const { return vertex_normals_.get(); }
    VkBuffer corner_normals() const { return corner_normals_.get(); }
    std::vector<Vec3> read_vertex_normals() const;  // by VertexId
    std::vector<Vec3> read_corner_normals() const;  // by slot * 3 + corner

    // Bakes both maps on `grid` (compute_normals() must have run for the current heights).
    BakedMaps bake(const MapGrid& grid, BakeNormals normals = BakeNormals::Smooth);

    uint64_t dispatches_recorded() const { return dispatches_; }

  private:
    struct Push {
        uint32_t count;
        uint32_t mode;
        uint32_t width;
        uint32_t height;
        float z_scale;
        float x0;
        float y_top;
        float dx;
        float dy;
        float offset;
    };
    void ensure_buffers(VkDeviceSize map_texels);
    void bind_all();

    TinMirror& mirror_;
    ComputeKernel vertex_kernel_;
    ComputeKernel corner_kernel_;
    ComputeKernel bake_kernel_;
    Buffer vertex_normals_;
    Buffer corner_normals_;
    Buffer height_map_;
    Buffer normal_map_;
    uint32_t vertex_capacity_ = 0;
    uint32_t slot_capacity_ = 0;
    VkDeviceSize map_texels_ = 0;
    uint64_t bound_generation_ = UINT64_MAX;
    bool bound_ = false;
    float z_scale_ = 1.0f;
    uint64_t dispatches_ = 0;
};

}  // namespace sandtin::gpu
