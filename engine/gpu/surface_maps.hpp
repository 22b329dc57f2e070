#pragma once
// Normals and map bakes on the GPU from a TinMirror:
//  - compute_normals(): smooth per-vertex normals (area-weighted, the twin of
//    maps/vertex_normals) and creased normals per triangle corner (slot * 3 + corner; the fan
//    around the corner's vertex up to constrained edges, so tool walls keep their crease).
//  - bake(): height map and normal map on a MapGrid (maps/map_grid.hpp) at any resolution,
//    returned as MapImage for the existing exporters (io/export_maps).
// Normal buffers are device-local vec4 arrays (xyz, w = 0) the renderer can bind directly.

#include <cstdint>
#include <functional>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec3.hpp"
#include "gpu/buffer.hpp"
#include "gpu/compute_kernel.hpp"
#include "gpu/tin_mirror.hpp"
#include "maps/map_grid.hpp"

namespace sandtin::gpu {

enum class BakeNormals : uint32_t { Smooth = 0, Creased = 1 };

// Inclusive rectangle of map texels (col0..col1, row0..row1; row 0 north).
struct TexelRect {
    uint32_t col0 = 0;
    uint32_t row0 = 0;
    uint32_t col1 = 0;
    uint32_t row1 = 0;
    uint32_t width() const { return col1 - col0 + 1; }
    uint32_t height() const { return row1 - row0 + 1; }
    friend bool operator==(const TexelRect&, const TexelRect&) = default;
};

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

    // Re-bake after a local change, with nothing read back (the renderer copies the device
    // maps into its texture): recomputes the normals of the vertices inside `region` (metres,
    // world coordinates; every vertex when the normal buffers were just (re)allocated), then
    // bakes only the texels of `texels` on `grid`. Texels outside keep what the previous bake
    // of the same grid wrote. The caller chooses `region` so that it holds every vertex whose
    // normal changed and `texels` so that it holds every texel whose triangle or corner
    // normals changed.
    // `then` records more commands into the same submission after the bake (the renderer's
    // copy into its texture; it makes the bake's writes visible itself).
    void bake_region(const MapGrid& grid, const Rect& region, TexelRect texels,
                     BakeNormals normals = BakeNormals::Smooth,
                     const std::function<void(VkCommandBuffer)>& then = {});
    // The device maps of the last bake, row-major on its grid: height float, normal vec4.
    VkBuffer height_map() const { return height_map_.get(); }
    VkBuffer normal_map() const { return normal_map_.get(); }

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
        uint32_t col0 = 0;  // bake clip rectangle (inclusive)
        uint32_t row0 = 0;
        uint32_t col1 = UINT32_MAX;
        uint32_t row1 = UINT32_MAX;
        uint32_t in_region = 0;          // normals: only vertices inside `region`
        float region[4] = {0, 0, 0, 0};  // x0, y0, x1, y1 relative to the mirror's origin
    };
    Push grid_push(const MapGrid& grid, BakeNormals normals) const;
    void record_normals(VkCommandBuffer cb, const Push& base, bool corners);
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
    bool normals_valid_ = false;  // the vertex normal buffer holds every vertex's normal
    bool corners_valid_ = false;  // the corner normal buffer holds every corner's normal
    float z_scale_ = 1.0f;
    uint64_t dispatches_ = 0;
};

}  // namespace sandtin::gpu
