#pragma once
// The terrain's baked normal map as a texture: the GPU bake of gpu/SurfaceMaps (smooth vertex
// normals interpolated per texel, so long TIN edges shade smoothly) on a grid of texel centres
// over the domain, converted into a sampled RG16_SNORM image (the unit normal's x and y; z > 0
// follows) that terrain.frag reads by world xy.
// After a change only the texels whose triangles or corner normals changed are re-baked and
// copied: the 2-ring of the journal's dirty vertices and the corners of its dirty triangle
// slots (a vertex normal depends on the 1-ring's heights, a texel on its triangle's corner
// normals).
//
// Texel (col, row) covers x in [x0 + col dx, x0 + (col + 1) dx] and row 0 is the north edge, so
// a fragment at world (x, y) samples u = (x - x0) / width, v = (y1 - y) / height.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "geom/rect.hpp"
#include "gpu/image.hpp"
#include "gpu/surface_maps.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu/vk_handle.hpp"
#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin::render {

/// The world rectangle (metres) holding every normal-map texel `changes` can have altered:
/// the bounding box of the 2-ring (in `graph`, which must already reflect the change) of the
/// live dirty vertices and of the corners of the dirty slots. Nothing when nothing is dirty.
std::optional<Rect> normal_map_dirty_region(const Tin& tin, const AdjacencyGraph& graph,
                                            const ChangeSet& changes);

/// Map size for a domain: `max_side` texels along its longer side, the other in proportion.
MapGrid normal_map_grid(const Rect& domain, std::uint32_t max_side);

class TerrainNormalMap {
  public:
    /// The mirror must have been synced at least once and outlive this object. Bakes the
    /// whole map, or with `bake_now` false nothing yet: bake_rows() then bakes it a band at a
    /// time (an editor frame each), complete() says when every texel is.
    TerrainNormalMap(gpu::TinMirror& mirror, const Rect& domain, std::uint32_t max_side = 1024,
                     bool bake_now = true);
    ~TerrainNormalMap();
    TerrainNormalMap(const TerrainNormalMap&) = delete;
    TerrainNormalMap& operator=(const TerrainNormalMap&) = delete;

    /// Bakes the next `rows` rows not baked yet, from the mirror as it is now (the first band
    /// computes every vertex normal); the GPU must not be reading the texture. What changed in
    /// the TIN meanwhile is for rebake() once the map is complete.
    void bake_rows(std::uint32_t rows);
    bool complete() const { return next_row_ >= grid_.height; }
    /// Re-bakes what `changes` touched; the mirror must already hold the changed TIN (synced)
    /// and the GPU must not be reading the texture. Returns the texels re-baked, if any. Only
    /// on a complete map (std::logic_error otherwise).
    std::optional<gpu::TexelRect> rebake(const Tin& tin, const ChangeSet& changes);
    /// Everything (a new terrain, or a mirror whose buffers were reallocated).
    void bake_all();

    VkImageView view() const { return view_.get(); }
    VkSampler sampler() const { return sampler_.get(); }
    const MapGrid& grid() const { return grid_; }
    gpu::TinMirror& mirror() const { return mirror_; }
    /// Texels baked since construction (a full bake counts them all).
    std::uint64_t texels_baked() const { return texels_baked_; }
    /// The texture read back and decoded as the shader does (x, y, z = sqrt(1 - x^2 - y^2), 0
    /// per texel, row-major, row 0 north): for tests.
    std::vector<float> read_back() const;

  private:
    void bake(const Rect& region, gpu::TexelRect texels);

    gpu::TinMirror& mirror_;
    MapGrid grid_;
    gpu::SurfaceMaps maps_;
    gpu::Image staging_;  ///< RGBA32F, as baked (a blit source between bakes)
    gpu::Image image_;    ///< RG16_SNORM: the normal's x and y
    gpu::UniqueImageView view_;
    gpu::UniqueSampler sampler_;
    bool initialised_ = false;    ///< the image left UNDEFINED layout
    std::uint32_t next_row_ = 0;  ///< rows before it are baked
    std::uint64_t texels_baked_ = 0;
};

}  // namespace sandtin::render
