#include "gpu/surface_maps.hpp"

#include <array>
#include <cstring>

#include "gpu/gpu_error.hpp"
#include "gpu/shaders.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

namespace {

constexpr uint32_t kMapBindings = 12;
constexpr VkBufferUsageFlags kMapStorage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
    VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;

std::vector<Vec3> to_vec3(const std::vector<float>& f) {
    std::vector<Vec3> out(f.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) {
        out[i] = Vec3{static_cast<double>(f[4 * i]), static_cast<double>(f[4 * i + 1]),
                      static_cast<double>(f[4 * i + 2])};
    }
    return out;
}

}  // namespace

SurfaceMaps::SurfaceMaps(TinMirror& mirror)
    : mirror_(mirror),
      vertex_kernel_(mirror.context(), "vertex_normals", shaders::vertex_normals(), kMapBindings,
                     sizeof(Push)),
      corner_kernel_(mirror.context(), "corner_normals", shaders::corner_normals(), kMapBindings,
                     sizeof(Push)),
      bake_kernel_(mirror.context(), "bake_maps", shaders::bake_maps(), kMapBindings,
                   sizeof(Push)) {}

void SurfaceMaps::ensure_buffers(VkDeviceSize map_texels) {
    const VulkanContext& ctx = mirror_.context();
    const uint32_t vcap = mirror_.vertex_capacity();
    const uint32_t scap = mirror_.slot_capacity();
    if (vcap == 0 || scap == 0) {
        throw GpuError("SurfaceMaps: the mirror is empty (call TinMirror::sync first)");
    }
    bool changed = false;
    if (vcap != vertex_capacity_) {
        vertex_normals_ = Buffer(ctx, VkDeviceSize{vcap} * 16, kMapStorage, MemoryUse::Device);
        vertex_capacity_ = vcap;
        changed = true;
    }
    if (scap != slot_capacity_) {
        corner_normals_ = Buffer(ctx, VkDeviceSize{scap} * 48, kMapStorage, MemoryUse::Device);
        slot_capacity_ = scap;
        changed = true;
    }
    if (map_texels > map_texels_ || !height_map_) {
        const VkDeviceSize n = std::max<VkDeviceSize>(map_texels, 1);
        height_map_ = Buffer(ctx, n * 4, kMapStorage, MemoryUse::Device);
        normal_map_ = Buffer(ctx, n * 16, kMapStorage, MemoryUse::Device);
        map_texels_ = n;
        changed = true;
    }
    if (changed || !bound_ || bound_generation_ != mirror_.generation()) {
        bind_all();
        normals_valid_ = false;
        corners_valid_ = false;
    }
}

void SurfaceMaps::bind_all() {
    const std::array<VkBuffer, kMapBindings> b = {mirror_.vertex_buffer(VertexBuffer::Position),
                                                  mirror_.vertex_buffer(VertexBuffer::Height),
                                                  mirror_.vertex_buffer(VertexBuffer::RowOffset),
                                                  mirror_.vertex_buffer(VertexBuffer::RowDegree),
                                                  mirror_.edge_buffer(EdgeBuffer::Target),
                                                  mirror_.edge_buffer(EdgeBuffer::EdgeFlags),
                                                  vertex_normals_.get(),
                                                  mirror_.slot_buffer(SlotBuffer::Triangles),
                                                  mirror_.slot_buffer(SlotBuffer::SlotFlags),
                                                  corner_normals_.get(),
                                                  height_map_.get(),
                                                  normal_map_.get()};
    for (ComputeKernel* k : {&vertex_kernel_, &corner_kernel_, &bake_kernel_})
        k->bind(b);
    bound_generation_ = mirror_.generation();
    bound_ = true;
}

void SurfaceMaps::record_normals(VkCommandBuffer cb, const Push& base, bool corners) {
    Push pv = base;
    pv.count = vertex_capacity_;
    pv.z_scale = z_scale_;
    Push ps = pv;
    ps.count = slot_capacity_;
    compute_transfer_barrier(cb);  // mirror uploads and relaxation -> normals
    vertex_kernel_.dispatch(cb, pv.count, &pv);
    ++dispatches_;
    if (corners) {
        corner_kernel_.dispatch(cb, ps.count, &ps);
        ++dispatches_;
    }
}

void SurfaceMaps::compute_normals(double z_scale) {
    ensure_buffers(map_texels_);
    z_scale_ = static_cast<float>(z_scale);
    mirror_.context().submit_and_wait(
        [&](VkCommandBuffer cb) { record_normals(cb, Push{}, true); });
    normals_valid_ = true;
    corners_valid_ = true;
}

std::vector<Vec3> SurfaceMaps::read_vertex_normals() const {
    if (!vertex_normals_) return {};
    return to_vec3(
        read_buffer_floats(mirror_.context(), vertex_normals_.get(), vertex_normals_.size()));
}

std::vector<Vec3> SurfaceMaps::read_corner_normals() const {
    if (!corner_normals_) return {};
    return to_vec3(
        read_buffer_floats(mirror_.context(), corner_normals_.get(), corner_normals_.size()));
}

SurfaceMaps::Push SurfaceMaps::grid_push(const MapGrid& grid, BakeNormals normals) const {
    const Vec2 o = mirror_.origin();
    Push p{};
    p.count = slot_capacity_;
    p.mode = static_cast<uint32_t>(normals);
    p.width = grid.width;
    p.height = grid.height;
    p.z_scale = z_scale_;
    if (grid.at == SampleAt::Corners) {
        p.dx = static_cast<float>(grid.domain.width() / (grid.width - 1));
        p.dy = static_cast<float>(grid.domain.height() / (grid.height - 1));
        p.offset = 0.0f;
    } else {
        p.dx = static_cast<float>(grid.domain.width() / grid.width);
        p.dy = static_cast<float>(grid.domain.height() / grid.height);
        p.offset = 0.5f;
    }
    p.x0 = static_cast<float>(grid.domain.min.x - o.x);
    p.y_top = static_cast<float>(grid.domain.max.y - o.y);
    return p;
}

void SurfaceMaps::bake_region(const MapGrid& grid, const Rect& region, TexelRect texels,
                              BakeNormals normals,
                              const std::function<void(VkCommandBuffer)>& then) {
    if (texels.col1 < texels.col0 || texels.row1 < texels.row0 || texels.col1 >= grid.width ||
        texels.row1 >= grid.height) {
        throw GpuError("SurfaceMaps::bake_region: the texel rectangle is empty or off the grid");
    }
    ensure_buffers(grid.size());
    const Vec2 o = mirror_.origin();
    // A smooth bake reads no corner normals: they are left stale (and recomputed in full by
    // the next creased bake or compute_normals()).
    const bool creased = normals == BakeNormals::Creased;
    const bool whole = !normals_valid_ || (creased && !corners_valid_);
    Push n{};
    if (!whole) {
        n.in_region = 1;
        n.region[0] = static_cast<float>(region.min.x - o.x);
        n.region[1] = static_cast<float>(region.min.y - o.y);
        n.region[2] = static_cast<float>(region.max.x - o.x);
        n.region[3] = static_cast<float>(region.max.y - o.y);
    }
    Push p = grid_push(grid, normals);
    p.col0 = texels.col0;
    p.row0 = texels.row0;
    p.col1 = texels.col1;
    p.row1 = texels.row1;
    // An empty region recomputes no normal: no dispatch at all (a band of a new map after the
    // first, 10^6 vertices' worth of threads that would each find themselves outside it).
    const bool any_normals = whole || !region.empty();
    mirror_.context().submit_and_wait([&](VkCommandBuffer cb) {
        if (any_normals) record_normals(cb, n, creased);
        compute_transfer_barrier(cb);
        bake_kernel_.dispatch(cb, p.count, &p);
        if (then) then(cb);
    });
    ++dispatches_;
    normals_valid_ = true;
    corners_valid_ = creased;
}

BakedMaps SurfaceMaps::bake(const MapGrid& grid, BakeNormals normals) {
    const VkDeviceSize texels = grid.size();
    ensure_buffers(texels);
    Push p = grid_push(grid, normals);
    const VulkanContext& ctx = mirror_.context();
    ctx.submit_and_wait([&](VkCommandBuffer cb) {
        vkCmdFillBuffer(cb, height_map_.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cb, normal_map_.get(), 0, VK_WHOLE_SIZE, 0);
        compute_transfer_barrier(cb);
        bake_kernel_.dispatch(cb, p.count, &p);
    });
    ++dispatches_;
    const std::vector<float> h = read_buffer_floats(ctx, height_map_.get(), texels * 4);
    const std::vector<float> n = read_buffer_floats(ctx, normal_map_.get(), texels * 16);
    BakedMaps out;
    out.height.width = out.normal.width = grid.width;
    out.height.height = out.normal.height = grid.height;
    out.height.channels = 1;
    out.normal.channels = 3;
    out.height.values.resize(texels);
    out.normal.values.resize(texels * 3);
    for (size_t i = 0; i < texels; ++i) {
        out.height.values[i] = static_cast<double>(h[i]) + mirror_.height_origin();
        for (size_t c = 0; c < 3; ++c)
            out.normal.values[3 * i + c] = static_cast<double>(n[4 * i + c]);
    }
    return out;
}

}  // namespace sandtin::gpu
